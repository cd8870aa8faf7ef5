!> contact_pair: one CONTACT pair, from its statement to what its constraint rows
!> need (contact_set assembles the rows of all pairs): the slave and master
!> polylines, or quadratic traces, the pair's mortar operator pi_h^1 (eq. (8):
!> mortar_operator, mortar_quadratic, rigid_obstacle), along the common normals
!> for a pair with friction, the check of the initial penetration, the slave
!> nodes that carry a row, and the projection P kept sparse by rows.
!>
!> Entries of P below 1e-16 of their row's largest are dropped (pi_h^1 decays
!> exponentially away from the diagonal; the dropped part is below round-off).
!>
!> Programming interface
!>   type(pair_spec_t)        what a CONTACT statement says, resolved to indices
!>   type(contact_pair_t)     one pair: polylines, operator, the layout of its rows
!>   type(projection_rows_t)  the rows of P that the rows of B and T take, in CSR
!>   build_contact_pair(bodies, spec, row0, pr, prj, err)
!>                            one pair, its rows numbered after row0
!>   has_friction(spec)       the pair has tangential rows
module contact_pair
  use kinds, only: dp
  use errors, only: error_t, set_error, error_input
  use mesh, only: is_quadratic
  use body, only: body_t
  use boundary_chain, only: boundary_polyline, trace_chain
  use mortar_operator, only: mortar_t, build_mortar, zone_point, segment_rule
  use mortar_geometry, only: intersection_t, intersect_segments, common_normals
  use rigid_obstacle, only: rigid_shape_t, build_rigid_mortar, orient_shape
  use mortar_quadratic, only: build_mortar_quadratic, quadratic_common_normals
  implicit none
  private
  public :: pair_spec_t, contact_pair_t, projection_rows_t, build_contact_pair, has_friction

  !> What a CONTACT statement says, resolved to indices.
  type :: pair_spec_t
    integer :: slave_body = 0, slave_bnd = 0   !< body index, boundary index in its mesh
    integer :: master_body = 0, master_bnd = 0
    logical :: gap_zero = .false.
    logical :: interference = .false.         !< initial penetrations deeper than a slave element accepted
    logical :: finite = .false.               !< sliding=finite: rebuilt from the current configuration;
                                              !< both dofs of every slave node are contact dofs
    real(dp) :: mu = 0.0_dp                   !< Coulomb coefficient (0: none)
    real(dp) :: tresca = 0.0_dp               !< Tresca slip bound, a shear stress (0: none)
    integer :: rigid = 0                      !< master=RIGID: its index (master_body 0), else 0
    type(rigid_shape_t) :: shape              !< the RIGID's shape and dofs (rigid > 0)
  end type pair_spec_t

  !> One pair: its polylines (or traces), its operator and the layout of its rows.
  type :: contact_pair_t
    type(pair_spec_t) :: spec
    integer, allocatable :: snode(:)       !< (ns) slave polyline, node ids of the slave mesh
    integer, allocatable :: mnode(:)       !< (nm) master polyline, node ids of the master mesh
    real(dp), allocatable :: xs(:,:)       !< (2, ns) slave node coordinates
    type(mortar_t) :: mortar               !< pi_h^1, normals, gap0, weights
    integer :: row0 = 0                    !< rows row0+1 .. row0+nrow of B
    integer :: nrow = 0                    !< constrained slave nodes
    logical, allocatable :: row(:)         !< (ns) slave node carries a constraint row: in the
                                           !< effective zone and with master opposite
    logical :: single = .false.            !< the zone is one slave segment: one mean-value row
    logical :: closed = .false.            !< the slave polyline is a closed curve (snode(ns) = snode(1))
    logical :: quadratic = .false.         !< either trace is quadratic (mortar_quadratic): snode and mnode
                                           !< list the mid-side nodes too, between their corners
    integer :: degree(2) = 1               !< degree of the slave (1) and master (2) traces
    real(dp) :: slave_weight = 1.0_dp      !< friction: the slave normal's weight in the common normal
    logical :: fold(2) = .false.           !< the row of a cut zone start (1) / end (2) is reported on
                                           !< the node next to it: the end node has no master opposite
    logical :: axis_fold(2) = .false.      !< quadratic slave trace, zone start (1) / end (2) on the axis:
                                           !< that node's hat has no weight, its pressure is read with the
                                           !< mid-side node's row (node_rows)
    real(dp), allocatable :: mcov(:)       !< (nm) int of each master hat over the covered part
  end type contact_pair_t

  !> The rows first..last of a pair's projection P, its entries above 1e-16
  !> of their row's largest, in increasing master index (CSR).
  type :: projection_rows_t
    integer, allocatable :: ptr(:)         !< (first:last+1) row pointers
    integer, allocatable :: col(:)         !< master polyline index j
    real(dp), allocatable :: val(:)        !< P_ij
  end type projection_rows_t

contains

  !> Build one pair: its polylines, operator and rows (module header).
  !>   bodies (in)  the bodies, dof0 set
  !>   spec   (in)  the CONTACT statement, resolved
  !>   row0   (in)  the rows of the pairs before it: its rows are row0+1 .. row0+nrow
  !>   pr     (out) the pair
  !>   prj    (out) the rows of its projection P (none for a RIGID master or a one-row zone)
  !>   err    (out) allocated when a boundary cannot be used, the operator fails, or
  !>                the slave starts deep inside the master; the caller names the pair
  subroutine build_contact_pair(bodies, spec, row0, pr, prj, err)
    type(body_t), intent(in) :: bodies(:)
    type(pair_spec_t), intent(in) :: spec
    integer, intent(in) :: row0
    type(contact_pair_t), intent(out) :: pr
    type(projection_rows_t), intent(out) :: prj
    type(error_t), allocatable, intent(out) :: err
    real(dp), allocatable :: nsl(:,:)
    character(len=:), allocatable :: why

    pr%spec = spec
    call boundary_polyline(bodies(spec%slave_body), spec%slave_bnd, pr%snode, pr%xs, nsl, why)
    if (len(why) > 0) then
      call set_error(err, 'the slave boundary cannot be used: ' // why, error_input)
      return
    end if
    if (spec%rigid > 0) then
      call build_rigid_operator(bodies, nsl, pr, err)
    else
      call build_mesh_operator(bodies, nsl, pr, err)
    end if
    if (allocated(err)) return
    if (.not. spec%interference) then
      call check_penetration(pr, err)
      if (allocated(err)) return
    end if
    call number_rows(row0, pr)
    if (spec%rigid > 0) return
    call fold_zone_ends(pr)
    ! the projection lives on in the rows of B and T: the dense (ns, nm)
    ! matrix P is not kept (5 MB for 852 x 741 nodes)
    if (pr%mortar%first > 0 .and. .not. pr%single) call projection_rows(pr%mortar, prj)
    if (allocated(pr%mortar%P)) deallocate(pr%mortar%P)
  end subroutine build_contact_pair

  !> The operator of a pair whose master is a RIGID: its exact shape, no
  !> master mesh (rigid_obstacle); on a quadratic slave the trace with its
  !> mid-side nodes, the rows at every trace node.
  !>   bodies (in) the bodies
  !>   nsl (in) (2, ns-1) the slave segment normals (one per element)
  !>   pr  (inout) spec and the slave polyline on entry; the shape oriented,
  !>               the operator, the trace, and empty master lists on exit
  !>   err (out) the operator's failure
  subroutine build_rigid_operator(bodies, nsl, pr, err)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(in) :: nsl(:,:)
    type(contact_pair_t), intent(inout) :: pr
    type(error_t), allocatable, intent(out) :: err
    type(error_t), allocatable :: merr
    integer :: ps
    call orient_shape(pr%spec%shape, pr%xs, nsl)
    associate(slave => bodies(pr%spec%slave_body))
      call trace_chain(slave%mesh, pr%spec%slave_bnd, pr%snode, ps)
      pr%xs = slave%mesh%x(:, pr%snode)
      pr%quadratic = ps == 2
      pr%degree = [ps, 1]
      call build_rigid_mortar(pr%xs, ps, nsl, pr%spec%shape, slave%axisymmetric, pr%mortar, merr)
    end associate
    if (allocated(merr)) then
      call set_error(err, merr%message, merr%category)
      return
    end if
    pr%axis_fold = pr%mortar%axis_end .and. ps == 2
    allocate(pr%mnode(0), pr%mcov(0))
  end subroutine build_rigid_operator

  !> The operator of a pair whose master is a body's boundary: linear
  !> (mortar_operator) on two linear meshes, quadratic (mortar_quadratic)
  !> when either is quadratic, the chains then with their mid-side nodes;
  !> with friction (beyond the paper) along the common normals, which pair
  !> the points that meet and leave the normal approach out of the slip.
  !> Also mcov, the integrals of the master hats over the covered part.
  !>   bodies (in) the bodies
  !>   nsl    (inout) (2, ns-1) the slave segment normals (a closed slave
  !>                  polyline is opened where the master does not cover it)
  !>   pr     (inout) spec and the slave polyline on entry; the master
  !>                  polyline, the operator, degree and mcov on exit
  !>   err    (out) an unusable master boundary (error_input), the operator's failure
  subroutine build_mesh_operator(bodies, nsl, pr, err)
    type(body_t), intent(in) :: bodies(:)
    real(dp), intent(inout) :: nsl(:,:)
    type(contact_pair_t), intent(inout) :: pr
    type(error_t), allocatable, intent(out) :: err
    integer, allocatable :: mnodes(:)
    real(dp), allocatable :: xm(:,:), nms(:,:), pairing(:,:), mcov_q(:)
    character(len=:), allocatable :: why
    type(error_t), allocatable :: merr
    integer :: ps, pm

    associate(sp => pr%spec, slave => bodies(pr%spec%slave_body), master => bodies(pr%spec%master_body))
      call boundary_polyline(master, sp%master_bnd, mnodes, xm, nms, why)
      if (len(why) > 0) then
        call set_error(err, 'the master boundary cannot be used: ' // why, error_input)
        return
      end if
      pr%mnode = mnodes
      ! a closed slave curve that the master does not cover all round is
      ! opened where it is not covered (its zone has two ends)
      if (pr%snode(1) == pr%snode(size(pr%snode))) call open_at_gap(pr%snode, pr%xs, nsl, xm, nms)
      pr%quadratic = is_quadratic(slave%mesh) .or. is_quadratic(master%mesh)
      if (pr%quadratic) then
        call trace_chain(slave%mesh, sp%slave_bnd, pr%snode, ps)
        call trace_chain(master%mesh, sp%master_bnd, mnodes, pm)
        pr%xs = slave%mesh%x(:, pr%snode)
        xm = master%mesh%x(:, mnodes)
        pr%mnode = mnodes
        pr%degree = [ps, pm]
        if (has_friction(sp)) then
          call quadratic_common_normals(pr%xs, ps, nsl, xm, pm, nms, pairing, pr%slave_weight)
          call build_mortar_quadratic(pr%xs, ps, nsl, xm, pm, nms, sp%gap_zero, pr%mortar, mcov_q, merr, &
                                      pairing=pairing, axisymmetric=slave%axisymmetric)
        else
          call build_mortar_quadratic(pr%xs, ps, nsl, xm, pm, nms, sp%gap_zero, pr%mortar, mcov_q, merr, &
                                      axisymmetric=slave%axisymmetric)
        end if
      else if (has_friction(sp)) then
        call common_normals(pr%xs, nsl, xm, nms, pairing, pr%slave_weight)
        call build_mortar(pr%xs, nsl, xm, nms, sp%gap_zero, pr%mortar, merr, pairing, &
                          axisymmetric=slave%axisymmetric)
      else
        call build_mortar(pr%xs, nsl, xm, nms, sp%gap_zero, pr%mortar, merr, &
                          axisymmetric=slave%axisymmetric)
      end if
    end associate
    if (allocated(merr)) then
      call set_error(err, merr%message, merr%category)
      return
    end if
    if (pr%quadratic) then
      call move_alloc(mcov_q, pr%mcov)
    else
      call covered_master_integrals(pr%mortar, pr%xs, pr%mcov)
    end if
    if (mnodes(1) == mnodes(size(mnodes))) call close_master(pr%mortar, pr%mcov)
  end subroutine build_mesh_operator

  !> A closed master curve (its first node is its last): its last hat is its
  !> first, in P and in mcov.
  !>   mo   (inout) the operator, P (ns, nm) when it is kept
  !>   mcov (inout) (nm) the master hats' integrals over the covered part
  subroutine close_master(mo, mcov)
    type(mortar_t), intent(inout) :: mo
    real(dp), intent(inout) :: mcov(:)
    integer :: nm
    nm = size(mcov)
    if (allocated(mo%P)) then
      mo%P(:, 1) = mo%P(:, 1) + mo%P(:, nm)
      mo%P(:, nm) = 0.0_dp
    end if
    mcov(1) = mcov(1) + mcov(nm)
    mcov(nm) = 0.0_dp
  end subroutine close_master

  !> The rows of a pair: row0, the constrained slave nodes (a periodic zone's
  !> last node is its first), whether the slave polyline is closed, nrow.
  !>   row0 (in) the rows before the pair's;  pr (inout) the pair, its operator built
  subroutine number_rows(row0, pr)
    integer, intent(in) :: row0
    type(contact_pair_t), intent(inout) :: pr
    integer :: ns
    ns = size(pr%snode)
    pr%row0 = row0
    call constrained_nodes(pr%mortar, pr%row)
    pr%closed = pr%snode(1) == pr%snode(ns)
    if (pr%closed .and. pr%mortar%first == 1 .and. pr%mortar%last == ns) &
      pr%row(ns) = .false.                             ! periodic: the last node is the first
    pr%nrow = count(pr%row)
  end subroutine number_rows

  !> The zone ends of a pair with a mesh master: one slave segment is one
  !> mean-value row (the multiplier space is the constants, both end segments
  !> at once), the row of a cut end is reported on the node next to it (fold),
  !> and a quadratic trace's end node on the axis with its mid-side node (axis_fold).
  !>   pr (inout) the pair, its rows numbered (number_rows)
  subroutine fold_zone_ends(pr)
    type(contact_pair_t), intent(inout) :: pr
    pr%single = pr%mortar%first > 0 .and. pr%mortar%last == pr%mortar%first + 1 .and. .not. pr%quadratic
    if (pr%single) pr%nrow = 1
    pr%fold = [pr%mortar%cut(1) > 0.0_dp, pr%mortar%cut(2) < 1.0_dp] .and. .not. pr%single
    pr%axis_fold = pr%mortar%axis_end .and. pr%mortar%degree == 2
  end subroutine fold_zone_ends

  !> An initial penetration deeper than the slave elements beside the node
  !> (the mean length of its zone segments) is an input error (error_input): the
  !> bodies overlap by several elements, pass through each other, or the
  !> boundaries face away from each other (the master behind the slave body).
  !> Small interferences (shrink fits) stay legal; interference=allow lifts it.
  subroutine check_penetration(pr, err)
    type(contact_pair_t), intent(in) :: pr
    type(error_t), allocatable, intent(out) :: err
    integer :: i, worst
    real(dp) :: depth, size, ratio, x(2)
    character(len=48) :: buf
    associate(mo => pr%mortar)
      if (mo%first == 0) return
      worst = 0
      ratio = 1.0_dp
      do i = mo%first, mo%last
        depth = -mo%gap0(i)
        size = element_size(i)
        if (depth > ratio * size) then
          worst = i
          ratio = depth / size
        end if
      end do
      if (worst == 0) return
      x = zone_point(mo, pr%xs, worst)
      buf = '(' // trim(real_text(x(1))) // ', ' // trim(real_text(x(2))) // ')'
      call set_error(err, 'the slave point at ' // trim(buf) // ' starts ' // trim(real_text(-mo%gap0(worst))) // &
        ' inside the master, deeper than its slave elements (' // trim(real_text(element_size(worst))) // &
        '): the bodies overlap, or the two boundaries face away from each other (a gap, or a penetration ' // &
        'smaller than the slave elements, expected; interference=allow accepts it)', error_input)
    end associate
  contains
    real(dp) function element_size(i)
      integer, intent(in) :: i
      integer :: a, b
      a = max(i - 1, pr%mortar%first)
      b = min(i + 1, pr%mortar%last)
      if (b == a) b = a + 1
      element_size = norm2(pr%xs(:, b) - pr%xs(:, a)) / real(b - a, dp)
    end function element_size
  end subroutine check_penetration

  !> Short decimal text of a real, for messages.
  function real_text(v) result(t)
    real(dp), intent(in) :: v
    character(len=16) :: t
    write(t, '(g0.4)') v
    t = adjustl(t)
    ! the zero before the point is the compiler's choice under g0 (flang writes .2500)
    if (t(1:1) == '.') t = '0' // t(1:len(t) - 1)   ! the last of 16 characters a blank
    if (t(1:2) == '-.') t = '-0' // t(2:)
  end function real_text

  !> Open a closed slave polyline (nodes(n) = nodes(1)) where the master does
  !> not cover it: rotate it to start at an uncovered segment, preferably one
  !> after another uncovered one (so that its first node lies off the zone).
  !> Left as it is when the master covers every segment (a periodic zone).
  !>   nodes (inout) (n) slave node ids;  x (inout) (2, n) coordinates;
  !>   nout (inout) (2, n-1) segment normals;  xm, nms (in) the master polyline and normals
  subroutine open_at_gap(nodes, x, nout, xm, nms)
    integer, intent(inout) :: nodes(:)
    real(dp), intent(inout) :: x(:,:), nout(:,:)
    real(dp), intent(in) :: xm(:,:), nms(:,:)
    type(intersection_t) :: inter
    logical, allocatable :: covered(:)
    integer :: n, e, k, start
    n = size(nodes) - 1
    call intersect_segments(x, nout, xm, nms, inter)
    allocate(covered(n), source=.false.)
    covered(inter%slave_seg(1:inter%nsub)) = .true.
    if (all(covered)) return
    start = 0
    do e = 1, n
      k = modulo(e - 2, n) + 1                               ! the segment before e
      if (.not. covered(e) .and. (start == 0 .or. .not. covered(k))) start = e
      if (.not. covered(e) .and. .not. covered(k)) exit
    end do
    if (start == 1) return
    nodes(1:n) = cshift(nodes(1:n), start - 1)
    nodes(n + 1) = nodes(1)
    x(:, 1:n) = cshift(x(:, 1:n), start - 1, dim=2)
    x(:, n + 1) = x(:, 1)
    nout = cshift(nout, start - 1, dim=2)
  end subroutine open_at_gap

  !> The rows first..last of mo%P, the entries above 1e-16 of their row's
  !> largest (pi_h^1 decays exponentially away from the diagonal: the
  !> dropped part is below round-off), in increasing j.  P is (ns, nm) and
  !> column-major: it is read column by column, three passes (row maxima,
  !> counts, entries), never along its rows.
  subroutine projection_rows(mo, pr)
    type(mortar_t), intent(in) :: mo
    type(projection_rows_t), intent(out) :: pr
    real(dp), allocatable :: drop(:)
    integer, allocatable :: next(:)
    integer :: i, j, f, l
    f = mo%first
    l = mo%last
    allocate(drop(f:l), source=0.0_dp)
    do j = 1, size(mo%P, 2)
      do i = f, l
        drop(i) = max(drop(i), abs(mo%P(i, j)))
      end do
    end do
    drop = 1.0e-16_dp * drop
    allocate(pr%ptr(f:l + 1), source=0)
    do j = 1, size(mo%P, 2)
      do i = f, l
        if (abs(mo%P(i, j)) > drop(i)) pr%ptr(i + 1) = pr%ptr(i + 1) + 1
      end do
    end do
    pr%ptr(f) = 1
    do i = f, l
      pr%ptr(i + 1) = pr%ptr(i + 1) + pr%ptr(i)
    end do
    allocate(pr%col(pr%ptr(l + 1) - 1), pr%val(pr%ptr(l + 1) - 1))
    next = pr%ptr(f:l)
    do j = 1, size(mo%P, 2)
      do i = f, l
        if (abs(mo%P(i, j)) > drop(i)) then
          pr%col(next(i - f + 1)) = j
          pr%val(next(i - f + 1)) = mo%P(i, j)
          next(i - f + 1) = next(i - f + 1) + 1
        end if
      end do
    end do
  end subroutine projection_rows

  !> mcov(j) = integral of master hat j over the covered part of the slave
  !> zone (sub-segments: chi is linear in the slave coordinate on each; the
  !> rule of segment_rule, exact with the radial weight too).
  !>   xs (in) (2, ns) the slave polyline
  subroutine covered_master_integrals(mo, xs, mcov)
    type(mortar_t), intent(in) :: mo
    real(dp), intent(in) :: xs(:,:)
    real(dp), allocatable, intent(out) :: mcov(:)
    integer :: k, f, e, q, nq
    real(dp) :: rm, sq(4), wq(4), xi(4)
    allocate(mcov(mo%nm), source=0.0_dp)
    if (mo%first == 0) return
    do k = 1, mo%inter%nsub
      f = mo%inter%master_seg(k)
      e = mo%inter%slave_seg(k)
      call segment_rule(xs(:, e), xs(:, e + 1), mo%inter%s(1, k), mo%inter%s(2, k), 1, mo%axisymmetric, sq, wq, nq, xi)
      do q = 1, nq                                              ! chi_{f+1} at the point
        rm = 0.5_dp * (mo%inter%r(1, k) + mo%inter%r(2, k)) + (0.5_dp * xi(q)) * (mo%inter%r(2, k) - mo%inter%r(1, k))
        mcov(f) = mcov(f) + wq(q) * (1.0_dp - rm)
        mcov(f + 1) = mcov(f + 1) + wq(q) * rm
      end do
    end do
  end subroutine covered_master_integrals

  !> Slave nodes that carry a constraint row: the nodes first..last of the
  !> effective zone, a cut end's row standing for the point where the zone ends
  !> inside the end segment (mortar_operator, 2.).
  subroutine constrained_nodes(mo, row)
    type(mortar_t), intent(in) :: mo
    logical, allocatable, intent(out) :: row(:)
    allocate(row(mo%ns), source=.false.)
    if (mo%first == 0) return
    row(mo%first:mo%last) = .true.
  end subroutine constrained_nodes

  !> A pair has tangential rows when its friction bound is not identically
  !> zero (mu = 0 and tresca = 0 are the frictionless problem, exactly).
  pure logical function has_friction(spec)
    type(pair_spec_t), intent(in) :: spec
    has_friction = spec%mu > 0.0_dp .or. spec%tresca > 0.0_dp
  end function has_friction

end module contact_pair
