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

  subroutine parse_command_line(deck_path, outdir, check_only, quiet, gmsh, overrides, cases_path, case_number, jobs, &
                                collect)
    character(len=:), allocatable, intent(out) :: deck_path, outdir
    logical, intent(out) :: check_only, quiet
    type(gmsh_options_t), intent(out) :: gmsh
    type(parameter_set_t), intent(out) :: overrides
    character(len=:), allocatable, intent(out) :: cases_path
    integer, intent(out) :: case_number
    integer, intent(out) :: jobs            !< -j N; 0 when not given
    logical, intent(out) :: collect         !< --collect: the sweep table from what has run
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
    collect = .false.
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
      case ('--collect')
        collect = .true.
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
                                                '-D name=value, --cases FILE.csv, --case N, --collect, ' // &
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
    if (collect .and. len(cases_path) == 0) &
      call usage_error('option --collect needs --cases FILE.csv (the sweep whose table it writes)')
    if (collect .and. case_number > 0) &
      call usage_error('option --collect with --case N (expected one of them: --collect writes the table of every case)')
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
      'Unilateral (Signorini) contact between elastic bodies in 2D by the mortar finite element method:', &
      'plane strain, plane stress or axisymmetric elasticity on linear (tri3, quad4) and quadratic (tri6,', &
      'quad8, quad9) elements; contact between bodies and against rigid obstacles, frictionless or with', &
      'Coulomb or Tresca friction, under small or finite sliding, in load steps; the condensed LCP solved', &
      'by Lemke, projected Gauss-Seidel or a primal-dual active set (semismooth Newton) method, each with', &
      'or without friction.  Every run estimates its own error; ADAPT re-meshes with gmsh to a target.', &
      '', &
      'options:', &
      '  -o DIR       write all outputs into DIR (made with its parents when missing; default .)', &
      '  -j N         run on N threads, 1 to 9999 (OpenMP and OpenBLAS; default: OMP_NUM_THREADS,', &
      '               else one per core)', &
      '  --check      read and check the deck and meshes, build the contact pairs, print the scene;', &
      '               solve nothing, write nothing', &
      '  -q           quiet: nothing on stdout, errors on stderr (the output files are still written)', &
      '  --trust-geo  let gmsh run a .geo as it is: no screen, no sandbox (it may then run commands and', &
      '               write files); without it a .geo that runs commands, writes files or reads outside', &
      '               the deck''s folder is refused (exit 2)', &
      '  --gmsh-timeout SECONDS', &
      '               time limit of gmsh on each .geo (a number > 0, at most 1e6; default 600)', &
      '  --no-mesh-cache  mesh every .geo with gmsh; by default the meshes gmsh makes are kept in', &
      '               DIR/.mesh_cache and reused by the runs into DIR (the cases of a sweep, re-runs)', &
      '               that ask for the same .geo, parameters, order and gmsh', &
      '  -D name=value  (also -Dname=value; repeatable) replace the default of the deck''s PARAMETER', &
      '               name by a number or an expression of numbers; an undeclared name is an error', &
      '  --cases FILE.csv  a sweep: header row = parameter names, one row per case; runs every case', &
      '               in turn, case N into DIR/case_N (exit status: the worst of the cases), then', &
      '               writes DIR/cases.csv, a row per case; a case whose DIR/case_N holds a complete', &
      '               summary is not run again', &
      '  --case N     with --cases: row N only (without it, SLURM_ARRAY_TASK_ID when set)', &
      '  --collect    with --cases: run nothing, write DIR/cases.csv from what has run', &
      '  --version    print the version', &
      '  -h, --help   this help', &
      '', &
      'deck statements (keywords, keys and fixed words case-insensitive; ! and # start comments;', &
      '[optional], with the default where there is one):', &
      '  PARAMETER name=value ...          then ${name} or ${expression} anywhere in a later line:', &
      '                                    numbers, parameters, + - * / ^ ( ), pi, sqrt exp log sin', &
      '                                    cos tan abs min max', &
      '  TITLE free text', &
      '  PLANE strain | PLANE stress [thickness=1] | PLANE axisymmetric   (x = r >= 0, y = z;', &
      '                                    forces of the full circle)', &
      '  BODY name ... END                 an elastic body (at least one), with:', &
      '    MESH rect [x0=0] [y0=0] [x1=1] [y1=1] nx=N ny=N [elem=tri3|quad4|tri6|quad8|quad9]', &
      '              [diag=right|left|alt]  (boundaries left, right, bottom, top)', &
      '    MESH gmsh file=F.msh            (MSH 2.2 or 4.1 ASCII, first or second order; physical', &
      '                                    curves name boundaries, physical points point sets)', &
      '    MESH gmsh file=F.geo [order=1|2] [name=value ...]   (meshed by gmsh -order N', &
      '                                    -setnumber name value; order=2 keeps curved edges)', &
      '    MATERIAL isotropic E= nu=', &
      '    MATERIAL orthotropic E1= E2= nu12= G12= [angle=0] [E3=E2] [nu13=nu12] [nu23=nu12]', &
      '    MATERIAL neo_hookean mu= K=  |  MATERIAL mooney_rivlin c10= c01= K=   (finite strain, Newton;', &
      '                                    not plane stress: refused)', &
      '    DENSITY rho=                    (with GRAVITY)', &
      '    FIX boundary [ux=] [uy=] [ramp=k0:k1|curve=NAME]   (neither ux nor uy: both 0; also a point set)', &
      '    FIX boundary [un=] [ut=] [ramp=k0:k1|curve=NAME]   (local axes: outward normal n, t = (-n_y, n_x))', &
      '    TRACTION boundary [tx=0] [ty=0] [ramp=k0:k1|curve=NAME]', &
      '    TRACTION boundary [tn=0] [tt=0] [ramp=k0:k1|curve=NAME]   (along each edge''s n and t)', &
      '    PRESSURE boundary p= [ramp=k0:k1|curve=NAME]   (p > 0 pushes into the body)', &
      '    BODYFORCE [fx=0] [fy=0] [ramp=k0:k1|curve=NAME]   (per unit volume)', &
      '    THERMAL alpha= dT= [region=NAME] [curve=NAME]   (a temperature change; region: a physical surface)', &
      '    OFFSET [dx=0] [dy=0]            (a rigid shift of the body''s geometry)', &
      '    FORCE point [fx=0] [fy=0] [ramp=k0:k1|curve=NAME]   (at each node of a point set: a Physical Point)', &
      '    SPRING boundary kn= [kt=0]      (an elastic foundation, per unit area of the boundary)', &
      '    SPRING point [kx=0] [ky=0]      (a spring to the ground at each node of a point set)', &
      '  GRAVITY [gx=0] [gy=0] [ramp=k0:k1|curve=NAME]   (on the bodies with a DENSITY)', &
      '  CONTACT slave=body:boundary master=body:boundary [gap=geometry|zero] [mu=C | tresca=S]', &
      '          [interference=allow|reject] [sliding=small|finite] [name=NAME]', &
      '                                    frictionless unless mu= (Coulomb) or tresca= (slip bound);', &
      '                                    name: a word, the pair''s label in the summary and the', &
      '                                    tables'' columns (contact_force_NAME_fx; default its number);', &
      '                                    on linear and quadratic elements, plane or axisymmetric; a', &
      '                                    side may be a closed curve; interference=reject: an initial', &
      '                                    penetration deeper than a slave element is refused;', &
      '                                    sliding=small: the pairing and normals of the initial', &
      '                                    configuration, exit 1 when a slave node slides further;', &
      '                                    sliding=finite: the contact geometry rebuilt in each load', &
      '                                    step from the current positions (refused with gap=zero)', &
      '  CONTACT slave=body:boundary master=RIGIDNAME [mu=C | tresca=S] [interference=...] [sliding=...]', &
      '                                    against the RIGID''s exact shape; the slave of linear or', &
      '                                    quadratic elements, plane or axisymmetric', &
      '  RIGID name ... END                a rigid obstacle, dofs ux, uy, rz of its reference point;', &
      '                                    in PLANE axisymmetric a solid of revolution (a sphere, a', &
      '                                    cone, a flat punch) moving along the axis, ux and rz held at 0', &
      '                                    (FIX ux=/rz= or FORCE fx=/m= other than 0: refused), with:', &
      '    SHAPE line x0= y0= x1= y1=  |  SHAPE circle xc= yc= r= [solid=inside|outside]', &
      '    SHAPE polyline points=x1:y1,x2:y2,...   (solid on the side the slave faces)', &
      '    REF x= y=                       (default: the circle''s centre, the first point)', &
      '    FIX [ux=] [uy=] [rz=] [ramp=k0:k1|curve=NAME]   (prescribed; FIX alone: all 0)', &
      '    FORCE [fx=] [fy=] [m=] [ramp=k0:k1|curve=NAME]   (on the directions FIX leaves free; no FIX,', &
      '                                    no FORCE: held fixed)', &
      '  SOLVER [lcp=auto|lemke|pgs|pdas] [tol=1e-10] [maxit=0] [omega=1] [updates=30]', &
      '         [ordering=auto|metis|amd] [condense=auto|solve|inverse] [cut=auto|off]', &
      '         [newton_tol=1e-8] [newton_maxit=25] [newton_lcp=lemke|active_set]', &
      '                                    (hyperelastic bodies; active_set: frictionless pairs)', &
      '                                    every lcp method with or without friction; auto: Lemke', &
      '                                    up to 100 contact rows, PDAS above; with friction PDAS,', &
      '                                    then Lemke, then PGS, then a fixed point on the Tresca', &
      '                                    threshold; each next when one fails; every answer', &
      '                                    checked (summary: certificate); a failing step of', &
      '                                    a friction or sliding=finite history is split in two;', &
      '                                    lcp=pgs with friction on a body or a RIGID held only by', &
      '                                    contact is refused; maxit=0: each method''s own limit;', &
      '                                    updates: most contact geometry rebuilds in a', &
      '                                    sliding=finite step; cut: accepted, ignored', &
      '  STEPS n                           load steps (default 1); ramp=k0:k1: load 0 up to step k0,', &
      '                                    rising to 1 at k1 (default 0:n)', &
      '  CURVE name t0:v0 t1:v1 ...        load factor v against the step t, piecewise linear', &
      '  ESTIMATE [on|off|bound]           the run''s own error estimate (default on; bound: guaranteed)', &
      '  ADAPT target=REL [quantity=energy|pressure] [max_steps=10] [max_dofs=2000000]', &
      '                                    solve, re-mesh every body with gmsh from the error', &
      '                                    indicators, solve again until the estimate <= target', &
      '  OUTPUT [vtk=NAME] [contact=NAME] [summary=NAME] [steps=last|all] [plot=none|png]', &
      '         [x=COLUMN] [fields=all|none|displacement,contact_pressure,gap,stress,von_mises]', &
      '                                    steps=all: per step STEM_0001.vtu and a contact table,', &
      '                                    STEM.pvd, STEM_steps.csv; plot=png: STEM_pressure.png (and', &
      '                                    STEM_steps.png), drawn by gnuplot; x: the steps picture''s', &
      '                                    abscissa, a column of STEM_steps.csv (default the load factor)', &
      '', &
      'outputs (doc/outputs.md): DECK.vtk (ParaView), DECK_contact.csv (a row per slave node),', &
      'DECK.summary (key value lines: energy, reactions of each FIX, per pair the contact force, zone,', &
      'peak pressure and centre of pressure, the stick zone with friction, the error estimate, warnings,', &
      'timings); with steps=all DECK_steps.csv, a row per step.', &
      '', &
      'exit status: 0 solved, 1 solver failure or an answer outside the model (diagnostic on stderr),', &
      '2 bad input.  Warnings (the answer rests on an assumption the run has left) go to stderr, not', &
      'with -q, and to the summary.  See doc/deck.md for every statement, key, default and error.'
  end subroutine print_help

end module command_line
