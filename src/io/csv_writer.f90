! SPDX-License-Identifier: MIT
!> Writing a CSV file line by line: the header, then one line per row, each already joined
!> by the caller. The first failure (open, write, close) is kept and reported once at close,
!> so a writer loop needs no error test per line and no failure goes unnoticed.
module csv_writer
    use status, only: status_t, STATUS_IO
    use filesystem, only: end_output
    implicit none
    private

    integer, parameter :: MSG_LEN = 512

    type, public :: csv_writer_t
        private
        integer :: unit = -1
        integer :: ios = 0
        character(len=MSG_LEN) :: msg = ''
        character(len=:), allocatable :: path
    contains
        procedure :: open => csv_writer_open
        procedure :: row => csv_writer_row
        procedure :: close => csv_writer_close
    end type csv_writer_t

contains

    !> Create (or replace) `path` and write `header` as its first line.
    subroutine csv_writer_open(this, path, header)
        class(csv_writer_t), intent(inout) :: this
        character(len=*), intent(in) :: path, header
        this%path = path
        this%ios = 0
        open (newunit=this%unit, file=path, status='replace', action='write', &
              iostat=this%ios, iomsg=this%msg)
        if (this%ios /= 0) then
            this%unit = -1
            return
        end if
        call this%row(header)
    end subroutine csv_writer_open

    !> One line; nothing after the first failure.
    subroutine csv_writer_row(this, line)
        class(csv_writer_t), intent(inout) :: this
        character(len=*), intent(in) :: line
        if (this%ios /= 0) return
        write (this%unit, '(a)', iostat=this%ios, iomsg=this%msg) line
    end subroutine csv_writer_row

    !> Close the file; `stat` names the file and the first failure, if any.
    subroutine csv_writer_close(this, stat)
        class(csv_writer_t), intent(inout) :: this
        type(status_t), intent(out) :: stat
        if (this%unit /= -1) then
            ! checks that the whole file reached the disk: see close_output
            call end_output(this%unit, this%path, this%ios, this%msg)
            this%unit = -1
        end if
        if (this%ios /= 0) call stat%fail(STATUS_IO, this%path//': cannot write: '// &
                                          trim(this%msg))
    end subroutine csv_writer_close
end module csv_writer
