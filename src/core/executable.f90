! SPDX-License-Identifier: MIT
!> Where the running program lives, and where its helper scripts are: next to an installed
!> nceig in <prefix>/share/nceig/scripts, else in the source tree it was built from.
module executable
    use iso_c_binding, only: c_char, c_int
    use version, only: NCEIG_SCRIPTS_DIR
    use strings, only: from_c_chars
    implicit none
    private
    public :: executable_path, scripts_directory

    integer, parameter :: PATH_CAPACITY = 4096
    !> The installed layout, relative to the folder of the executable (<prefix>/bin).
    character(len=*), parameter :: INSTALLED_SCRIPTS = '/../share/nceig/scripts'

    interface
        function nceig_executable_path(path, capacity) result(length) &
                bind(C, name='nceig_executable_path')
            import :: c_char, c_int
            character(kind=c_char), intent(out) :: path(*)
            integer(c_int), value :: capacity
            integer(c_int) :: length
        end function nceig_executable_path
    end interface

contains

    !> Absolute path of the running executable ('' where /proc is not mounted).
    function executable_path() result(path)
        character(len=:), allocatable :: path
        character(kind=c_char) :: buffer(PATH_CAPACITY)
        path = from_c_chars(buffer, nceig_executable_path(buffer, PATH_CAPACITY))
    end function executable_path

    !> The folder of the helper scripts: the installed one when the executable sits in an
    !> installed prefix, else the source tree's scripts/ folder.
    function scripts_directory() result(directory)
        character(len=:), allocatable :: directory
        character(len=:), allocatable :: exe
        logical :: installed
        exe = executable_path()
        directory = NCEIG_SCRIPTS_DIR
        if (index(exe, '/', back=.true.) == 0) return
        directory = exe(:index(exe, '/', back=.true.) - 1)//INSTALLED_SCRIPTS
        inquire (file=directory//'/plot_lambda_sweep.sh', exist=installed)
        if (.not. installed) directory = NCEIG_SCRIPTS_DIR
    end function scripts_directory
end module executable
