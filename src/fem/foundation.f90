!> foundation: the springs that tie a body to the ground (SPRING), as small
!> element matrices that join K beside the elements' (module body).
!>
!> An elastic (Winkler) foundation on a boundary curve, normal stiffness kn
!> and tangential kt per unit length of the boundary (per unit area in
!> axisymmetric, per unit length and thickness in plane stress, as TRACTION):
!> the traction it puts on the body is -(kn n n' + kt t t') u, so that
!>     K_s = int_edge N' (kn n n' + kt t t') N w ds,
!> w the thickness (1 in plane strain) or 2 pi r (axisymmetric, the full
!> circle), n the unit normal of the edge and t = (-n_y, n_x).  K_s is the
!> boundary mass matrix with the projector kn n n' + kt t t' in it: a rigid
!> translation along the boundary's normal meets its full stiffness, not a
!> lumped approximation.  n n' and t t' do not change with the sign of n:
!> the matrix does not depend on the edge's orientation.  The rule is 4-point
!> Gauss-Legendre on s in [-1, 1]: exact (degree 7) for the products N_a N_b
!> of a straight 2- or 3-node edge (degree 2 or 4), with the radial weight r(s)
!> (one degree more); on a curved 3-node edge the normal turns along the edge
!> and the integrand is no longer a polynomial, which the same rule
!> integrates to its order.
!>
!> A point spring, kx and ky to the ground at one node: K_s = diag(kx, ky)
!> (forces for the full circle in axisymmetric, as every force).
!>
!> The matrices are in x, y components; module body turns them to a node's
!> local axes (FIX un=/ut=) when it assembles them.
!>
!> Programming interface
!>   type(spring_set_t)                          the spring elements of one body
!>   edge_spring_matrix(nen, xe, kn, kt, w, radial, ke)   K_s of one boundary edge
!>   add_spring(set, nodes, ke, owner)           append one spring element to a set
module foundation
  use kinds, only: dp
  implicit none
  private
  public :: spring_set_t, edge_spring_matrix, add_spring

  !> The springs of one body: n small matrices on 1, 2 or 3 nodes each.
  type :: spring_set_t
    integer :: n = 0                         !< number of spring elements
    integer, allocatable :: nodes(:,:)       !< (3, capacity) nodes of each: an edge's ends then its
                                             !< mid-side node, or the one node of a point spring
    integer, allocatable :: nen(:)           !< (capacity) nodes of each, 1, 2 or 3
    real(dp), allocatable :: k(:,:,:)        !< (6, 6, capacity) its matrix, dofs (x, y) node by node
    integer, allocatable :: owner(:)         !< (capacity) the body's SPRING statement it comes from
  end type spring_set_t

  real(dp), parameter :: two_pi = 2.0_dp * acos(-1.0_dp)

contains

  !> K_s = int N' (kn n n' + kt t t') N w ds on one boundary edge.
  !>   nen    (in)  2 (straight edge) or 3 (ends, then the mid-side node)
  !>   xe     (in)  (2, nen) node coordinates
  !>   kn, kt (in)  normal and tangential moduli (force per length per length of boundary)
  !>   w      (in)  thickness (plane); ignored when radial
  !>   radial (in)  axisymmetric: the weight is 2 pi r(s)
  !>   ke     (out) (2 nen, 2 nen) the matrix, symmetric positive semi-definite
  pure subroutine edge_spring_matrix(nen, xe, kn, kt, w, radial, ke)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xe(:,:), kn, kt, w
    logical, intent(in) :: radial
    real(dp), intent(out) :: ke(:,:)
    ! 4-point Gauss-Legendre on [-1, 1]
    real(dp), parameter :: a4 = sqrt(3.0_dp / 7.0_dp - 2.0_dp / 7.0_dp * sqrt(1.2_dp))
    real(dp), parameter :: b4 = sqrt(3.0_dp / 7.0_dp + 2.0_dp / 7.0_dp * sqrt(1.2_dp))
    real(dp), parameter :: g4(4) = [-b4, -a4, a4, b4]
    real(dp), parameter :: wa = (18.0_dp + sqrt(30.0_dp)) / 36.0_dp, wb = (18.0_dp - sqrt(30.0_dp)) / 36.0_dp
    real(dp), parameter :: w4(4) = [wb, wa, wa, wb]
    real(dp) :: s, shp(3), dshp(3), tang(2), len_s, n(2), t(2), p(2, 2), f
    integer :: q, a, b
    ke(1:2 * nen, 1:2 * nen) = 0.0_dp
    do q = 1, 4
      s = g4(q)
      if (nen == 2) then
        shp(1:2) = [0.5_dp * (1 - s), 0.5_dp * (1 + s)]
        dshp(1:2) = [-0.5_dp, 0.5_dp]
      else
        shp = [0.5_dp * s * (s - 1), 0.5_dp * s * (s + 1), 1 - s * s]
        dshp = [s - 0.5_dp, s + 0.5_dp, -2 * s]
      end if
      tang = matmul(xe(:, 1:nen), dshp(1:nen))                  ! dx/ds
      len_s = norm2(tang)                                      ! |dx/ds|
      n = [tang(2), -tang(1)] / len_s
      t = [-n(2), n(1)]
      p(:, 1) = kn * n(1) * n + kt * t(1) * t                  ! kn n n' + kt t t'
      p(:, 2) = kn * n(2) * n + kt * t(2) * t
      f = w4(q) * len_s * w
      if (radial) f = w4(q) * len_s * two_pi * dot_product(shp(1:nen), xe(1, 1:nen))
      do b = 1, nen
        do a = 1, nen
          ke(2 * a - 1:2 * a, 2 * b - 1:2 * b) = ke(2 * a - 1:2 * a, 2 * b - 1:2 * b) + (f * shp(a) * shp(b)) * p
        end do
      end do
    end do
  end subroutine edge_spring_matrix

  !> Append a spring element (the set grows by doubling).
  !>   set   (inout) the body's springs
  !>   nodes (in)    its 1, 2 or 3 nodes
  !>   ke    (in)    (2 size(nodes), 2 size(nodes)) its matrix in x, y components
  !>   owner (in)    the body's SPRING statement it comes from
  pure subroutine add_spring(set, nodes, ke, owner)
    type(spring_set_t), intent(inout) :: set
    integer, intent(in) :: nodes(:), owner
    real(dp), intent(in) :: ke(:,:)
    integer, allocatable :: gn(:,:), gi(:), go(:)
    real(dp), allocatable :: gk(:,:,:)
    integer :: cap, m
    if (.not. allocated(set%nen)) then
      allocate(set%nodes(3, 8), set%nen(8), set%k(6, 6, 8), set%owner(8))
    else if (set%n == size(set%nen)) then
      cap = 2 * size(set%nen)
      allocate(gn(3, cap), gi(cap), gk(6, 6, cap), go(cap))
      gn(:, 1:set%n) = set%nodes(:, 1:set%n)
      gi(1:set%n) = set%nen(1:set%n)
      gk(:, :, 1:set%n) = set%k(:, :, 1:set%n)
      go(1:set%n) = set%owner(1:set%n)
      call move_alloc(gn, set%nodes)
      call move_alloc(gi, set%nen)
      call move_alloc(gk, set%k)
      call move_alloc(go, set%owner)
    end if
    m = size(nodes)
    set%n = set%n + 1
    set%nodes(:, set%n) = 0
    set%nodes(1:m, set%n) = nodes
    set%nen(set%n) = m
    set%k(:, :, set%n) = 0.0_dp
    set%k(1:2 * m, 1:2 * m, set%n) = ke(1:2 * m, 1:2 * m)
    set%owner(set%n) = owner
  end subroutine add_spring

end module foundation
