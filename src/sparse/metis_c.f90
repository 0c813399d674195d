! SPDX-License-Identifier: MIT
!> The one binding of METIS_NodeND (nested-dissection ordering of a graph), typed like
!> metis.h, its return codes and a sentence for each. The node renumbering of a mesh and
!> the fill-reducing dof ordering both call it through this module. No logic beyond the
!> messages.
module metis_c
    use, intrinsic :: iso_c_binding, only: c_int, c_int32_t, c_ptr
    use strings, only: to_string
    implicit none
    private
    public :: metis_nodend, metis_status_message
    public :: IDX_T, METIS_OK, METIS_ERROR_INPUT, METIS_ERROR_MEMORY

    !> metis.h's idx_t: Debian builds METIS with IDXTYPEWIDTH 32.
    integer, parameter :: IDX_T = c_int32_t

    integer(c_int), parameter :: METIS_OK = 1
    integer(c_int), parameter :: METIS_ERROR_INPUT = -2
    integer(c_int), parameter :: METIS_ERROR_MEMORY = -3

    interface
        !> int METIS_NodeND(idx_t *nvtxs, idx_t *xadj, idx_t *adjncy, idx_t *vwgt,
        !> idx_t *options, idx_t *perm, idx_t *iperm). xadj and adjncy: the 0-based CSR
        !> graph without self loops or repeated edges; metis.h passes them without const
        !> (METIS renumbers them in place when asked for 1-based numbering), hence inout.
        !> NULL vwgt: unit weights; NULL options: the defaults, 0-based numbering among them.
        !> perm(k) = the vertex ordered k-th, iperm its inverse, both 0-based.
        function metis_nodend(nvtxs, xadj, adjncy, vwgt, options, perm, iperm) &
                bind(C, name='METIS_NodeND') result(code)
            import :: c_int, c_ptr, IDX_T
            integer(IDX_T), intent(in) :: nvtxs
            integer(IDX_T), intent(inout) :: xadj(*), adjncy(*)
            type(c_ptr), value :: vwgt, options
            integer(IDX_T), intent(out) :: perm(*), iperm(*)
            integer(c_int) :: code
        end function metis_nodend
    end interface

contains

    !> A sentence for each METIS return code.
    pure function metis_status_message(code) result(message)
        integer, intent(in) :: code
        character(len=:), allocatable :: message
        select case (code)
        case (METIS_OK)
            message = 'success'
        case (METIS_ERROR_INPUT)
            message = 'METIS rejected its input graph (METIS_ERROR_INPUT)'
        case (METIS_ERROR_MEMORY)
            message = 'METIS ran out of memory (METIS_ERROR_MEMORY)'
        case default
            message = 'METIS failed (code '//to_string(code)//')'
        end select
    end function metis_status_message
end module metis_c
