! SPDX-License-Identifier: MIT
!> The spectrum record: the output order of docs/outputs.md (positive real ascending,
!> negative real by modulus, complex by modulus with the positive imaginary part first),
!> the relative backward error in closed form on a diagonal pencil (0 at an eigenpair,
!> ||r|| / ((||K|| + |mu| ||B||) ||phi||) elsewhere), and the normalisation of a mode.
program test_spectrum
    use kinds, only: wp
    use csr_matrix, only: csr_matrix_t
    use spectrum, only: spectrum_t, kind_name, order_eigenvalues, backward_error, &
                        normalise_mode, KIND_POSITIVE, KIND_NEGATIVE, KIND_COMPLEX
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    type(csr_matrix_t) :: k, b
    type(spectrum_t) :: spec, empty
    complex(wp) :: mu(8), phi(3)
    logical :: is_real(8)
    integer :: order(8), kinds(8)

    t%name = 'test_spectrum'
    call t%check('kind_name', kind_name(KIND_POSITIVE) == 'positive' .and. &
                 kind_name(KIND_NEGATIVE) == 'negative' .and. kind_name(KIND_COMPLEX) == &
                 'complex')

    mu = [(3.0_wp, 0.0_wp), (-1.0_wp, 0.0_wp), (1.0_wp, -3.0_wp), (2.0_wp, -1.0_wp), &
          (0.5_wp, 0.0_wp), (-4.0_wp, 0.0_wp), (2.0_wp, 1.0_wp), (1.0_wp, 3.0_wp)]
    is_real = abs(aimag(mu)) <= 0.0_wp
    call order_eigenvalues(mu, is_real, order, kinds)
    call t%check('order_eigenvalues: 0.5, 3; -1, -4; 2+i, 2-i, 1+3i, 1-3i', &
                 all(order == [5, 1, 2, 6, 7, 4, 8, 3]))
    call t%check('order_eigenvalues: their kinds', all(kinds == [KIND_POSITIVE, &
                 KIND_POSITIVE, KIND_NEGATIVE, KIND_NEGATIVE, KIND_COMPLEX, KIND_COMPLEX, &
                 KIND_COMPLEX, KIND_COMPLEX]))

    ! K = diag(1, 2, 3), B = I
    k%row_start = [1, 2, 3, 4]
    k%col = [1, 2, 3]
    k%val = [1.0_wp, 2.0_wp, 3.0_wp]
    b%row_start = [1, 2, 3, 4]
    b%col = [1, 2, 3]
    b%val = [1.0_wp, 1.0_wp, 1.0_wp]
    phi = [(0.0_wp, 0.0_wp), (1.0_wp, 1.0_wp), (0.0_wp, 0.0_wp)]
    call t%check('backward_error: 0 at an eigenpair, a complex vector too', &
                 backward_error(k, b, (2.0_wp, 0.0_wp), phi) <= 0.0_wp)
    phi = [(1.0_wp, 0.0_wp), (0.0_wp, 0.0_wp), (0.0_wp, 0.0_wp)]
    ! K e1 - 2 e1 = -e1: 1 / ((3 + 2) 1)
    call t%check_close('backward_error: 1/5 for mu = 2 on e1', &
                       backward_error(k, b, (2.0_wp, 0.0_wp), phi), 0.2_wp, 1.0e-15_wp)
    ! K e1 - i e1 = (1 - i) e1: sqrt(2) / ((3 + 1) 1), and the norms passed in
    call t%check_close('backward_error: sqrt(2)/4 for mu = i on e1, norms given', &
                       backward_error(k, b, (0.0_wp, 1.0_wp), phi, 3.0_wp, 1.0_wp), &
                       sqrt(2.0_wp)/4.0_wp, 1.0e-15_wp)

    phi = [(1.0_wp, 0.0_wp), (0.0_wp, -4.0_wp), (2.0_wp, 0.0_wp)]
    call normalise_mode(phi)
    call t%check('normalise_mode: the largest entry becomes 1', &
                 abs(phi(2) - (1.0_wp, 0.0_wp)) <= 0.0_wp .and. &
                 abs(phi(1) - (0.0_wp, 0.25_wp)) <= 0.0_wp)
    phi = (0.0_wp, 0.0_wp)
    call normalise_mode(phi)
    call t%check('normalise_mode: a zero vector stays zero', all(abs(phi) <= 0.0_wp))

    spec%mu = mu(order)
    spec%kind = kinds
    spec%residual = [1.0e-16_wp, 3.0e-15_wp, 0.0_wp, 2.0e-16_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                     0.0_wp]
    call t%check('spectrum_t: n, the lowest positive first, the largest residual', &
                 spec%n() == 8 .and. spec%lowest_positive() == 1 .and. &
                 abs(spec%max_residual() - 3.0e-15_wp) <= 0.0_wp)
    spec%kind(1) = KIND_NEGATIVE
    call t%check('spectrum_t: no positive eigenvalue first, none lowest', &
                 spec%lowest_positive() == 0)
    call t%check('spectrum_t: an empty one', empty%n() == 0 .and. &
                 empty%lowest_positive() == 0 .and. empty%max_residual() <= 0.0_wp)
    call t%report()
end program test_spectrum
