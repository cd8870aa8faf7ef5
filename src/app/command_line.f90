!> command_line: the options of contact2d (doc/deck.md, "Command line") read
!> into the program's settings, the help text and the usage errors.  One job:
!> the words a user typed, checked and turned into values; everything they
!> mean for the run happens in the program.
!>
!> Programming interface
!>   version                      the program's version
!>   parse_command_line(...)      every option; exit 2 on a bad one, 0 after --help / --version
!>   case_index(text, what)       a case number (1, 2, ...) from an option or SLURM_ARRAY_TASK_ID
!>   usage_error(text)            `contact2d: error: TEXT` on stderr, exit 2
module command_line
  use kinds, only: dp
  use exits, only: exit_program
  use deck_expressions, only: parameter_set_t, add_parameter, find_parameter, evaluate, is_parameter_name
  use gmsh_runner, only: gmsh_options_t
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  implicit none
  private
  public :: version, parse_command_line, case_index, usage_error

  character(len=*), parameter :: version = '1.0.0'

contains

  subroutine parse_command_line(deck_path, outdir, check_only, quiet, gmsh, overrides, cases_path, case_number, jobs)
    character(len=:), allocatable, intent(out) :: deck_path, outdir
    logical, intent(out) :: check_only, quiet
    type(gmsh_options_t), intent(out) :: gmsh
    type(parameter_set_t), intent(out) :: overrides
    character(len=:), allocatable, intent(out) :: cases_path
    integer, intent(out) :: case_number
    integer, intent(out) :: jobs            !< -j N; 0 when not given
    integer :: n, j, length, ios
    character(len=:), allocatable :: arg
    logical :: keep_meshes
    check_only = .false.
    keep_meshes = .true.
    quiet = .false.
    jobs = 0
    outdir = '.'
    deck_path = ''
    cases_path = ''
    case_number = 0
    n = command_argument_count()
    j = 0
    do while (j < n)
      j = j + 1
      call get_command_argument(j, length=length)
      allocate(character(len=length) :: arg)
      call get_command_argument(j, arg)
      select case (arg)
      case ('-h', '--help')
        call print_help()
        call exit_program(0)
      case ('--version')
        write(output_unit, '(a)') 'contact2d ' // version
        call exit_program(0)
      case ('--check')
        check_only = .true.
      case ('-q')
        quiet = .true.
      case ('--trust-geo')
        gmsh%trust_geo = .true.
      case ('--no-mesh-cache')
        keep_meshes = .false.
      case ('--gmsh-timeout')
        call option_value(j, n, arg, 'option --gmsh-timeout needs a number of seconds (--gmsh-timeout SECONDS)')
        ios = 1
        if (verify(arg, '0123456789.eE+') == 0 .and. len(arg) > 0) read(arg, *, iostat=ios) gmsh%timeout
        if (ios /= 0 .or. .not. (gmsh%timeout > 0.0_dp .and. gmsh%timeout <= 1.0e6_dp)) &
          call usage_error('bad value "' // arg // '" for --gmsh-timeout (seconds, a number > 0 and <= 1e6, ' // &
                           'expected)')
      case ('-D')
        call option_value(j, n, arg, 'option -D needs a parameter value (-D name=value)')
        call add_override(arg, overrides)
      case ('--cases')
        call option_value(j, n, arg, 'option --cases needs a case table (--cases FILE.csv)')
        cases_path = arg
        if (len(cases_path) == 0) call usage_error('option --cases needs a case table (--cases FILE.csv)')
      case ('--case')
        call option_value(j, n, arg, 'option --case needs a case number (--case N)')
        case_number = case_index(arg, '--case')
      case ('-j')
        call option_value(j, n, arg, 'option -j needs a number of threads (-j N)')
        ios = 1
        if (verify(arg, '0123456789') == 0 .and. len(arg) > 0 .and. len(arg) <= 4) read(arg, *, iostat=ios) jobs
        if (ios /= 0 .or. jobs < 1) call usage_error('bad value "' // arg // '" for -j (a number of threads, ' // &
                                                     '1 to 9999, expected)')
      case ('-o')
        if (j == n) call usage_error('option -o needs a folder (-o DIR)')
        j = j + 1
        call get_command_argument(j, length=length)
        deallocate(outdir)
        allocate(character(len=length) :: outdir)
        call get_command_argument(j, outdir)
        if (length == 0) call usage_error('option -o needs a folder (-o DIR)')
      case default
        if (len(arg) > 2) then
          if (arg(1:2) == '-D') then                 ! -Dname=value
            call add_override(arg(3:), overrides)
            deallocate(arg)
            cycle
          end if
        end if
        if (len(arg) > 0) then
          if (arg(1:1) == '-') call usage_error('unknown option "' // arg // '" (expected -o DIR, -j N, --check, -q, ' // &
                                                '-D name=value, --cases FILE.csv, --case N, ' // &
                                                '--trust-geo, --gmsh-timeout SECONDS, --no-mesh-cache, ' // &
                                                '--version, -h)')
        end if
        if (len(deck_path) > 0) call usage_error('more than one deck given ("' // deck_path // '" and "' // arg // &
                                                  '"; one DECK expected)')
        deck_path = arg
      end select
      deallocate(arg)
    end do
    if (len(deck_path) == 0) call usage_error('no deck given (usage: contact2d [options] DECK)')
    ! the meshes gmsh makes are kept in the output folder given, which the
    ! cases of a sweep share (each case's outputs go to DIR/case_N below it)
    gmsh%cache = ''
    if (keep_meshes) gmsh%cache = outdir // '/.mesh_cache'
    if (case_number > 0 .and. len(cases_path) == 0) &
      call usage_error('option --case N needs --cases FILE.csv (the table the case is a row of)')
  end subroutine parse_command_line

  !> -D name=value: value is a number or an expression of numbers (no parameters).
  subroutine add_override(text, set)
    character(len=*), intent(in) :: text
    type(parameter_set_t), intent(inout) :: set
    type(parameter_set_t) :: none
    character(len=:), allocatable :: message
    integer :: eq
    real(dp) :: x
    eq = index(text, '=')
    if (eq < 2) call usage_error('bad -D "' // text // '" (expected -D name=value)')
    if (.not. is_parameter_name(text(1:eq - 1))) &
      call usage_error('bad parameter name in -D "' // text // '" (expected a letter or _ then letters, digits, _)')
    if (find_parameter(set, text(1:eq - 1)) > 0) &
      call usage_error('-D ' // text(1:eq - 1) // ' given twice (expected each parameter once)')
    call evaluate(text(eq + 1:), none, x, message)
    if (allocated(message)) call usage_error('-D ' // text // ': ' // message)
    call add_parameter(set, text(1:eq - 1), x, '-D')
  end subroutine add_override

  !> A case number (1, 2, ...) from option or variable `what`.
  integer function case_index(text, what) result(k)
    character(len=*), intent(in) :: text, what
    integer :: ios
    k = 0
    ios = 1
    if (len(text) > 0 .and. len(text) <= 9 .and. verify(text, '0123456789') == 0) read(text, *, iostat=ios) k
    if (ios /= 0 .or. k < 1) call usage_error('bad case number "' // text // '" in ' // what // &
                                             ' (expected an integer >= 1: a row of the case table)')
  end function case_index

  !> The value of the option at argument j of n: j moves to the next
  !> argument, arg becomes it; missing is the error when there is none.
  subroutine option_value(j, n, arg, missing)
    integer, intent(inout) :: j
    integer, intent(in) :: n
    character(len=:), allocatable, intent(inout) :: arg
    character(len=*), intent(in) :: missing
    integer :: length
    if (j == n) call usage_error(missing)
    j = j + 1
    call get_command_argument(j, length=length)
    deallocate(arg)
    allocate(character(len=length) :: arg)
    call get_command_argument(j, arg)
  end subroutine option_value

  subroutine usage_error(text)
    character(len=*), intent(in) :: text
    write(error_unit, '(a)') 'contact2d: error: ' // text
    call exit_program(2)
  end subroutine usage_error

  subroutine print_help()
    write(output_unit, '(a)') &
      'usage: contact2d [options] DECK', &
      '', &
      'Unilateral (Signorini) contact between elastic bodies in 2D by the mortar', &
      'finite element method: plane strain, plane stress or axisymmetric elasticity', &
      'on linear (tri3, quad4) and quadratic (tri6, quad8, quad9) elements; contact', &
      'between bodies and against rigid obstacles, frictionless or with Coulomb or', &
      'Tresca friction in load steps; the condensed LCP solved by Lemke, projected', &
      'Gauss-Seidel or a primal-dual active set (semismooth Newton) method.', &
      '', &
      'options:', &
      '  -o DIR       write all outputs into DIR (created if missing; default .)', &
      '  -j N         run on N threads (OpenMP and OpenBLAS; default: OMP_NUM_THREADS,', &
      '               else one per core)', &
      '  --check      read and validate the deck and meshes, print the scene, solve nothing', &
      '  -q           quiet: only errors on stderr (the summary file is still written)', &
      '  --trust-geo  let gmsh run a .geo as it is: no screen, no sandbox (it may then run', &
      '               commands and write files); without it, a .geo that runs commands, writes', &
      '               files or reads outside the deck''s folder is refused (exit 2)', &
      '  --gmsh-timeout SECONDS', &
      '               time limit of gmsh on each .geo (default 600); gmsh is then stopped', &
      '  --no-mesh-cache  mesh every .geo with gmsh; by default the meshes gmsh makes are', &
      '               kept in DIR/.mesh_cache and reused by the runs (the cases of a sweep,', &
      '               re-runs) with the same .geo, parameters, order and gmsh', &
      '  -D name=value  replace the default of the deck''s PARAMETER name (repeatable; value a', &
      '               number or an expression of numbers); an undeclared name is an error', &
      '  --cases FILE.csv  a sweep: header row = parameter names, one row per case; runs every', &
      '               case in turn, case N into DIR/case_N (exit status: the worst of the cases)', &
      '  --case N     with --cases: row N only (without it, SLURM_ARRAY_TASK_ID when set)', &
      '  --version    print the version', &
      '  -h, --help   this help', &
      '', &
      'deck statements (keywords and keys case-insensitive; ! and # start comments):', &
      '  PARAMETER name=value ...          (then ${name} or ${expression} anywhere in a later', &
      '                                    line: numbers, parameters, + - * / ^ ( ), pi,', &
      '                                    sqrt exp log sin cos tan abs min max)', &
      '  TITLE text', &
      '  PLANE strain | PLANE stress thickness=T | PLANE axisymmetric   (x = r >= 0, y = z; full-circle forces)', &
      '  BODY name ... END', &
      '    MESH rect x0= y0= x1= y1= nx= ny= [elem=tri3|quad4|tri6|quad8|quad9] [diag=right|left|alt]', &
      '                                      (tri6, quad8 serendipity, quad9 Lagrange: quadratic elements)', &
      '    MESH gmsh file=F.msh              (MSH 2.2 or 4.1 ASCII; physical groups name boundaries;', &
      '                                      first or second order: 6-node triangles, 8-/9-node quads)', &
      '    MESH gmsh file=F.geo [order=1|2] [name=value ...]   (meshed by gmsh -2 -order N', &
      '                                      -setnumber name value; order=2: curved edges kept)', &
      '    MATERIAL isotropic E= nu=', &
      '    MATERIAL orthotropic E1= E2= nu12= G12= [angle=0] [E3= nu13= nu23=]', &
      '    DENSITY rho=', &
      '    FIX boundary [ux=] [uy=] [ramp=k0:k1|curve=NAME]', &
      '    FIX boundary [un=] [ut=] [...]    (local axes: outward normal n, t = (-n_y, n_x))', &
      '    TRACTION boundary tx= ty= [ramp=k0:k1|curve=NAME]', &
      '    TRACTION boundary tn= tt= [...]   (along each edge''s outward normal n and t)', &
      '    PRESSURE boundary p= [ramp=k0:k1|curve=NAME]', &
      '    BODYFORCE fx= fy= [ramp=k0:k1|curve=NAME]', &
      '    THERMAL alpha= dT= [region=NAME] [curve=NAME]  (uniform temperature change; per physical surface)', &
      '    OFFSET dx= dy=                    (rigid shift of the body''s geometry)', &
      '    FORCE point [fx=] [fy=] [ramp=k0:k1|curve=NAME]  (at each node of a point set: a gmsh Physical Point)', &
      '    SPRING boundary kn= [kt=0]        (elastic foundation, per unit length (area axisymmetric), n and t)', &
      '    SPRING point [kx=] [ky=]          (a spring to the ground at each node of a point set)', &
      '  GRAVITY gx= gy= [ramp=k0:k1|curve=NAME]', &
      '  CONTACT slave=body:boundary master=body:boundary [gap=geometry|zero] [mu=C | tresca=S]', &
      '          [interference=allow|reject] [sliding=small]  (a boundary may be a closed curve; an', &
      '                                    initial penetration deeper than a slave element is refused', &
      '                                    unless allowed; sliding=small, the pairing and normals of the', &
      '                                    initial configuration, is the only kinematics: finite is refused)', &
      '                                    (frictionless unless mu= (Coulomb) or tresca= (slip bound);', &
      '                                    quadratic elements: frictionless, and not in PLANE axisymmetric)', &
      '  CONTACT slave=body:boundary master=RIGIDNAME [mu=C | tresca=S]   (against a RIGID''s exact shape)', &
      '  RIGID name ... END                (a rigid obstacle: its dofs ux, uy, rz of the reference point;', &
      '                                    not in PLANE axisymmetric)', &
      '    SHAPE line x0= y0= x1= y1=  |  SHAPE circle xc= yc= r= [solid=inside|outside]', &
      '    SHAPE polyline points=x1:y1,x2:y2,...   (solid on the side the slave faces)', &
      '    REF x= y=                         (default: the circle''s centre, the first point)', &
      '    FIX [ux=] [uy=] [rz=] [ramp=k0:k1|curve=NAME]   (prescribed; FIX alone: all 0)', &
      '    FORCE [fx=] [fy=] [m=] [ramp=k0:k1|curve=NAME]  (on the directions FIX leaves free)', &
      '                                    (no FIX and no FORCE: held fixed)', &
      '  SOLVER lcp=auto|lemke|pgs|pdas [tol=1e-10] [maxit=N] [omega=1.0]   (pdas: frictionless only)', &
      '         [ordering=auto|metis|amd]  (fill-reducing ordering; auto: AMD up to 5e5 free dofs, METIS above)', &
      '         [condense=auto|solve|inverse]  (W per body: triangular solves or the block''s inverse)', &
      '         [cut=auto|off]  (accepted and ignored: no body is cut)', &
      '  STEPS n                           (load steps; ramp=k0:k1: load 0 at step k0 rising to 1 at k1)', &
      '  CURVE name t0:v0 t1:v1 ...        (load factor v against the step t, piecewise linear: curve=name)', &
      '  ESTIMATE [on|off]                 (the run''s own error estimate, on by default)', &
      '  OUTPUT [vtk=FILE] [contact=FILE.csv] [summary=FILE] [fields=displacement,contact_pressure,gap,stress,von_mises]', &
      '         [steps=last|all]  (all: FILE_0001.vtu and a contact table per step, FILE.pvd, FILE_steps.csv)', &
      '         [plot=none|png]  (png: FILE_pressure.png, with steps=all FILE_steps.png, drawn by gnuplot)', &
      '', &
      'outputs (doc/outputs.md): DECK.vtk (ParaView), DECK_contact.csv (a row per slave node),', &
      'DECK.summary (key value lines: energy, reactions and mean displacement of each FIX boundary,', &
      'per pair the contact force, the contact zone''s ends and length, the peak pressure and where', &
      'it is, the centre of pressure, the stick zone with friction; the error estimate, timings);', &
      'with steps=all DECK_steps.csv, a row per step, columns named reaction_BODY:BOUNDARY_fx,', &
      'displacement_BODY:BOUNDARY_ux, contact_force_PAIR_fx, contact_zone_PAIR_x0, rigid_NAME_ux, ...', &
      '', &
      'exit status: 0 solved, 1 solver failure (diagnostic on stderr), 2 bad input.', &
      'See doc/deck.md for every statement, default and output.'
  end subroutine print_help

end module command_line
