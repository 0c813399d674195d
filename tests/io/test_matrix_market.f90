! SPDX-License-Identifier: MIT
!> matrix_market: a write/read round trip is exact, hand-written files with comments,
!> duplicates and a symmetric header read as specified, and failures name the path.
program test_matrix_market
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_IO, STATUS_BAD_INPUT
    use csr_matrix, only: csr_matrix_t
    use matrix_market, only: write_matrix_market, read_matrix_market
    use testing, only: test_suite_t
    implicit none

    character(len=*), parameter :: ROUND_TRIP = 'test_matrix_market_round_trip.mtx'
    character(len=*), parameter :: HAND_WRITTEN = 'test_matrix_market_hand_written.mtx'
    character(len=*), parameter :: MISSING_DIR = 'no_such_directory/K.mtx'
    type(test_suite_t) :: t
    type(csr_matrix_t) :: a, back, expected
    type(status_t) :: stat
    integer :: unit

    t%name = 'test_matrix_market'

    ! Values chosen to need all 17 significant digits, the extremes of the exponent range
    ! (three exponent digits), a subnormal, a negative zero and an integer.
    a%row_start = [1, 3, 3, 7, 9]
    a%col = [1, 4, 1, 2, 3, 4, 2, 4]
    a%val = [1.0_wp/3.0_wp, -huge(1.0_wp), tiny(1.0_wp), -2.0_wp/7.0_wp*1.0e-300_wp, &
             tiny(1.0_wp)*epsilon(1.0_wp), -0.0_wp, 12345.0_wp, acos(-1.0_wp)*1.0e300_wp]
    call write_matrix_market(ROUND_TRIP, a, stat)
    call t%check('write succeeds', stat%ok())
    call read_matrix_market(ROUND_TRIP, back, stat)
    call t%check('read back succeeds', stat%ok())
    ! es24.16 writes 17 significant digits, which identify every double uniquely, and
    ! the reader rounds correctly: the bits must come back unchanged, sign of zero included.
    call t%check('round trip keeps row starts and columns', same_pattern(back, a))
    call t%check('round trip keeps every value to the bit', same_bits(back%val, a%val))

    ! Comments, blank lines, upper case, unsorted entries and a duplicate (3, 1) that sums.
    open (newunit=unit, file=HAND_WRITTEN, status='replace', action='write')
    write (unit, '(a)') '%%MatrixMarket MATRIX Coordinate Real General', &
        '% written by hand', '', '3 3 5', '3 1 1.5', '1 2 -2', '3 3 4', '3 1 0.25', '1 1 1'
    close (unit)
    expected%row_start = [1, 3, 3, 5]
    expected%col = [1, 2, 1, 3]
    expected%val = [1.0_wp, -2.0_wp, 1.75_wp, 4.0_wp]   ! 1.5 + 0.25 is exact
    call read_matrix_market(HAND_WRITTEN, back, stat)
    call t%check('a hand-written general file reads', stat%ok())
    call t%check('its rows are sorted, duplicates summed', same_pattern(back, expected) .and. &
                 same_bits(back%val, expected%val))

    ! A symmetric file stores one triangle; the reader mirrors the off-diagonal entries.
    open (newunit=unit, file=HAND_WRITTEN, status='replace', action='write')
    write (unit, '(a)') '%%MatrixMarket matrix coordinate real symmetric', '2 2 2', &
        '1 1 2', '2 1 -1'
    close (unit)
    expected%row_start = [1, 3, 5]
    expected%col = [1, 2, 1, 2]
    expected%val = [2.0_wp, -1.0_wp, -1.0_wp, 0.0_wp]
    call read_matrix_market(HAND_WRITTEN, back, stat)
    call t%check('a symmetric file reads', stat%ok())
    call t%check('it is mirrored', all(back%row_start == [1, 3, 4]) .and. &
                 all(back%col == [1, 2, 1]) .and. same_bits(back%val, expected%val(1:3)))

    ! --- failures ---
    call write_matrix_market(MISSING_DIR, a, stat)
    call t%check('writing into a missing directory is STATUS_IO', stat%code == STATUS_IO)
    if (allocated(stat%message)) call t%check('the write message names the path', &
                                              index(stat%message, MISSING_DIR) > 0)
    call read_matrix_market(MISSING_DIR, back, stat)
    call t%check('reading a missing file is STATUS_IO', stat%code == STATUS_IO)
    if (allocated(stat%message)) call t%check('the read message names the path', &
                                              index(stat%message, MISSING_DIR) > 0)

    open (newunit=unit, file=HAND_WRITTEN, status='replace', action='write')
    write (unit, '(a)') '%%MatrixMarket matrix array real general', '2 2', '1', '2', '3', '4'
    close (unit)
    call read_matrix_market(HAND_WRITTEN, back, stat)
    call t%check('an array (dense) file is bad input', stat%code == STATUS_BAD_INPUT)

    open (newunit=unit, file=HAND_WRITTEN, status='replace', action='write')
    write (unit, '(a)') '%%MatrixMarket matrix coordinate real general', '2 2 3', '1 1 1', &
        '2 3 1'
    close (unit)
    call read_matrix_market(HAND_WRITTEN, back, stat)
    call t%check('an entry outside the matrix is bad input', stat%code == STATUS_BAD_INPUT)

    open (newunit=unit, file=HAND_WRITTEN, status='replace', action='write')
    write (unit, '(a)') '%%MatrixMarket matrix coordinate real general', '2 2 3', '1 1 1'
    close (unit)
    call read_matrix_market(HAND_WRITTEN, back, stat)
    call t%check('a file with fewer entries than announced is bad input', &
                 stat%code == STATUS_BAD_INPUT)
    call t%report()

contains

    logical function same_pattern(a, b)
        type(csr_matrix_t), intent(in) :: a, b
        same_pattern = size(a%row_start) == size(b%row_start) .and. size(a%col) == size(b%col)
        if (same_pattern) same_pattern = all(a%row_start == b%row_start) .and. &
                                         all(a%col == b%col)
    end function same_pattern

    logical function same_bits(x, y)
        real(wp), intent(in) :: x(:), y(:)
        same_bits = size(x) == size(y)
        if (same_bits) same_bits = all(transfer(x, [0_i8]) == transfer(y, [0_i8]))
    end function same_bits
end program test_matrix_market
