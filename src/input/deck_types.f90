!> deck_types: the input deck as data (deck_t and its parts), what deck_reader
!> returns and scene reads.  Every component is documented where it is
!> declared; doc/deck.md and DECK.md give the statements they come from.
!>
!> Load steps.  ramp=k0:k1 (integers, 0 <= k0 < k1 <= STEPS) scales the statement's
!> values by the load factor 0 up to step k0, rising linearly to 1 at step k1, 1 after;
!> absent, the ramp is 0:STEPS.  Every ramp is resolved by the reader (fix_t%ramp,
!> load_t%ramp, body_deck_t%bodyforce_ramp, deck_t%gravity_ramp hold [k0, k1], also
!> for absent statements; their initial value [0, 1] is the default for STEPS 1).
!> curve=NAME instead of ramp= follows a CURVE: the statements' `curve` index
!> (0: the ramp); curve_factor(c, k) is curve c's factor at step k.
!>
!> Programming interface
!>   types fix_t, load_t, mesh_spec_t, material_t, thermal_t, body_deck_t,
!>         rigid_load_t, rigid_deck_t, contact_deck_t, solver_deck_t,
!>         output_deck_t, curve_t, deck_t
!>   spring_deck_t                  a SPRING statement
!>   load_traction, load_pressure, load_point   values of load_t%kind
!>   curve_factor(c, k)             load factor of CURVE c at step k
module deck_types
  use kinds, only: dp
  use deck_expressions, only: parameter_set_t
  implicit none
  private
  public :: fix_t, load_t, mesh_spec_t, material_t, thermal_t, body_deck_t, contact_deck_t, adapt_deck_t
  public :: solver_deck_t, output_deck_t, deck_t, curve_t, curve_factor, rigid_deck_t, rigid_load_t
  public :: load_traction, load_pressure, load_point, spring_deck_t

  integer, parameter :: load_traction = 1   !< load_t%kind of TRACTION
  integer, parameter :: load_pressure = 2   !< load_t%kind of PRESSURE
  integer, parameter :: load_point = 3      !< load_t%kind of FORCE in a BODY: tx, ty hold fx, fy

  !> FIX boundary [ux=] [uy=] [ramp=k0:k1]
  type :: fix_t
    character(len=:), allocatable :: boundary   !< boundary or point-set name
    logical :: has_ux = .false., has_uy = .false.
    real(dp) :: ux = 0, uy = 0                  !< prescribed displacements
    logical :: local = .false.                  !< un=/ut=: has_ux, ux hold un (normal), has_uy, uy ut
    integer :: ramp(2) = [0, 1]                 !< load steps k0, k1 of the ramp; default [0, steps]
    integer :: curve = 0                        !< curve=NAME: index into deck%curves (0: the ramp)
    character(len=:), allocatable :: curve_name !< curve=NAME as written ('' when absent)
    integer :: line = 0                         !< deck line
  end type fix_t

  !> TRACTION or PRESSURE on a boundary, or FORCE on the node(s) of a point set
  type :: load_t
    integer :: kind = 0                         !< load_traction, load_pressure or load_point
    character(len=:), allocatable :: boundary   !< boundary (point set for FORCE) name
    real(dp) :: tx = 0, ty = 0, p = 0           !< force per unit length (FORCE: the force); pressure
    logical :: local = .false.                  !< TRACTION tn= tt=: tx holds tn, ty holds tt (boundary axes)
    integer :: ramp(2) = [0, 1]                 !< load steps k0, k1 of the ramp; default [0, steps]
    integer :: curve = 0                        !< curve=NAME: index into deck%curves (0: the ramp)
    character(len=:), allocatable :: curve_name !< curve=NAME as written ('' when absent)
    integer :: line = 0
  end type load_t

  !> SPRING boundary kn= [kt=] (an elastic foundation, stiffness per unit
  !> length, per unit area axisymmetric, along the boundary's outward normal
  !> and its tangent) or SPRING point [kx=] [ky=] (a spring to the ground at
  !> the node(s) of a point set).  A stiffness, not a load: no ramp, no curve.
  type :: spring_deck_t
    character(len=:), allocatable :: boundary   !< boundary or point-set name
    logical :: point = .false.                  !< kx=/ky= given: a point spring; else kn=/kt=
    real(dp) :: kn = 0, kt = 0                  !< foundation moduli, >= 0
    real(dp) :: kx = 0, ky = 0                  !< point spring stiffnesses, >= 0
    integer :: line = 0
  end type spring_deck_t

  !> MESH rect ... or MESH gmsh file=...
  type :: mesh_spec_t
    character(len=:), allocatable :: kind       !< 'rect' or 'gmsh' ('' when the statement was bad)
    real(dp) :: x0 = 0, y0 = 0, x1 = 1, y1 = 1  !< rect: corners
    integer :: nx = 0, ny = 0                   !< rect: cells along x and y
    character(len=:), allocatable :: elem       !< rect: 'tri3' (default), 'quad4', 'tri6', 'quad8', 'quad9'; gmsh: ''
    character(len=:), allocatable :: diag       !< rect: 'right' (default), 'left' or 'alt'; gmsh: ''
    character(len=:), allocatable :: file       !< gmsh: path as written in the deck; rect: ''
    character(len=:), allocatable :: path       !< gmsh: path resolved against the deck's folder
    logical :: is_geo = .false.                 !< gmsh: file ends in .geo (mesh with gmsh -2)
    integer :: order = 1                        !< gmsh .geo: element order, gmsh -order 1 or 2 (order=)
    character(len=64), allocatable :: set_names(:)  !< (nset) .geo parameters, case as written
    real(dp), allocatable :: set_values(:)      !< (nset) their values
    integer :: line = 0                         !< line of the MESH statement (0: none)
  end type mesh_spec_t

  !> MATERIAL isotropic ... or MATERIAL orthotropic ...
  type :: material_t
    character(len=:), allocatable :: kind       !< 'isotropic', 'orthotropic', 'neo_hookean',
                                                !< 'mooney_rivlin' ('' when bad)
    real(dp) :: e = 0, nu = 0                   !< isotropic
    real(dp) :: e1 = 0, e2 = 0, nu12 = 0, g12 = 0, angle = 0   !< orthotropic; angle in degrees
    real(dp) :: e3 = 0, nu13 = 0, nu23 = 0      !< out-of-plane; defaults E3=E2, nu13=nu23=nu12
    real(dp) :: c10 = 0, c01 = 0, bulk = 0      !< hyperelastic (neo_hookean: c10 = mu/2, c01 = 0), K > 0
    integer :: line = 0                         !< line of the MATERIAL statement (0: none)
  end type material_t

  !> ADAPT target= [quantity=] [max_steps=] [max_dofs=]: solve, re-mesh
  !> every body with gmsh from the error indicators, solve again, until the
  !> estimate is below target or a limit is hit.
  type :: adapt_deck_t
    logical :: on = .false.
    real(dp) :: target = 0                      !< relative error sought, 0 < target < 1
    character(len=:), allocatable :: quantity   !< 'energy' (default) or 'pressure'
    integer :: max_steps = 10                   !< meshes solved, the deck's first one included
    integer :: max_dofs = 2000000               !< no mesh beyond this many dofs
    integer :: line = 0                         !< line of the ADAPT statement (0: none)
  end type adapt_deck_t

  !> One BODY ... END block.
  !> THERMAL alpha= dT= [region=]: a uniform temperature change dT (from the
  !> stress-free state) with expansion coefficient alpha, on the whole body or on
  !> one physical surface (element region) of a gmsh mesh.
  type :: thermal_t
    real(dp) :: alpha = 0, dt = 0
    character(len=:), allocatable :: region     !< '' for the whole body
    integer :: curve = 0                        !< curve=NAME: index into deck%curves (0: ramp 0:STEPS)
    character(len=:), allocatable :: curve_name !< curve=NAME as written ('' when absent)
    integer :: line = 0
  end type thermal_t

  type :: body_deck_t
    character(len=:), allocatable :: name
    integer :: line = 0                         !< line of the BODY statement
    type(mesh_spec_t) :: mesh
    type(material_t) :: material
    logical :: has_density = .false.; real(dp) :: rho = 0; integer :: density_line = 0
    type(fix_t), allocatable :: fixes(:)        !< (nfix), always allocated
    type(load_t), allocatable :: loads(:)       !< (nload), always allocated
    integer :: nfix = 0, nload = 0              !< statements held while reading: the arrays
                                                !< grow by doubling and are cut to these at the end
    logical :: has_bodyforce = .false.; real(dp) :: fx = 0, fy = 0; integer :: bodyforce_line = 0
    integer :: bodyforce_ramp(2) = [0, 1]       !< BODYFORCE ramp k0, k1; default [0, steps]
    integer :: bodyforce_curve = 0              !< BODYFORCE curve=: index into deck%curves (0: the ramp)
    character(len=:), allocatable :: bodyforce_curve_name
    type(thermal_t), allocatable :: thermals(:) !< (nthermal), always allocated
    type(spring_deck_t), allocatable :: springs(:) !< (nspring) SPRING statements, always allocated
    logical :: has_offset = .false.; real(dp) :: dx = 0, dy = 0; integer :: offset_line = 0
  end type body_deck_t

  !> FIX [ux=] [uy=] [rz=] or FORCE [fx=] [fy=] [m=] of a RIGID, with its load path.
  type :: rigid_load_t
    logical :: has(3) = .false.                 !< the directions it names (u_x, u_y, theta / f_x, f_y, m)
    real(dp) :: value(3) = 0                    !< their values (theta in radians)
    integer :: ramp(2) = [0, 1]                 !< ramp k0:k1; default [0, steps]
    integer :: curve = 0                        !< curve=NAME: index into deck%curves (0: the ramp)
    character(len=:), allocatable :: curve_name !< curve=NAME as written ('' when absent)
    integer :: line = 0
  end type rigid_load_t

  !> RIGID name ... END: a rigid obstacle, its exact shape and the motion or
  !> load of its reference point (FIX ux= uy= rz=, FORCE fx= fy= m=).  The
  !> directions FIX names are prescribed, the others free and loaded by FORCE
  !> (0 when FORCE does not name them); no FIX and no FORCE: held fixed.
  type :: rigid_deck_t
    character(len=:), allocatable :: name
    integer :: line = 0                         !< line of the RIGID statement
    character(len=:), allocatable :: shape      !< 'line', 'circle', 'polyline' ('' when none)
    real(dp), allocatable :: points(:,:)        !< (2, np) line: its two ends; polyline: its points
    real(dp) :: centre(2) = 0, radius = 0       !< circle
    logical :: outside = .false.                !< circle solid=outside: a hole in a rigid solid
    integer :: shape_line = 0
    logical :: has_ref = .false.; real(dp) :: ref(2) = 0; integer :: ref_line = 0
    type(rigid_load_t), allocatable :: fixes(:)   !< FIX statements (each direction in one at most)
    type(rigid_load_t), allocatable :: forces(:)  !< FORCE statements (each direction in one at most)
  end type rigid_deck_t

  !> CONTACT slave=body:boundary master=body:boundary|RIGID [gap=] [mu= | tresca=] [name=]
  type :: contact_deck_t
    integer :: slave_body = 0, master_body = 0  !< indices into deck%bodies (master 0 for a RIGID)
    integer :: master_rigid = 0                 !< master=RIGIDNAME: index into deck%rigids
    character(len=:), allocatable :: slave_boundary, master_boundary
    logical :: gap_zero = .false.               !< gap=zero; default gap=geometry
    logical :: interference = .false.           !< interference=allow: any initial penetration accepted
    logical :: finite = .false.                 !< sliding=finite: the geometry follows the bodies
    logical :: small_given = .false.            !< sliding=small written (a hyperelastic body refuses it)
    character(len=:), allocatable :: friction   !< 'none' (default), 'coulomb' (mu=) or 'tresca' (tresca=)
    real(dp) :: mu = 0                          !< Coulomb coefficient, 0 <= mu <= 1000
    real(dp) :: tresca = 0                      !< Tresca slip bound (a shear stress), >= 0
    character(len=:), allocatable :: name       !< name=NAME, what the outputs call the pair ('' : its number)
    integer :: line = 0
  end type contact_deck_t

  !> SOLVER [lcp=] [tol=] [maxit=] [omega=] [ordering=] [condense=] [cut=] [updates=]
  !> [newton_tol=] [newton_maxit=] [newton_lcp=]
  type :: solver_deck_t
    character(len=:), allocatable :: lcp        !< 'auto' (default), 'lemke', 'pgs', 'pdas'
    character(len=:), allocatable :: ordering   !< 'auto' (default), 'metis', 'amd'
    character(len=:), allocatable :: condense   !< 'auto' (default), 'solve', 'inverse'
    character(len=:), allocatable :: cut        !< 'auto' or 'off' when given (else unallocated): read, checked, said to be ignored (no body is cut)
    real(dp) :: tol = 1.0e-10_dp
    integer :: maxit = 0                        !< 0: the solver's default
    real(dp) :: omega = 1.0_dp
    integer :: updates = 30                     !< sliding=finite: geometry updates allowed per load step
    real(dp) :: newton_tol = 1.0e-8_dp          !< finite strain: Newton residual / load scale at convergence
    integer :: newton_maxit = 25                !< finite strain: Newton iterations before a step is cut
    character(len=:), allocatable :: newton_lcp  !< finite strain: 'lemke' (default) or 'active_set' when given
    integer :: line = 0
  end type solver_deck_t

  !> OUTPUT [vtk=] [contact=] [summary=] [fields=] [steps=] [plot=] [x=]; names relative to the output folder
  type :: output_deck_t
    character(len=:), allocatable :: vtk, contact, summary
    !> fields of the VTK file: displacement, contact_pressure, gap, stress, von_mises
    logical :: fields(5) = .true.
    logical :: steps_all = .false.              !< steps=all: VTK per step, .pvd, NAME_steps.csv
    logical :: plot = .false.                   !< plot=png: NAME_pressure.png (and NAME_steps.png) drawn by gnuplot
    character(len=:), allocatable :: x          !< x=: the steps plot's abscissa, a column of NAME_steps.csv
                                                !< (unallocated: the default ramp's load factor)
    integer :: line = 0
  end type output_deck_t

  !> CURVE name t0:v0 t1:v1 ...: a piecewise-linear load factor v(t) against
  !> the step number t, constant before t0 and after the last point.
  type :: curve_t
    character(len=:), allocatable :: name
    real(dp), allocatable :: t(:), v(:)         !< (npoint) t strictly increasing
    integer :: line = 0
  end type curve_t

  !> The whole deck.
  type :: deck_t
    character(len=:), allocatable :: file       !< the deck path as given (used in messages)
    character(len=:), allocatable :: dir        !< its folder ('.' when none)
    character(len=:), allocatable :: name       !< file name without folder and extension
    character(len=:), allocatable :: title      !< '' when none
    logical :: plane_stress = .false.; real(dp) :: thickness = 1.0_dp
    logical :: axisymmetric = .false.           !< PLANE axisymmetric: x = r >= 0, y = z
    integer :: plane_line = 0                   !< line of the PLANE statement (0: none)
    type(body_deck_t), allocatable :: bodies(:) !< (nbody), always allocated
    logical :: has_gravity = .false.; real(dp) :: gx = 0, gy = 0; integer :: gravity_line = 0
    integer :: gravity_ramp(2) = [0, 1]         !< GRAVITY ramp k0, k1; default [0, steps]
    integer :: gravity_curve = 0                !< GRAVITY curve=: index into deck%curves (0: the ramp)
    character(len=:), allocatable :: gravity_curve_name
    type(curve_t), allocatable :: curves(:)     !< (ncurve) CURVE statements, always allocated
    integer :: steps = 1                        !< STEPS n: load steps, 1 <= n <= max_steps
    integer :: steps_line = 0                   !< line of the STEPS statement (0: none)
    logical :: estimate = .true.                !< ESTIMATE [on|off|bound]: the a posteriori error estimate
    logical :: estimate_bound = .false.         !< ESTIMATE bound: its guaranteed upper bound too
    integer :: estimate_line = 0                !< line of the ESTIMATE statement (0: none)
    type(adapt_deck_t) :: adapt                 !< ADAPT (adapt%on false when none)
    type(contact_deck_t), allocatable :: contacts(:)   !< (ncontact), always allocated
    type(rigid_deck_t), allocatable :: rigids(:) !< (nrigid) RIGID blocks, always allocated
    type(solver_deck_t) :: solver
    type(output_deck_t) :: output
    type(parameter_set_t) :: params             !< PARAMETER: names, final values, origins
  end type deck_t

contains

  !> Load factor of curve c at step k: linear between its points, its first
  !> value before the first point and its last value after the last one.
  pure real(dp) function curve_factor(c, k) result(f)
    type(curve_t), intent(in) :: c
    real(dp), intent(in) :: k
    integer :: i, n
    n = size(c%t)
    if (k <= c%t(1)) then
      f = c%v(1)
    else if (k >= c%t(n)) then
      f = c%v(n)
    else
      do i = 2, n
        if (k <= c%t(i)) exit
      end do
      f = c%v(i - 1) + (c%v(i) - c%v(i - 1)) * (k - c%t(i - 1)) / (c%t(i) - c%t(i - 1))
    end if
  end function curve_factor

end module deck_types
