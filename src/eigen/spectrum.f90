! SPDX-License-Identifier: MIT
!> The computed eigenvalues mu of K phi = mu B phi, whatever solver found them: their kind,
!> backward errors and condition numbers, in the output order of docs/outputs.md (positive
!> real ascending, negative real by modulus, complex by modulus), and the full eigenvectors
!> of the first few.
module spectrum
    use kinds, only: wp
    use csr_matrix, only: csr_matrix_t
    implicit none
    private
    public :: spectrum_t, kind_name, order_eigenvalues, backward_error, normalise_mode
    public :: KIND_POSITIVE, KIND_NEGATIVE, KIND_COMPLEX

    integer, parameter :: KIND_POSITIVE = 1
    integer, parameter :: KIND_NEGATIVE = 2
    integer, parameter :: KIND_COMPLEX = 3

    type, public :: spectrum_t
        !> (n_ev) in output order, in the units of the matrices solved (problem_t%units: the
        !> scaled ones of the eigen analyses; the report converts)
        complex(wp), allocatable :: mu(:)
        integer, allocatable :: kind(:)            !! KIND_* of each
        real(wp), allocatable :: residual(:)       !! relative backward error on (K, B)
        real(wp), allocatable :: condition(:)      !! relative condition number; < 0: unknown
        !> |d mu/d lambda| |lambda| / |mu|: relative change of mu per relative change of
        !> lambda; about |lambda / (lambda - lambda_c)| near a critical lambda_c. < 0: unknown
        !> (the dense solver fills it for the lowest positive and the largest real |mu|).
        real(wp), allocatable :: lambda_sensitivity(:)
        !> Of the lowest positive mu only, < 0 elsewhere and when unknown: the bound of its
        !> relative round-off error (module roundoff), whatever the solver.
        real(wp), allocatable :: roundoff(:)
        real(wp) :: roundoff_seconds = 0.0_wp      !! time spent on it (left eigenvector, bound, hp quotient)
        !> the left eigenvector of the lowest positive mu on the free dofs (K' y = mu B' y),
        !> kept with the bound (hp_rayleigh refines mu from it); unallocated when unknown
        real(wp), allocatable :: left(:)
        complex(wp), allocatable :: vectors(:, :)  !! (n_free, n_kept) modes of the first n_kept
        integer :: n_operator = 0                  !! operator applications (iterative solvers)
        !> the iterative solver could not certify its answer and all p eigenvalues of the
        !> reduced matrix decided it (always true of the dense solver)
        logical :: dense_decision = .false.
    contains
        procedure :: n => spectrum_n
        procedure :: lowest_positive => spectrum_lowest_positive
        procedure :: max_residual => spectrum_max_residual
    end type spectrum_t

contains

    pure integer function spectrum_n(this)
        class(spectrum_t), intent(in) :: this
        spectrum_n = 0
        if (allocated(this%mu)) spectrum_n = size(this%mu)
    end function spectrum_n

    !> Index of the lowest positive real eigenvalue (the output order puts it first), or 0.
    pure integer function spectrum_lowest_positive(this)
        class(spectrum_t), intent(in) :: this
        spectrum_lowest_positive = 0
        if (this%n() == 0) return
        if (this%kind(1) == KIND_POSITIVE) spectrum_lowest_positive = 1
    end function spectrum_lowest_positive

    pure real(wp) function spectrum_max_residual(this)
        class(spectrum_t), intent(in) :: this
        spectrum_max_residual = 0.0_wp
        if (this%n() > 0) spectrum_max_residual = maxval(this%residual)
    end function spectrum_max_residual

    pure function kind_name(kind) result(name)
        integer, intent(in) :: kind
        character(len=:), allocatable :: name
        select case (kind)
        case (KIND_POSITIVE); name = 'positive'
        case (KIND_NEGATIVE); name = 'negative'
        case default; name = 'complex'
        end select
    end function kind_name

    !> Permutation putting eigenvalues in output order; `is_real` says which are real (the
    !> solver decides: LAPACK returns exact zero imaginary parts for real eigenvalues).
    !> A conjugate pair stays together, positive imaginary part first.
    pure subroutine order_eigenvalues(mu, is_real, order, kinds)
        complex(wp), intent(in) :: mu(:)
        logical, intent(in) :: is_real(:)
        integer, intent(out) :: order(:), kinds(:)
        real(wp) :: key(size(mu))
        integer :: i, j, pick, k(size(mu))
        do i = 1, size(mu)
            if (.not. is_real(i)) then
                k(i) = KIND_COMPLEX
                ! modulus, then the member with positive imaginary part first
                key(i) = abs(mu(i)) + merge(0.0_wp, spacing(abs(mu(i))), aimag(mu(i)) > 0.0_wp)
            else if (real(mu(i), wp) > 0.0_wp) then
                k(i) = KIND_POSITIVE
                key(i) = real(mu(i), wp)
            else
                k(i) = KIND_NEGATIVE
                key(i) = abs(real(mu(i), wp))
            end if
        end do
        order = [(i, i=1, size(mu))]
        ! selection sort on (kind, key): n_ev is at most a few thousand, done once
        do i = 1, size(mu)
            pick = i
            do j = i + 1, size(mu)
                if (k(order(j)) < k(order(pick)) .or. (k(order(j)) == k(order(pick)) .and. &
                    key(order(j)) < key(order(pick)))) pick = j
            end do
            if (pick /= i) order([i, pick]) = order([pick, i])
        end do
        kinds = k(order)
    end subroutine order_eigenvalues

    !> Relative backward error ||K phi - mu B phi|| / ((||K|| + |mu| ||B||) ||phi||) in the
    !> infinity norm (a subordinate norm, so the formula is exact for that norm). A caller
    !> looping over many pairs passes ||K|| and ||B|| once (each is a pass over the matrix).
    function backward_error(k, b, mu, phi, k_norm, b_norm) result(eta)
        type(csr_matrix_t), intent(in) :: k, b
        complex(wp), intent(in) :: mu, phi(:)
        real(wp), intent(in), optional :: k_norm, b_norm   !! k%norm_inf(), b%norm_inf()
        real(wp) :: eta
        real(wp), allocatable :: k_re(:), k_im(:), b_re(:), b_im(:)
        real(wp) :: r_norm, norm_of_k, norm_of_b
        allocate (k_re(size(phi)), k_im(size(phi)), b_re(size(phi)), b_im(size(phi)))
        call k%matvec(real(phi, wp), k_re)
        call b%matvec(real(phi, wp), b_re)
        ! a real mode (the common case) needs no products with its zero imaginary part:
        ! on meshes of millions of dofs each product with K costs as much as the rest
        if (any(abs(aimag(phi)) > 0.0_wp)) then
            call k%matvec(aimag(phi), k_im)
            call b%matvec(aimag(phi), b_im)
        else
            k_im = 0.0_wp
            b_im = 0.0_wp
        end if
        ! K phi - mu B phi in real arithmetic: complex abs() calls hypot per entry, which
        ! took as long as the product with K
        k_re = k_re - (real(mu, wp)*b_re - aimag(mu)*b_im)
        k_im = k_im - (real(mu, wp)*b_im + aimag(mu)*b_re)
        r_norm = max_modulus(k_re, k_im)
        if (present(k_norm)) then
            norm_of_k = k_norm
        else
            norm_of_k = k%norm_inf()
        end if
        if (present(b_norm)) then
            norm_of_b = b_norm
        else
            norm_of_b = b%norm_inf()
        end if
        eta = r_norm/((norm_of_k + abs(mu)*norm_of_b)*max_modulus(real(phi, wp), aimag(phi)))
    end function backward_error

    !> max_i |re_i + i im_i| without a hypot per entry; scaled so that squares neither
    !> overflow nor underflow to zero.
    pure real(wp) function max_modulus(re, im)
        real(wp), intent(in) :: re(:), im(:)
        real(wp) :: scale
        scale = max(maxval(abs(re)), maxval(abs(im)))
        max_modulus = 0.0_wp
        if (.not. scale > 0.0_wp) return
        if (.not. any(abs(im) > 0.0_wp)) then
            max_modulus = scale
        else
            max_modulus = scale*sqrt(maxval((re/scale)**2 + (im/scale)**2))
        end if
    end function max_modulus

    !> Scale a mode so that its largest entry is 1 (real): the real part then carries the
    !> shape a user expects to see in ParaView, and runs are comparable.
    pure subroutine normalise_mode(phi)
        complex(wp), intent(inout) :: phi(:)
        integer :: i
        i = maxloc(abs(phi), dim=1)
        if (abs(phi(i)) > 0.0_wp) phi = phi/phi(i)
    end subroutine normalise_mode
end module spectrum
