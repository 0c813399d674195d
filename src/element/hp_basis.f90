! SPDX-License-Identifier: MIT
!> Hierarchical H1 basis on the reference triangle (0,0), (1,0), (0,1) of any degree, with a
!> degree per edge (the minimum rule: an edge takes the smaller degree of its two cells) and
!> one for the interior. In barycentric coordinates l1 = 1 - x - y, l2 = x, l3 = y:
!>
!> - vertex k: l_k;
!> - edge from vertex a to vertex b, i = 2..p_e: the scaled integrated Legendre polynomial
!>   Lhat_i(l_b - l_a, l_a + l_b) = (l_a + l_b)^i Lhat_i((l_b - l_a)/(l_a + l_b)), with
!>   Lhat_i(s) = int_{-1}^s P_{i-1}. It vanishes on the other two edges (Lhat_i(+-1) = 0),
!>   and on its own edge it is Lhat_i(s) of the position s in [-1, 1] from a to b alone, so
!>   two cells agree on their common edge when both run it the same way: a global direction
!>   (from the lower to the higher vertex number) given to each cell as `flip`;
!> - interior, total degree n = 3..p, i = 2..n-1, j = n - 1 - i:
!>   Lhat_i(l2 - l1, l1 + l2) l3 P_j(2 l3 - 1), which vanish on the boundary.
!>
!> Integrated Legendre polynomials are orthogonal in the H1 seminorm in 1D, which keeps the
!> stiffness matrix's condition number growing only polynomially in p. Local order: the three
!> vertices, the edges' functions (edge k from vertex k to k + 1, i ascending), the interior
!> ones (n ascending): lower degrees first, so the space of degree p is a prefix.
module hp_basis
    use kinds, only: rk => wp
    include 'hp_basis_body.inc'
end module hp_basis
