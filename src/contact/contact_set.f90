!> contact_set: the discrete contact constraints of all CONTACT pairs, the
!> paper's K_h = { v_h : v1.n1 + pi_h^1(v2.n2) <= 0 on Gamma_c } (eq. (10))
!> extended to an initial gap, in matrix form  B u <= g.
!>
!> Row i of B belongs to a slave node x_i of the effective contact zone of its
!> pair (see mortar_operator):
!>     B_i u = n_i . u1(x_i) - n_i . sum_j P_ij u2(y_j)      (n2 = -n1)
!> with n_i the slave nodal normal and P the matrix of pi_h^1; g_i = gap0_i.
!> A pair with friction (beyond the paper) also has tangential rows
!>     T_i u = t_i . u1(x_i) - t_i . sum_j P_ij u2(y_j),   t_i = (-n_y, n_x),
!> the mortar relative tangential displacement (slip) at slave node i, stored
!> after the rows of B in the same CSR arrays (rows nrow+1 .. nrow+ntan).
!> B is kept sparse by rows over a compact list of "contact dofs" (the global
!> dofs of the slave and master boundary nodes that B touches); entries of P
!> below 1e-16 of their row's largest entry are dropped (pi_h^1 decays
!> exponentially away from the diagonal; the dropped part is below round-off).
!>
!> Programming interface
!>   type(contact_set_t)   pairs, rows, B in CSR over contact dofs, g
!>   build_contact_set(bodies, specs, cs, err)   all pairs -> rows of B, g
module contact_set
  use kinds, only: dp
  use strings, only: int_to_str
  use errors, only: error_t, set_error
  use mesh, only: mesh_t, is_quadratic
  use body, only: body_t
  use boundary_chain, only: boundary_polyline, trace_chain
  use mortar_operator, only: mortar_t, build_mortar, zone_node_terms, zone_point, segment_rule
  use mortar_geometry, only: intersection_t, intersect_segments, common_normals
  use rigid_obstacle, only: rigid_shape_t, build_rigid_mortar, orient_shape, rigid_terms
  use mortar_quadratic, only: build_mortar_quadratic, quadratic_common_normals
  implicit none
  private
  public :: contact_set_t, pair_spec_t, contact_pair_t
  public :: build_contact_set, row_of_node, state_row_of_node, node_rows, node_traction, has_friction

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

  type :: contact_set_t
    integer :: npair = 0
    type(contact_pair_t), allocatable :: pair(:)
    integer :: nrow = 0                     !< constraints, all pairs
    integer, allocatable :: row_pair(:)     !< (nrow) pair of each row
    integer, allocatable :: row_node(:)     !< (nrow) index into the pair's slave polyline
    integer :: ncdof = 0                    !< contact dofs
    integer, allocatable :: cdof(:)         !< (ncdof) their global dofs, ascending
    integer, allocatable :: bptr(:)         !< (nrow+1) CSR row pointers of B
    integer, allocatable :: bcol(:)         !< column = index into cdof
    real(dp), allocatable :: bval(:)        !< values
    real(dp), allocatable :: g(:)           !< (nrow) initial gaps
    real(dp), allocatable :: weight(:)      !< (nrow) length a row's multiplier acts on: the pressure
                                            !< is mu / weight (int phi_i over the covered part)
    integer :: ntan = 0                     !< tangential rows (pairs with friction), rows
                                            !< nrow+1 .. nrow+ntan of the CSR arrays
    integer, allocatable :: tan_row(:)      !< (ntan) the normal row of each tangential row
    real(dp), allocatable :: tan_mu(:)      !< (ntan) Coulomb coefficient, 0 for Tresca
    real(dp), allocatable :: tan_bound(:)   !< (ntan) Tresca force bound tresca * weight, 0 for Coulomb
  end type contact_set_t

  !> The rows first..last of a pair's projection P, its entries above 1e-16
  !> of their row's largest, in increasing master index (CSR).
  type :: projection_rows_t
    integer, allocatable :: ptr(:)         !< (first:last+1) row pointers
    integer, allocatable :: col(:)         !< master polyline index j
    real(dp), allocatable :: val(:)        !< P_ij
  end type projection_rows_t

contains

  !> Build the constraint rows of every pair.
  !>   bodies (in)  the bodies, dof0 set
  !>   specs  (in)  (npair) the CONTACT statements, resolved
  !>   cs     (out) the contact set
  !>   err    (out) allocated on failure; err%pair is the pair (1-based, its CONTACT statement)
  subroutine build_contact_set(bodies, specs, cs, err)
    type(body_t), intent(in) :: bodies(:)
    type(pair_spec_t), intent(in) :: specs(:)
    type(contact_set_t), intent(out) :: cs
    type(error_t), allocatable, intent(out) :: err
    integer :: ip, i, j, r, nm, nnz, k, c, q, d0s, d0m, maxdof, ps, pm
    real(dp), allocatable :: mcov_q(:)
    integer, allocatable :: mnodes(:), colmap(:)
    real(dp), allocatable :: xm(:,:), nsl(:,:), nms(:,:), pairing(:,:)
    character(len=:), allocatable :: why
    type(error_t), allocatable :: merr
    logical, allocatable :: touched(:)
    type(projection_rows_t), allocatable :: prj(:)

    cs%npair = size(specs)
    allocate(cs%pair(cs%npair), prj(cs%npair))
    cs%nrow = 0
    do ip = 1, cs%npair
      associate(pr => cs%pair(ip), sp => specs(ip))
        pr%spec = sp
        call boundary_polyline(bodies(sp%slave_body), sp%slave_bnd, pr%snode, pr%xs, nsl, why)
        if (len(why) > 0) then
          call set_error(err, 'the slave boundary cannot be used: ' // why, 2)
          err%pair = ip
          return
        end if
        if (sp%rigid > 0) then
          ! a rigid master: its exact shape, no master mesh (rigid_obstacle)
          call orient_shape(pr%spec%shape, pr%xs, nsl)
          call build_rigid_mortar(pr%xs, nsl, pr%spec%shape, pr%mortar, merr)
          if (allocated(merr)) then
            call set_error(err, merr%message, merr%status)
            err%pair = ip
            return
          end if
          allocate(pr%mnode(0), pr%mcov(0))
          call finish_rows()
          if (allocated(err)) return
          cs%nrow = cs%nrow + pr%nrow
          cycle
        end if
        call boundary_polyline(bodies(sp%master_body), sp%master_bnd, mnodes, xm, nms, why)
        if (len(why) > 0) then
          call set_error(err, 'the master boundary cannot be used: ' // why, 2)
          err%pair = ip
          return
        end if
        pr%mnode = mnodes
        ! a closed slave curve that the master does not cover all round is
        ! opened where it is not covered (its zone has two ends)
        if (pr%snode(1) == pr%snode(size(pr%snode))) call open_at_gap(pr%snode, pr%xs, nsl, xm, nms)
        pr%quadratic = is_quadratic(bodies(sp%slave_body)%mesh) .or. is_quadratic(bodies(sp%master_body)%mesh)
        if (pr%quadratic) then
          ! quadratic traces (mortar_quadratic): the chains with their mid-side nodes
          call trace_chain(bodies(sp%slave_body)%mesh, sp%slave_bnd, pr%snode, ps)
          call trace_chain(bodies(sp%master_body)%mesh, sp%master_bnd, mnodes, pm)
          pr%xs = bodies(sp%slave_body)%mesh%x(:, pr%snode)
          xm = bodies(sp%master_body)%mesh%x(:, mnodes)
          pr%mnode = mnodes
          pr%degree = [ps, pm]
          if (has_friction(sp)) then      ! rows along the common normal, as below
            call quadratic_common_normals(pr%xs, ps, nsl, xm, pm, nms, pairing, pr%slave_weight)
            call build_mortar_quadratic(pr%xs, ps, nsl, xm, pm, nms, sp%gap_zero, pr%mortar, mcov_q, merr, &
                                        pairing=pairing, axisymmetric=bodies(sp%slave_body)%axisymmetric)
          else
            call build_mortar_quadratic(pr%xs, ps, nsl, xm, pm, nms, sp%gap_zero, pr%mortar, mcov_q, merr, &
                                        axisymmetric=bodies(sp%slave_body)%axisymmetric)
          end if
        else if (has_friction(sp)) then
          ! friction: the pair's rows along the common normal, which pairs the
          ! points that meet and leaves the normal approach out of the slip
          call common_normals(pr%xs, nsl, xm, nms, pairing, pr%slave_weight)
          call build_mortar(pr%xs, nsl, xm, nms, sp%gap_zero, pr%mortar, merr, pairing, &
                            axisymmetric=bodies(sp%slave_body)%axisymmetric)
        else
          call build_mortar(pr%xs, nsl, xm, nms, sp%gap_zero, pr%mortar, merr, &
                            axisymmetric=bodies(sp%slave_body)%axisymmetric)
        end if
        if (allocated(merr)) then
          call set_error(err, merr%message, merr%status)
          err%pair = ip
          return
        end if
        call finish_rows()
        if (allocated(err)) return
        if (mnodes(1) == mnodes(size(mnodes)) .and. allocated(pr%mortar%P)) then
          ! a closed master curve: its last hat is its first
          pr%mortar%P(:, 1) = pr%mortar%P(:, 1) + pr%mortar%P(:, size(mnodes))
          pr%mortar%P(:, size(mnodes)) = 0.0_dp
        end if
        if (pr%quadratic) then
          call move_alloc(mcov_q, pr%mcov)
        else
          call covered_master_integrals(pr%mortar, pr%xs, pr%mcov)
        end if
        if (mnodes(1) == mnodes(size(mnodes))) then
          pr%mcov(1) = pr%mcov(1) + pr%mcov(size(mnodes))
          pr%mcov(size(mnodes)) = 0.0_dp
        end if
        ! one slave segment: the multiplier space is the constants (both end
        ! segments at once), so one mean-value row replaces the two nodal ones
        pr%single = pr%mortar%first > 0 .and. pr%mortar%last == pr%mortar%first + 1 .and. .not. pr%quadratic
        if (pr%single) pr%nrow = 1
        pr%fold = [pr%mortar%cut(1) > 0.0_dp, pr%mortar%cut(2) < 1.0_dp] .and. .not. pr%single
        pr%axis_fold = pr%mortar%axis_end .and. pr%mortar%degree == 2
        ! the projection lives on in the rows of B and T: the dense (ns, nm)
        ! matrix P is not kept (5 MB for 852 x 741 nodes)
        if (pr%mortar%first > 0 .and. .not. pr%single) call projection_rows(pr%mortar, prj(ip))
        if (allocated(pr%mortar%P)) deallocate(pr%mortar%P)
        cs%nrow = cs%nrow + pr%nrow
      end associate
    end do

    ! tangential rows: one per normal row of a pair with a non-zero friction bound
    cs%ntan = 0
    do ip = 1, cs%npair
      if (has_friction(cs%pair(ip)%spec)) cs%ntan = cs%ntan + cs%pair(ip)%nrow
    end do

    ! contact dofs: mark every dof B (and T) touches
    maxdof = 0
    do i = 1, size(bodies)
      maxdof = max(maxdof, bodies(i)%dof0 + 2 * bodies(i)%mesh%nnode)
    end do
    do ip = 1, cs%npair                              ! a RIGID's dofs follow the bodies'
      if (cs%pair(ip)%spec%rigid > 0) maxdof = max(maxdof, cs%pair(ip)%spec%shape%dof0 + 3)
    end do
    allocate(touched(maxdof), source=.false.)
    allocate(cs%row_pair(cs%nrow), cs%row_node(cs%nrow), cs%g(cs%nrow), cs%bptr(cs%nrow + cs%ntan + 1), &
             cs%weight(cs%nrow), cs%tan_row(cs%ntan), cs%tan_mu(cs%ntan), cs%tan_bound(cs%ntan))
    nnz = 0
    do ip = 1, cs%npair
      call mark_pair_dofs(.false.)
      if (has_friction(cs%pair(ip)%spec)) call mark_pair_dofs(.true.)
      if (cs%pair(ip)%spec%finite) call mark_finite_dofs()
    end do
    cs%ncdof = count(touched)
    allocate(cs%cdof(cs%ncdof), colmap(maxdof))
    colmap = 0
    k = 0
    do i = 1, maxdof
      if (touched(i)) then
        k = k + 1
        cs%cdof(k) = i
        colmap(i) = k
      end if
    end do

    ! rows of B, then of T (CSR over contact dofs)
    allocate(cs%bcol(nnz), cs%bval(nnz))
    k = 0
    cs%bptr(1) = 1
    do ip = 1, cs%npair
      if (cs%pair(ip)%nrow == 0) cycle
      r = cs%pair(ip)%row0
      call fill_pair_rows(.false.)
    end do
    r = cs%nrow
    do ip = 1, cs%npair
      if (cs%pair(ip)%nrow == 0 .or. .not. has_friction(cs%pair(ip)%spec)) cycle
      do i = 1, cs%pair(ip)%nrow                      ! tangential row r+i belongs to normal row row0+i
        cs%tan_row(r - cs%nrow + i) = cs%pair(ip)%row0 + i
        cs%tan_mu(r - cs%nrow + i) = cs%pair(ip)%spec%mu
        cs%tan_bound(r - cs%nrow + i) = cs%pair(ip)%spec%tresca * cs%weight(cs%pair(ip)%row0 + i)
      end do
      call fill_pair_rows(.true.)
    end do
  contains

    !> The checks and rows of pair ip once its mortar operator is built: the
    !> initial penetration (unless allowed), its first row, the constrained
    !> slave nodes (a periodic zone's last node is its first), nrow.  err is
    !> set (with the pair's number) on a penetration.
    subroutine finish_rows()
      associate(pr => cs%pair(ip))
        if (.not. pr%spec%interference) then
          call check_penetration(pr, err)
          if (allocated(err)) then
            err%pair = ip
            return
          end if
        end if
        pr%row0 = cs%nrow
        call constrained_nodes(pr%mortar, pr%row)
        pr%closed = pr%snode(1) == pr%snode(size(pr%snode))
        if (pr%closed .and. pr%mortar%first == 1 .and. pr%mortar%last == size(pr%snode)) &
          pr%row(size(pr%snode)) = .false.                 ! periodic: the last node is the first
        pr%nrow = count(pr%row)
      end associate
    end subroutine finish_rows

    !> Open the next row r, for slave node i of pair ip: a normal row also
    !> records its pair, node, weight int psi_i and initial gap.
    subroutine open_row(mo, i, tangent)
      type(mortar_t), intent(in) :: mo
      integer, intent(in) :: i
      logical, intent(in) :: tangent
      r = r + 1
      if (tangent) return
      cs%weight(r) = mo%zone_weight(i)
      cs%row_pair(r) = ip
      cs%row_node(r) = i
      cs%g(r) = mo%gap0(i)
    end subroutine open_row

    !> Direction of the rows of slave node i: the nodal normal n_i, or the
    !> tangent t_i = (-n_y, n_x) (n turned a quarter turn anticlockwise).
    pure function row_direction(mo, i, tangent) result(v)
      type(mortar_t), intent(in) :: mo
      integer, intent(in) :: i
      logical, intent(in) :: tangent
      real(dp) :: v(2)
      v = mo%normal(:, i)
      if (tangent) v = [-mo%normal(2, i), mo%normal(1, i)]
    end function row_direction

    !> A finite-sliding pair: both dofs of every node of its slave and master
    !> boundaries, whether a row reaches them now or not.  The pairing moves
    !> with the bodies, the factorization's contact dofs (its trailing block)
    !> must not: every node the zone can reach is one of them from the start.
    subroutine mark_finite_dofs()
      associate(pr => cs%pair(ip))
        d0s = bodies(pr%spec%slave_body)%dof0
        do i = 1, size(pr%snode)
          touched(d0s + 2 * pr%snode(i) - 1:d0s + 2 * pr%snode(i)) = .true.
        end do
        if (pr%spec%rigid > 0) then
          touched(pr%spec%shape%dof0 + 1:pr%spec%shape%dof0 + 3) = .true.
          return
        end if
        d0m = bodies(pr%spec%master_body)%dof0
        do j = 1, size(pr%mnode)
          touched(d0m + 2 * pr%mnode(j) - 1:d0m + 2 * pr%mnode(j)) = .true.
        end do
      end associate
    end subroutine mark_finite_dofs

    !> Mark the dofs the rows of pair ip touch (normal or tangential rows) and
    !> count their entries in nnz.
    subroutine mark_pair_dofs(tangent)
      logical, intent(in) :: tangent
      real(dp) :: v(2), sc(3)
      integer :: sn(3), nt
      associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
        if (pr%nrow == 0) return
        d0s = bodies(pr%spec%slave_body)%dof0
        if (pr%spec%rigid > 0) then                  ! slave terms, then the rigid's three dofs
          do i = mo%first, mo%last
            if (.not. pr%row(i)) cycle
            v = row_direction(mo, i, tangent)
            do c = 1, 2
              ! finite sliding keeps both: the normals turn, the factor's contact dofs stay
              if (v(c) == 0.0_dp .and. .not. pr%spec%finite) cycle
              touched(d0s + 2 * (pr%snode(i) - 1) + c) = .true.
              nnz = nnz + 1
            end do
            nnz = nnz + 3
          end do
          touched(pr%spec%shape%dof0 + 1:pr%spec%shape%dof0 + 3) = .true.
          return
        end if
        d0m = bodies(pr%spec%master_body)%dof0
        nm = size(pr%mnode)
        if (pr%single) then
          do c = 1, 2
            do i = mo%first, mo%last
              touched(d0s + 2 * (pr%snode(i) - 1) + c) = .true.
            end do
            do j = 1, nm
              if (pr%mcov(j) > 0.0_dp) touched(d0m + 2 * (pr%mnode(j) - 1) + c) = .true.
            end do
          end do
          nnz = nnz + 2 * (2 + count(pr%mcov > 0.0_dp))
          return
        end if
        do i = mo%first, mo%last
          if (.not. pr%row(i)) cycle
          v = row_direction(mo, i, tangent)
          call zone_node_terms(mo, i, sn, sc, nt)
          do c = 1, 2                       ! a dof is a contact dof only where its coefficient is non-zero
            if (v(c) == 0.0_dp) cycle
            touched(d0s + 2 * (pr%snode(sn(1:nt)) - 1) + c) = .true.
            nnz = nnz + nt + prj(ip)%ptr(i + 1) - prj(ip)%ptr(i)
            do q = prj(ip)%ptr(i), prj(ip)%ptr(i + 1) - 1
              touched(d0m + 2 * (pr%mnode(prj(ip)%col(q)) - 1) + c) = .true.
            end do
          end do
        end do
      end associate
    end subroutine mark_pair_dofs

    !> The rows of pair ip after row r (r advanced): normal rows with their
    !> gaps and weights, or tangential rows.
    subroutine fill_pair_rows(tangent)
      logical, intent(in) :: tangent
      real(dp) :: v(2), sc(3)
      integer :: sn(3), nt, t
      associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
        d0s = bodies(pr%spec%slave_body)%dof0
        if (pr%spec%rigid > 0) then
          call rigid_rows(tangent)
          return
        end if
        d0m = bodies(pr%spec%master_body)%dof0
        nm = size(pr%mnode)
        if (pr%single) then
          call single_row(tangent)
          return
        end if
        do i = mo%first, mo%last
          if (.not. pr%row(i)) cycle
          call open_row(mo, i, tangent)
          v = row_direction(mo, i, tangent)
          call zone_node_terms(mo, i, sn, sc, nt)
          do c = 1, 2
            if (v(c) == 0.0_dp) cycle
            do t = 1, nt                                ! + v_i . u1(x_i), at a cut end interpolated
              k = k + 1
              cs%bcol(k) = colmap(d0s + 2 * (pr%snode(sn(t)) - 1) + c)
              cs%bval(k) = v(c) * sc(t)
            end do
            do q = prj(ip)%ptr(i), prj(ip)%ptr(i + 1) - 1   ! - v_i . sum_j P_ij u2(y_j)
              k = k + 1
              cs%bcol(k) = colmap(d0m + 2 * (pr%mnode(prj(ip)%col(q)) - 1) + c)
              cs%bval(k) = -v(c) * prj(ip)%val(q)
            end do
          end do
          cs%bptr(r + 1) = k + 1
        end do
      end associate
    end subroutine fill_pair_rows

    !> The rows of pair ip against a RIGID (rigid_obstacle): v_i . u1(x_i) on
    !> the slave node, minus the rigid motion's v_i . U(x_i) on its three dofs.
    subroutine rigid_rows(tangent)
      logical, intent(in) :: tangent
      real(dp) :: v(2), rt(3)
      integer :: t
      associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
        do i = mo%first, mo%last
          if (.not. pr%row(i)) cycle
          call open_row(mo, i, tangent)
          if (.not. tangent .and. pr%spec%gap_zero) cs%g(r) = 0.0_dp
          v = row_direction(mo, i, tangent)
          do c = 1, 2
            if (v(c) == 0.0_dp .and. .not. pr%spec%finite) cycle
            k = k + 1
            cs%bcol(k) = colmap(d0s + 2 * (pr%snode(i) - 1) + c)
            cs%bval(k) = v(c)
          end do
          rt = rigid_terms(pr%spec%shape, pr%xs(:, i), v)
          do t = 1, 3
            k = k + 1
            cs%bcol(k) = colmap(pr%spec%shape%dof0 + t)
            cs%bval(k) = -rt(t)
          end do
          cs%bptr(r + 1) = k + 1
        end do
      end associate
    end subroutine rigid_rows

    !> The mean-value row of a one-segment zone (pair ip, row r+1):
    !>   (1/L) int_cov (u1 - u2).n ds <= (1/L) int_cov (y - x).n ds,
    !> n the segment's normal, L the covered length; with tangent, the same
    !> mean of (u1 - u2).t with t the segment's tangent.
    subroutine single_row(tangent)
      logical, intent(in) :: tangent
      real(dp) :: nseg(2), len_cov, gsum
      integer :: ii
      associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
        nseg = mo%normal(:, mo%first) + mo%normal(:, mo%last)
        nseg = nseg / norm2(nseg)
        if (tangent) nseg = [-nseg(2), nseg(1)]
        len_cov = sum(pr%mcov)
        r = r + 1
        if (.not. tangent) then
          cs%row_pair(r) = ip
          cs%row_node(r) = mo%first
          cs%weight(r) = len_cov
        end if
        gsum = 0.0_dp
        do c = 1, 2
          do ii = mo%first, mo%last                    ! + int phi_i (u1_i . n)
            k = k + 1
            cs%bcol(k) = colmap(d0s + 2 * (pr%snode(ii) - 1) + c)
            cs%bval(k) = nseg(c) * mo%covered_weight(ii) / len_cov
            gsum = gsum - nseg(c) * mo%covered_weight(ii) * pr%xs(c, ii)
          end do
          do j = 1, nm                                 ! - int chi_j (u2_j . n)
            if (.not. (pr%mcov(j) > 0.0_dp)) cycle
            k = k + 1
            cs%bcol(k) = colmap(d0m + 2 * (pr%mnode(j) - 1) + c)
            cs%bval(k) = -nseg(c) * pr%mcov(j) / len_cov
            gsum = gsum + nseg(c) * pr%mcov(j) * bodies(pr%spec%master_body)%mesh%x(c, pr%mnode(j))
          end do
        end do
        if (.not. tangent) then
          cs%g(r) = 0.0_dp
          if (.not. pr%spec%gap_zero) cs%g(r) = gsum / len_cov
        end if
        cs%bptr(r + 1) = k + 1
      end associate
    end subroutine single_row

  end subroutine build_contact_set

  !> An initial penetration deeper than the slave elements beside the node
  !> (the mean length of its zone segments) is an input error (status 2): the
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
        'smaller than the slave elements, expected; interference=allow accepts it)', 2)
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

  !> The rows that slave node i of pair ip reports in the outputs: its own
  !> row first, then the rows of cut zone ends folded onto it (nr = 0: none).
  !> The node's pressure is the sum of their multipliers over the sum of their
  !> weights, int (phi_a + phi_i) over the covered part: the mean pressure
  !> on the support of the multiplier basis function psi of the end segment.
  !> On a quadratic trace the cut element's mid-side node reports its two zone
  !> points' rows, and a corner on the axis (whose hat weighs nothing) its own
  !> and its mid-side neighbour's.
  pure subroutine node_rows(cs, ip, i, rows, nr)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip, i
    integer, intent(out) :: rows(3), nr
    rows = 0
    nr = 0
    rows(1) = row_of_node(cs, ip, i)
    if (rows(1) == 0) return
    nr = 1
    associate(pr => cs%pair(ip))
      if (pr%fold(1) .and. i == pr%mortar%first + 1) then
        nr = nr + 1
        rows(nr) = pr%row0 + 1
      end if
      if (pr%fold(2) .and. i == pr%mortar%last - 1) then
        nr = nr + 1
        rows(nr) = pr%row0 + pr%nrow
      end if
      ! the node on the axis of a quadratic trace: its hat weighs int phi 2 pi r ds = 0,
      ! its multiplier is read with the mid-side node's next to it
      if (pr%axis_fold(1) .and. i == pr%mortar%first) then
        nr = nr + 1
        rows(nr) = row_of_node(cs, ip, i + 1)
      end if
      if (pr%axis_fold(2) .and. i == pr%mortar%last) then
        nr = nr + 1
        rows(nr) = row_of_node(cs, ip, i - 1)
      end if
    end associate
  end subroutine node_rows

  !> The traction slave node i of pair ip reports: the forces of its rows
  !> (node_rows) over their weights; 0 when it has no row.
  !>   force (in) (nrow) a force per normal row (mu, or the tangential force of its row)
  pure real(dp) function node_traction(cs, ip, i, force) result(p)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip, i
    real(dp), intent(in) :: force(:)
    integer :: rows(3), nr
    call node_rows(cs, ip, i, rows, nr)
    p = 0.0_dp
    if (nr > 0) p = sum(force(rows(1:nr))) / sum(cs%weight(rows(1:nr)))
  end function node_traction

  !> The normal row whose slip and friction state slave node i of pair ip
  !> reports: its own (row_of_node), or on a quadratic trace's node on the
  !> axis, whose hat weighs nothing (no friction bound of its own), the
  !> mid-side neighbour's, with which it reports its tractions (node_rows).
  pure integer function state_row_of_node(cs, ip, i) result(r)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip, i
    r = row_of_node(cs, ip, i)
    if (r == 0) return
    if (cs%pair(ip)%axis_fold(1) .and. i == cs%pair(ip)%mortar%first) r = row_of_node(cs, ip, i + 1)
    if (cs%pair(ip)%axis_fold(2) .and. i == cs%pair(ip)%mortar%last) r = row_of_node(cs, ip, i - 1)
  end function state_row_of_node

  !> Constraint row of slave node i of pair ip, 0 when it has none or when
  !> it is a cut zone end reported on its neighbour (node_rows).
  pure integer function row_of_node(cs, ip, i) result(r)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip, i
    r = 0
    if (.not. cs%pair(ip)%row(i)) return
    if (cs%pair(ip)%fold(1) .and. i == cs%pair(ip)%mortar%first) return
    if (cs%pair(ip)%fold(2) .and. i == cs%pair(ip)%mortar%last) return
    if (cs%pair(ip)%single) then
      r = cs%pair(ip)%row0 + 1
      return
    end if
    r = cs%pair(ip)%row0 + count(cs%pair(ip)%row(1:i))
  end function row_of_node

end module contact_set
