!> local_axes: the constraint rows of contact in the solver basis of the
!> nodes held in local axes (FIX un=/ut=, body%axes).
!>
!> A node in local axes carries the dofs (u.n, u.t) instead of (u_x, u_y):
!> u_xy = Q u_nt with Q = [n t].  The contact rows are built in x, y
!> (contact_set), C u_xy = C Q u_nt, so each row's pair of entries on such a
!> node becomes [c_x c_y] Q = [c.n c.t].  An entry on one component alone (a
!> row along e_y skips its zero e_x entry) yields two entries; repeated
!> entries of a column are allowed in C (every use sums them).
!>
!> Programming interface
!>   rotate_constraint_rows(cs, bodies)   cs%cdof, bptr, bcol, bval rewritten
module local_axes
  use kinds, only: dp
  use body, only: body_t
  use contact_set, only: contact_set_t
  implicit none
  private
  public :: rotate_constraint_rows

contains

  !> C = C_xy Q on the nodes in local axes; nothing when no body has any.
  !>   cs     (inout) the constraint rows (x, y on entry, the solver basis on exit)
  !>   bodies (in)    the bodies, with their axes
  subroutine rotate_constraint_rows(cs, bodies)
    type(contact_set_t), intent(inout) :: cs
    type(body_t), intent(in) :: bodies(:)
    real(dp), allocatable :: nrm(:,:), val(:)
    integer, allocatable :: colmap(:), col(:), ptr(:)
    logical, allocatable :: touched(:)
    integer :: b, a, ndof, nrows, r, k, kk, d, node, c, m
    real(dp) :: q(2, 2)

    if (.not. any([(allocated(bodies(b)%axes), b = 1, size(bodies))])) return
    ndof = 0
    do b = 1, size(bodies)
      ndof = max(ndof, bodies(b)%dof0 + 2 * bodies(b)%mesh%nnode)
    end do
    ! a RIGID's three dofs follow the bodies' and may be contact dofs: they
    ! are in x, y (their "nodes" below have no normal)
    if (cs%ncdof > 0) ndof = max(ndof, maxval(cs%cdof))
    ndof = ndof + mod(ndof, 2)
    allocate(nrm(2, ndof / 2), source=0.0_dp)          ! the normal of each global node, 0: x, y
    do b = 1, size(bodies)
      if (.not. allocated(bodies(b)%axes)) cycle
      do a = 1, bodies(b)%mesh%nnode
        nrm(:, bodies(b)%dof0 / 2 + a) = bodies(b)%axes(:, a)
      end do
    end do
    ! the contact dofs: both dofs of every node in local axes that a row reaches
    allocate(touched(ndof), source=.false.)
    touched(cs%cdof) = .true.
    do k = 1, cs%ncdof
      node = (cs%cdof(k) + 1) / 2
      if (any(nrm(:, node) /= 0.0_dp)) touched(2 * node - 1:2 * node) = .true.
    end do
    allocate(colmap(ndof), source=0)
    m = 0
    do d = 1, ndof
      if (.not. touched(d)) cycle
      m = m + 1
      colmap(d) = m
    end do
    nrows = size(cs%bptr) - 1
    allocate(ptr(nrows + 1), col(2 * size(cs%bcol)), val(2 * size(cs%bcol)))
    kk = 0
    ptr(1) = 1
    do r = 1, nrows
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        d = cs%cdof(cs%bcol(k))
        node = (d + 1) / 2
        if (all(nrm(:, node) == 0.0_dp)) then
          kk = kk + 1
          col(kk) = colmap(d)
          val(kk) = cs%bval(k)
        else
          c = d - 2 * (node - 1)                       ! 1: x, 2: y
          q(:, 1) = nrm(:, node)
          q(:, 2) = [-nrm(2, node), nrm(1, node)]
          col(kk + 1:kk + 2) = colmap(2 * node - 1:2 * node)
          val(kk + 1:kk + 2) = cs%bval(k) * q(c, :)    ! c_c e_c . [n t]
          kk = kk + 2
        end if
      end do
      ptr(r + 1) = kk + 1
    end do
    cs%ncdof = m
    cs%cdof = pack([(d, d = 1, ndof)], touched)
    cs%bptr = ptr
    cs%bcol = col(1:kk)
    cs%bval = val(1:kk)
  end subroutine rotate_constraint_rows

end module local_axes
