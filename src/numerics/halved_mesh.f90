! SPDX-License-Identifier: MIT
!> The problem on the mesh of halved cells, whose space holds the given one's: the
!> difference of a value there is the estimate of an element with no degree above it (Q1,
!> Q2, P4), and a second, independent estimate beside the enriched one where that one can
!> cancel (collision points on coarse meshes). The rectangle with 2 nx x 2 ny cells, or a
!> Gmsh triangle mesh (P1 to P3) whose every cell is bisected twice (newest vertex: nested,
!> h / 2, parts and the contact segment carried to the children).
module halved_mesh
    use status, only: status_t
    use scene, only: scene_t, MESH_RECTANGLE
    use mesh, only: mesh_t
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use element_types, only: element_name
    use problem, only: problem_t, build_problem
    use enrichment, only: enriched_element
    implicit none
    private
    public :: build_halved_problem

contains

    !> `fine`, the problem of the scene `scn` on the mesh of `prob` with every cell halved,
    !> and `halved`, its scene (scene_halved: the one to halve again). `why_not` says why
    !> there is none ('' when built; a failure to build is stat's).
    subroutine build_halved_problem(scn, prob, halved, fine, why_not, stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(scene_t), intent(out) :: halved
        type(problem_t), intent(out) :: fine
        character(len=:), allocatable, intent(out) :: why_not
        type(status_t), intent(out) :: stat
        type(refinable_mesh_t) :: tree
        type(mesh_t) :: refined
        integer :: i, pass

        why_not = ''
        halved = scn%halved()
        if (scn%source == MESH_RECTANGLE) then
            call build_problem(halved, fine, stat)
        else if (enriched_element(prob%mesh%element) /= 0) then   ! triangles P1 to P3
            call build_refinable_mesh(prob%mesh, tree, stat)
            do pass = 1, 2
                if (stat%ok()) call tree%refine([(i, i=1, tree%n_cells())], stat)
            end do
            if (stat%ok()) call tree%to_mesh(prob%mesh%element, refined, stat)
            if (stat%ok()) call build_problem(halved, fine, stat, given_mesh=refined)
        else
            why_not = element_name(prob%mesh%element)//' cells of a Gmsh mesh are not halved here'
        end if
    end subroutine build_halved_problem
end module halved_mesh
