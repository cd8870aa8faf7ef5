!> setup_checks: the monitors of the set-up mistakes that a solve does not
!> notice, run once on the final state, each a warning naming the likely
!> mistake and its remedy (doc/theory.md, "Monitors of the set-up"):
!>   lifted_off    a pair that carries no load because a free rigid motion
!>                 of one of its bodies (or RIGIDs), held by contact alone,
!>                 took that body away: without the motion the pair would
!>                 close.  Named: the body, the motion, the FIX likely missing
!>   coarse_zone   a zone in contact narrower than zone_elements slave
!>                 elements, away from the ends of the pair's rows; with a units hint when E looks like Pa (E >=
!>                 pa_like_modulus) or the largest strain is implausibly small
!>   coarse_slave  slave elements more than coarse_ratio times the master's
!>                 along the zone: make the finer side the slave, or refine it
!>   few_steps     friction ending in partial slip where one load step
!>                 made most of the contact and dragged it at once (a single
!>                 step that presses and shears): the answer depends on the path
!>
!> Why it exists: each of these runs ends with exit 0 and a plausible-looking
!> answer (a body that translates instead of pressing, a zone of one node, a
!> pressure 30 % off, a stick zone that depends on the step count); the
!> numbers that would betray them are here, measured once, each threshold
!> with its reason.  Who may use it: the program (one call, after the
!> results are computed).
!>
!> Programming interface
!>   check_setup(prob, sol, res, log)   the monitors; a warning (run_log's add_warning) for each one met
module setup_checks
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str, format_number
  use problem, only: problem_t
  use step_solution, only: step_solution_t
  use results_writer, only: results_t
  use run_log, only: log_t, add_warning
  use contact_set, only: row_of_node
  use contact_condensation, only: constraint_values
  implicit none
  private
  public :: check_setup

  !> a gap that the free motions opened from below -lift_tol times the slave
  !> chain's length: round-off in the free motions stays below 1e-12 of it
  real(dp), parameter :: lift_tol = 1.0e-6_dp
  !> slave elements a zone must span: the pressure's square-root ends need
  !> two or three elements each to be seen, a zone of fewer is one node's
  !> value smeared (its estimate pressure 35 % and more)
  real(dp), parameter :: zone_elements = 3.0_dp
  !> slave over master element length along the zone above which the
  !> pressure of the mortar rows (on the slave) misses the master's finer
  !> field: 16 times gives 30 % off and spurious peaks at the zone's ends
  real(dp), parameter :: coarse_ratio = 4.0_dp
  !> a modulus at least this large is a modulus in Pa (N/m^2) for any solid
  !> (rubber 1e6 to 1e7 Pa; in MPa or in psi no solid reaches it)
  real(dp), parameter :: pa_like_modulus = 1.0e8_dp
  !> a largest strain below this, in a run with a contact zone, is far
  !> below what a contact worth modelling makes (1e-4 and up): a load or a
  !> modulus in units the lengths do not share
  real(dp), parameter :: tiny_strain = 1.0e-7_dp
  !> share of the final contact rows that one load step may both make and
  !> drag: more, and the step's own order of loads decides the answer
  real(dp), parameter :: entry_share = 0.5_dp

contains

  !> The set-up monitors on the run's final state (module header).
  !>   sol (in)    the final step's solution: its free motions, the friction history's counts
  !>   res (in)    the results: multipliers, status, gaps, zones, max_strain
  !>   log (inout) the warnings
  subroutine check_setup(prob, sol, res, log)
    type(problem_t), intent(in) :: prob
    type(step_solution_t), intent(in) :: sol
    type(results_t), intent(in) :: res
    type(log_t), intent(inout) :: log
    integer :: ip
    if (prob%cs%nrow == 0 .or. .not. (allocated(res%status) .and. allocated(res%gap))) return
    call check_lifted_off(prob, sol, res, log)
    do ip = 1, prob%cs%npair
      if (prob%cs%pair(ip)%nrow == 0) cycle
      call check_zone_mesh(prob, res, ip, log)
    end do
    call check_friction_steps(prob, sol, log)
  end subroutine check_setup

  !> `warning lifted_off`: a pair none of whose rows is in contact, whose
  !> gaps without the free motions of its two sides (the bodies' free
  !> rigid modes R alpha, a RIGID's free directions) would be negative:
  !> the deck's prescribed motions push the two together, and one of them
  !> gave way as a rigid body, held by nothing but this contact.  The side
  !> whose motion opened the most is named, with the components it moved
  !> along: a support there is likely missing.
  subroutine check_lifted_off(prob, sol, res, log)
    type(problem_t), intent(in) :: prob
    type(step_solution_t), intent(in) :: sol
    type(results_t), intent(in) :: res
    type(log_t), intent(inout) :: log
    real(dp), allocatable :: v(:), side(:,:), bv(:), bside(:,:)
    real(dp) :: closed, length, opened(2)
    integer :: ip, r0, r1, s, worst
    character(len=:), allocatable :: moved, held
    logical :: moves
    moves = prob%fl%k > 0 .and. allocated(sol%alpha)
    if (allocated(sol%rigid_alpha)) moves = moves .or. size(sol%rigid_alpha) > 0
    if (.not. moves) return
    allocate(v(prob%sc%ndof), bv(prob%cs%nrow + prob%cs%ntan), bside(prob%cs%nrow + prob%cs%ntan, 2))
    v = 0.0_dp
    if (prob%fl%k > 0 .and. allocated(sol%alpha)) v = matmul(prob%fl%r, sol%alpha)
    if (allocated(sol%rigid_alpha)) v(prob%rsplit%dof) = sol%rigid_alpha
    call constraint_values(prob%cs, v, bv)
    do ip = 1, prob%cs%npair
      associate (pr => prob%cs%pair(ip))
        if (pr%nrow == 0) cycle
        r0 = pr%row0 + 1
        r1 = pr%row0 + pr%nrow
        if (any(res%status(r0:r1) == 1)) cycle
        ! gap = g - B u: the gap without the free motions v is gap + B v
        worst = r0 - 1 + minloc(res%gap(r0:r1) + bv(r0:r1), dim=1)
        closed = res%gap(worst) + bv(worst)
        length = sum(norm2(pr%xs(:, 2:) - pr%xs(:, :size(pr%xs, 2) - 1), dim=1))
        if (closed >= -lift_tol * length) cycle
        call side_motions(prob, ip, v, side)
        do s = 1, 2
          call constraint_values(prob%cs, side(:, s), bside(:, s))
          opened(s) = -bside(worst, s)
        end do
        s = maxloc(opened, dim=1)
        call moved_along(prob, ip, s, side(:, s), moved, held)
        call add_warning(log, 'lifted_off', prob%deck%file // ':' // int_to_str(prob%deck%contacts(ip)%line) // &
          ': the pair carries no load: ' // side_name(prob, ip, s) // ' moved away from it as a rigid body (' // &
          moved // '), held by nothing but this contact, though the prescribed motions push the two sides ' // &
          'together (they would overlap by ' // real_to_str(-closed) // ' without that motion); a FIX ' // &
          'holding ' // held // ' of ' // side_name(prob, ip, s) // ' (its support) is likely missing')
      end associate
    end do
  end subroutine check_lifted_off

  !> The free motions v split by side of pair ip: side(:, 1) on the slave
  !> body's dofs, side(:, 2) on the master body's (or the master RIGID's).
  subroutine side_motions(prob, ip, v, side)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: ip
    real(dp), intent(in) :: v(:)
    real(dp), allocatable, intent(out) :: side(:,:)
    integer :: s, b, d0, d1, k
    allocate(side(size(v), 2), source=0.0_dp)
    associate (sp => prob%cs%pair(ip)%spec)
      do s = 1, 2
        b = merge(sp%slave_body, sp%master_body, s == 1)
        if (b > 0) then
          d0 = prob%sc%bodies(b)%dof0 + 1
          d1 = prob%sc%bodies(b)%dof0 + 2 * prob%sc%bodies(b)%mesh%nnode
          side(d0:d1, s) = v(d0:d1)
        else if (sp%rigid > 0 .and. allocated(prob%rsplit%owner)) then
          do k = 1, prob%rsplit%k
            if (prob%rsplit%owner(k) == sp%rigid) side(prob%rsplit%dof(k), s) = v(prob%rsplit%dof(k))
          end do
        end if
      end do
    end associate
  end subroutine side_motions

  !> 'body "NAME"' or 'RIGID "NAME"': side s of pair ip (1 slave, 2 master).
  function side_name(prob, ip, s) result(t)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: ip, s
    character(len=:), allocatable :: t
    associate (sp => prob%cs%pair(ip)%spec)
      if (s == 1) then
        t = 'body "' // prob%sc%bodies(sp%slave_body)%name // '"'
      else if (sp%master_body > 0) then
        t = 'body "' // prob%sc%bodies(sp%master_body)%name // '"'
      else
        t = 'RIGID "' // prob%sc%rigids(sp%rigid)%name // '"'
      end if
    end associate
  end function side_name

  !> The components a side's free motion w moved along: moved, 'uy by
  !> -5.04E-03' (a body: its translation and its rotation about its
  !> centroid; a RIGID: its free dofs), and held, the FIX keys that would
  !> hold them, 'uy'.  A component whose motion at the body's size is below
  !> 1 % of the largest is left out (a rotation about a point of a
  !> supported line rides along with the translation that lifts it).
  subroutine moved_along(prob, ip, s, w, moved, held)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: ip, s
    real(dp), intent(in) :: w(:)
    character(len=:), allocatable, intent(out) :: moved, held
    real(dp) :: a(3), size_of(3)
    integer :: b, k, j
    character(len=2), parameter :: comp(3) = ['ux', 'uy', 'rz']
    a = 0.0_dp
    size_of = 1.0_dp
    associate (sp => prob%cs%pair(ip)%spec)
      b = merge(sp%slave_body, sp%master_body, s == 1)
      if (b > 0) then
        do j = 1, prob%fl%k                      ! mode j = (tx, ty, rotation / size) coef_j / norm_j
          if (prob%fl%mode_body(j) /= b) cycle
          a = a + dot_product(prob%fl%r(:, j), w) * prob%fl%coef(:, j) / prob%fl%norm(j) * &
            [1.0_dp, 1.0_dp, 1.0_dp / prob%fl%length(j)]
          size_of(3) = prob%fl%length(j)
        end do
      else
        do k = 1, prob%rsplit%k
          if (prob%rsplit%owner(k) /= sp%rigid) cycle
          a(prob%rsplit%comp(k)) = w(prob%rsplit%dof(k))
          size_of(prob%rsplit%comp(k)) = prob%rsplit%scale(k)
        end do
      end if
    end associate
    moved = ''
    held = ''
    do k = 1, 3
      if (abs(a(k)) * size_of(k) <= 0.01_dp * maxval(abs(a) * size_of) .or. a(k) == 0.0_dp) cycle
      moved = moved // ', ' // comp(k) // ' by ' // real_to_str(a(k))
      held = held // ' ' // comp(k)
    end do
    if (len(moved) == 0) then
      moved = 'a free rigid mode'
      held = 'it'
    else
      moved = moved(3:)
      held = held(2:)
    end if
  end subroutine moved_along

  !> `warning coarse_zone` and `warning coarse_slave` on the zone in
  !> contact of pair ip: its width against the slave elements there, the
  !> slave elements against the master's that face them.  The lengths of
  !> a quadratic trace's elements are two of its chain's segments.
  subroutine check_zone_mesh(prob, res, ip, log)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(in) :: res
    integer, intent(in) :: ip
    type(log_t), intent(inout) :: log
    logical, allocatable :: active(:), has_row(:)
    real(dp), allocatable :: xm(:,:)
    real(dp) :: seg, hs, hm, hs_sum, hm_sum, width, d, dmin, nearest, near_sum, hnode
    integer :: ns, nm, i, j, r, nseg, near
    character(len=:), allocatable :: where
    associate (pr => prob%cs%pair(ip))
      if (.not. allocated(res%zones)) return
      width = res%zones(ip)%contact%total
      ns = size(pr%snode)
      allocate(active(ns), has_row(ns), source=.false.)
      do i = 1, ns
        r = row_of_node(prob%cs, ip, i)
        has_row(i) = r > 0
        if (r > 0) active(i) = res%status(r) == 1
      end do
      if (.not. any(active)) return
      ! the slave elements the zone touches
      hs = 0.0_dp
      nseg = 0
      do i = 1, ns - 1
        if (.not. (active(i) .or. active(i + 1))) cycle
        hs = hs + pr%degree(1) * norm2(pr%xs(:, i + 1) - pr%xs(:, i))
        nseg = nseg + 1
      end do
      if (nseg == 0) return
      hs = hs / nseg
      where = prob%deck%file // ':' // int_to_str(prob%deck%contacts(ip)%line) // ': '
      ! a zone that reaches an end of the pair's rows ends at the slave's own
      ! corner (a patch pressed all over, a tilted flat on a corner): the
      ! geometry bounds it there, not a pressure falling to zero over elements
      if (width < zone_elements * hs .and. .not. pr%closed .and. .not. (active(findloc(has_row, .true., dim=1)) &
          .or. active(findloc(has_row, .true., dim=1, back=.true.)))) &
        call add_warning(log, 'coarse_zone', where // 'the zone in contact is ' // real_to_str(width) // &
          ' wide, ' // hundredths(width / hs) // ' slave elements of ' // real_to_str(hs) // &
          ': its pressure is not resolved (fewer than ' // format_number(zone_elements) // ' elements across ' // &
          'it); refine both sides there to elements of ' // real_to_str(width / 10) // ' or less' // &
          units_hint(prob, res, ip))
      if (pr%spec%master_body == 0) return          ! a RIGID's shape has no elements
      nm = size(pr%mnode)
      allocate(xm(2, nm))
      xm = prob%sc%bodies(pr%spec%master_body)%mesh%x(:, pr%mnode)
      ! each active slave node: its elements' length against that of the master
      ! segments whose middles lie within it (the nearest one when none does)
      hs_sum = 0.0_dp
      hm_sum = 0.0_dp
      do i = 1, ns
        if (.not. active(i)) cycle
        hnode = 0.0_dp
        r = 0
        if (i > 1) then
          hnode = hnode + norm2(pr%xs(:, i) - pr%xs(:, i - 1))
          r = r + 1
        end if
        if (i < ns) then
          hnode = hnode + norm2(pr%xs(:, i + 1) - pr%xs(:, i))
          r = r + 1
        end if
        hnode = pr%degree(1) * hnode / max(r, 1)
        near_sum = 0.0_dp
        near = 0
        dmin = huge(1.0_dp)
        nearest = 0.0_dp
        do j = 1, nm - 1
          seg = pr%degree(2) * norm2(xm(:, j + 1) - xm(:, j))
          d = norm2(0.5_dp * (xm(:, j + 1) + xm(:, j)) - pr%xs(:, i))
          if (d <= hnode) then
            near_sum = near_sum + seg
            near = near + 1
          end if
          if (d < dmin) then
            dmin = d
            nearest = seg
          end if
        end do
        hm = nearest
        if (near > 0) hm = near_sum / near
        hs_sum = hs_sum + hnode
        hm_sum = hm_sum + hm
      end do
      if (hm_sum <= 0.0_dp) return
      if (hs_sum > coarse_ratio * hm_sum) &
        call add_warning(log, 'coarse_slave', where // 'the slave elements along the zone in contact are ' // &
          hundredths(hs_sum / hm_sum) // ' times as long as the master''s (' // &
          real_to_str(hs_sum / count(active)) // ' against ' // real_to_str(hm_sum / count(active)) // &
          '): the mortar rows, on the slave, cannot follow the finer master (a pressure off by tens of % ' // &
          'and spurious peaks); make the finer side the slave (CONTACT slave=' // &
          prob%sc%bodies(pr%spec%master_body)%name // ':... master=' // &
          prob%sc%bodies(pr%spec%slave_body)%name // ':...), or refine the slave there')
    end associate
  end subroutine check_zone_mesh

  !> The units hint of a zone too narrow: a modulus of either side that
  !> only Pa gives (the lengths then in m), or a largest strain far below
  !> any contact's; '' when neither.
  function units_hint(prob, res, ip) result(t)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(in) :: res
    integer, intent(in) :: ip
    character(len=:), allocatable :: t
    integer :: s, b
    real(dp) :: e
    t = ''
    associate (sp => prob%cs%pair(ip)%spec)
      do s = 1, 2
        b = merge(sp%slave_body, sp%master_body, s == 1)
        if (b == 0) cycle
        associate (mat => prob%deck%bodies(b)%material)
          if (.not. allocated(mat%kind)) cycle
          if (mat%kind /= 'isotropic') cycle
          e = mat%e
        end associate
        if (e < pa_like_modulus) cycle
        t = '; check the units: E = ' // real_to_str(e) // ' of body "' // prob%sc%bodies(b)%name // &
          '" is a modulus in Pa (N/m^2), which asks for lengths in m and forces in N; with lengths in mm, ' // &
          'E is in MPa (N/mm^2), 1e6 times smaller'
        return
      end do
    end associate
    if (res%max_strain(1) < tiny_strain) t = '; check the units: the largest strain, ' // &
      real_to_str(res%max_strain(1)) // ', is far below any contact''s (a load or a modulus in units the ' // &
      'lengths do not share)'
  end function units_hint

  !> `warning few_steps`: friction ending in partial slip where one load
  !> step made most of a pair's final contact and dragged it at once
  !> (load_steps' slip_entries: rows come into contact in a step that ends
  !> in partial slip under a net shear), more than entry_share of the rows
  !> in contact at the end.  Stepping the load path shrinks that share
  !> (Hertz: the zone grows as the root of the load, a quarter of the load
  !> makes half of it), so more steps, the press first, silence it.
  subroutine check_friction_steps(prob, sol, log)
    type(problem_t), intent(in) :: prob
    type(step_solution_t), intent(in) :: sol
    type(log_t), intent(inout) :: log
    integer :: ip, t, nstick, nslip, steps
    if (prob%cs%ntan == 0 .or. .not. allocated(sol%fstate) .or. sol%slip_entry_step == 0) return
    ip = sol%slip_entry_pair
    nstick = 0
    nslip = 0
    do t = 1, prob%cs%ntan
      if (prob%cs%row_pair(prob%cs%tan_row(t)) /= ip) cycle
      if (sol%fstate(t) == 1) nstick = nstick + 1
      if (sol%fstate(t) == 2) nslip = nslip + 1
    end do
    if (nstick == 0 .or. nslip == 0) return
    if (sol%slip_entries <= entry_share * (nstick + nslip)) return
    steps = max(4, 4 * prob%sc%steps)
    call add_warning(log, 'few_steps', prob%deck%file // ':' // int_to_str(prob%deck%contacts(ip)%line) // &
      ': friction ends in partial slip (' // int_to_str(nstick) // ' rows stick, ' // int_to_str(nslip) // &
      ' slip), and load step ' // int_to_str(sol%slip_entry_step) // ' of ' // int_to_str(prob%sc%steps) // &
      ' both made ' // int_to_str(sol%slip_entries) // ' of the ' // int_to_str(nstick + nslip) // &
      ' rows in contact and dragged them: the answer (the stick zone, the shear) depends on the order of ' // &
      'that step''s loads, which one step cannot follow; give the loads over more steps in the order they ' // &
      'act (e.g. STEPS ' // int_to_str(steps) // ', ramp= on the FIX and FORCE lines: the press first)')
  end subroutine check_friction_steps

  !> x rounded to hundredths, shortest: '16', '0.25', '1.5'.
  function hundredths(x) result(t)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: t
    t = format_number(anint(100 * x) / 100)
  end function hundredths

end module setup_checks
