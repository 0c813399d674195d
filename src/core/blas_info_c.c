/* SPDX-License-Identifier: MIT */
/* Which BLAS the process runs on: the library that provides dgemm_ (found by dladdr, so a
 * Debian alternative or an LD_PRELOAD is seen as it really resolves), OpenBLAS's own
 * configuration string and thread count when that library is OpenBLAS. The reference BLAS
 * makes the factorization about 5x slower, so a run says which one it had. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <string.h>

static void copy_text(char *to, int capacity, const char *from)
{
    size_t n;
    if (capacity <= 0)
        return;
    n = from ? strlen(from) : 0;
    if (n >= (size_t)capacity)
        n = (size_t)capacity - 1;
    if (n > 0)
        memcpy(to, from, n);
    to[n] = '\0';
}

/* library: path of the object that defines dgemm_ ("" if unknown); config: OpenBLAS's
 * configuration ("" for another BLAS); *threads: OpenBLAS's thread count, else 1. */
void nceig_blas_info(char *library, int library_capacity, char *config, int config_capacity,
                     int *threads)
{
    Dl_info info;
    void *dgemm = dlsym(RTLD_DEFAULT, "dgemm_");
    char *(*get_config)(void) = (char *(*)(void))dlsym(RTLD_DEFAULT, "openblas_get_config");
    int (*get_threads)(void) = (int (*)(void))dlsym(RTLD_DEFAULT, "openblas_get_num_threads");

    copy_text(library, library_capacity, "");
    if (dgemm && dladdr(dgemm, &info) && info.dli_fname)
        copy_text(library, library_capacity, info.dli_fname);
    copy_text(config, config_capacity, get_config ? get_config() : "");
    *threads = get_threads ? get_threads() : 1;
}
