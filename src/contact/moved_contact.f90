!> moved_contact: the contact set of the current configuration, for CONTACT
!> ... sliding=finite (doc/theory.md, "Finite sliding"): the bodies of finite
!> pairs placed at x + u and their RIGIDs moved, the rows built there by
!> contact_set and linearized at u; and the keys that follow a row from one
!> rebuild to the next as the zone moves.
!>
!> Why it exists: small sliding builds its rows once, on the initial
!> configuration (contact_set); finite sliding rebuilds them at every update
!> from a displacement, which needs the displacement's basis (local axes),
!> the RIGIDs' motion and the linearization.  Who may use it: finite_sliding.
!>
!> Programming interface
!>   build_moved_contact_set(bodies, specs, u, cs, err)  the contact set in the configuration
!>                                               x + u, g the current gaps linearized at u
!>   row_keys(cs)                                (nrow) each row's pair and slave node as one
!>                                               number, to follow rows from one rebuild to the next
module moved_contact
  use kinds, only: dp, i8
  use errors, only: error_t
  use body, only: body_t
  use contact_set, only: contact_set_t, pair_spec_t, build_contact_set
  use rigid_obstacle, only: rigid_shape_t
  implicit none
  private
  public :: build_moved_contact_set, row_keys

contains

  !> The contact set of the configuration x + u (CONTACT sliding=finite): the
  !> slave bodies and master bodies of finite-sliding pairs at x + u, their RIGIDs moved by
  !> their motion (translation, small rotation about the reference point,
  !> which moves along), then build_contact_set.  B is then the linearization
  !> at u of the current gaps g(u): g(v) ~ g(u) - B (v - u), so the rows keep
  !> the form B v <= g of the initial configuration with g = g(u) + B u.  The
  !> pairs with small sliding keep the initial geometry (their bodies are not
  !> moved unless a finite pair moves them too).
  !>   bodies (in)  the bodies at their initial configuration, dof0 set
  !>   specs  (in)  (npair) the CONTACT statements, resolved (shapes at rest)
  !>   u      (in)  (ndof) the current displacement, in the solver basis (a node in
  !>                local axes, FIX un=/ut=, has (u.n, u.t))
  !>   cs     (out) the contact set at x + u in x, y (local_axes rotates its rows),
  !>                g = g(u) + B u
  !>   err    (out) as build_contact_set
  subroutine build_moved_contact_set(bodies, specs, u, cs, err)
    type(body_t), intent(in) :: bodies(:)
    type(pair_spec_t), intent(in) :: specs(:)
    real(dp), intent(in) :: u(:)
    type(contact_set_t), intent(out) :: cs
    type(error_t), allocatable, intent(out) :: err
    type(body_t), allocatable :: moved(:)
    type(pair_spec_t), allocatable :: mspecs(:)
    logical, allocatable :: done(:)
    real(dp), allocatable :: uxy(:)
    integer :: ip, a, r, k, b, d
    real(dp) :: du(3), bu, n(2)
    moved = bodies
    mspecs = specs
    uxy = u                                            ! a node in local axes (FIX un=/ut=): (u.n, u.t) to x, y
    do b = 1, size(bodies)
      if (.not. allocated(bodies(b)%axes)) cycle
      do a = 1, bodies(b)%mesh%nnode
        n = bodies(b)%axes(:, a)
        if (all(n == 0.0_dp)) cycle
        d = bodies(b)%dof0 + 2 * a - 1
        uxy(d:d + 1) = u(d) * n + u(d + 1) * [-n(2), n(1)]
      end do
    end do
    allocate(done(size(bodies)), source=.false.)
    do ip = 1, size(specs)
      if (.not. specs(ip)%finite) cycle
      ! an overlap of the current configuration is the linearization's, of the
      ! order of the step's slide squared: the fixed point decides, not the entry check
      mspecs(ip)%interference = .true.
      call move_body(specs(ip)%slave_body)
      if (specs(ip)%rigid == 0) call move_body(specs(ip)%master_body)
      if (specs(ip)%rigid > 0) then
        associate(sh => mspecs(ip)%shape)
          du = u(sh%dof0 + 1:sh%dof0 + 3)
          if (allocated(sh%pt)) then
            do k = 1, size(sh%pt, 2)
              sh%pt(:, k) = sh%pt(:, k) + rigid_motion(sh, sh%pt(:, k), du)
            end do
          end if
          sh%centre = sh%centre + rigid_motion(sh, sh%centre, du)
          sh%ref = sh%ref + du(1:2)
        end associate
      end if
    end do
    call build_contact_set(moved, mspecs, cs, err)
    if (allocated(err)) return
    do r = 1, cs%nrow                                  ! g = g(u) + B u
      bu = 0.0_dp
      do k = cs%bptr(r), cs%bptr(r + 1) - 1
        bu = bu + cs%bval(k) * uxy(cs%cdof(cs%bcol(k)))
      end do
      cs%g(r) = cs%g(r) + bu
    end do
  contains
    !> Body b to x + u (once)
    subroutine move_body(b)
      integer, intent(in) :: b
      if (done(b)) return
      do a = 1, moved(b)%mesh%nnode
        moved(b)%mesh%x(:, a) = bodies(b)%mesh%x(:, a) + uxy(bodies(b)%dof0 + 2 * a - 1:bodies(b)%dof0 + 2 * a)
      end do
      done(b) = .true.
    end subroutine move_body

    !> U(x) of the rigid motion du = (u_x, u_y, theta) (small rotation)
    pure function rigid_motion(sh, x, du) result(v)
      type(rigid_shape_t), intent(in) :: sh
      real(dp), intent(in) :: x(2), du(3)
      real(dp) :: v(2)
      v = [du(1) - du(3) * (x(2) - sh%ref(2)), du(2) + du(3) * (x(1) - sh%ref(1))]
    end function rigid_motion
  end subroutine build_moved_contact_set

  !> Each normal row's pair and slave node (its global node id) as one
  !> number: the rows of two rebuilds of a moving contact are the same rows
  !> when their keys are (a zone that gains or loses a node renumbers them).
  pure function row_keys(cs) result(keys)
    type(contact_set_t), intent(in) :: cs
    integer(i8), allocatable :: keys(:)
    integer :: r
    allocate(keys(cs%nrow))
    do r = 1, cs%nrow
      keys(r) = int(cs%row_pair(r), i8) * 2_i8**31 + cs%pair(cs%row_pair(r))%snode(cs%row_node(r))
    end do
  end function row_keys

end module moved_contact
