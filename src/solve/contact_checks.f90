!> contact_checks: monitors that compare what a solved step did with what the
!> small-sliding contact model assumes, so that a run outside the model does
!> not end as a plain success (doc/theory.md, "Monitors of small sliding and
!> of the initial gap").
!>
!> Small sliding (CONTACT sliding=small, the default and the only kinematics
!> solved) pairs each slave point with the master point facing it in the
!> initial configuration and keeps that pairing, the gaps and the normals
!> through the run.  Two things it cannot see are measured here:
!>
!> 1. The slide.  For every active slave node x_i (status 1 in the contact
!>    table: multiplier above 1e-12 of the largest) the slide
!>    is the relative displacement along the slave surface,
!>        s_i = | (u_slave(x_i) - u_master(y_i)) . t_i |,
!>    y_i the master point nearest x_i in the initial configuration (for a
!>    RIGID the motion of its shape: U(x_i), or a circle's centre's, which
!>    a rolling cylinder's contact follows), t_i the unit
!>    tangent of the slave chain at x_i.  The run ends with exit 1 naming
!>    sliding=finite when s_i > max(h_i, a/4) at some node, h_i the slave
!>    element length there and a the half-width of the contiguous active
!>    zone that contains it, or when a row that only a slide can close is
!>    active: its direction more than 60 degrees from the slave surface's
!>    normal (a RIGID's end or corner met edge-on).  Why these bounds: a
!>    slide below one element moves the pairing by less than the mesh
!>    resolves anyway; a slide of a/4 moves the pressure field by an eighth
!>    of the zone's width, and beyond it the frozen pairing describes a zone
!>    that is no longer where the bodies touch (with friction: gross slip of
!>    a body held only by contact, an equilibrium that exists only in the
!>    frozen geometry).
!>
!> 2. Polygon gaps.  Two polygons inscribed in one curve start apart by the
!>    chords' sagittas, h^2 / (8 R), a gap that is not in the geometry.  A
!>    pair whose two chains are curved with nearly the same radius, one
!>    convex and one concave (they wrap each other), and whose initial gaps
!>    over the zone are all of one sign and no larger than twice the coarser
!>    chain's sagitta gets `warning polygon_gap` naming the remedies.
!>
!> Why it exists: what a solved step did, measured against what the
!> small-sliding rows assumed; the caller of each solved step asks once.  A
!> slide beyond small sliding returns an error_t of category error_model;
!> the polygon gaps are a warning (run_log).
!>
!> Programming interface
!>   check_contact_model(prob, u, mu, kstep, log, err)  the monitors after load step kstep
!>                                    (the last: also polygon gaps)
module contact_checks
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str
  use errors, only: error_t, set_error, error_model
  use run_log, only: log_t, add_warning
  use problem, only: problem_t, step_label
  use contact_set, only: row_of_node, contact_pair_t
  use rigid_obstacle, only: rigid_terms, shape_circle
  use mortar_geometry, only: mean_curvature
  use contact_zones, only: true_runs
  implicit none
  private
  public :: check_contact_model

  real(dp), parameter :: zone_fraction = 0.25_dp   ! a slide up to a/4 of the zone's half-width
  real(dp), parameter :: edge_on_cos = 0.5_dp      ! a row more than 60 degrees from the slave normal
  real(dp), parameter :: radius_match = 0.1_dp     ! two radii within 10 % are "the same curve"
  real(dp), parameter :: sag_factor = 2.0_dp       ! gaps up to twice the coarser chain's sagitta

contains

  !> The monitors after load step kstep: the slide of every small-sliding
  !> pair (error_model beyond it); after the last step also the polygon gaps
  !> (a warning).
  !>   u     (in)    (ndof) the step's displacement, global axes (unallocated: none)
  !>   mu    (in)    (nrow) its normal multipliers (unallocated: none)
  !>   kstep (in)    the load step just solved (prob%sc%steps: the last)
  !>   log   (inout) the polygon gaps' warnings
  !>   err   (out)   a pair slides beyond small sliding
  subroutine check_contact_model(prob, u, mu, kstep, log, err)
    type(problem_t), intent(in) :: prob
    real(dp), allocatable, intent(in) :: u(:), mu(:)
    integer, intent(in) :: kstep
    type(log_t), intent(inout) :: log
    type(error_t), allocatable, intent(out) :: err
    integer :: ip
    if (allocated(u) .and. allocated(mu)) then
      do ip = 1, prob%cs%npair
        if (prob%cs%pair(ip)%spec%finite) cycle      ! sliding=finite: the geometry follows the slide
        if (prob%cs%pair(ip)%nrow > 0) call check_sliding(prob, u, mu, ip, kstep, err)
        if (allocated(err)) return
      end do
    end if
    if (kstep < prob%sc%steps) return
    do ip = 1, prob%cs%npair
      call check_polygon_gap(prob, ip, log)
    end do
  end subroutine check_contact_model

  !> The slide of the active nodes of pair ip against max(h, a/4), and the
  !> edge-on rows (module header, 1.); exit 1 naming sliding=finite.
  !>   u (in) (ndof) the displacement, global axes;  mu (in) (nrow) the normal multipliers
  subroutine check_sliding(prob, u, mu, ip, kstep, err)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: u(:), mu(:)
    integer, intent(in) :: ip, kstep
    type(error_t), allocatable, intent(out) :: err
    logical, allocatable :: active(:)
    real(dp), allocatable :: arc(:), halfwidth(:)
    real(dp) :: t(2), nu(2), du(2), slide, cap, h, worst, ratio, mumax, worst_slide, worst_cap, worst_h
    integer :: ns, i, r, a, b, iworst
    logical :: edge_on, worst_edge
    associate(pr => prob%cs%pair(ip))
      ns = size(pr%snode)
      ! active as the outputs' status says: a multiplier above 1e-12 of the largest
      ! (a round-off one far from the zone is no contact)
      mumax = maxval(abs(mu))                  ! this pair has rows: mu is not empty
      allocate(active(ns), source=.false.)
      do i = 1, ns
        r = row_of_node(prob%cs, ip, i)
        if (r > 0) active(i) = mu(r) > 1.0e-12_dp * mumax
      end do
      if (.not. any(active)) return
      allocate(arc(ns), halfwidth(ns), source=0.0_dp)
      do i = 2, ns
        arc(i) = arc(i - 1) + norm2(pr%xs(:, i) - pr%xs(:, i - 1))
      end do
      call zone_halfwidths(active, arc, halfwidth)
      worst = 1.0_dp
      iworst = 0
      worst_edge = .false.
      do i = 1, ns
        if (.not. active(i)) cycle
        call neighbours(pr, i, a, b)
        t = pr%xs(:, b) - pr%xs(:, a)
        t = t / norm2(t)
        nu = [-t(2), t(1)]
        h = element_length(pr, i)
        du = relative_displacement(prob, u, pr, i)
        slide = abs(dot_product(du, t))
        cap = max(h, zone_fraction * halfwidth(i))
        ratio = slide / cap
        edge_on = abs(dot_product(pr%mortar%normal(:, i), nu)) < edge_on_cos
        ! the first edge-on node, else the largest ratio above 1
        if (.not. worst_edge .and. (edge_on .or. ratio > worst)) then
          worst_edge = edge_on
          iworst = i
          worst = ratio
          worst_slide = slide
          worst_cap = cap
          worst_h = h
        end if
      end do
      if (iworst == 0) return
      call set_error(err, sliding_text(prob, ip, kstep, pr%xs(:, iworst), worst_slide, worst_h, halfwidth(iworst), &
                                       worst_cap, worst_edge), error_model)
    end associate
  end subroutine check_sliding

  !> The half-width of the contact zone that each active node belongs to.  A
  !> zone is a run of active nodes; two runs separated by a hole shorter than
  !> the longer of them are one zone with a hole in it (a fine slave on a
  !> coarse master opens such holes; two separate contacts are farther apart
  !> than they are long).
  !>   active (in) (ns) the active nodes;  arc (in) (ns) arc length along the slave chain
  !>   halfwidth (out) (ns) half the zone's length on its nodes, 0 elsewhere
  subroutine zone_halfwidths(active, arc, halfwidth)
    logical, intent(in) :: active(:)
    real(dp), intent(in) :: arc(:)
    real(dp), intent(out) :: halfwidth(:)
    integer, allocatable :: first(:), last(:)
    integer :: k, nrun, z0
    call true_runs(active, first, last, nrun)      ! the runs of active nodes
    halfwidth = 0.0_dp
    z0 = 1
    do k = 1, nrun                                 ! runs z0..k form one zone until a wide hole
      if (k < nrun) then
        if (arc(first(k + 1)) - arc(last(k)) < max(arc(last(k)) - arc(first(k)), &
                                                   arc(last(k + 1)) - arc(first(k + 1)))) cycle
      end if
      halfwidth(first(z0):last(k)) = 0.5_dp * (arc(last(k)) - arc(first(z0)))
      z0 = k + 1
    end do
  end subroutine zone_halfwidths

  !> The diagnosis of a pair that slides beyond small sliding.
  function sliding_text(prob, ip, kstep, x, slide, h, halfwidth, cap, edge_on) result(t)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: ip, kstep
    real(dp), intent(in) :: x(2), slide, h, halfwidth, cap
    logical, intent(in) :: edge_on
    character(len=:), allocatable :: t
    t = prob%deck%file // ':' // int_to_str(prob%deck%contacts(ip)%line) // ': ' // step_label(prob, kstep) // &
      'CONTACT pair ' // int_to_str(ip) // &
      ' slides beyond small sliding: the slave node at (' // real_to_str(x(1)) // ', ' // real_to_str(x(2)) // ') '
    if (edge_on) then
      t = t // 'touches the master edge-on, along its own surface, a contact that only a slide of ' // &
        real_to_str(slide) // ' (slave element ' // real_to_str(h) // ') against the initial pairing closes'
    else
      t = t // 'moves ' // real_to_str(slide) // ' along its surface against the master point it faced initially (a slide, ' // &
        'or a roll of a RIGID circle), more than ' // &
        'max(h, a/4) = ' // real_to_str(cap) // ' (slave element h = ' // real_to_str(h) // ', contact zone ' // &
        'half-width a = ' // real_to_str(halfwidth) // ')'
    end if
    t = t // '; the pairing, gaps and normals of the initial configuration no longer describe where the bodies ' // &
      'touch'
    if (prob%cs%pair(ip)%spec%mu > 0.0_dp .or. prob%cs%pair(ip)%spec%tresca > 0.0_dp) t = t // &
      ' (with friction: gross slip, an equilibrium that may exist only because the geometry is frozen, e.g. ' // &
      'a body pushed beyond what friction holds)'
    t = t // ' (expected a slide within small sliding, or CONTACT ... sliding=finite)'
  end function sliding_text

  !> The two slave nodes around node i for its tangent (a closed chain wraps).
  subroutine neighbours(pr, i, a, b)
    type(contact_pair_t), intent(in) :: pr
    integer, intent(in) :: i
    integer, intent(out) :: a, b
    integer :: ns
    ns = size(pr%snode)
    a = max(1, i - 1)
    b = min(ns, i + 1)
    if (pr%closed .and. i == 1) a = ns - 1
    if (pr%closed .and. i == ns) b = 2
  end subroutine neighbours

  !> The slave element length at node i: the mean of its chain segments
  !> (a quadratic chain lists the mid-side nodes: two segments an element).
  real(dp) function element_length(pr, i) result(h)
    type(contact_pair_t), intent(in) :: pr
    integer, intent(in) :: i
    integer :: a, b
    call neighbours(pr, i, a, b)
    if (a < i .and. b > i) then
      h = 0.5_dp * (norm2(pr%xs(:, i) - pr%xs(:, a)) + norm2(pr%xs(:, b) - pr%xs(:, i)))
    else
      h = norm2(pr%xs(:, b) - pr%xs(:, a))
    end if
    h = h * real(pr%degree(1), dp)
  end function element_length

  !> u of slave node i (global axes) less the master's at the point paired
  !> with it: a RIGID's motion U(x_i); else the master chain's displacement
  !> interpolated at its point nearest x_i in the initial configuration.
  function relative_displacement(prob, ug, pr, i) result(u)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: ug(:)
    type(contact_pair_t), intent(in) :: pr
    integer, intent(in) :: i
    real(dp) :: u(2)
    real(dp) :: e(2), w(2), y(2), len2, s, dist, best, sbest
    integer :: d0, j, jbest, da, db
    d0 = prob%sc%bodies(pr%spec%slave_body)%dof0 + 2 * (pr%snode(i) - 1)
    u = ug(d0 + 1:d0 + 2)
    if (pr%spec%rigid > 0) then
      ! the shape's motion at x_i: a circle's is its centre's (turning about
      ! its centre moves no point of the shape: a rolling cylinder's contact
      ! moves with its centre), a line's or polyline's its motion at x_i
      y = pr%xs(:, i)
      if (pr%spec%shape%kind == shape_circle) y = pr%spec%shape%centre
      d0 = pr%spec%shape%dof0
      u(1) = u(1) - dot_product(rigid_terms(pr%spec%shape, y, [1.0_dp, 0.0_dp]), ug(d0 + 1:d0 + 3))
      u(2) = u(2) - dot_product(rigid_terms(pr%spec%shape, y, [0.0_dp, 1.0_dp]), ug(d0 + 1:d0 + 3))
      return
    end if
    associate(x => prob%sc%bodies(pr%spec%master_body)%mesh%x)
      best = huge(1.0_dp)
      jbest = 1
      sbest = 0.0_dp
      do j = 1, size(pr%mnode) - 1
        e = x(:, pr%mnode(j + 1)) - x(:, pr%mnode(j))
        w = pr%xs(:, i) - x(:, pr%mnode(j))
        len2 = dot_product(e, e)
        s = 0.0_dp
        if (len2 > 0.0_dp) s = min(1.0_dp, max(0.0_dp, dot_product(w, e) / len2))
        dist = norm2(w - s * e)
        if (dist < best) then
          best = dist
          jbest = j
          sbest = s
        end if
      end do
    end associate
    d0 = prob%sc%bodies(pr%spec%master_body)%dof0
    da = d0 + 2 * (pr%mnode(jbest) - 1)
    db = d0 + 2 * (pr%mnode(min(jbest + 1, size(pr%mnode))) - 1)
    u = u - ((1.0_dp - sbest) * ug(da + 1:da + 2) + sbest * ug(db + 1:db + 2))
  end function relative_displacement

  !> Polygon gaps of pair ip (module header, 2.): a warning when the two
  !> chains are polygons of one curve and the initial gaps are their sags.
  subroutine check_polygon_gap(prob, ip, log)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: ip
    type(log_t), intent(inout) :: log
    real(dp), allocatable :: xm(:,:), nm(:,:), ns_seg(:,:), g(:)
    logical, allocatable :: sface(:), mface(:)
    real(dp) :: ks, km, hs, hm, sag, gmax, vote
    integer :: e, f, k, nmn
    associate(pr => prob%cs%pair(ip), mo => prob%cs%pair(ip)%mortar)
      if (pr%spec%rigid > 0 .or. pr%spec%gap_zero .or. pr%quadratic .or. mo%first == 0) return
      if (mo%inter%nsub == 0) return
      xm = prob%sc%bodies(pr%spec%master_body)%mesh%x(:, pr%mnode)
      nmn = size(pr%mnode)
      ! the segments' unit normals, one turn of the tangent on each chain; the
      ! slave's outward by its nodal normals, the master's facing the slave
      ! segments it meets (a vote over the intersection), so that no mesh
      ! adjacency is needed
      allocate(ns_seg(2, size(pr%snode) - 1), nm(2, nmn - 1))
      allocate(sface(size(pr%snode) - 1), mface(nmn - 1), source=.false.)
      do e = 1, size(pr%snode) - 1
        ns_seg(:, e) = [pr%xs(2, e + 1) - pr%xs(2, e), pr%xs(1, e) - pr%xs(1, e + 1)]
        ns_seg(:, e) = ns_seg(:, e) / norm2(ns_seg(:, e))
        if (dot_product(ns_seg(:, e), mo%normal(:, e) + mo%normal(:, e + 1)) < 0.0_dp) ns_seg(:, e) = -ns_seg(:, e)
      end do
      do f = 1, nmn - 1
        nm(:, f) = [xm(2, f + 1) - xm(2, f), xm(1, f) - xm(1, f + 1)]
        if (norm2(nm(:, f)) > 0.0_dp) nm(:, f) = nm(:, f) / norm2(nm(:, f))
      end do
      vote = 0.0_dp
      do k = 1, mo%inter%nsub
        sface(mo%inter%slave_seg(k)) = .true.
        mface(mo%inter%master_seg(k)) = .true.
        vote = vote + dot_product(nm(:, mo%inter%master_seg(k)), ns_seg(:, mo%inter%slave_seg(k)))
      end do
      if (vote > 0.0_dp) nm = -nm                      ! outward normals oppose the slave's
      ks = mean_curvature(pr%xs, ns_seg, sface)
      km = mean_curvature(xm, nm, mface)
      ! one curve: one chain convex, the other concave, radii within radius_match
      if (.not. (ks * km < 0.0_dp)) return
      if (abs(abs(ks) - abs(km)) > radius_match * max(abs(ks), abs(km))) return
      hs = 0.0_dp
      hm = 0.0_dp
      do e = 1, size(sface)
        if (sface(e)) hs = max(hs, norm2(pr%xs(:, e + 1) - pr%xs(:, e)))
      end do
      do f = 1, size(mface)
        if (mface(f)) hm = max(hm, norm2(xm(:, f + 1) - xm(:, f)))
      end do
      sag = max(hs, hm)**2 * 0.125_dp * abs(ks)        ! h^2 / (8 R) of the coarser chain
      g = mo%gap0(mo%first:mo%last)
      gmax = maxval(abs(g))
      ! gaps of one sign, of the order of the sagitta, and not zero (matching polygons)
      if (gmax > sag_factor * sag .or. gmax < 0.05_dp * sag) return
      if (any(g > 0.05_dp * gmax) .and. any(g < -0.05_dp * gmax)) return
      call add_warning(log, 'polygon_gap', prob%deck%file // ':' // int_to_str(prob%deck%contacts(ip)%line) // &
        ': CONTACT pair ' // int_to_str(ip) // ': the two boundaries are polygons of one curve (radius ' // &
        real_to_str(1.0_dp / abs(ks)) // ') and start ' // trim(merge('open       ', 'penetrating', sum(g) > 0.0_dp)) // &
        ' by up to ' // real_to_str(gmax) // ', the chords'' sagitta h^2/(8R) = ' // real_to_str(sag) // &
        ', a gap that is not in the geometry: the pressures can be far off (remedies: gap=zero when the ' // &
        'curves coincide, matching nodes on the two curves, order=2 meshes whose edges follow the curve, ' // &
        'or a gap measured on the true curve)')
    end associate
  end subroutine check_polygon_gap

end module contact_checks
