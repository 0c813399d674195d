! SPDX-License-Identifier: MIT
!> What an adaptive run writes besides the files of its last level's spectrum: adapt.csv (one
!> row per level: of the lowest positive mu on h or hp levels, or of the critical lambdas),
!> mesh.msh (the final mesh, which any analysis reads back) and, from hp levels,
!> degrees.csv (its cell degrees). Values in the input's units (reported_units).
module adapt_files
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string
    use real_format, only: real_to_text, known_text
    use problem, only: problem_t
    use hp_space, only: hp_space_t
    use eigen_goal, only: eigen_level_t
    use threshold_goal, only: threshold_level_t
    use critical_lambda, only: SIDE_PLUS, SIDE_MINUS
    use output_stage, only: output_stage_t
    use csv_writer, only: csv_writer_t
    use gmsh_writer, only: write_gmsh
    implicit none
    private
    public :: write_adapted_mesh, write_adapt_csv, write_hp_adapt_csv, write_degrees, &
              write_threshold_adapt_csv

    character(len=*), parameter, public :: MESH_FILE = 'mesh.msh'
    character(len=*), parameter, public :: DEGREES_FILE = 'degrees.csv'
    character(len=*), parameter, public :: ADAPT_HEADER = &
        'level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s,error_bar'
    character(len=*), parameter, public :: HP_ADAPT_HEADER = &
        'level,layers,p_min,p_max,n_dofs,n_contact,n_cells,mu,error_bar,roundoff,time_s'
    character(len=*), parameter, public :: THRESHOLD_ADAPT_HEADER = 'level,n_dofs,'// &
        'n_contact,n_cells,lambda_plus,error_estimate_plus,lambda_minus,'// &
        'error_estimate_minus,time_s,error_bar_plus,error_bar_minus,collision_plus,'// &
        'error_estimate_collision_plus,error_bar_collision_plus,collision_minus,'// &
        'error_estimate_collision_minus,error_bar_collision_minus'
    !> the columns adapt.csv of hp levels adds to the thresholds' h columns
    character(len=*), parameter, public :: HP_THRESHOLD_COLUMNS = ',layers,p_min,p_max'

contains

    !> mesh.msh: the final mesh of an adaptive run, for &mesh source = 'gmsh'.
    subroutine write_adapted_mesh(stage, prob, stat)
        type(output_stage_t), intent(inout) :: stage
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        call stage%add(MESH_FILE, path)
        call write_gmsh(path, prob%mesh, stat)
    end subroutine write_adapted_mesh

    !> level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s,error_bar (the bar is last so
    !> that the columns before it keep their places); mu, error_estimate and error_bar empty
    !> where there is no positive mu or no estimate.
    subroutine write_adapt_csv(path, levels, stat)
        character(len=*), intent(in) :: path
        type(eigen_level_t), intent(in) :: levels(:)
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: i

        call csv%open(path, ADAPT_HEADER)
        do i = 1, size(levels)
            associate (row => levels(i))
                call csv%row(to_string(row%level)//','//to_string(row%n_dofs)//','// &
                    to_string(row%n_contact)//','//to_string(row%n_cells)//','// &
                    known_text(row%has_mu, row%mu)//','// &
                    known_text(row%estimated, row%error_estimate)//','// &
                    real_to_text(row%time_s)//','//known_text(row%error_bar >= 0.0_wp, &
                                                              row%error_bar))
            end associate
        end do
        call csv%close(stat)
    end subroutine write_adapt_csv

    !> adapt.csv of an hp run (HP_ADAPT_HEADER); mu, error_bar and roundoff empty where
    !> there is none.
    subroutine write_hp_adapt_csv(path, levels, stat)
        character(len=*), intent(in) :: path
        type(eigen_level_t), intent(in) :: levels(:)
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: i
        call csv%open(path, HP_ADAPT_HEADER)
        do i = 1, size(levels)
            associate (row => levels(i))
                call csv%row(to_string(row%level)//','//to_string(row%layers)//','// &
                    to_string(row%p_min)//','//to_string(row%p_max)//','// &
                    to_string(row%n_dofs)//','//to_string(row%n_contact)//','// &
                    to_string(row%n_cells)//','//known_text(row%has_mu, row%mu)//','// &
                    known_text(row%error_bar >= 0.0_wp, row%error_bar)//','// &
                    known_text(row%roundoff >= 0.0_wp, row%roundoff)//','// &
                    real_to_text(row%time_s))
            end associate
        end do
        call csv%close(stat)
    end subroutine write_hp_adapt_csv

    !> degrees.csv: cell,degree for the cells of mesh.msh, in its order.
    subroutine write_degrees(path, space, stat)
        character(len=*), intent(in) :: path
        type(hp_space_t), intent(in) :: space
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: c
        call csv%open(path, 'cell,degree')
        do c = 1, size(space%cell_degree)
            call csv%row(to_string(c)//','//to_string(space%cell_degree(c)))
        end do
        call csv%close(stat)
    end subroutine write_degrees

    !> level,n_dofs,n_contact,n_cells,lambda_plus,error_estimate_plus,lambda_minus,
    !> error_estimate_minus,time_s,error_bar_plus,error_bar_minus, then per side the collision
    !> onset, its estimate and bar; a side's cells empty where it has no threshold (collision
    !> onset) or no estimate.
    !> With `hp`, the columns layers, p_min, p_max follow.
    subroutine write_threshold_adapt_csv(path, levels, hp, stat)
        character(len=*), intent(in) :: path
        type(threshold_level_t), intent(in) :: levels(:)
        logical, intent(in) :: hp
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        character(len=:), allocatable :: line
        integer :: i, side

        if (hp) then
            call csv%open(path, THRESHOLD_ADAPT_HEADER//HP_THRESHOLD_COLUMNS)
        else
            call csv%open(path, THRESHOLD_ADAPT_HEADER)
        end if
        do i = 1, size(levels)
            associate (row => levels(i))
                line = to_string(row%level)//','//to_string(row%n_dofs)//','// &
                    to_string(row%n_contact)//','//to_string(row%n_cells)
                do side = SIDE_PLUS, SIDE_MINUS
                    line = line//','
                    if (row%found(side)) line = line//real_to_text(row%lambda(side))
                    line = line//','
                    if (row%estimated(side)) line = line//real_to_text(row%error_estimate(side))
                end do
                line = line//','//real_to_text(row%time_s)
                do side = SIDE_PLUS, SIDE_MINUS
                    line = line//','
                    if (row%error_bar(side) >= 0.0_wp) line = line// &
                        real_to_text(row%error_bar(side))
                end do
                ! a side whose onset is a collision of two real mu: its lambda, estimate, bar
                do side = SIDE_PLUS, SIDE_MINUS
                    line = line//','
                    if (row%collision(side)) line = line//real_to_text(row%collision_lambda(side))
                    line = line//','
                    if (row%collision_estimate(side) >= 0.0_wp) line = line// &
                        real_to_text(row%collision_estimate(side))
                    line = line//','
                    if (row%collision_bar(side) >= 0.0_wp) line = line// &
                        real_to_text(row%collision_bar(side))
                end do
                if (hp) line = line//','//to_string(row%layers)//','// &
                    to_string(row%p_min)//','//to_string(row%p_max)
                call csv%row(line)
            end associate
        end do
        call csv%close(stat)
    end subroutine write_threshold_adapt_csv
end module adapt_files
