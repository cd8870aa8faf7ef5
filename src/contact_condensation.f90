!> contact_condensation: the contact problem condensed onto the constraint rows
!> (the Delassus matrix) and the recovery of the displacement.
!>
!> With K u = f - B' mu (the KKT system of min 1/2 u'Ku - f'u, B u <= g) and
!> u0 = K^-1 f, the final gap is  g - B u = q + W mu  with
!>     W = B K^-1 B'      q = g - B u0
!> and (mu, q + W mu) solve LCP(W, q).  Only the contact dofs C enter B, so
!> W = B_C (K^-1)_CC B_C'.  The contact dofs are ordered last in the Cholesky
!> factorization, K = L L' with L = [L_rr 0; L_cr L_cc], hence
!> (K^-1)_CC = (L_cc L_cc')^-1 and
!>     X = L_cc^-1 B_C'  (dtrsm),   W = X' X  (dsyrk)
!> at the cost of a dense triangular solve, not of ncdof sparse solves.  K
!> does not couple two bodies, so L_cc has one diagonal block per body that
!> has contact dofs: the solve runs block by block (half the flops of the
!> whole block for two bodies of equal share).
!>
!> One solve in all.  With y = L^-1 P f (the forward half of u0 = K^-1 f),
!> the contact dofs of u0 are the end of the backward half,
!>     u0_C = L_cc'^-1 y_c,
!> which is all that q needs; and the contact forces -B' mu reach only the
!> trailing pivots, so the forward half of the recovery is
!>     L^-1 P (f - B' mu) = y - [0; X mu]
!> and one backward solve gives u.  The displacement costs one forward and
!> one backward solve, not two solves.
!>
!> Programming interface
!>   contact_equations(cs, eq, last)        free equations of the contact dofs, in
!>                                          the order to be factorized last
!>   condense(cs, eq, factor, y, u0, w, q, xc, err)
!>                                          W (nc, nc), q (nc), nc = nrow + ntan,
!>                                          u0 on the contact dofs from y, and X
!>                                          in xc for recover
!>   constraint_values(cs, u, v)            v = C u, C = [B; T] (the tangential
!>                                          rows T of friction pairs after B)
!>   contact_forces(cs, mu, fc)             fc = -B' mu on every dof (fc sized ndof)
!>   recover(eq, factor, y, xc, u0, mu, u)  u = K^-1 (f - C' mu) by one backward
!>                                          solve (y overwritten, xc released)
module contact_condensation
  use kinds, only: dp
  use lapack_interfaces, only: dgemv, dsyrk, dtrsm
  use diagnostics, only: error_t
  use contact_set, only: contact_set_t
  use sparse_cholesky, only: factor_t, trailing_factor_block, trailing_block_end, solve_backward
  implicit none
  private
  public :: contact_equations, condense, contact_forces, recover, constraint_values


contains

  !> Free equations of the contact dofs (ascending dof order): the block
  !> ordered last in the factorization.
  subroutine contact_equations(cs, eq, last)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: eq(:)
    integer, allocatable, intent(out) :: last(:)
    integer :: k, n
    n = count(eq(cs%cdof) > 0)
    allocate(last(n))
    n = 0
    do k = 1, cs%ncdof
      if (eq(cs%cdof(k)) > 0) then
        n = n + 1
        last(n) = eq(cs%cdof(k))
      end if
    end do
  end subroutine contact_equations

  !> W = C_C (K^-1)_CC C_C' and q = g - C u0, C = [B; T] (T: tangential rows
  !> of friction pairs, g = 0 there; C = B without friction).
  !>   cs     (in)  constraint rows; factor (in) K = L L' with contact_equations last
  !>   eq     (in)  (ndof) free equation numbers
  !>   u0     (inout) (ndof) on entry the prescribed values on the fixed dofs;
  !>                on exit also u0 = K^-1 f on the free contact dofs
  !>                (u0_C = L_cc'^-1 y_c; the other free dofs are not set)
  !>   w      (out) (nc, nc) symmetric positive semi-definite, nc = nrow + ntan
  !>   q      (out) (nc)
  !>   err    (out) allocated when the trailing block cannot be had
  !>   y      (in)  (nfree) the forward half L^-1 P f of u0's solve
  !>   xc     (out) X = L_cc^-1 C_C' (nfc, nc), for recover
  subroutine condense(cs, eq, factor, y, u0, w, q, xc, err)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: eq(:)
    type(factor_t), intent(inout) :: factor
    real(dp), intent(in) :: y(:)
    real(dp), intent(inout) :: u0(:)
    real(dp), allocatable, intent(out) :: w(:,:), q(:), xc(:,:)
    type(error_t), allocatable, intent(out) :: err
    integer :: nc, nfc, r, k, col, i, j, s, e, c1, c2
    integer, allocatable :: fcol(:)
    real(dp), allocatable :: x(:,:), lcc(:,:), uc(:)

    nc = cs%nrow + cs%ntan
    ! column of each contact dof in the free block (0 when fixed)
    allocate(fcol(cs%ncdof))
    nfc = 0
    do k = 1, cs%ncdof
      if (eq(cs%cdof(k)) > 0) then
        nfc = nfc + 1
        fcol(k) = nfc
      else
        fcol(k) = 0
      end if
    end do
    if (nfc == 0 .or. nc == 0) then
      call gap_offsets()
      allocate(w(nc, nc), source=0.0_dp)
      allocate(xc(nfc, nc), source=0.0_dp)
      return
    end if
    ! X = B_C' restricted to free contact dofs, (nfc, nc)
    allocate(x(nfc, nc), source=0.0_dp)
    do r = 1, nc
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        col = fcol(cs%bcol(k))
        if (col > 0) x(col, r) = x(col, r) + cs%bval(k)
      end do
    end do
    ! X = L_cc^-1 B_C', one diagonal block of L_cc at a time: bodies that K
    ! does not couple give L_cc a block per body; a block is read out of the
    ! factor only when it is solved (the whole L_cc is never held), and solved
    ! only on the constraint rows that reach it (the rest of X stays zero there)
    uc = y(size(y) - nfc + 1:)
    s = 1
    do while (s <= nfc)
      call trailing_block_end(factor, nfc, s, e, err)
      if (.not. allocated(err)) call trailing_factor_block(factor, nfc, lcc, err, first=s, count=e - s + 1)
      if (allocated(err)) then
        err%message = 'cannot extract the contact block of the Cholesky factor: ' // err%message
        return
      end if
      ! the end of the backward half of u0 = K^-1 f: u0_C = L_cc'^-1 y_c
      call dtrsm('L', 'L', 'T', 'N', e - s + 1, 1, 1.0_dp, lcc, e - s + 1, uc(s), nfc)
      call nonzero_columns(x, s, e, c1, c2)
      if (c1 <= c2) call dtrsm('L', 'L', 'N', 'N', e - s + 1, c2 - c1 + 1, 1.0_dp, lcc, e - s + 1, x(s, c1), nfc)
      deallocate(lcc)
      s = e + 1
    end do
    do k = 1, cs%ncdof
      if (fcol(k) > 0) u0(cs%cdof(k)) = uc(fcol(k))
    end do
    call gap_offsets()
    allocate(w(nc, nc))
    call dsyrk('U', 'T', nc, nfc, 1.0_dp, x, nfc, 0.0_dp, w, nc)           ! W = X' X (upper)
    do j = 1, nc
      do i = j + 1, nc
        w(i, j) = w(j, i)
      end do
    end do
    call move_alloc(x, xc)

  contains

    !> q = g - C u0 (fixed contact dofs carry their prescribed values; g = 0
    !> on tangential rows)
    subroutine gap_offsets()
      allocate(q(nc))
      do r = 1, nc
        q(r) = 0.0_dp
        if (r <= cs%nrow) q(r) = cs%g(r)
        do k = cs%bptr(r), cs%bptr(r + 1) - 1
          q(r) = q(r) - cs%bval(k) * u0(cs%cdof(cs%bcol(k)))
        end do
      end do
    end subroutine gap_offsets
  end subroutine condense

  !> The first and last columns c1..c2 of x with a non-zero in rows s..e
  !> (c1 > c2 when there is none).
  pure subroutine nonzero_columns(x, s, e, c1, c2)
    real(dp), intent(in) :: x(:,:)
    integer, intent(in) :: s, e
    integer, intent(out) :: c1, c2
    integer :: j
    c1 = size(x, 2) + 1
    c2 = 0
    do j = 1, size(x, 2)
      if (any(x(s:e, j) /= 0.0_dp)) then
        c1 = min(c1, j)
        c2 = j
      end if
    end do
  end subroutine nonzero_columns

  !> v = C u: the values of every constraint row (B u, then T u) at u.
  !>   cs (in) rows; u (in) (ndof); v (out) (nrow + ntan)
  subroutine constraint_values(cs, u, v)
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:)
    real(dp), intent(out) :: v(:)
    integer :: r, k
    do r = 1, cs%nrow + cs%ntan
      v(r) = 0.0_dp
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        v(r) = v(r) + cs%bval(k) * u(cs%cdof(cs%bcol(k)))
      end do
    end do
  end subroutine constraint_values

  !> Nodal contact forces fc = -C' mu on all dofs (zero away from contact);
  !> mu holds the normal multipliers (nrow), followed by the tangential ones
  !> (ntan) when there is friction.
  subroutine contact_forces(cs, mu, fc)
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: mu(:)
    real(dp), intent(inout) :: fc(:)
    integer :: r, k
    fc = 0.0_dp
    do r = 1, size(mu)
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        fc(cs%cdof(cs%bcol(k))) = fc(cs%cdof(cs%bcol(k))) - cs%bval(k) * mu(r)
      end do
    end do
  end subroutine contact_forces

  !> u = K^-1 (f - C' mu): the backward half of the solve, of y - [0; X mu]
  !> (y the forward half L^-1 P f, X = L_cc^-1 C_C' from condense); u takes
  !> u0's prescribed values on the fixed dofs.
  !>   y  (inout) (nfree) overwritten;  xc (inout) X, released before the solve
  !>   u0 (in) (ndof), only its fixed dofs read;  mu (in) (nc);  u (out) (ndof)
  subroutine recover(eq, factor, y, xc, u0, mu, u)
    integer, intent(in) :: eq(:)
    type(factor_t), intent(inout) :: factor
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), allocatable, intent(inout) :: xc(:,:)
    real(dp), intent(in) :: u0(:), mu(:)
    real(dp), intent(out) :: u(:)
    real(dp), allocatable :: du(:)
    integer :: i, nfree, nfc
    nfree = size(y)
    nfc = size(xc, 1)
    if (nfc > 0 .and. size(mu) > 0) &
      call dgemv('N', nfc, size(mu), -1.0_dp, xc, nfc, mu, 1, 1.0_dp, y(nfree - nfc + 1:), 1)
    deallocate(xc)                                   ! before the solve: a lower peak
    allocate(du(nfree))
    call solve_backward(factor, y, du)
    u = u0
    do i = 1, size(eq)
      if (eq(i) > 0) u(i) = du(eq(i))
    end do
  end subroutine recover

end module contact_condensation
