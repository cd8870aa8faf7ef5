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
!> dofs of the slave and master boundary nodes that B touches).  Each pair,
!> its operator and the rows of P that B takes are built by contact_pair.
!>
!> Programming interface
!>   type(contact_set_t)   pairs, rows, B in CSR over contact dofs, g
!>   type(pair_spec_t), type(contact_pair_t), has_friction(spec)   contact_pair's
!>   build_contact_set(bodies, specs, cs, err)   all pairs -> rows of B, g
!>   node_rows, node_traction, row_of_node, state_row_of_node
!>                         the rows a slave node reports, and its traction
module contact_set
  use kinds, only: dp
  use errors, only: error_t
  use body, only: body_t
  use mortar_operator, only: mortar_t, zone_node_terms
  use rigid_obstacle, only: rigid_terms
  use contact_pair, only: pair_spec_t, contact_pair_t, projection_rows_t, build_contact_pair, has_friction
  implicit none
  private
  public :: contact_set_t, pair_spec_t, contact_pair_t
  public :: build_contact_set, row_of_node, state_row_of_node, node_rows, node_traction, has_friction

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
    integer :: ip, nnz
    integer, allocatable :: colmap(:)
    type(projection_rows_t), allocatable :: prj(:)

    cs%npair = size(specs)
    allocate(cs%pair(cs%npair), prj(cs%npair))
    cs%nrow = 0
    do ip = 1, cs%npair
      call build_contact_pair(bodies, specs(ip), cs%nrow, cs%pair(ip), prj(ip), err)
      if (allocated(err)) then
        err%pair = ip
        return
      end if
      cs%nrow = cs%nrow + cs%pair(ip)%nrow
    end do
    ! tangential rows: one per normal row of a pair with a non-zero friction bound
    cs%ntan = 0
    do ip = 1, cs%npair
      if (has_friction(cs%pair(ip)%spec)) cs%ntan = cs%ntan + cs%pair(ip)%nrow
    end do
    call number_contact_dofs(bodies, cs%pair, prj, cs%cdof, colmap, nnz)
    cs%ncdof = size(cs%cdof)
    call assemble_rows(bodies, prj, colmap, nnz, cs)
    call set_friction_bounds(cs)
  end subroutine build_contact_set

  !> The contact dofs: every dof a row of B or T has a coefficient on, and
  !> both dofs of every boundary node of a finite-sliding pair.
  !>   bodies (in) the bodies;  pairs (in) (npair) the pairs;  prj (in) (npair) their rows of P
  !>   cdof   (out) (ncdof) the contact dofs' global numbers, ascending
  !>   colmap (out) (maxdof) the column of each global dof in B, 0 when it is not a contact dof
  !>   nnz    (out) the entries of B and T
  subroutine number_contact_dofs(bodies, pairs, prj, cdof, colmap, nnz)
    type(body_t), intent(in) :: bodies(:)
    type(contact_pair_t), intent(in) :: pairs(:)
    type(projection_rows_t), intent(in) :: prj(:)
    integer, allocatable, intent(out) :: cdof(:), colmap(:)
    integer, intent(out) :: nnz
    logical, allocatable :: touched(:)
    integer :: maxdof, i, ip, k

    maxdof = 0
    do i = 1, size(bodies)
      maxdof = max(maxdof, bodies(i)%dof0 + 2 * bodies(i)%mesh%nnode)
    end do
    do ip = 1, size(pairs)                           ! a RIGID's dofs follow the bodies'
      if (pairs(ip)%spec%rigid > 0) maxdof = max(maxdof, pairs(ip)%spec%shape%dof0 + 3)
    end do
    allocate(touched(maxdof), source=.false.)
    nnz = 0
    do ip = 1, size(pairs)
      call mark_pair_dofs(bodies, pairs(ip), prj(ip), .false., touched, nnz)
      if (has_friction(pairs(ip)%spec)) call mark_pair_dofs(bodies, pairs(ip), prj(ip), .true., touched, nnz)
      if (pairs(ip)%spec%finite) call mark_finite_dofs(bodies, pairs(ip), touched)
    end do
    allocate(cdof(count(touched)), colmap(maxdof))
    colmap = 0
    k = 0
    do i = 1, maxdof
      if (touched(i)) then
        k = k + 1
        cdof(k) = i
        colmap(i) = k
      end if
    end do
  end subroutine number_contact_dofs

  !> Mark the dofs the rows of a pair touch (normal or tangential rows) and
  !> count their entries.
  !>   bodies (in) the bodies;  pr (in) the pair;  prj (in) its rows of P
  !>   tangent (in) the tangential rows, else the normal ones
  !>   touched (inout) (maxdof) the contact dofs found so far;  nnz (inout) the entries so far
  subroutine mark_pair_dofs(bodies, pr, prj, tangent, touched, nnz)
    type(body_t), intent(in) :: bodies(:)
    type(contact_pair_t), intent(in) :: pr
    type(projection_rows_t), intent(in) :: prj
    logical, intent(in) :: tangent
    logical, intent(inout) :: touched(:)
    integer, intent(inout) :: nnz
    real(dp) :: v(2), sc(3)
    integer :: sn(3), nt, d0s, d0m, i, j, c, q
    if (pr%nrow == 0) return
    associate(mo => pr%mortar)
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
      if (pr%single) then
        do c = 1, 2
          do i = mo%first, mo%last
            touched(d0s + 2 * (pr%snode(i) - 1) + c) = .true.
          end do
          do j = 1, size(pr%mnode)
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
          nnz = nnz + nt + prj%ptr(i + 1) - prj%ptr(i)
          do q = prj%ptr(i), prj%ptr(i + 1) - 1
            touched(d0m + 2 * (pr%mnode(prj%col(q)) - 1) + c) = .true.
          end do
        end do
      end do
    end associate
  end subroutine mark_pair_dofs

  !> A finite-sliding pair: both dofs of every node of its slave and master
  !> boundaries, whether a row reaches them now or not.  The pairing moves
  !> with the bodies, the factorization's contact dofs (its trailing block)
  !> must not: every node the zone can reach is one of them from the start.
  !>   bodies (in) the bodies;  pr (in) the pair;  touched (inout) (maxdof) the contact dofs
  subroutine mark_finite_dofs(bodies, pr, touched)
    type(body_t), intent(in) :: bodies(:)
    type(contact_pair_t), intent(in) :: pr
    logical, intent(inout) :: touched(:)
    integer :: d0s, d0m, i, j
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
  end subroutine mark_finite_dofs

  !> The rows of B, then of T, in CSR over the contact dofs, with each normal
  !> row's pair, node, weight and initial gap.
  !>   bodies (in) the bodies;  prj (in) (npair) the pairs' rows of P
  !>   colmap (in) (maxdof) column of each global dof;  nnz (in) the entries
  !>   cs (inout) pairs, nrow and ntan on entry; the rows on exit
  subroutine assemble_rows(bodies, prj, colmap, nnz, cs)
    type(body_t), intent(in) :: bodies(:)
    type(projection_rows_t), intent(in) :: prj(:)
    integer, intent(in) :: colmap(:), nnz
    type(contact_set_t), intent(inout) :: cs
    integer :: ip, r, k

    allocate(cs%row_pair(cs%nrow), cs%row_node(cs%nrow), cs%g(cs%nrow), cs%bptr(cs%nrow + cs%ntan + 1), &
             cs%weight(cs%nrow), cs%bcol(nnz), cs%bval(nnz))
    k = 0
    cs%bptr(1) = 1
    do ip = 1, cs%npair
      if (cs%pair(ip)%nrow == 0) cycle
      r = cs%pair(ip)%row0
      call fill_pair_rows(bodies, prj(ip), colmap, ip, .false., cs, r, k)
    end do
    r = cs%nrow
    do ip = 1, cs%npair
      if (cs%pair(ip)%nrow == 0 .or. .not. has_friction(cs%pair(ip)%spec)) cycle
      call fill_pair_rows(bodies, prj(ip), colmap, ip, .true., cs, r, k)
    end do
  end subroutine assemble_rows

  !> The bound of each tangential row, in the order of assemble_rows: tangential
  !> row i of a pair belongs to its normal row row0+i.  Against a RIGID, the
  !> row of a slave node on the axis (PLANE axisymmetric) acts on held dofs
  !> alone (the node's u_r, the RIGID's u_x and theta): its shear, zero by
  !> symmetry, gets the bound 0 (with any other, every value in the cone
  !> solves the step and the Newton systems are singular).
  !>   cs (inout) the rows and their weights on entry; tan_row, tan_mu, tan_bound on exit
  subroutine set_friction_bounds(cs)
    type(contact_set_t), intent(inout) :: cs
    integer :: ip, i, t, node
    logical :: on_axis
    allocate(cs%tan_row(cs%ntan), cs%tan_mu(cs%ntan), cs%tan_bound(cs%ntan))
    t = 0
    do ip = 1, cs%npair
      if (cs%pair(ip)%nrow == 0 .or. .not. has_friction(cs%pair(ip)%spec)) cycle
      associate(pr => cs%pair(ip))
        do i = 1, pr%nrow
          t = t + 1
          cs%tan_row(t) = pr%row0 + i
          cs%tan_mu(t) = pr%spec%mu
          cs%tan_bound(t) = pr%spec%tresca * cs%weight(pr%row0 + i)
          node = cs%row_node(pr%row0 + i)
          on_axis = (pr%mortar%axis_end(1) .and. node == pr%mortar%first) .or. &
                    (pr%mortar%axis_end(2) .and. node == pr%mortar%last)
          if (pr%spec%rigid > 0 .and. on_axis) then
            cs%tan_mu(t) = 0.0_dp
            cs%tan_bound(t) = 0.0_dp
          end if
        end do
      end associate
    end do
  end subroutine set_friction_bounds

  !> The rows of pair ip after row r: normal rows with their gaps and
  !> weights, or tangential rows.
  !>   bodies (in) the bodies;  prj (in) the pair's rows of P;  colmap (in) column of each global dof
  !>   ip (in) the pair;  tangent (in) tangential rows, else normal ones
  !>   cs (inout) the set, its rows up to r filled
  !>   r  (inout) the last row filled;  k (inout) the last entry filled
  subroutine fill_pair_rows(bodies, prj, colmap, ip, tangent, cs, r, k)
    type(body_t), intent(in) :: bodies(:)
    type(projection_rows_t), intent(in) :: prj
    integer, intent(in) :: colmap(:), ip
    logical, intent(in) :: tangent
    type(contact_set_t), intent(inout) :: cs
    integer, intent(inout) :: r, k
    real(dp) :: v(2), sc(3)
    integer :: sn(3), nt, t, d0s, d0m, i, c, q
    d0s = bodies(cs%pair(ip)%spec%slave_body)%dof0
    if (cs%pair(ip)%spec%rigid > 0) then
      call rigid_rows(d0s, colmap, ip, tangent, cs, r, k)
      return
    end if
    d0m = bodies(cs%pair(ip)%spec%master_body)%dof0
    if (cs%pair(ip)%single) then
      call single_row(d0s, d0m, bodies(cs%pair(ip)%spec%master_body)%mesh%x, colmap, ip, tangent, cs, r, k)
      return
    end if
    associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
      do i = mo%first, mo%last
        if (.not. pr%row(i)) cycle
        call open_row(ip, i, tangent, cs, r)
        v = row_direction(mo, i, tangent)
        call zone_node_terms(mo, i, sn, sc, nt)
        do c = 1, 2
          if (v(c) == 0.0_dp) cycle
          do t = 1, nt                                ! + v_i . u1(x_i), at a cut end interpolated
            k = k + 1
            cs%bcol(k) = colmap(d0s + 2 * (pr%snode(sn(t)) - 1) + c)
            cs%bval(k) = v(c) * sc(t)
          end do
          do q = prj%ptr(i), prj%ptr(i + 1) - 1       ! - v_i . sum_j P_ij u2(y_j)
            k = k + 1
            cs%bcol(k) = colmap(d0m + 2 * (pr%mnode(prj%col(q)) - 1) + c)
            cs%bval(k) = -v(c) * prj%val(q)
          end do
        end do
        cs%bptr(r + 1) = k + 1
      end do
    end associate
  end subroutine fill_pair_rows

  !> The rows of pair ip against a RIGID (rigid_obstacle): v_i . u1(x_i) on
  !> the slave node, minus the rigid motion's v_i . U(x_i) on its three dofs.
  !>   d0s (in) the slave body's first dof less one;  other arguments as fill_pair_rows
  subroutine rigid_rows(d0s, colmap, ip, tangent, cs, r, k)
    integer, intent(in) :: d0s, colmap(:), ip
    logical, intent(in) :: tangent
    type(contact_set_t), intent(inout) :: cs
    integer, intent(inout) :: r, k
    real(dp) :: v(2), rt(3)
    integer :: t, i, c
    associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
      do i = mo%first, mo%last
        if (.not. pr%row(i)) cycle
        call open_row(ip, i, tangent, cs, r)
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
  !>   d0s, d0m (in) the slave and master bodies' first dofs less one
  !>   xm (in) (2, nnode) the master body's node coordinates;  other arguments as fill_pair_rows
  subroutine single_row(d0s, d0m, xm, colmap, ip, tangent, cs, r, k)
    integer, intent(in) :: d0s, d0m, colmap(:), ip
    real(dp), intent(in) :: xm(:,:)
    logical, intent(in) :: tangent
    type(contact_set_t), intent(inout) :: cs
    integer, intent(inout) :: r, k
    real(dp) :: nseg(2), len_cov, gsum
    integer :: i, j, c
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
        do i = mo%first, mo%last                     ! + int phi_i (u1_i . n)
          k = k + 1
          cs%bcol(k) = colmap(d0s + 2 * (pr%snode(i) - 1) + c)
          cs%bval(k) = nseg(c) * mo%covered_weight(i) / len_cov
          gsum = gsum - nseg(c) * mo%covered_weight(i) * pr%xs(c, i)
        end do
        do j = 1, size(pr%mnode)                     ! - int chi_j (u2_j . n)
          if (.not. (pr%mcov(j) > 0.0_dp)) cycle
          k = k + 1
          cs%bcol(k) = colmap(d0m + 2 * (pr%mnode(j) - 1) + c)
          cs%bval(k) = -nseg(c) * pr%mcov(j) / len_cov
          gsum = gsum + nseg(c) * pr%mcov(j) * xm(c, pr%mnode(j))
        end do
      end do
      if (.not. tangent) then
        cs%g(r) = 0.0_dp
        if (.not. pr%spec%gap_zero) cs%g(r) = gsum / len_cov
      end if
      cs%bptr(r + 1) = k + 1
    end associate
  end subroutine single_row

  !> Open the next row r, for slave node i of pair ip: a normal row also
  !> records its pair, node, weight int psi_i and initial gap.
  !>   ip, i (in) the pair and its slave node;  tangent (in) a tangential row
  !>   cs (inout) the set;  r (inout) the last row, then this one
  subroutine open_row(ip, i, tangent, cs, r)
    integer, intent(in) :: ip, i
    logical, intent(in) :: tangent
    type(contact_set_t), intent(inout) :: cs
    integer, intent(inout) :: r
    r = r + 1
    if (tangent) return
    cs%weight(r) = cs%pair(ip)%mortar%zone_weight(i)
    cs%row_pair(r) = ip
    cs%row_node(r) = i
    cs%g(r) = cs%pair(ip)%mortar%gap0(i)
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
