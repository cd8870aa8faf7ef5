!> model_checks: the monitors of the model's assumptions, run once on the
!> final state, each a warning when the answer rests on an assumption it has
!> broken (doc/theory.md, "The model's assumptions, and the monitors that
!> guard them"):
!>   locking         3-node triangles with nu > 0.45 in plane strain or
!>                   axisymmetric analysis: they lock as nu -> 1/2 (4-node
!>                   quadrangles take B-bar then, quadratic elements do not lock)
!>   large_strain    a principal strain above 0.05 over more than 1 % of a
!>                   body's area: the strain is the linearized one,
!>                   eps = (grad u + grad u')/2
!>   large_rotation  a rotation above 0.05 rad over more than 1 % of a body's
!>                   area, or a RIGID turned by more: rotations are linearized too
!> and the summary's max_strain and max_rotation, the measures themselves.
!>
!> Why it exists: a small-strain linear elastic answer is silent about the
!> loads and geometries it does not describe; these checks make the run say
!> so.  Each threshold lives here once, with its reason.  Who may use it: the
!> program (one call, after the results are computed).
!>
!> Programming interface
!>   check_model(prob, res, log)   the monitors: res%max_strain, res%max_rotation set,
!>                                 a warning (run_log's add_warning) for each one broken
module model_checks
  use kinds, only: dp
  use strings, only: int_to_str, real_to_str, format_number
  use problem, only: problem_t
  use results_writer, only: results_t
  use run_log, only: log_t, add_warning
  use body, only: body_t
  use elements, only: quadrature_rule, shape_at, max_nen
  use material, only: locking_nu
  implicit none
  private
  public :: check_model

  !> strain above which the linearized strain misses its quadratic term
  !> (Green-Lagrange E = eps + grad u' grad u / 2) by more than 2.5 %
  real(dp), parameter :: strain_limit = 0.05_dp
  !> rotation (rad) above which the linearized rotation's spurious stretch
  !> theta^2 / 2 (1.25e-3) reaches the elastic strains of a metal at yield
  real(dp), parameter :: rotation_limit = 0.05_dp
  !> share of a body's area over a limit above which the run warns: the
  !> singular points of a linear solution (a punch's edge, a loaded corner, a
  !> zone end) pass any limit on a fine enough mesh, but over a zone that
  !> shrinks with the elements (below 0.6 % of the body in every deck of the
  !> tests); a load the model cannot carry passes it over a zone of its own
  !> size (1.6 % and more)
  real(dp), parameter :: area_limit = 0.01_dp

contains

  !> The model's monitors on the run's final state (module header).
  !>   res (inout) u (x, y components) on entry;
  !>               res%max_strain, max_rotation and the warnings on exit
  subroutine check_model(prob, res, log)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    type(log_t), intent(inout) :: log
    real(dp), allocatable :: over(:,:)
    call check_locking(prob, log)
    call measure_deformation(prob, res, over)
    call check_deformation(prob, res, over, log)
  end subroutine check_model

  !> A `warning locking` per body of isotropic material with nu > 0.45 meshed
  !> (in part) by elements that lock and that the scene's B-bar does not cure
  !> (body, elements' pressure_modes): 3-node triangles, whose strain is
  !> constant, so that its mean is itself; in plane strain or axisymmetric
  !> analysis.  4-node quadrangles take the mean dilatation (B-bar), and
  !> the quadratic elements have enough modes to follow div u = 0 without
  !> freezing (doc/theory.md, "Nearly incompressible materials").  Plane
  !> stress: the through-thickness strain takes up the volume change, nu
  !> causes no locking.  Orthotropic laws are not judged (their
  !> incompressibility is not one number).
  subroutine check_locking(prob, log)
    type(problem_t), intent(in) :: prob
    type(log_t), intent(inout) :: log
    integer :: b, ntri
    character(len=:), allocatable :: model
    if (prob%deck%plane_stress) return
    model = merge('axisymmetric analysis', 'plane strain         ', prob%deck%axisymmetric)
    do b = 1, size(prob%sc%bodies)
      associate (mat => prob%deck%bodies(b)%material, m => prob%sc%bodies(b)%mesh)
        if (.not. allocated(mat%kind)) cycle
        if (mat%kind /= 'isotropic' .or. mat%nu <= locking_nu) cycle
        ntri = count(m%nen == 3)
        if (ntri == 0) cycle
        call add_warning(log, 'locking', prob%deck%file // ':' // int_to_str(mat%line) // ': body "' // &
          prob%sc%bodies(b)%name // '": nu = ' // format_number(mat%nu) // ' above ' // format_number(locking_nu) // &
          ' on ' // int_to_str(ntri) // ' 3-node triangles in ' // trim(model) // ': they lock as nu -> 1/2 ' // &
          '(the displacements come out too small, the stresses oscillate); 4-node quadrangles (B-bar) and ' // &
          'quadratic elements (elem=tri6, quad8, quad9 or order=2) do not')
      end associate
    end do
  end subroutine check_locking

  !> res%max_strain and res%max_rotation: over the quadrature points of the
  !> stiffness rule of every element, the largest principal strain magnitude
  !> of eps = (grad u + grad u')/2 (in-plane; with the hoop strain u_r / r in
  !> axisymmetric analysis) and the largest |omega|, omega = (du_y/dx -
  !> du_x/dy)/2, with the point and the body where each is reached; and the
  !> share of each body's area (of its section, axisymmetric) where each
  !> passes its limit.
  !>   over (out) (2, nbody) that share, strain then rotation
  subroutine measure_deformation(prob, res, over)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(inout) :: res
    real(dp), allocatable, intent(out) :: over(:,:)
    real(dp) :: xe(2, max_nen), ue(2, max_nen), n(max_nen), dndx(2, max_nen), detj
    real(dp) :: g(2, 2), x(2), ur, c, r, strain, omega, da, area
    real(dp), allocatable :: xi(:,:), w(:)
    integer :: b, e, a, k, nen, d, rule_nen
    allocate(over(2, size(prob%sc%bodies)), source=0.0_dp)
    res%max_strain = 0.0_dp
    res%max_rotation = 0.0_dp
    res%max_strain_body = prob%sc%bodies(1)%name
    res%max_rotation_body = prob%sc%bodies(1)%name
    rule_nen = 0
    do b = 1, size(prob%sc%bodies)
      if (prob%sc%bodies(b)%finite) cycle      ! solved in finite strain: its strain is simulated, not linearized
      associate (bd => prob%sc%bodies(b), m => prob%sc%bodies(b)%mesh)
        area = 0.0_dp
        do e = 1, m%nelem
          nen = m%nen(e)
          do a = 1, nen
            xe(:, a) = m%x(:, m%conn(a, e))
            d = bd%dof0 + 2 * (m%conn(a, e) - 1)
            ue(:, a) = res%u(d + 1:d + 2)
          end do
          if (nen /= rule_nen) call quadrature_rule(nen, 1, xi, w)   ! once per element kind met
          rule_nen = nen
          do k = 1, size(w)
            call shape_at(nen, xe(:, 1:nen), xi(:, k), n(1:nen), dndx(:, 1:nen), detj)
            g = matmul(ue(:, 1:nen), transpose(dndx(:, 1:nen)))    ! g(i, j) = du_i / dx_j
            x = matmul(xe(:, 1:nen), n(1:nen))
            c = 0.5_dp * (g(1, 1) + g(2, 2))                       ! principal strains c +- r
            r = hypot(0.5_dp * (g(1, 1) - g(2, 2)), 0.5_dp * (g(1, 2) + g(2, 1)))
            strain = abs(c) + r
            if (bd%axisymmetric .and. x(1) > 0.0_dp) then
              ur = dot_product(ue(1, 1:nen), n(1:nen))
              strain = max(strain, abs(ur / x(1)))                 ! eps_tt = u_r / r
            end if
            omega = abs(0.5_dp * (g(2, 1) - g(1, 2)))
            da = w(k) * abs(detj)                                  ! the point's share of the area
            area = area + da
            if (strain > strain_limit) over(1, b) = over(1, b) + da
            if (omega > rotation_limit) over(2, b) = over(2, b) + da
            if (strain > res%max_strain(1)) then
              res%max_strain = [strain, x(1), x(2)]
              res%max_strain_body = bd%name
            end if
            if (omega > res%max_rotation(1)) then
              res%max_rotation = [omega, x(1), x(2)]
              res%max_rotation_body = bd%name
            end if
          end do
        end do
        if (area > 0.0_dp) over(:, b) = over(:, b) / area
      end associate
    end do
  end subroutine measure_deformation

  !> `warning large_strain` and `warning large_rotation` when the measures
  !> pass their limits over more than area_limit of a body (the body with the
  !> largest share named, with the largest value and its point); a RIGID
  !> turned by more than the rotation limit too
  !> (its points move by the linearized U(x) = u + theta e_z x (x - x_r)),
  !> unless it is a circle turned about its centre.
  subroutine check_deformation(prob, res, over, log)
    type(problem_t), intent(in) :: prob
    type(results_t), intent(in) :: res
    type(log_t), intent(inout) :: log
    real(dp), intent(in) :: over(:,:)
    integer :: r, bs, bo
    character(len=*), parameter :: why = ': the model is small-deformation linear elasticity (strains and ' // &
      'rotations linearized, contact pairing and normals of the initial configuration); its answer is not to be ' // &
      'trusted there'
    bs = maxloc(over(1, :), dim=1)
    bo = maxloc(over(2, :), dim=1)
    associate (s => res%max_strain, o => res%max_rotation)
      if (over(1, bs) > area_limit) call add_warning(log, 'large_strain', 'the principal strain exceeds ' // &
        format_number(strain_limit) // ' over ' // percent(over(1, bs)) // ' of body "' // prob%sc%bodies(bs)%name // &
        '" (the largest, ' // real_to_str(s(1)) // ', in body "' // res%max_strain_body // '" at (' // &
        real_to_str(s(2)) // ', ' // real_to_str(s(3)) // '))' // why // ' (check the loads and units, and ' // &
        'any initial penetration an interference=allow pair accepts)')
      if (over(2, bo) > area_limit) call add_warning(log, 'large_rotation', 'the rotation exceeds ' // &
        format_number(rotation_limit) // ' rad over ' // percent(over(2, bo)) // ' of body "' // &
        prob%sc%bodies(bo)%name // '" (the largest, ' // real_to_str(o(1)) // ' rad, in body "' // &
        res%max_rotation_body // '" at (' // real_to_str(o(2)) // ', ' // real_to_str(o(3)) // '))' // why)
    end associate
    do r = 1, size(prob%sc%rigids)
      if (abs(res%rigid(3, r)) <= rotation_limit) cycle
      ! a circle turned about its centre moves along itself: its gaps do not
      ! depend on the rotation, linearized or not
      associate (sh => prob%sc%rigids(r))
        if (prob%deck%rigids(r)%shape == 'circle' .and. norm2(sh%ref - sh%centre) <= 1.0e-12_dp * sh%radius) cycle
      end associate
      call add_warning(log, 'large_rotation', 'RIGID "' // prob%sc%rigids(r)%name // '" turns by ' // &
        real_to_str(res%rigid(3, r)) // ' rad, above ' // format_number(rotation_limit) // ' rad' // why)
    end do
  end subroutine check_deformation

  !> f (a fraction) as a percentage: '100 %', '41 %', '4.1 %', '0.12 %', '1.2E-03 %'.
  function percent(f) result(t)
    real(dp), intent(in) :: f
    character(len=:), allocatable :: t
    character(len=16) :: buf
    real(dp) :: p
    p = 100.0_dp * f
    if (p >= 9.95_dp) then
      write(buf, '(i0)') nint(p)
    else if (p >= 0.995_dp) then
      write(buf, '(f4.1)') p
    else if (p >= 0.00995_dp) then
      write(buf, '(f5.2)') p
    else
      buf = real_to_str(p)
    end if
    t = trim(adjustl(buf)) // ' %'
  end function percent

end module model_checks
