! SPDX-License-Identifier: MIT
!> Gauss rules of any order, for the hierarchical elements of any degree: Gauss-Legendre on
!> the segment [-1, 1] and the collapsed (Duffy) product rule on the reference triangle
!> (0,0), (1,0), (0,1). Unlike quadrature.f90's fixed small tables, these are computed (Newton
!> on the Legendre recurrence), so their size is open-ended and held in allocatable arrays.
module gauss_rules
    use kinds, only: rk => wp
    include 'gauss_rules_body.inc'
end module gauss_rules
