!> run_estimate: every run's estimate of its own error (ESTIMATE, on unless
!> the deck says off), from the final displacement.
!>
!> The relative energy-norm error of the displacement,
!>     estimate_energy = eta / sqrt(||u_h||_E^2 + eta^2),
!> eta^2 = sum_K eta_K^2 over the elements of every body, by stress recovery
!> (module error_estimate; doc/theory.md, "Error estimate"): ||u_h||_E^2 +
!> eta^2 stands for ||u||_E^2, since u_h is the energy projection of u on an
!> elastic problem (Galerkin orthogonality, exact without contact and a good
!> guide with it).  Each element gets error_indicator = eta_K / sqrt(||u_h||_E^2
!> + eta^2), whose squares add up to estimate_energy^2: the VTK's picture of
!> where the error is.
!>
!> The contact pressure.  On each pair's slave trace a second approximation
!> p* is rebuilt from the mortar pressure p_h itself (module
!> pressure_recovery: a next-order fit inside the zone, a square-root law at
!> its free ends), and their difference estimates the error of p_h:
!>     e_zone = ||p_h - p*||_L2(zone) / ||p_h||_L2(zone),
!> p_h linear between the slave trace's nodes, over the segments of the
!> effective zone (dS = ds, or 2 pi r ds in axisymmetry).  To it is added,
!> in quadrature, the share of the bodies' stiffness, which p* cannot see:
!>     estimate_pressure = sqrt(e_zone^2 + estimate_energy^4).
!> A coarse bulk makes the bodies too stiff as a whole, and under a
!> prescribed approach every node's pressure is offset alike; the offset of
!> a load against its own displacement is the energy error squared (Galerkin
!> orthogonality: the compliance's error is ||e||_E^2 / ||u||_E^2).  Measured
!> on Hertz P1 graded toward the zone (bulk at hf = 0.05): at hc = 0.028 the
!> zone term read 0.16 % of a true 0.59 %, the energy estimate 7.8 %, and the
!> sum 0.62 %; on even meshes and on quadratic elements it adds a few percent
!> of e_zone at most (doc/theory.md, "Error estimate").  Not the normal
!> traction of the recovered stress: on the boundary that is O(h) wrong where
!> p_h is nearly exact (a press fit: 20-100 times the true error), and it
!> smooths away the square root at a zone's end, where most of the error is
!> (doc/theory.md, "Error estimate").  The same difference enters the energy
!> estimate as the contact term of the slave element K on each segment E,
!>     eta_K^2 += (|E| / E_K) int_E (p_h - p*)^2 dS,
!> the energy of a traction error spread over a depth |E| of a material of
!> stiffness E_K (its largest Young's modulus): ADAPT refines where the
!> pressure is wrong, the zone's ends first.
!>
!> The cost of the next digit.  estimate cost_to_halve is the dofs and the
!> CPU time (cpu_total) of a run with half this run's energy error, on the
!> mesh ADAPT would make for it: the fewest elements for the error
!> (estimate / 2)^2 (module size_field), each element's error falling as
!> h^(2 p) with p its order, or the rate observed between ADAPT's last two
!> meshes when that is lower (a singularity's).  The dofs grow as the
!> elements, by r; each phase's CPU seconds (cpu_total's parts: the elapsed
!> time would count gmsh's sandbox starting, which does not grow) by r^g,
!> g = 1 for the phases that visit each element or dof a fixed number of
!> times, 1.5 for the factorization (nested dissection in 2D), the
!> condensation and the LCP (their rows grow as the contact boundary,
!> sqrt(r), their work per row as the factor).  The mesh phase does not
!> shrink below this run's when r < 1: where the optimal mesh is coarser
!> than the run's, that phase is mostly fixed costs (the process's and
!> gmsh's start, the deck).
!>
!> Programming interface
!>   estimate_results(prob, res)   res%estimated, res%estimate_energy, res%error_indicator,
!>                                 res%estimate_pressure of a state's results (u in x, y)
!>   predict_cost(prob, res, spent, energy_prev, dofs_prev)   res%cost_seconds, res%cost_dofs,
!>                                 from the indicators and this mesh's phase times
!>   element_rates(prob, estimate, energy_prev, dofs_prev)    the rate in h of each element's
!>                                 energy error (ADAPT, predict_cost)
module run_estimate
  use kinds, only: dp
  use run_log, only: ph_output
  use problem, only: problem_t
  use size_field, only: optimal_scales, element_count
  use results_writer, only: results_t
  use error_estimate, only: recover_stress, energy_indicators
  use body, only: node_elements
  use axisymmetric_elements, only: radial_weight
  use contact_set, only: row_of_node
  use pressure_recovery, only: trace_errors
  implicit none
  private
  public :: estimate_results, predict_cost, element_rates

  !> how each phase's time grows with the dofs (module header): r^growth
  real(dp), parameter :: growth(ph_output) = [1.0_dp, 1.0_dp, 1.5_dp, 1.5_dp, 1.5_dp, 1.0_dp, 1.0_dp, 1.0_dp]

contains

  !> The error estimate of one state's results: the final state's, or a
  !> load step's (its VTK file shows error_indicator too).
  !>   res (inout) u in x, y components, adt and node_pressure on entry; estimated,
  !>               estimate_energy, error_indicator and estimate_pressure on exit,
  !>               when deck%estimate (else estimated false, no indicators)
  subroutine estimate_results(prob, res)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    real(dp), allocatable :: u(:,:), eta2(:), srec(:,:)
    real(dp) :: energy2, body_energy2, total
    integer :: b, nn, d0, e0, ne
    res%estimated = .false.
    if (allocated(res%error_indicator)) deallocate(res%error_indicator)
    if (.not. prob%deck%estimate) return
    ! the estimators are linear elasticity's: none for a state in finite strain (run_steps says so)
    if (any(prob%sc%bodies(:)%finite)) return
    allocate(eta2(prob%sc%nelem), source=0.0_dp)
    energy2 = 0.0_dp
    do b = 1, size(prob%sc%bodies)
      associate (bd => prob%sc%bodies(b))
        nn = bd%mesh%nnode
        ne = bd%mesh%nelem
        d0 = bd%dof0
        e0 = bd%elem0
        u = reshape(res%u(d0 + 1:d0 + 2 * nn), [2, nn])
        call recover_stress(bd, u, res%adt(e0 + 1:e0 + ne), srec)
        call energy_indicators(bd, u, res%adt(e0 + 1:e0 + ne), srec, eta2(e0 + 1:e0 + ne), body_energy2)
        energy2 = energy2 + body_energy2
      end associate
    end do
    call pressure_estimates(prob, res, eta2)
    ! the norm is the whole system's, u'Ku = 2 energy, springs included: on a
    ! body that rides on its springs the elements' own energy is round-off,
    ! and an error relative to it would be noise
    total = max(energy2, 2 * res%energy) + sum(eta2)
    if (total > 0.0_dp) then
      res%estimate_energy = sqrt(sum(eta2) / total)
      allocate(res%error_indicator, source=sqrt(eta2 / total))
    else                                          ! no deformation at all: nothing to be wrong about
      res%estimate_energy = 0.0_dp
      allocate(res%error_indicator(prob%sc%nelem), source=0.0_dp)
    end if
    ! the zone's own term with the bodies' stiffness's share (module header)
    res%estimate_pressure = res%estimate_zone
    where (res%estimate_zone >= 0.0_dp) res%estimate_pressure = sqrt(res%estimate_zone**2 + res%estimate_energy**4)
    res%estimated = .true.
  end subroutine estimate_results

  !> estimate cost_to_halve (module header): res%cost_dofs and
  !> res%cost_seconds, from the indicators, the elements' orders (or ADAPT's
  !> observed rate) and this mesh's phase times.
  !>   res         (inout) error_indicator, estimate_energy on entry
  !>   spent       (in)    (ph_output) this mesh's CPU seconds per phase
  !>   energy_prev, dofs_prev (in) ADAPT's last mesh (< 0: none)
  subroutine predict_cost(prob, res, spent, energy_prev, dofs_prev)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    real(dp), intent(in) :: spent(:), energy_prev, dofs_prev
    real(dp), allocatable :: s(:)
    real(dp) :: r
    res%cost_dofs = -1
    res%cost_seconds = -1
    ! an error at round-off (a patch test, a rigid motion on springs) has no next digit to buy
    if (.not. res%estimated .or. .not. res%estimate_energy > 1.0e-8_dp) return
    allocate(s(prob%sc%nelem))
    call optimal_scales(res%error_indicator**2, element_rates(prob, res%estimate_energy, energy_prev, dofs_prev), &
                        (res%estimate_energy / 2)**2, 1.0e-3_dp, 8.0_dp, s)
    r = element_count(s) / prob%sc%nelem
    res%cost_dofs = prob%sc%ndof * r
    ! the mesh phase holds what a coarser mesh does not make cheaper (the
    ! process's and gmsh's start, the deck): it never shrinks below this run's
    res%cost_seconds = sum(max(0.0_dp, spent(2:ph_output)) * r**growth(2:)) + &
                       max(0.0_dp, spent(1)) * max(1.0_dp, r)**growth(1)
  end subroutine predict_cost

  !> The rate in h of each element's energy error: its order (1 for 3- and
  !> 4-node elements, 2 for quadratic ones), or the rate ADAPT observed
  !> between its last two meshes when lower, error ~ dofs^(-p/2) in 2D:
  !> p = 2 log(e_prev / e) / log(dofs / dofs_prev), at least 1/2.
  !>   estimate    (in) this mesh's energy estimate
  !>   energy_prev, dofs_prev (in) ADAPT's last mesh's estimate and dofs (< 0: none)
  function element_rates(prob, estimate, energy_prev, dofs_prev) result(rate)
    type(problem_t), intent(in) :: prob
    real(dp), intent(in) :: estimate, energy_prev, dofs_prev
    real(dp), allocatable :: rate(:)
    real(dp) :: observed, dofs
    integer :: b, e
    allocate(rate(prob%sc%nelem))
    do b = 1, size(prob%sc%bodies)
      associate (m => prob%sc%bodies(b)%mesh, e0 => prob%sc%bodies(b)%elem0)
        do e = 1, m%nelem
          rate(e0 + e) = merge(1.0_dp, 2.0_dp, m%nen(e) <= 4)
        end do
      end associate
    end do
    dofs = real(prob%sc%ndof, dp)
    if (energy_prev > 0.0_dp .and. dofs_prev > 0.0_dp .and. dofs > 1.2_dp * dofs_prev .and. estimate > 0.0_dp) then
      observed = 2 * log(energy_prev / estimate) / log(dofs / dofs_prev)
      rate = min(rate, max(0.5_dp, observed))
    end if
  end function element_rates

  !> res%estimate_zone of every pair (e_zone, -1 where the pair has no zone),
  !> and the contact terms added to the slave elements' eta2 (module header;
  !> the reconstruction p*: module pressure_recovery).
  !>   prob (in)    the contact set
  !>   res  (inout) node_pressure and node_gap on entry; estimate_zone on exit
  !>   eta2 (inout) (nelem) the element indicators squared
  subroutine pressure_estimates(prob, res, eta2)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    real(dp), intent(inout) :: eta2(:)
    real(dp), allocatable :: s(:), ph(:), gap(:), wn(:), d2(:), p2(:)
    logical, allocatable :: zone(:)
    integer, allocatable :: eptr(:), elist(:)
    integer :: ip, k, ns, owner, gnode
    if (allocated(res%estimate_zone)) deallocate(res%estimate_zone)
    allocate(res%estimate_zone(prob%cs%npair), source=-1.0_dp)
    do ip = 1, prob%cs%npair
      associate (pr => prob%cs%pair(ip), bd => prob%sc%bodies(prob%cs%pair(ip)%spec%slave_body))
        ns = size(pr%snode)
        if (ns < 2) cycle
        allocate(s(ns), ph(ns), gap(ns), wn(ns), zone(ns), d2(ns - 1), p2(ns - 1))
        s(1) = 0.0_dp
        do k = 1, ns                        ! the trace's nodes: arc length, p_h, gap, measure, in the zone
          if (k > 1) s(k) = s(k - 1) + norm2(pr%xs(:, k) - pr%xs(:, k - 1))
          gnode = bd%dof0 / 2 + pr%snode(k)
          ph(k) = res%node_pressure(gnode)
          gap(k) = res%node_gap(gnode)
          wn(k) = merge(radial_weight(pr%xs(1, k)), bd%thick, bd%axisymmetric)
          zone(k) = row_of_node(prob%cs, ip, k) > 0
        end do
        call trace_errors(s, ph, gap, wn, zone, pr%quadratic, d2, p2)
        call node_elements(bd%mesh, eptr, elist)
        do k = 1, ns - 1                    ! each segment's share to the slave element that owns it
          if (d2(k) <= 0.0_dp) cycle
          owner = common_element(eptr, elist, pr%snode(k), pr%snode(k + 1))
          if (owner > 0 .and. bd%law%emax > 0.0_dp) &
            eta2(bd%elem0 + owner) = eta2(bd%elem0 + owner) + (s(k + 1) - s(k)) / bd%law%emax * d2(k)
        end do
        if (sum(p2) > 0.0_dp) res%estimate_zone(ip) = sqrt(sum(d2) / sum(p2))
        deallocate(s, ph, gap, wn, zone, d2, p2)
      end associate
    end do
  end subroutine pressure_estimates

  !> An element that has both nodes a and b (0: none), from the lists of
  !> the elements around each node.
  pure integer function common_element(eptr, elist, a, b) result(e)
    integer, intent(in) :: eptr(:), elist(:), a, b
    integer :: i
    e = 0
    do i = eptr(a), eptr(a + 1) - 1
      if (any(elist(eptr(b):eptr(b + 1) - 1) == elist(i))) then
        e = elist(i)
        return
      end if
    end do
  end function common_element

end module run_estimate
