/* SPDX-License-Identifier: MIT */
/*
 * A flat C API over CHOLMOD for the Fortran module sparse_cholesky: Fortran never sees
 * cholmod_common or cholmod_factor, only an opaque handle owning both.
 *
 * CHOLMOD's long-index API (cholmod_l_*): every index and count that crosses is an int64_t
 * (SuiteSparse_long), so that a factor may hold more than 2^31 entries, where the int API
 * stops with CHOLMOD_TOO_LARGE.
 *
 * The matrix comes as a full symmetric matrix in 0-based CSR, which is also its CSC.
 * CHOLMOD reads it in place (no copy) as a symmetric matrix through its upper triangle
 * (stype = 1); entries below the diagonal are ignored, so the caller guarantees symmetry.
 *
 * The factor is supernodal LL' with A = P' L L' P, so that the forward solve with L alone
 * is meaningful: W = L^{-1} P B gives B1' A^{-1} B2 = W1' W2.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <float.h>
#include <cholmod.h>

/* The Fortran side passes integer(c_int64_t) arrays where CHOLMOD reads SuiteSparse_long. */
_Static_assert(sizeof(SuiteSparse_long) == sizeof(int64_t),
               "SuiteSparse_long must be a 64-bit integer");
typedef SuiteSparse_long index_t;

/* Return codes, mirrored by the constants of sparse_cholesky.f90. */
enum {
    NCEIG_CHOLMOD_OK = 0,
    NCEIG_CHOLMOD_NOT_POSDEF = 1,     /* a pivot was <= 0; info[3] holds the column */
    NCEIG_CHOLMOD_SINGULAR = 2,       /* pivots all > 0 but rcond below the threshold */
    NCEIG_CHOLMOD_OUT_OF_MEMORY = 3,
    NCEIG_CHOLMOD_TOO_LARGE = 4,      /* a size overflows CHOLMOD's size_t arithmetic */
    NCEIG_CHOLMOD_INVALID = 5,        /* bad argument: n, ordering or permutation */
    NCEIG_CHOLMOD_NOT_FACTORED = 6,   /* solve on a null handle */
    NCEIG_CHOLMOD_FAILED = 7          /* any other CHOLMOD failure */
};

/* Orderings requested by the caller (argument `ordering`). */
enum {
    NCEIG_ORDER_DEFAULT = 0,
    NCEIG_ORDER_AMD = 1,
    NCEIG_ORDER_METIS = 2,
    NCEIG_ORDER_NATURAL = 3,
    NCEIG_ORDER_GIVEN = 4
};

/*
 * A singular positive semi-definite matrix (a stiffness matrix without Dirichlet boundary)
 * often does not break down in floating point: its last pivot is rounding noise of either
 * sign. Its size relative to the largest pivot is then a modest multiple of machine epsilon,
 * so a pivot ratio (CHOLMOD's rcond estimate, (min L_jj / max L_jj)^2) below this threshold
 * is reported as singular. A legitimate K with such a pivot ratio would have lost about 12
 * of its 16 digits anyway.
 */
#define NCEIG_RCOND_SINGULAR (1.0e3 * DBL_EPSILON)

typedef struct {
    cholmod_common common;
    cholmod_factor *factor;
    index_t n;
} nceig_cholmod_t;

static int code_from_common(const cholmod_common *common)
{
    switch (common->status) {
    case CHOLMOD_OK:
        return NCEIG_CHOLMOD_OK;
    case CHOLMOD_NOT_POSDEF:
        return NCEIG_CHOLMOD_NOT_POSDEF;
    case CHOLMOD_OUT_OF_MEMORY:
        return NCEIG_CHOLMOD_OUT_OF_MEMORY;
    case CHOLMOD_TOO_LARGE:
        return NCEIG_CHOLMOD_TOO_LARGE;
    case CHOLMOD_INVALID:
        return NCEIG_CHOLMOD_INVALID;
    default:
        /* CHOLMOD_DSMALL is only a warning that some diagonal is tiny: the factor exists. */
        return common->status > 0 ? NCEIG_CHOLMOD_OK : NCEIG_CHOLMOD_FAILED;
    }
}

/* The CHOLMOD method of an NCEIG_ORDER_* request; -1 for NCEIG_ORDER_DEFAULT (CHOLMOD's
   own choice). */
static int cholmod_method(int ordering)
{
    switch (ordering) {
    case NCEIG_ORDER_AMD: return CHOLMOD_AMD;
    case NCEIG_ORDER_METIS: return CHOLMOD_METIS;
    case NCEIG_ORDER_NATURAL: return CHOLMOD_NATURAL;
    case NCEIG_ORDER_GIVEN: return CHOLMOD_GIVEN;
    default: return -1;
    }
}

/* 1 if perm0 holds each of 0..n-1 exactly once. */
static int is_permutation(index_t n, const index_t *perm0)
{
    char *seen = calloc((size_t)n + 1, 1);
    int ok = seen != NULL;
    for (index_t k = 0; ok && k < n; k++) {
        ok = perm0[k] >= 0 && perm0[k] < n && !seen[perm0[k]];
        if (ok) seen[perm0[k]] = 1;
    }
    free(seen);
    return ok;
}

static void destroy(nceig_cholmod_t *h)
{
    cholmod_l_free_factor(&h->factor, &h->common);
    cholmod_l_finish(&h->common);
    free(h);
}

/* Release everything the handle owns; a null handle is left alone, so freeing twice is safe. */
void nceig_cholmod_free(void **handle)
{
    if (handle == NULL || *handle == NULL) return;
    destroy(*handle);
    *handle = NULL;
}

/*
 * Analyse and factorize. On success *handle owns the factor; on failure *handle is NULL.
 * info[0] = nnz(L) (fundamental, without supernodal padding), info[1] = flop count,
 * info[2] = ordering used (CHOLMOD_NATURAL, _GIVEN, _AMD, _METIS, ...),
 * info[3] = 0-based row/column of A where the factorization broke down (-1 if it did not),
 * info[4] = rcond estimate (min L_jj / max L_jj)^2, 0 if not available.
 */
/* Whether the last `keep_last` pivots of the analysed factor are, as a set, the last
 * `keep_last` entries of the caller's permutation. */
static int keeps_tail(const cholmod_factor *f, index_t n, const index_t *perm0,
                      index_t keep_last)
{
    const index_t *perm = (const index_t *)f->Perm;
    char *in_tail = calloc((size_t)n, 1);
    int ok = 1;
    if (in_tail == NULL) return 0;
    for (index_t k = n - keep_last; k < n; k++) in_tail[perm0[k]] = 1;
    for (index_t k = n - keep_last; k < n; k++) ok = ok && in_tail[perm[k]];
    free(in_tail);
    return ok;
}

int nceig_cholmod_factor(index_t n, const index_t *row_start0, const index_t *col0,
                         const double *val, int ordering, const index_t *perm0,
                         index_t keep_last, void **handle, double *info)
{
    for (int k = 0; k < 5; k++) info[k] = 0.0;
    info[3] = -1.0;
    *handle = NULL;
    if (n < 1 || ordering < NCEIG_ORDER_DEFAULT || ordering > NCEIG_ORDER_GIVEN)
        return NCEIG_CHOLMOD_INVALID;
    if (keep_last < 0 || keep_last > n) return NCEIG_CHOLMOD_INVALID;
    if (ordering == NCEIG_ORDER_GIVEN && (perm0 == NULL || !is_permutation(n, perm0)))
        return NCEIG_CHOLMOD_INVALID;

    nceig_cholmod_t *h = calloc(1, sizeof *h);
    if (h == NULL) return NCEIG_CHOLMOD_OUT_OF_MEMORY;
    h->n = n;
    cholmod_common *c = &h->common;
    if (!cholmod_l_start(c)) {
        free(h);
        return NCEIG_CHOLMOD_FAILED;
    }
    c->print = 0;                       /* library code does not print: codes travel up */
    c->supernodal = CHOLMOD_SUPERNODAL; /* LL' by construction: forward solves need L */
    c->final_ll = 1;
    c->quick_return_if_not_posdef = 1; /* a failed factor is discarded anyway */
    int method = cholmod_method(ordering);
    if (method >= 0) {
        c->nmethods = 1;
        c->method[0].ordering = method;
    } /* else nmethods = 0: AMD, then METIS if AMD's fill-in is high */

    /* A view of the caller's arrays: CHOLMOD reads A but never writes it. */
    cholmod_sparse a = {0};
    a.nrow = (size_t)n;
    a.ncol = (size_t)n;
    a.nzmax = (size_t)row_start0[n];
    a.p = (void *)row_start0;
    a.i = (void *)col0;
    a.x = (void *)val;
    a.stype = 1;
    a.itype = CHOLMOD_LONG;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;

    index_t *perm = ordering == NCEIG_ORDER_GIVEN ? (index_t *)perm0 : NULL;
    h->factor = cholmod_l_analyze_p(&a, perm, NULL, 0, c);
    if (h->factor != NULL && perm != NULL && keep_last > 0 &&
        !keeps_tail(h->factor, n, perm0, keep_last)) {
        /* CHOLMOD's etree postorder (about 20% faster factors at N = 512) moved some of the
         * last pivots forward, as it can when they hang off separate branches of the tree
         * (bisected meshes): the caller reads a trailing block, so keep its order as it is. */
        cholmod_l_free_factor(&h->factor, c);
        c->postorder = 0;
        h->factor = cholmod_l_analyze_p(&a, perm, NULL, 0, c);
    }
    if (h->factor == NULL) {
        int code = code_from_common(c);
        destroy(h);
        return code == NCEIG_CHOLMOD_OK ? NCEIG_CHOLMOD_FAILED : code;
    }
    info[0] = c->lnz;
    info[1] = c->fl;
    info[2] = (double)h->factor->ordering;

    int ok = cholmod_l_factorize(&a, h->factor, c);
    int code = ok ? code_from_common(c) : NCEIG_CHOLMOD_FAILED;
    if (code == NCEIG_CHOLMOD_OK && h->factor->minor < (size_t)n)
        code = NCEIG_CHOLMOD_NOT_POSDEF;
    if (code == NCEIG_CHOLMOD_NOT_POSDEF) {
        /* minor is a column of L, i.e. of P A P'; Perm maps it back to A. */
        size_t minor = h->factor->minor < (size_t)n ? h->factor->minor : (size_t)n - 1;
        info[3] = (double)((const index_t *)h->factor->Perm)[minor];
    }
    if (code == NCEIG_CHOLMOD_OK) {
        info[4] = cholmod_l_rcond(h->factor, c);
        if (info[4] < NCEIG_RCOND_SINGULAR) code = NCEIG_CHOLMOD_SINGULAR;
    }
    if (code != NCEIG_CHOLMOD_OK) {
        destroy(h);
        return code;
    }
    *handle = h;
    return NCEIG_CHOLMOD_OK;
}

/* Dense column-major n x nrhs view of caller memory, which CHOLMOD only reads. */
static cholmod_dense dense_view(index_t n, index_t nrhs, const double *b)
{
    cholmod_dense d = {0};
    d.nrow = (size_t)n;
    d.ncol = (size_t)nrhs;
    d.nzmax = (size_t)n * (size_t)nrhs;
    d.d = (size_t)n;
    d.x = (void *)b;
    d.xtype = CHOLMOD_REAL;
    d.dtype = CHOLMOD_DOUBLE;
    return d;
}

/* Copy a CHOLMOD result into caller memory and free it. */
static void copy_and_free(cholmod_dense **x, double *out, cholmod_common *c)
{
    const double *values = (*x)->x;
    size_t count = (*x)->nrow * (*x)->ncol;
    for (size_t k = 0; k < count; k++) out[k] = values[k];
    cholmod_l_free_dense(x, c);
}

/* X = S2 S1 B into caller memory for the CHOLMOD systems S1 = first and S2 = second
 * (second < 0: S1 alone), dense column-major n x nrhs B and X. */
static int solve_in_steps(void *handle, index_t nrhs, const double *b, double *x, int first,
                          int second)
{
    nceig_cholmod_t *h = handle;
    if (h == NULL) return NCEIG_CHOLMOD_NOT_FACTORED;
    if (nrhs < 1) return nrhs == 0 ? NCEIG_CHOLMOD_OK : NCEIG_CHOLMOD_INVALID;
    cholmod_dense bview = dense_view(h->n, nrhs, b);
    cholmod_dense *result = cholmod_l_solve(first, h->factor, &bview, &h->common);
    if (result != NULL && second >= 0) {
        cholmod_dense *step = result;
        result = cholmod_l_solve(second, h->factor, step, &h->common);
        cholmod_l_free_dense(&step, &h->common);
    }
    if (result == NULL) {
        int code = code_from_common(&h->common);
        return code == NCEIG_CHOLMOD_OK ? NCEIG_CHOLMOD_FAILED : code;
    }
    copy_and_free(&result, x, &h->common);
    return NCEIG_CHOLMOD_OK;
}

/* X = A^{-1} B for dense column-major n x nrhs B and X. */
int nceig_cholmod_solve(void *handle, index_t nrhs, const double *b, double *x)
{
    return solve_in_steps(handle, nrhs, b, x, CHOLMOD_A, -1);
}

/* W = L^{-1} P B, so that B1' A^{-1} B2 = W1' W2. */
int nceig_cholmod_forward(void *handle, index_t nrhs, const double *b, double *w)
{
    return solve_in_steps(handle, nrhs, b, w, CHOLMOD_P, CHOLMOD_L);
}

/* X = P' L^{-T} W: the second half of a solve, for a W = L^{-1} P B known otherwise (e.g.
 * B supported on unknowns ordered last, where W is zero but for a small trailing part). */
int nceig_cholmod_backward(void *handle, index_t nrhs, const double *w, double *x)
{
    return solve_in_steps(handle, nrhs, w, x, CHOLMOD_Lt, CHOLMOD_Pt);
}

/*
 * The last m rows and columns of L (P A P' = L L'), as a dense column-major m x m lower
 * triangle in out (upper part zeroed), and perm_tail[k] = the 0-based row of A that is pivot
 * n - m + k. When the caller ordered a set of m unknowns last, L_tail L_tail' is the Schur
 * complement of A onto them and (A^{-1}) on that set is L_tail^{-T} L_tail^{-1}: the whole
 * inverse restricted to the set without touching the rest of L.
 */
int nceig_cholmod_trailing(void *handle, index_t m, double *out, index_t *perm_tail)
{
    nceig_cholmod_t *h = handle;
    if (h == NULL) return NCEIG_CHOLMOD_NOT_FACTORED;
    if (m < 1 || m > h->n) return NCEIG_CHOLMOD_INVALID;
    const cholmod_factor *f = h->factor;
    if (!f->is_super || !f->is_ll) return NCEIG_CHOLMOD_FAILED;
    const index_t n = h->n, first = n - m;
    const index_t *super = f->super, *pi = f->pi, *px = f->px, *s = f->s, *perm = f->Perm;
    const double *x = f->x;
    for (size_t k = 0; k < (size_t)m * (size_t)m; k++) out[k] = 0.0;
    for (index_t k = 0; k < m; k++) perm_tail[k] = perm[first + k];
    for (size_t sn = 0; sn < f->nsuper; sn++) {
        index_t k1 = super[sn], k2 = super[sn + 1];
        if (k2 <= first) continue;
        index_t nsrow = pi[sn + 1] - pi[sn];
        const index_t *rows = s + pi[sn];
        for (index_t j = k1 > first ? k1 : first; j < k2; j++) {
            const double *column = x + px[sn] + (size_t)(j - k1) * (size_t)nsrow;
            /* rows of column j: the diagonal block rows k1..k2-1, then the pattern below */
            for (index_t i = j - k1; i < nsrow; i++)
                out[(size_t)(j - first) * (size_t)m + (size_t)(rows[i] - first)] = column[i];
        }
    }
    return NCEIG_CHOLMOD_OK;
}
