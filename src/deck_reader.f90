!> deck_reader: read a contact2d input deck (doc/deck.md, DECK.md) into deck_t and
!> check everything that can be checked without reading the meshes.
!>
!> Syntax.  One statement per line: a keyword, then positional words and key=value
!> pairs separated by blanks or tabs.  Keywords, keys and the fixed words (rect, gmsh,
!> isotropic, strain, tri3, ...) are case-insensitive; names of bodies, boundaries and
!> files are case-sensitive.  '!' and '#' start a comment anywhere on a line, TITLE
!> included.  Blank lines are ignored, CRLF line endings and a UTF-8 byte-order mark
!> are accepted.  Blanks around '=' are allowed (`E = 2e5`) when unambiguous.
!> Numbers are Fortran or C reals (200000, 2e5, 2.0d5, -1.5E-3, .5, 5.) with
!> |x| < 1e308; NaN, Inf, hexadecimal and trailing characters are rejected.
!> Names (bodies, boundaries, output files) are made of [A-Za-z0-9_.-].
!>
!> Statements (keys in brackets are optional, with their default):
!>   PARAMETER name=expression ...     then ${expression} anywhere in a later line,
!>                                      replaced before the line is split (deck_expressions)
!>   TITLE free text                                     default ''
!>   PLANE strain | PLANE stress [thickness=1] | PLANE axisymmetric   default strain
!>   BODY name ... END                                    at least one
!>     MESH rect [x0=0] [y0=0] [x1=1] [y1=1] nx= ny= [elem=tri3|quad4|tri6|quad8|quad9]
!>          [diag=right|left|alt]      (diag only with triangles; boundaries left, right, bottom, top)
!>     MESH gmsh file=NAME.msh | file=NAME.geo [name=number ...]
!>     MATERIAL isotropic E= nu=
!>     MATERIAL orthotropic E1= E2= nu12= G12= [angle=0] [E3=E2] [nu13=nu12] [nu23=nu12]
!>     DENSITY rho=
!>     FIX boundary [ux=] [uy=] [ramp=0:STEPS]     (neither ux nor uy: ux = uy = 0)
!>     FIX boundary [un=] [ut=] [ramp=0:STEPS]     (local axes of the boundary; not with ux, uy)
!>     TRACTION boundary [tx=0] [ty=0] [ramp=0:STEPS]   (at least one of tx, ty)
!>     TRACTION boundary [tn=0] [tt=0] [ramp=0:STEPS]   (the edges' axes; not with tx, ty)
!>     PRESSURE boundary p= [ramp=0:STEPS]
!>     BODYFORCE [fx=0] [fy=0] [ramp=0:STEPS]      (at least one of fx, fy)
!>     THERMAL alpha= dT= [region=NAME] [curve=NAME]
!>     OFFSET [dx=0] [dy=0]              (at least one)
!>   GRAVITY [gx=0] [gy=0] [ramp=0:STEPS]          (at least one of gx, gy)
!>   CONTACT slave=body:boundary master=body:boundary [gap=geometry|zero]
!>           [mu=number | tresca=number]           (default frictionless)
!>   SOLVER [lcp=auto|lemke|pgs|pdas] [tol=1e-10] [maxit=0] [omega=1] [ordering=auto|metis|amd]
!>          [condense=auto|solve|inverse] [cut=auto|off]
!>   STEPS n                             default 1; 1 <= n <= 100000
!>   CURVE name t0:v0 t1:v1 ...          load factor v against the step t (t increasing)
!>   OUTPUT [vtk=NAME.vtk] [contact=NAME_contact.csv] [summary=NAME.summary] [steps=last|all]
!>                                      (NAME: deck file name without folder and
!>                                      extension; '.vtk' is appended to vtk= if missing)
!> TITLE, PLANE, GRAVITY, SOLVER, STEPS, OUTPUT: at most once each, outside BODY blocks.
!> MESH, MATERIAL, DENSITY, BODYFORCE, OFFSET: at most once per body; FIX, TRACTION,
!> PRESSURE, THERMAL: any number.  Statements may come in any order (CONTACT before the
!> BODY it names, STEPS after the ramps it bounds).
!>
!> Grammar.  Each statement is a row of a table (define_statements): its
!> keyword, the block it stands in (the top level, BODY, or anywhere), the block
!> it opens, whether it may come once, its keys with the forms of their values
!> (number, integer, k0:k1, NAME, a|b|c), and its handler.  The dispatcher
!> checks from the row where a statement stands (a top-level statement inside
!> a block is read, with a "missing END?" hint; a block statement outside its
!> block is refused), its repetition ("second X"), and hands the handler the
!> row's keys, which match_keys checks (unknown, repeated, empty); the handler
!> converts the values and checks their ranges and the rules between keys.
!> A new statement is a row and a handler; a new block (RIGID ... END) is a row
!> that opens it and rows whose block it is; END closes whatever block is open.
!>
!> Size.  About 2,700 lines, over the house's 800: the twenty handlers share
!> the reader's state (state_t: errors, open block, the statement lists) and
!> deck_t, and other branches are adding statements to this file now.  The
!> split that follows the table: the deck types to a module of their own, the
!> checks after the whole deck (finish_checks and what it calls, ~500 lines)
!> to another, once those additions have landed.
!>
!> Load steps.  ramp=k0:k1 (integers, 0 <= k0 < k1 <= STEPS) scales the statement's
!> values by the load factor 0 up to step k0, rising linearly to 1 at step k1, 1 after;
!> absent, the ramp is 0:STEPS.  Every ramp is resolved on return (fix_t%ramp,
!> load_t%ramp, body_deck_t%bodyforce_ramp, deck_t%gravity_ramp hold [k0, k1], also
!> for absent statements; their initial value [0, 1] is the default for STEPS 1).
!> curve=NAME instead of ramp= (on FIX, TRACTION, PRESSURE, BODYFORCE, GRAVITY,
!> THERMAL; both on one statement: an error) follows a CURVE: the names are
!> resolved after the whole deck into the statements' `curve` index (0: the
!> ramp); curve_factor(c, k) is curve c's factor at step k.  Friction: mu= (Coulomb, 0 <= mu <= 1000) or tresca= (a
!> slip bound, a shear stress >= 0) on CONTACT, not both; mu=0 and tresca=0 are the
!> frictionless problem.
!>
!> Checks beyond the syntax: value ranges (E > 0, -1 < nu < 0.5, orthotropic
!> compliance positive definite, in plane strain with the out-of-plane terms too,
!> x1 > x0, nx, ny positive integers, 0 < omega < 2, ...); one MESH and one MATERIAL per
!> body; block structure; gmsh files exist; boundary names of rect meshes; CONTACT
!> bodies exist and the two sides differ; every body is held by a FIX, directly or
!> through CONTACT with a held body; every ramp ends at step STEPS at the latest;
!> lcp=pdas only without friction (no CONTACT with mu > 0 or tresca > 0).  Errors are
!> collected (at most max_errors), sorted by line and handed to diag as
!> `FILE:LINE: what is wrong (what was expected)` with the line echoed.
!>
!> Programming interface
!>   types fix_t, load_t, mesh_spec_t, material_t, body_deck_t, contact_deck_t,
!>         solver_deck_t, output_deck_t, deck_t (see their component comments)
!>   load_traction, load_pressure   values of load_t%kind
!>   read_deck(path, deck, diag)    parse and check the deck file `path`
module deck_reader
  use kinds, only: dp, i8
  use diagnostics, only: diag_t, add_error, int_to_str
  use safe_files, only: open_input, file_kind, kind_name, folder_of, c2d_regular, c2d_missing, c2d_unreadable
  use deck_expressions, only: parameter_set_t, add_parameter, find_parameter, evaluate, substitute, is_parameter_name, &
                              format_number
  use text_scan, only: scan_integer, parse_real, line_items, is_blank, is_digit, is_letter, lower, upper
  use, intrinsic :: iso_fortran_env, only: iostat_eor, iostat_end, int64
  implicit none
  private
  public :: fix_t, load_t, mesh_spec_t, material_t, body_deck_t, contact_deck_t
  public :: solver_deck_t, output_deck_t, deck_t, curve_t, read_deck, curve_factor, rigid_deck_t, rigid_load_t
  public :: load_traction, load_pressure, path_too_long

  integer, parameter :: load_traction = 1   !< load_t%kind of TRACTION
  integer, parameter :: load_pressure = 2   !< load_t%kind of PRESSURE

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

  !> TRACTION or PRESSURE on a boundary
  type :: load_t
    integer :: kind = 0                         !< load_traction or load_pressure
    character(len=:), allocatable :: boundary
    real(dp) :: tx = 0, ty = 0, p = 0           !< force per unit length; pressure
    logical :: local = .false.                  !< TRACTION tn= tt=: tx holds tn, ty holds tt (boundary axes)
    integer :: ramp(2) = [0, 1]                 !< load steps k0, k1 of the ramp; default [0, steps]
    integer :: curve = 0                        !< curve=NAME: index into deck%curves (0: the ramp)
    character(len=:), allocatable :: curve_name !< curve=NAME as written ('' when absent)
    integer :: line = 0
  end type load_t

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
    character(len=:), allocatable :: kind       !< 'isotropic', 'orthotropic' ('' when bad)
    real(dp) :: e = 0, nu = 0                   !< isotropic
    real(dp) :: e1 = 0, e2 = 0, nu12 = 0, g12 = 0, angle = 0   !< orthotropic; angle in degrees
    real(dp) :: e3 = 0, nu13 = 0, nu23 = 0      !< out-of-plane; defaults E3=E2, nu13=nu23=nu12
    integer :: line = 0                         !< line of the MATERIAL statement (0: none)
  end type material_t

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

  !> CONTACT slave=body:boundary master=body:boundary|RIGID [gap=] [mu= | tresca=]
  type :: contact_deck_t
    integer :: slave_body = 0, master_body = 0  !< indices into deck%bodies (master 0 for a RIGID)
    integer :: master_rigid = 0                 !< master=RIGIDNAME: index into deck%rigids
    character(len=:), allocatable :: slave_boundary, master_boundary
    logical :: gap_zero = .false.               !< gap=zero; default gap=geometry
    logical :: interference = .false.           !< interference=allow: any initial penetration accepted
    character(len=:), allocatable :: friction   !< 'none' (default), 'coulomb' (mu=) or 'tresca' (tresca=)
    real(dp) :: mu = 0                          !< Coulomb coefficient, 0 <= mu <= 1000
    real(dp) :: tresca = 0                      !< Tresca slip bound (a shear stress), >= 0
    integer :: line = 0
  end type contact_deck_t

  !> SOLVER [lcp=] [tol=] [maxit=] [omega=] [ordering=] [condense=] [cut=]
  type :: solver_deck_t
    character(len=:), allocatable :: lcp        !< 'auto' (default), 'lemke', 'pgs', 'pdas'
    character(len=:), allocatable :: ordering   !< 'auto' (default), 'metis', 'amd'
    character(len=:), allocatable :: condense   !< 'auto' (default), 'solve', 'inverse'
    character(len=:), allocatable :: cut        !< 'auto' (default) or 'off': read and checked, then ignored (no body is cut)
    real(dp) :: tol = 1.0e-10_dp
    integer :: maxit = 0                        !< 0: the solver's default
    real(dp) :: omega = 1.0_dp
    integer :: line = 0
  end type solver_deck_t

  !> OUTPUT [vtk=] [contact=] [summary=]; names relative to the output folder
  type :: output_deck_t
    character(len=:), allocatable :: vtk, contact, summary
    !> fields of the VTK file: displacement, contact_pressure, gap, stress, von_mises
    logical :: fields(5) = .true.
    logical :: steps_all = .false.              !< steps=all: VTK per step, .pvd, NAME_steps.csv
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
    type(contact_deck_t), allocatable :: contacts(:)   !< (ncontact), always allocated
    type(rigid_deck_t), allocatable :: rigids(:) !< (nrigid) RIGID blocks, always allocated
    type(solver_deck_t) :: solver
    type(output_deck_t) :: output
    type(parameter_set_t) :: params             !< PARAMETER: names, final values, origins
  end type deck_t

  ! ---------------------------------------------------------------- internal types

  integer, parameter :: max_errors = 100    ! stop reading after this many errors
  integer, parameter :: echo_len = 160      ! echoed lines are cut after this many chars
  integer, parameter :: quote_len = 40      ! quoted user text is cut after this many chars
  integer, parameter :: max_line_len = 1048576   ! longer lines: not a deck (e.g. /dev/zero, binary)
  integer, parameter :: max_steps = 100000  ! largest STEPS n
  real(dp), parameter :: max_mu = 1.0e3_dp  ! largest Coulomb coefficient mu=
  ! ramp(2) = 0 marks a ramp= not (validly) given until fill_defaults sets [0, steps]
  integer, parameter :: ramp_unset(2) = [0, 0]

  type :: text_t
    character(len=:), allocatable :: s
  end type text_t

  !> One error before sorting by line.
  type :: err_t
    integer :: line = 0
    logical :: echo = .true.                  ! echo the deck line under the message
    character(len=:), allocatable :: text
  end type err_t

  !> One statement split into words.
  type :: stmt_t
    integer :: line = 0
    character(len=:), allocatable :: keyword   ! as written
    character(len=:), allocatable :: rest      ! text after the keyword (TITLE)
    integer :: nword = 0                       ! positional words after the keyword
    type(text_t), allocatable :: word(:)
    integer :: npair = 0                       ! key=value pairs
    type(text_t), allocatable :: key(:), value(:)
    character(len=12), allocatable :: names(:) ! the statement's keys (its row of the table)
    character(len=28), allocatable :: forms(:) ! the form of each key's value, for messages
  end type stmt_t

  !> Reader state, local to one read_deck call.
  type :: state_t
    integer :: nerr = 0
    type(err_t), allocatable :: errs(:)
    logical :: gave_up = .false.
    integer :: nline = 0
    type(text_t), allocatable :: echo(:)      ! (nline) cut lines for echoing
    integer :: nbody = 0, ncontact = 0
    integer :: cur = 0                        ! body whose block is open, 0 outside
    logical :: end_hinted = .false.           ! a "missing END?" was said for cur
    character(len=8) :: block = ''            ! the open block's keyword ('BODY'), '' at the top level
    character(len=:), allocatable :: block_name   ! its name, for messages
    integer :: block_line = 0                 ! its opening line
    integer, allocatable :: first_line(:)     ! (nrow) line of each top-level statement seen (once rows)
    integer, allocatable :: block_first(:)    ! (nrow) the same in the open block
    logical :: contact_bad = .false.          ! some CONTACT statement had an error
    logical :: steps_bad = .false.            ! the STEPS statement had an error
    type(text_t), allocatable :: slave_name(:), master_name(:)   ! (ncontact) body names
    type(parameter_set_t) :: overrides        ! -D and --cases values of declared parameters
  end type state_t

  !> The routine that reads one statement into the deck (a row's handler).
  abstract interface
    subroutine statement_handler(s, deck, st)
      import :: state_t, deck_t, stmt_t
      type(state_t), intent(inout) :: s
      type(deck_t), intent(inout) :: deck
      type(stmt_t), intent(in) :: st
    end subroutine statement_handler
  end interface

  !> One row of the deck's grammar (define_statements): a statement, where it
  !> may stand, how often, its keys and the routine that reads it.  Where a
  !> statement stands, its repetition, its keys (unknown, repeated, empty)
  !> are checked from the row before the handler runs, which reads the values.
  type :: statement_t
    character(len=12) :: keyword = ''          !< upper case
    character(len=8) :: block = ''             !< block it stands in: '' the top level, 'BODY', '*' anywhere
    character(len=8) :: opens = ''             !< block it opens, '' none (END closes the open block)
    logical :: once = .false.                  !< at most once: per deck, or per block inside a block
    character(len=:), allocatable :: expected  !< what the "second ..." message expects
    character(len=12), allocatable :: names(:) !< its keys (canonical spelling); none when they vary
    character(len=28), allocatable :: forms(:) !< the form of each key's value, for messages
    procedure(statement_handler), pointer, nopass :: run => null()   !< its handler; none for END
  end type statement_t

contains

  ! ================================================================ entry point

  !> Read and check the deck file `path`.
  !>   path  (in)    deck file as given on the command line
  !>   deck  (out)   the parsed deck; every allocatable component is allocated on
  !>                 return, also when errors were found (then the values are partial)
  !>   diag  (inout) receives every error, sorted by line; file-level errors
  !>                 (cannot open, no BODY) have line 0
  !>   overrides (in, optional) values replacing the defaults of PARAMETERs of
  !>                 these names, with their origins ('-D', 'case N'); names the
  !>                 deck does not declare are the caller's to report
  subroutine read_deck(path, deck, diag, overrides)
    character(len=*), intent(in) :: path
    type(deck_t), intent(out) :: deck
    type(diag_t), intent(inout) :: diag
    type(parameter_set_t), intent(in), optional :: overrides
    type(state_t) :: s
    type(statement_t), allocatable :: table(:)
    character(len=:), allocatable :: line
    integer :: u, ios, kind
    integer(int64) :: fsize
    logical :: readable

    deck%file = path
    call split_path(path, deck%dir, deck%name)
    allocate(deck%bodies(0), deck%contacts(0), deck%curves(0), deck%rigids(0))
    allocate(s%errs(16), s%echo(64), s%slave_name(4), s%master_name(4))
    if (present(overrides)) s%overrides = overrides
    call define_statements(table)
    allocate(s%first_line(size(table)), s%block_first(size(table)), source=0)

    readable = .false.
    ! a FIFO or a device would block or never end: refused before it is read
    call open_input(path, u, .false., kind)
    if (kind == c2d_missing) then
      call report(s, 0, 'cannot open the deck: no such file (expected an existing deck file)')
    else
      if (kind /= c2d_regular .and. kind /= c2d_unreadable) then
        call report(s, 0, 'the deck is ' // kind_name(kind) // ', not a regular file: refused (a deck file expected)')
      else if (kind /= c2d_regular) then
        call report(s, 0, 'cannot open the deck (expected a readable file)')
      else
        readable = .true.
        do
          call read_line(u, line, ios)
          if (ios == iostat_end) exit
          if (ios == 0 .and. len(line) > max_line_len) then
            call store_echo(s, line)
            call report(s, s%nline, 'line longer than ' // int_to_str(max_line_len) // &
                        ' characters (expected a text deck; is this a binary file?)')
            readable = .false.
            exit
          end if
          if (ios /= 0) then
            call report(s, 0, 'cannot read the deck after line ' // int_to_str(s%nline) // &
                        ' (expected a readable text file)')
            readable = .false.
            exit
          end if
          call process_line(s, deck, line, table)
          if (s%gave_up) exit
        end do
        close(u)
        if (s%nline == 0 .and. s%nerr == 0) then
          inquire(file=path, size=fsize)
          if (fsize /= 0) then
            call report(s, 0, 'cannot read the deck (expected a text file, not a folder)')
            readable = .false.
          end if
        end if
      end if
    end if
    call cut_statement_lists(s, deck)
    if (readable .and. .not. s%gave_up) call finish_checks(s, deck)
    call fill_defaults(deck)
    call hand_over(s, deck%file, diag)
  end subroutine read_deck

  !> Read one line (non-advancing, in chunks); strip a final CR.  Reading stops
  !> after max_line_len + 1 characters, so that a file without line ends
  !> (/dev/zero, a large binary file) cannot exhaust the memory.
  !>   u     (in)  connected formatted unit
  !>   line  (out) the line without its end-of-line characters; longer than
  !>               max_line_len when the line was cut there
  !>   ios   (out) 0 a line was read, iostat_end no more lines, other: read error
  subroutine read_line(u, line, ios)
    integer, intent(in) :: u
    character(len=:), allocatable, intent(out) :: line
    integer, intent(out) :: ios
    character(len=4096) :: chunk
    character(len=:), allocatable :: buf, grown
    integer :: n, used

    allocate(character(len=4096) :: buf)
    used = 0
    do
      read(u, '(a)', advance='no', size=n, iostat=ios) chunk
      if (ios /= 0 .and. ios /= iostat_eor .and. ios /= iostat_end) return
      if (used + n > len(buf)) then
        allocate(character(len=2 * (used + n)) :: grown)
        grown(1:used) = buf(1:used)
        call move_alloc(grown, buf)
      end if
      buf(used + 1:used + n) = chunk(1:n)
      used = used + n
      if (ios == 0 .and. used > max_line_len) exit
      if (ios == 0) cycle
      if (ios == iostat_end .and. used == 0) return
      exit
    end do
    ios = 0
    if (used > 0) then
      if (buf(used:used) == achar(13)) used = used - 1
    end if
    line = buf(1:used)
  end subroutine read_line

  !> Folder and bare name of a path: 'a/b/c.deck' -> 'a/b', 'c'; 'c.deck' -> '.', 'c'.
  subroutine split_path(path, dir, name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: dir, name
    integer :: slash, dot
    dir = folder_of(path)
    slash = index(path, '/', back=.true.)
    name = path(slash + 1:)
    dot = index(name, '.', back=.true.)
    if (dot > 1) name = name(1:dot - 1)
    if (len(name) == 0) name = 'contact2d'
  end subroutine split_path

  ! ================================================================ lines and words

  !> Split one line into a statement and dispatch it.
  subroutine process_line(s, deck, raw, table)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(in) :: raw
    type(statement_t), intent(in) :: table(:)
    character(len=:), allocatable :: text
    type(text_t), allocatable :: tok(:)
    type(stmt_t) :: st
    character(len=:), allocatable :: kw
    integer :: i, ntok, kwend

    text = raw
    if (s%nline == 0 .and. len(text) >= 3) then    ! UTF-8 byte-order mark
      if (text(1:3) == char(239) // char(187) // char(191)) text = text(4:)
    end if
    call store_echo(s, text)
    if (index(text, achar(0)) > 0) then            ! binary file: one message, stop
      call report(s, s%nline, 'NUL byte in the deck (expected a text file; is this a binary file?)')
      s%gave_up = .true.
      return
    end if
    i = scan(text, '!#')
    if (i > 0) text = text(1:i - 1)
    if (index(text, '${') > 0) then                ! ${expression}: the line as the parameters make it
      if (.not. substituted(s, deck, text)) return
    end if
    do i = 1, len(text)
      if (is_blank(text(i:i))) text(i:i) = ' '
    end do
    call split_words(text, tok, ntok)
    if (ntok == 0) return

    st%line = s%nline
    st%keyword = tok(1)%s
    kwend = index(text, tok(1)%s) + len(tok(1)%s)
    st%rest = trim(adjustl(text(kwend:)))
    call join_equals(tok, ntok)
    call classify_words(tok, ntok, st)
    kw = upper(st%keyword)
    call dispatch(s, deck, st, kw, table)
  end subroutine process_line

  !> Replace each ${expression} of text by its value; .false. (the error
  !> reported) when an expression is bad.
  logical function substituted(s, deck, text)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    character(len=:), allocatable, intent(inout) :: text
    character(len=:), allocatable :: out, message
    call substitute(text, deck%params, out, message)
    substituted = .not. allocated(message)
    if (substituted) then
      call move_alloc(out, text)
    else
      call report(s, s%nline, message)
    end if
  end function substituted

  !> PARAMETER name=value ...: each value an expression of the parameters
  !> declared before it; a -D or --cases value replaces it.
  subroutine do_parameter(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=:), allocatable :: message
    real(dp) :: x
    integer :: i, k
    if (st%npair == 0) call report(s, st%line, 'PARAMETER declares nothing (expected PARAMETER name=value ...)')
    do i = 1, st%nword
      call report(s, st%line, 'word ' // quoted(st%word(i)%s) // ' in PARAMETER (expected name=value, ' // &
                  'without blanks inside the value, or ${...} around it)')
    end do
    do i = 1, st%npair
      associate (name => st%key(i)%s)
        if (.not. is_parameter_name(name)) then
          call report(s, st%line, 'bad parameter name ' // quoted(name) // ' (expected a letter or _ then ' // &
                      'letters, digits, _; at most 64; not pi or a function name)')
          cycle
        end if
        k = find_parameter(deck%params, name)
        if (k > 0) then
          call report(s, st%line, 'parameter ' // quoted(name) // ' declared twice (first at line ' // &
                      int_to_str(deck%params%line(k)) // '; expected each name once)')
          cycle
        end if
        call evaluate(st%value(i)%s, deck%params, x, message)
        if (allocated(message)) then
          call report(s, st%line, 'parameter ' // quoted(name) // ': ' // message)
          cycle
        end if
        k = find_parameter(s%overrides, name)
        if (k > 0) then
          call add_parameter(deck%params, name, s%overrides%value(k), s%overrides%origin(k), st%line)
        else
          call add_parameter(deck%params, name, x, 'default', st%line)
        end if
      end associate
    end do
  end subroutine do_parameter

  !> Keep a printable, cut copy of the current line for echoing under messages.
  subroutine store_echo(s, raw)
    type(state_t), intent(inout) :: s
    character(len=*), intent(in) :: raw
    type(text_t), allocatable :: grown(:)
    character(len=:), allocatable :: e
    integer :: i

    s%nline = s%nline + 1
    if (s%nline > size(s%echo)) then
      allocate(grown(2 * size(s%echo)))
      do i = 1, size(s%echo)
        call move_alloc(s%echo(i)%s, grown(i)%s)
      end do
      call move_alloc(grown, s%echo)
    end if
    if (len(raw) > echo_len) then
      e = raw(1:echo_len) // ' ...'
    else
      e = raw
    end if
    do i = 1, len(e)
      if (e(i:i) == achar(9)) e(i:i) = ' '
    end do
    s%echo(s%nline)%s = e
  end subroutine store_echo

  !> Blank-separated words of text (text_scan's items of a line).
  subroutine split_words(text, tok, ntok)
    character(len=*), intent(in) :: text
    type(text_t), allocatable, intent(out) :: tok(:)
    integer, intent(out) :: ntok
    integer(i8), allocatable :: b(:), e(:)
    integer :: k

    allocate(b(len(text) / 2 + 1), e(len(text) / 2 + 1))     ! a word and a blank at least each
    call line_items(text, 1_i8, len(text, i8), b, e, ntok)
    allocate(tok(ntok))
    do k = 1, ntok
      tok(k)%s = text(b(k):e(k))
    end do
  end subroutine split_words

  !> Join `key = value`, `key= value` and `key =value` into one word key=value,
  !> when that is unambiguous (the neighbours carry no '=' of their own); the
  !> keyword tok(1) is never joined.
  subroutine join_equals(tok, ntok)
    type(text_t), intent(inout) :: tok(:)
    integer, intent(inout) :: ntok
    type(text_t), allocatable :: out(:)
    integer :: i, n
    logical :: prev_plain, next_plain

    allocate(out(ntok))
    n = 1
    out(1)%s = tok(1)%s
    i = 2
    do while (i <= ntok)
      prev_plain = n >= 2
      if (prev_plain) prev_plain = index(out(n)%s, '=') == 0
      next_plain = i < ntok
      if (next_plain) next_plain = index(tok(i + 1)%s, '=') == 0
      if (tok(i)%s == '=' .and. prev_plain .and. next_plain) then          ! key = value
        out(n)%s = out(n)%s // '=' // tok(i + 1)%s
        i = i + 2
      else if (tok(i)%s(1:1) == '=' .and. prev_plain) then                ! key =value, key =
        out(n)%s = out(n)%s // tok(i)%s
        i = i + 1
      else if (ends_with_lone_equals(tok(i)%s) .and. next_plain) then     ! key= value
        n = n + 1
        out(n)%s = tok(i)%s // tok(i + 1)%s
        i = i + 2
      else
        n = n + 1
        out(n)%s = tok(i)%s
        i = i + 1
      end if
    end do
    do i = 1, n
      call move_alloc(out(i)%s, tok(i)%s)
    end do
    ntok = n
  end subroutine join_equals

  !> True for 'key=' (one '=', at the end, after at least one character).
  pure logical function ends_with_lone_equals(w)
    character(len=*), intent(in) :: w
    ends_with_lone_equals = .false.
    if (len(w) < 2) return
    ends_with_lone_equals = index(w, '=') == len(w)
  end function ends_with_lone_equals

  !> Sort the words after the keyword into positional words and key=value pairs.
  subroutine classify_words(tok, ntok, st)
    type(text_t), intent(in) :: tok(:)
    integer, intent(in) :: ntok
    type(stmt_t), intent(inout) :: st
    integer :: i, eq

    allocate(st%word(ntok), st%key(ntok), st%value(ntok))
    do i = 2, ntok
      eq = index(tok(i)%s, '=')
      if (eq == 0) then
        st%nword = st%nword + 1
        st%word(st%nword)%s = tok(i)%s
      else
        st%npair = st%npair + 1
        st%key(st%npair)%s = tok(i)%s(1:eq - 1)
        st%value(st%npair)%s = tok(i)%s(eq + 1:)
      end if
    end do
  end subroutine classify_words

  ! ================================================================ errors

  !> Collect one error at `line` (0: file level); the line is echoed under it.
  subroutine report(s, line, text, echo)
    type(state_t), intent(inout) :: s
    integer, intent(in) :: line
    character(len=*), intent(in) :: text
    logical, intent(in), optional :: echo
    type(err_t), allocatable :: grown(:)
    integer :: i

    if (s%gave_up) return
    if (s%nerr + 2 > size(s%errs)) then
      allocate(grown(2 * size(s%errs)))
      do i = 1, s%nerr
        grown(i)%line = s%errs(i)%line
        grown(i)%echo = s%errs(i)%echo
        call move_alloc(s%errs(i)%text, grown(i)%text)
      end do
      call move_alloc(grown, s%errs)
    end if
    s%nerr = s%nerr + 1
    s%errs(s%nerr)%line = line
    s%errs(s%nerr)%text = text
    if (present(echo)) s%errs(s%nerr)%echo = echo
    if (s%nerr == max_errors) then
      s%nerr = s%nerr + 1
      s%errs(s%nerr)%line = line
      s%errs(s%nerr)%text = 'too many errors, stopped reading the deck (fix these first)'
      s%gave_up = .true.
    end if
  end subroutine report

  !> Hand the collected errors to diag, stably sorted by line.
  subroutine hand_over(s, file, diag)
    type(state_t), intent(inout) :: s
    character(len=*), intent(in) :: file
    type(diag_t), intent(inout) :: diag
    integer, allocatable :: order(:)
    integer :: i, j, k, ln

    allocate(order(s%nerr))
    do i = 1, s%nerr
      order(i) = i
    end do
    do i = 2, s%nerr                       ! insertion sort: stable, few items
      k = order(i)
      j = i - 1
      do while (j >= 1)
        if (s%errs(order(j))%line <= s%errs(k)%line) exit
        order(j + 1) = order(j)
        j = j - 1
      end do
      order(j + 1) = k
    end do
    do i = 1, s%nerr
      k = order(i)
      ln = s%errs(k)%line
      if (ln > 0 .and. ln <= s%nline .and. s%errs(k)%echo) then
        call add_error(diag, file, ln, s%errs(k)%text, echo=s%echo(ln)%s)
      else
        call add_error(diag, file, ln, s%errs(k)%text)
      end if
    end do
  end subroutine hand_over

  ! ================================================================ the statements

  !> The deck's grammar, one row a statement (statement_t), in the order the
  !> unknown-keyword message lists them.  A new statement is a row here and
  !> its handler; a new block (BODY ... END) is a row that opens it and rows
  !> whose block it is.
  subroutine define_statements(table)
    type(statement_t), allocatable, intent(out) :: table(:)
    character(len=*), parameter :: ramp = 'k0:k1', name = 'NAME', number = 'number'

    allocate(table(0))
    call add_row(table, 'TITLE', '', do_title, once=.true.)
    call add_row(table, 'PLANE', '', do_plane, once=.true., &
                 names=[character(len=12) :: 'thickness'], forms=[character(len=28) :: number])
    call add_row(table, 'BODY', '', do_body, opens='BODY')
    call add_row(table, 'MESH', 'BODY', do_mesh, once=.true., expected='one MESH per body')
    call add_row(table, 'MATERIAL', 'BODY', do_material, once=.true., expected='one MATERIAL per body')
    call add_row(table, 'DENSITY', 'BODY', do_density, once=.true., &
                 names=[character(len=12) :: 'rho'], forms=[character(len=28) :: number])
    call add_row(table, 'FIX', 'BODY', do_fix, &
                 names=[character(len=12) :: 'ux', 'uy', 'ramp', 'curve', 'un', 'ut'], &
                 forms=[character(len=28) :: number, number, ramp, name, number, number])
    call add_row(table, 'TRACTION', 'BODY', do_load, &
                 names=[character(len=12) :: 'tx', 'ty', 'ramp', 'curve', 'tn', 'tt'], &
                 forms=[character(len=28) :: number, number, ramp, name, number, number])
    call add_row(table, 'PRESSURE', 'BODY', do_load, &
                 names=[character(len=12) :: 'p', 'ramp', 'curve'], forms=[character(len=28) :: number, ramp, name])
    call add_row(table, 'BODYFORCE', 'BODY', do_bodyforce, once=.true., &
                 names=[character(len=12) :: 'fx', 'fy', 'ramp', 'curve'], &
                 forms=[character(len=28) :: number, number, ramp, name])
    call add_row(table, 'THERMAL', 'BODY', do_thermal, &
                 names=[character(len=12) :: 'alpha', 'dT', 'region', 'curve'], &
                 forms=[character(len=28) :: number, number, name, name])
    call add_row(table, 'OFFSET', 'BODY', do_offset, once=.true., &
                 names=[character(len=12) :: 'dx', 'dy'], forms=[character(len=28) :: number, number])
    call add_row(table, 'END', '*')
    call add_row(table, 'GRAVITY', '', do_gravity, once=.true., &
                 names=[character(len=12) :: 'gx', 'gy', 'ramp', 'curve'], &
                 forms=[character(len=28) :: number, number, ramp, name])
    call add_row(table, 'CONTACT', '', do_contact, &
                 names=[character(len=12) :: 'slave', 'master', 'gap', 'mu', 'tresca', 'interference'], &
                 forms=[character(len=28) :: 'body:boundary', 'body:boundary', 'geometry|zero', number, number, &
                        'allow|reject'])
    call add_row(table, 'SOLVER', '', do_solver, once=.true., &
                 names=[character(len=12) :: 'lcp', 'tol', 'maxit', 'omega', 'ordering', 'condense', 'cut'], &
                 forms=[character(len=28) :: 'auto|lemke|pgs|pdas', number, 'integer', number, 'auto|metis|amd', &
                        'auto|solve|inverse', 'auto|off'])
    call add_row(table, 'STEPS', '', do_steps, once=.true.)
    call add_row(table, 'CURVE', '', do_curve)
    call add_row(table, 'OUTPUT', '', do_output, once=.true., &
                 names=[character(len=12) :: 'vtk', 'contact', 'summary', 'fields', 'steps'], &
                 forms=[character(len=28) :: name, name, name, 'LIST', 'last|all'])
    call add_row(table, 'PARAMETER', '*', do_parameter)
    call add_row(table, 'RIGID', '', do_rigid, opens='RIGID')
    call add_row(table, 'SHAPE', 'RIGID', rigid_shape_row, once=.true., expected='one SHAPE per RIGID')
    call add_row(table, 'REF', 'RIGID', rigid_ref_row, once=.true., expected='one REF per RIGID')
    call add_row(table, 'FIX', 'RIGID', rigid_fix_row)
    call add_row(table, 'FORCE', 'RIGID', rigid_force_row)
  end subroutine define_statements

  !> Append a row to the table.
  !>   keyword (in) upper case;  block (in) '' top level, 'BODY', '*' anywhere
  !>   run (in, optional) the handler (END has none: the dispatcher closes the block)
  !>   once, opens, expected, names, forms (in, optional): see statement_t
  subroutine add_row(table, keyword, block, run, once, opens, expected, names, forms)
    type(statement_t), allocatable, intent(inout) :: table(:)
    character(len=*), intent(in) :: keyword, block
    procedure(statement_handler), optional :: run
    logical, intent(in), optional :: once
    character(len=*), intent(in), optional :: opens, expected
    character(len=12), intent(in), optional :: names(:)
    character(len=28), intent(in), optional :: forms(:)
    type(statement_t) :: row
    type(statement_t), allocatable :: grown(:)

    row%keyword = keyword
    row%block = block
    if (present(run)) row%run => run
    if (present(once)) row%once = once
    if (present(opens)) row%opens = opens
    row%expected = 'at most one'
    if (present(expected)) row%expected = expected
    if (present(names)) then
      row%names = names
      row%forms = forms
    else
      allocate(row%names(0), row%forms(0))
    end if
    allocate(grown(size(table) + 1))
    grown(1:size(table)) = table
    grown(size(grown)) = row
    call move_alloc(grown, table)
  end subroutine add_row

  !> Row of keyword kw standing in block (a row of block '*' stands anywhere);
  !> with block = '?', the first row of kw wherever it stands; 0 when none.
  pure integer function find_statement(table, kw, block) result(k)
    type(statement_t), intent(in) :: table(:)
    character(len=*), intent(in) :: kw, block
    do k = 1, size(table)
      if (table(k)%keyword /= kw) cycle
      if (block == '?' .or. table(k)%block == block .or. table(k)%block == '*') return
    end do
    k = 0
  end function find_statement

  !> Check where statement st stands and how often, then run its row's handler.
  !>   kw    (in) its keyword in upper case
  !>   table (in) the grammar
  subroutine dispatch(s, deck, st, kw, table)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(inout) :: st
    character(len=*), intent(in) :: kw
    type(statement_t), intent(in) :: table(:)
    character(len=:), allocatable :: list
    integer :: k, first

    k = find_statement(table, kw, s%block)
    if (k == 0) then
      k = find_statement(table, kw, '?')
      if (k == 0) then
        list = ''
        do k = 1, size(table)
          if (find_statement(table, table(k)%keyword, '?') /= k) cycle
          if (k > 1) list = list // ', '
          list = list // trim(table(k)%keyword)
        end do
        call report(s, st%line, 'unknown keyword ' // quoted(st%keyword) // ' (expected one of ' // list // ')')
        return
      end if
      if (table(k)%block /= '') then            ! a block statement outside its block
        call report(s, st%line, 'statement ' // kw // ' outside a ' // trim(table(k)%block) // ' block (expected ' // &
                    'inside ' // trim(table(k)%block) // ' ... END)')
        return
      end if
      if (.not. s%end_hinted) then              ! a top-level statement inside a block: read as such
        if (table(k)%opens /= '') then
          call report(s, st%line, kw // ' inside ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                      ' opened at line ' // int_to_str(s%block_line) // ' (missing END?)')
        else
          call report(s, st%line, 'statement ' // kw // ' inside ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                      ' opened at line ' // int_to_str(s%block_line) // ' (expected after the END of the ' // &
                      lower(trim(s%block)) // ' block; missing END?)')
          s%end_hinted = .true.
        end if
      end if
    end if
    associate (row => table(k))
      if (row%once) then
        if (row%block == '') then
          first = s%first_line(k)
          s%first_line(k) = merge(first, st%line, first > 0)
        else
          first = s%block_first(k)
          s%block_first(k) = merge(first, st%line, first > 0)
        end if
        if (first > 0 .and. row%block == '') then
          call report(s, st%line, 'second ' // kw // ' (first at line ' // int_to_str(first) // '; expected ' // &
                      row%expected // ')')
          return
        else if (first > 0) then
          call report(s, st%line, 'second ' // kw // ' in ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                      ' (first at line ' // int_to_str(first) // '; expected ' // row%expected // ')')
          return
        end if
      end if
      if (row%opens /= '') then                 ! its handler names the block (block_name, block_line)
        s%block = row%opens
        s%block_first = 0
        s%end_hinted = .false.
      end if
      if (.not. associated(row%run)) then       ! END
        call close_block(s, st)
        return
      end if
      st%names = row%names
      st%forms = row%forms
      call row%run(s, deck, st)
    end associate
  end subroutine dispatch

  ! ================================================================ helpers for statements

  !> Match the key=value pairs of st against the allowed keys names(:) (canonical
  !> spelling, compared case-insensitively).  Reports empty keys, unknown keys,
  !> duplicates and empty values.
  !>   names  (in)  allowed keys
  !>   forms  (in)  value form for messages ('number', 'tri3|quad4', ...)
  !>   what   (in)  statement for messages, e.g. 'MESH rect'
  !>   seen   (out) key k was written (possibly without a value)
  !>   val    (out) val(k)%s the value of key k, allocated when given and non-empty
  subroutine match_keys(s, st, names, forms, what, seen, val)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    character(len=*), intent(in) :: names(:), forms(:), what
    logical, intent(out) :: seen(:)
    type(text_t), intent(out) :: val(:)
    integer :: i, k

    seen = .false.
    do i = 1, st%npair
      if (len(st%key(i)%s) == 0) then
        call report(s, st%line, 'missing key before ' // quoted('=' // st%value(i)%s) // ' (expected key=value)')
        cycle
      end if
      k = find_key(st%key(i)%s, names)
      if (k == 0) then
        call report(s, st%line, 'unknown key ' // quoted(st%key(i)%s) // ' for ' // what // ' (expected ' // &
                    join_list(names, ', ') // ')')
        cycle
      end if
      if (seen(k)) then
        call report(s, st%line, 'duplicate key ' // quoted(trim(names(k))) // ' (expected each key at most once)')
        cycle
      end if
      seen(k) = .true.
      if (len(st%value(i)%s) == 0) then
        call report(s, st%line, 'missing value for ' // quoted(trim(names(k))) // ' (expected ' // &
                    trim(names(k)) // '=' // trim(forms(k)) // ')')
        cycle
      end if
      val(k)%s = st%value(i)%s
    end do
  end subroutine match_keys

  !> Index of key (case-insensitive) in names, 0 when absent.
  pure integer function find_key(key, names) result(k)
    character(len=*), intent(in) :: key, names(:)
    do k = 1, size(names)
      if (lower(key) == lower(trim(names(k)))) return
    end do
    k = 0
  end function find_key

  !> 'a, b, c' (separator ', ') or 'a|b|c' (separator '|') from a list of padded names.
  pure function join_list(names, separator) result(s)
    character(len=*), intent(in) :: names(:), separator
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, size(names)
      if (k > 1) s = s // separator
      s = s // trim(names(k))
    end do
  end function join_list

  !> Report a missing required key.
  subroutine require_key(s, st, seen, name, what, usage)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    logical, intent(in) :: seen
    character(len=*), intent(in) :: name, what, usage
    if (.not. seen) call report(s, st%line, 'missing key ' // quoted(name) // ' for ' // what // &
                                ' (expected ' // usage // ')')
  end subroutine require_key

  !> Report words after the first nmax positional words, and (when nmax = 0) any.
  subroutine check_extra_words(s, st, nmax, usage)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    integer, intent(in) :: nmax
    character(len=*), intent(in) :: usage
    if (st%nword > nmax) call report(s, st%line, 'unexpected word ' // quoted(st%word(nmax + 1)%s) // &
                                     ' (expected ' // usage // ')')
  end subroutine check_extra_words

  !> Convert val to a real; report a bad number, and with positive, x <= 0.
  !> ok is false when absent or bad.
  subroutine get_real(s, st, val, name, x, ok, positive)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(text_t), intent(in) :: val
    character(len=*), intent(in) :: name
    real(dp), intent(inout) :: x
    logical, intent(out) :: ok
    logical, intent(in), optional :: positive
    real(dp) :: y
    ok = .false.
    if (.not. allocated(val%s)) return
    call parse_real(val%s, y, ok)
    if (ok) then
      x = y
    else
      call report(s, st%line, 'bad number ' // quoted(val%s) // ' for ' // quoted(name) // &
                  ' (expected a finite number)')
    end if
    if (.not. (ok .and. present(positive))) return
    if (positive .and. .not. x > 0) then
      call report(s, st%line, 'bad value ' // name // '=' // cut(val%s) // ' (expected ' // name // ' > 0)')
      ok = .false.
    end if
  end subroutine get_real

  !> Convert val to an integer >= lo; report otherwise.  ok false when absent or bad.
  subroutine get_integer(s, st, val, name, lo, k, ok)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(text_t), intent(in) :: val
    character(len=*), intent(in) :: name
    integer, intent(in) :: lo
    integer, intent(inout) :: k
    logical, intent(out) :: ok
    integer :: j
    ok = .false.
    if (.not. allocated(val%s)) return
    call parse_integer(val%s, j, ok)
    if (ok) ok = j >= lo
    if (ok) then
      k = j
    else if (lo == 1) then
      call report(s, st%line, 'bad value ' // name // '=' // cut(val%s) // ' (expected a positive integer)')
    else
      call report(s, st%line, 'bad value ' // name // '=' // cut(val%s) // ' (expected an integer >= ' // &
                  int_to_str(lo) // ')')
    end if
  end subroutine get_integer

  !> Lower-case value val checked against the choices (padded); '' when absent or bad.
  function get_choice(s, st, val, name, choices) result(c)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(text_t), intent(in) :: val
    character(len=*), intent(in) :: name, choices(:)
    character(len=:), allocatable :: c
    integer :: k
    c = ''
    if (.not. allocated(val%s)) return
    k = find_key(val%s, choices)
    if (k > 0) then
      c = trim(choices(k))
    else
      call report(s, st%line, 'bad value ' // name // '=' // cut(val%s) // ' (expected ' // name // '=' // &
                  join_list(choices, '|') // ')')
    end if
  end function get_choice

  !> Check a name (body, boundary) and report when bad; ok false when bad.
  subroutine check_name(s, st, name, what, ok)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    character(len=*), intent(in) :: name, what
    logical, intent(out) :: ok
    ok = is_name(name)
    if (.not. ok) call report(s, st%line, 'bad ' // what // ' name ' // quoted(name) // &
                              ' (expected letters, digits, _ . - only)')
  end subroutine check_name

  !> Convert the value of ramp=k0:k1; report a bad form and k0 >= k1.  The bound
  !> k1 <= STEPS is checked after the whole deck (check_ramps).
  !>   val   (in)  the value of ramp=, unallocated when the key is absent
  !>   ramp  (out) [k0, k1]; ramp_unset when absent or bad (then [0, steps] at the end)
  subroutine get_ramp(s, st, val, ramp)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(text_t), intent(in) :: val
    integer, intent(out) :: ramp(2)
    integer :: colon, k0, k1
    logical :: ok0, ok1

    ramp = ramp_unset
    if (.not. allocated(val%s)) return
    colon = index(val%s, ':')
    ok0 = .false.
    ok1 = .false.
    if (colon > 1 .and. colon < len(val%s)) then
      call parse_integer(val%s(1:colon - 1), k0, ok0)
      call parse_integer(val%s(colon + 1:), k1, ok1)
    end if
    if (ok0) ok0 = k0 >= 0
    if (ok1) ok1 = k1 >= 0
    if (.not. (ok0 .and. ok1)) then
      call report(s, st%line, 'bad ramp ' // quoted(val%s) // ' (expected ramp=k0:k1 with integers ' // &
                  '0 <= k0 < k1 <= STEPS n)')
    else if (k0 >= k1) then
      call report(s, st%line, 'bad ramp ' // quoted(val%s) // ' (expected ramp=k0:k1 with k0 < k1: the load ' // &
                  'rises from step k0 to step k1)')
    else
      ramp = [k0, k1]
    end if
  end subroutine get_ramp

  !> A pair of components in x, y (keys 1, 2 of seen and val) or in the
  !> boundary's axes n, t (keys 5, 6), not both.
  !>   names (in)  the four keys, e.g. ux, uy, un, ut
  !>   local (out) the n, t pair was given;  a, b (inout) its values (unchanged when absent)
  subroutine get_component_pair(s, st, seen, val, names, local, a, b)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    logical, intent(in) :: seen(6)
    type(text_t), intent(in) :: val(6)
    character(len=2), intent(in) :: names(4)
    logical, intent(out) :: local
    real(dp), intent(inout) :: a, b
    logical :: ok
    local = .false.
    if ((seen(1) .or. seen(2)) .and. (seen(5) .or. seen(6))) then
      call report(s, st%line, names(1) // '=/' // names(2) // '= and ' // names(3) // '=/' // names(4) // &
                  '= together (expected x, y components ' // names(1) // ', ' // names(2) // ' or boundary ' // &
                  'components ' // names(3) // ', ' // names(4) // ', not both: two statements for the two)')
    else if (seen(5) .or. seen(6)) then
      local = .true.
      call get_real(s, st, val(5), names(3), a, ok)
      call get_real(s, st, val(6), names(4), b, ok)
    else
      call get_real(s, st, val(1), names(1), a, ok)
      call get_real(s, st, val(2), names(2), b, ok)
    end if
  end subroutine get_component_pair

  !> The value of curve=NAME (checked as a name; resolved against the CURVE
  !> statements after the whole deck, resolve_curves).  ramp= and curve= on
  !> one statement are an error: a statement has one load path.
  !>   val       (in)  the value of curve=, unallocated when absent
  !>   ramp_val  (in)  the value of ramp= on the same statement, unallocated when absent
  !>   name      (out) the curve's name, '' when absent or bad
  subroutine get_curve_name(s, st, val, ramp_val, name)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(text_t), intent(in) :: val, ramp_val
    character(len=:), allocatable, intent(out) :: name
    logical :: ok
    name = ''
    if (.not. allocated(val%s)) return
    if (allocated(ramp_val%s)) then
      call report(s, st%line, 'ramp= and curve= together (expected one load path per statement: ramp=k0:k1 ' // &
                  'or curve=NAME)')
      return
    end if
    call check_name(s, st, val%s, 'curve', ok)
    if (ok) name = val%s
  end subroutine get_curve_name

  ! ================================================================ statements

  !> TITLE free text
  subroutine do_title(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    integer :: i
    deck%title = st%rest
    do i = 1, len(deck%title)
      if (iachar(deck%title(i:i)) < 32 .or. iachar(deck%title(i:i)) == 127) deck%title(i:i) = '?'
    end do
  end subroutine do_title

  !> PLANE strain | PLANE stress [thickness=] | PLANE axisymmetric
  subroutine do_plane(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'PLANE strain, PLANE stress [thickness=number] or PLANE axisymmetric'
    logical :: seen(1), ok
    type(text_t) :: val(1)
    character(len=:), allocatable :: kind

    deck%plane_line = st%line
    if (st%nword == 0) then
      call report(s, st%line, 'missing plane kind (expected ' // usage // ')')
      return
    end if
    kind = lower(st%word(1)%s)
    if (kind /= 'strain' .and. kind /= 'stress' .and. kind /= 'axisymmetric') then
      call report(s, st%line, 'unknown plane kind ' // quoted(st%word(1)%s) // ' (expected ' // usage // ')')
      return
    end if
    call check_extra_words(s, st, 1, usage)
    call match_keys(s, st, st%names, st%forms, 'PLANE ' // kind, seen, val)
    if (kind == 'strain') then
      deck%plane_stress = .false.
      if (seen(1)) call report(s, st%line, 'thickness= only with PLANE stress (PLANE strain is per unit thickness)')
    else if (kind == 'axisymmetric') then
      deck%axisymmetric = .true.
      if (seen(1)) call report(s, st%line, 'thickness= only with PLANE stress (PLANE axisymmetric is the ' // &
                               'full solid of revolution)')
    else
      deck%plane_stress = .true.
      call get_real(s, st, val(1), 'thickness', deck%thickness, ok, positive=.true.)
    end if
  end subroutine do_plane

  !> BODY name
  subroutine do_body(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    type(body_deck_t), allocatable :: grown(:)
    character(len=*), parameter :: usage = 'BODY name'
    integer :: b
    logical :: ok

    allocate(grown(s%nbody + 1))
    do b = 1, s%nbody
      grown(b) = deck%bodies(b)
    end do
    call move_alloc(grown, deck%bodies)
    s%nbody = s%nbody + 1
    s%cur = s%nbody
    s%end_hinted = .false.
    associate (body => deck%bodies(s%nbody))
      body%line = st%line
      body%name = ''
      allocate(body%fixes(0), body%loads(0), body%thermals(0))
      if (st%nword == 0) then
        call report(s, st%line, 'missing body name (expected ' // usage // ')')
      else
        body%name = st%word(1)%s
        call check_name(s, st, body%name, 'body', ok)
        if (ok) then
          do b = 1, s%nbody - 1
            if (deck%bodies(b)%name == body%name) then
              call report(s, st%line, 'duplicate BODY name ' // quoted(body%name) // ' (first at line ' // &
                          int_to_str(deck%bodies(b)%line) // '; expected a new name)')
              exit
            end if
          end do
        end if
        call check_extra_words(s, st, 1, usage)
      end if
      if (st%npair > 0) call report(s, st%line, 'unexpected ' // quoted(st%key(1)%s // '=' // st%value(1)%s) // &
                                    ' (expected ' // usage // ')')
      s%block_name = body%name
      s%block_line = body%line
    end associate
  end subroutine do_body

  !> END: closes the open block (BODY ... END).
  subroutine close_block(s, st)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    if (s%block == '') then
      call report(s, st%line, 'END without an open BODY (expected END only to close a BODY block)')
      return
    end if
    if (st%nword > 0) then
      call report(s, st%line, 'unexpected word ' // quoted(st%word(1)%s) // ' after END (expected END alone)')
    else if (st%npair > 0) then
      call report(s, st%line, 'unexpected ' // quoted(st%key(1)%s // '=' // st%value(1)%s) // &
                  ' after END (expected END alone)')
    end if
    s%cur = 0
    s%block = ''
    s%end_hinted = .false.
  end subroutine close_block

  !> MESH rect ... | MESH gmsh file=...
  subroutine do_mesh(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'MESH rect x0= y0= x1= y1= nx= ny= or MESH gmsh file=NAME.msh|NAME.geo'
    character(len=:), allocatable :: kind

    associate (body => deck%bodies(s%cur))
      body%mesh%line = st%line
      if (st%nword == 0) then
        call report(s, st%line, 'missing mesh kind (expected ' // usage // ')')
        return
      end if
      kind = lower(st%word(1)%s)
      select case (kind)
      case ('rect')
        body%mesh%kind = 'rect'
        call do_mesh_rect(s, body%mesh, st)
      case ('gmsh')
        body%mesh%kind = 'gmsh'
        call do_mesh_gmsh(s, deck%dir, body%mesh, st)
      case default
        call report(s, st%line, 'unknown mesh kind ' // quoted(st%word(1)%s) // ' (expected rect or gmsh)')
      end select
    end associate
  end subroutine do_mesh

  !> MESH rect [x0=] [y0=] [x1=] [y1=] nx= ny= [elem=] [diag=]
  subroutine do_mesh_rect(s, m, st)
    type(state_t), intent(inout) :: s
    type(mesh_spec_t), intent(inout) :: m
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'MESH rect x0=number y0=number x1=number y1=number nx=integer ' // &
                                           'ny=integer [elem=tri3|quad4|tri6|quad8|quad9] [diag=right|left|alt]'
    character(len=4), parameter :: names(8) = [character(len=4) :: 'x0', 'y0', 'x1', 'y1', 'nx', 'ny', 'elem', 'diag']
    character(len=27), parameter :: forms(8) = [character(len=27) :: 'number', 'number', 'number', 'number', &
                                                'integer', 'integer', 'tri3|quad4|tri6|quad8|quad9', 'right|left|alt']
    logical :: seen(8), okx0, oky0, okx1, oky1, ok
    type(text_t) :: val(8)

    call check_extra_words(s, st, 1, usage)
    call match_keys(s, st, names, forms, 'MESH rect', seen, val)
    call get_real(s, st, val(1), 'x0', m%x0, okx0)
    call get_real(s, st, val(2), 'y0', m%y0, oky0)
    call get_real(s, st, val(3), 'x1', m%x1, okx1)
    call get_real(s, st, val(4), 'y1', m%y1, oky1)
    okx0 = okx0 .or. .not. seen(1)
    oky0 = oky0 .or. .not. seen(2)
    okx1 = okx1 .or. .not. seen(3)
    oky1 = oky1 .or. .not. seen(4)
    if (okx0 .and. okx1 .and. .not. m%x1 > m%x0) &
      call report(s, st%line, 'bad rectangle x0=' // shown(val(1), '0') // ' x1=' // shown(val(3), '1') // &
                  ' (expected x1 > x0)')
    if (oky0 .and. oky1 .and. .not. m%y1 > m%y0) &
      call report(s, st%line, 'bad rectangle y0=' // shown(val(2), '0') // ' y1=' // shown(val(4), '1') // &
                  ' (expected y1 > y0)')
    call require_key(s, st, seen(5), 'nx', 'MESH rect', usage)
    call require_key(s, st, seen(6), 'ny', 'MESH rect', usage)
    call get_integer(s, st, val(5), 'nx', 1, m%nx, ok)
    call get_integer(s, st, val(6), 'ny', 1, m%ny, ok)
    if (m%nx > 0 .and. m%ny > 0) then
      if (int(m%nx, int64) * int(m%ny, int64) > 100000000_int64) &
        call report(s, st%line, 'rect mesh too large (expected nx*ny <= 100000000)')
    end if
    m%elem = 'tri3'
    m%diag = 'right'
    if (allocated(val(7)%s)) m%elem = get_choice(s, st, val(7), 'elem', ['tri3 ', 'quad4', 'tri6 ', 'quad8', 'quad9'])
    if (allocated(val(8)%s)) then
      m%diag = get_choice(s, st, val(8), 'diag', ['right', 'left ', 'alt  '])
      if (m%elem(1:1) == 'q') call report(s, st%line, 'diag= applies only to elem=tri3 or tri6 (got elem=' // &
                                          m%elem // ')')
    end if
  end subroutine do_mesh_rect

  !> Value as written, or a default text when not given.
  pure function shown(val, default) result(t)
    type(text_t), intent(in) :: val
    character(len=*), intent(in) :: default
    character(len=:), allocatable :: t
    if (allocated(val%s)) then
      t = cut(val%s)
    else
      t = default
    end if
  end function shown

  !> MESH gmsh file=NAME.msh | file=NAME.geo [name=number ...]
  subroutine do_mesh_gmsh(s, dir, m, st)
    type(state_t), intent(inout) :: s
    character(len=*), intent(in) :: dir
    type(mesh_spec_t), intent(inout) :: m
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'MESH gmsh file=NAME.msh or file=NAME.geo [order=1|2] [name=number ...]'
    integer :: i, j, nset, ifile, kind
    logical :: ok, is_msh, seen_order
    real(dp) :: x

    m%elem = ''
    m%diag = ''
    seen_order = .false.
    call check_extra_words(s, st, 1, usage)
    ifile = 0
    do i = 1, st%npair
      if (lower(st%key(i)%s) /= 'file') cycle
      if (ifile > 0) then
        call report(s, st%line, 'duplicate key "file" (expected each key at most once)')
      else
        ifile = i
      end if
    end do
    if (ifile == 0) then
      call report(s, st%line, 'missing key "file" for MESH gmsh (expected ' // usage // ')')
      return
    end if
    m%file = st%value(ifile)%s
    if (len(m%file) == 0) then
      call report(s, st%line, 'missing value for "file" (expected file=NAME.msh or file=NAME.geo)')
      return
    end if
    is_msh = ends_with_ci(m%file, '.msh')
    m%is_geo = ends_with_ci(m%file, '.geo')
    if (.not. (is_msh .or. m%is_geo) .or. len(m%file) < 5 .or. .not. is_printable(m%file)) then
      call report(s, st%line, 'bad mesh file name ' // quoted(m%file) // ' (expected a name ending in .msh or .geo)')
      return
    end if
    if (m%file(1:1) == '/' .or. dir == '.') then
      m%path = m%file
    else if (dir == '/') then
      m%path = '/' // m%file
    else
      m%path = dir // '/' // m%file
    end if
    kind = file_kind(m%path)
    if (kind == c2d_missing) then
      call report(s, st%line, 'cannot find mesh file ' // quoted(m%file) // ' (looked for ' // cut(m%path) // ')')
    else if (kind /= c2d_regular .and. kind /= c2d_unreadable) then
      call report(s, st%line, 'mesh file ' // quoted(m%file) // ' is ' // kind_name(kind) // &
                  ', not a regular file: refused (a .msh or .geo file expected)')
    end if

    nset = 0
    allocate(m%set_names(st%npair), m%set_values(st%npair))
    do i = 1, st%npair
      if (i == ifile .or. lower(st%key(i)%s) == 'file') cycle
      if (len(st%key(i)%s) == 0) then
        call report(s, st%line, 'missing key before ' // quoted('=' // st%value(i)%s) // ' (expected key=value)')
        cycle
      end if
      if (is_msh) then
        call report(s, st%line, 'unknown key ' // quoted(st%key(i)%s) // ' for MESH gmsh with a .msh file ' // &
                    '(expected file= only; name=number pairs are for .geo files)')
        cycle
      end if
      if (lower(st%key(i)%s) == 'order') then        ! gmsh -order 1 or 2, not a .geo variable
        if (seen_order) then
          call report(s, st%line, 'duplicate key "order" (expected each key at most once)')
        else if (st%value(i)%s == '1' .or. st%value(i)%s == '2') then
          m%order = merge(2, 1, st%value(i)%s == '2')
        else
          call report(s, st%line, 'bad value order=' // cut(st%value(i)%s) // ' (expected order=1|2)')
        end if
        seen_order = .true.
        cycle
      end if
      if (.not. is_identifier(st%key(i)%s)) then
        call report(s, st%line, 'bad parameter name ' // quoted(st%key(i)%s) // ' for MESH gmsh (expected a ' // &
                    '.geo variable: a letter or _, then letters, digits or _, at most 64 characters)')
        cycle
      end if
      do j = 1, nset
        if (trim(m%set_names(j)) == st%key(i)%s) exit
      end do
      if (j <= nset) then
        call report(s, st%line, 'duplicate key ' // quoted(st%key(i)%s) // ' (expected each key at most once)')
        cycle
      end if
      if (len(st%value(i)%s) == 0) then
        call report(s, st%line, 'missing value for ' // quoted(st%key(i)%s) // ' (expected ' // st%key(i)%s // &
                    '=number)')
        cycle
      end if
      call parse_real(st%value(i)%s, x, ok)
      if (.not. ok) then
        call report(s, st%line, 'bad number ' // quoted(st%value(i)%s) // ' for ' // quoted(st%key(i)%s) // &
                    ' (expected a finite number)')
        cycle
      end if
      nset = nset + 1
      m%set_names(nset) = st%key(i)%s
      m%set_values(nset) = x
    end do
    m%set_names = m%set_names(1:nset)
    m%set_values = m%set_values(1:nset)
  end subroutine do_mesh_gmsh

  !> MATERIAL isotropic E= nu= | MATERIAL orthotropic E1= E2= nu12= G12= [angle=] [E3=] [nu13=] [nu23=]
  subroutine do_material(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage_iso = 'MATERIAL isotropic E=number nu=number'
    character(len=*), parameter :: usage_ortho = 'MATERIAL orthotropic E1=number E2=number nu12=number ' // &
                                                 'G12=number [angle=degrees] [E3=number] [nu13=number] [nu23=number]'
    character(len=5), parameter :: iso_names(2) = [character(len=5) :: 'E', 'nu']
    character(len=5), parameter :: ortho_names(8) = [character(len=5) :: 'E1', 'E2', 'nu12', 'G12', 'angle', &
                                                     'E3', 'nu13', 'nu23']
    character(len=6), parameter :: forms(8) = [character(len=6) :: 'number', 'number', 'number', 'number', &
                                               'number', 'number', 'number', 'number']
    logical :: seen(8), ok(8)
    type(text_t) :: val(8)
    integer :: nerr0
    character(len=:), allocatable :: kind
    type(material_t) :: mat

    associate (body => deck%bodies(s%cur))
      body%material%line = st%line
      body%material%kind = ''
      if (st%nword == 0) then
        call report(s, st%line, 'missing material kind (expected ' // usage_iso // ' or MATERIAL orthotropic ...)')
        return
      end if
      kind = lower(st%word(1)%s)
      nerr0 = s%nerr
      mat%line = st%line
      select case (kind)
      case ('isotropic')
        call check_extra_words(s, st, 1, usage_iso)
        call match_keys(s, st, iso_names, forms(1:2), 'MATERIAL isotropic', seen(1:2), val(1:2))
        call require_key(s, st, seen(1), 'E', 'MATERIAL isotropic', usage_iso)
        call require_key(s, st, seen(2), 'nu', 'MATERIAL isotropic', usage_iso)
        call get_real(s, st, val(1), 'E', mat%e, ok(1), positive=.true.)
        call get_real(s, st, val(2), 'nu', mat%nu, ok(2))
        if (ok(2) .and. .not. (mat%nu > -1.0_dp .and. mat%nu < 0.5_dp)) &
          call report(s, st%line, 'bad value nu=' // cut(val(2)%s) // ' (expected -1 < nu < 0.5)')
      case ('orthotropic')
        call check_extra_words(s, st, 1, usage_ortho)
        call match_keys(s, st, ortho_names, forms, 'MATERIAL orthotropic', seen, val)
        call require_key(s, st, seen(1), 'E1', 'MATERIAL orthotropic', usage_ortho)
        call require_key(s, st, seen(2), 'E2', 'MATERIAL orthotropic', usage_ortho)
        call require_key(s, st, seen(3), 'nu12', 'MATERIAL orthotropic', usage_ortho)
        call require_key(s, st, seen(4), 'G12', 'MATERIAL orthotropic', usage_ortho)
        call get_real(s, st, val(1), 'E1', mat%e1, ok(1), positive=.true.)
        call get_real(s, st, val(2), 'E2', mat%e2, ok(2), positive=.true.)
        call get_real(s, st, val(3), 'nu12', mat%nu12, ok(3))
        call get_real(s, st, val(4), 'G12', mat%g12, ok(4), positive=.true.)
        call get_real(s, st, val(5), 'angle', mat%angle, ok(5))
        mat%e3 = mat%e2
        mat%nu13 = mat%nu12
        mat%nu23 = mat%nu12
        call get_real(s, st, val(6), 'E3', mat%e3, ok(6), positive=.true.)
        call get_real(s, st, val(7), 'nu13', mat%nu13, ok(7))
        call get_real(s, st, val(8), 'nu23', mat%nu23, ok(8))
        if (all(ok(1:3))) then
          if (.not. plane_compliance_ok(mat)) call report(s, st%line, 'orthotropic in-plane compliance not ' // &
                                                          'positive definite (expected nu12^2 < E1/E2)')
        end if
      case default
        call report(s, st%line, 'unknown material kind ' // quoted(st%word(1)%s) // ' (expected isotropic or orthotropic)')
        return
      end select
      if (s%nerr == nerr0) then
        mat%kind = kind
        body%material = mat
      end if
    end associate
  end subroutine do_material

  !> 1 - nu12^2 E2/E1 > 0, computed without overflow.
  pure logical function plane_compliance_ok(m) result(ok)
    type(material_t), intent(in) :: m
    ok = 1.0_dp - ratio_term(2, [m%nu12], m%e2, m%e1) > 0
  end function plane_compliance_ok

  !> det of the normal 3x3 compliance (times E1 E2 E3 / E1 ...) > 0 in the form
  !> 1 - nu12^2 E2/E1 - nu23^2 E3/E2 - nu13^2 E3/E1 - 2 nu12 nu23 nu13 E3/E1 > 0.
  pure logical function strain_compliance_ok(m) result(ok)
    type(material_t), intent(in) :: m
    real(dp) :: det
    det = 1.0_dp - ratio_term(2, [m%nu12], m%e2, m%e1) - ratio_term(2, [m%nu23], m%e3, m%e2) &
          - ratio_term(2, [m%nu13], m%e3, m%e1) - 2.0_dp * ratio_term(1, [m%nu12, m%nu23, m%nu13], m%e3, m%e1)
    ok = det > 0
  end function strain_compliance_ok

  !> prod(nu)^power * num/den with num, den > 0, through logarithms and clamped at
  !> 1e250 in magnitude, so that no input overflows.
  pure real(dp) function ratio_term(power, nu, num, den) result(t)
    integer, intent(in) :: power
    real(dp), intent(in) :: nu(:), num, den
    real(dp) :: lg, sgn
    integer :: i
    t = 0
    if (any(nu == 0) .or. .not. (num > 0 .and. den > 0)) return
    lg = log(num) - log(den)
    sgn = 1
    do i = 1, size(nu)
      lg = lg + power * log(abs(nu(i)))
      if (nu(i) < 0) sgn = -sgn
    end do
    if (power == 2) sgn = 1
    t = sgn * exp(min(lg, 575.0_dp))
  end function ratio_term

  !> DENSITY rho=
  subroutine do_density(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'DENSITY rho=number'
    logical :: seen(1), ok
    type(text_t) :: val(1)

    associate (body => deck%bodies(s%cur))
      body%density_line = st%line
      call check_extra_words(s, st, 0, usage)
      call match_keys(s, st, st%names, st%forms, 'DENSITY', seen, val)
      call require_key(s, st, seen(1), 'rho', 'DENSITY', usage)
      call get_real(s, st, val(1), 'rho', body%rho, ok, positive=.true.)
      body%has_density = ok
    end associate
  end subroutine do_density

  !> FIX boundary [ux=] [uy=] [ramp=]
  subroutine do_fix(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'FIX boundary [ux=number] [uy=number] | [un=number] [ut=number] ' // &
                                           '[ramp=k0:k1|curve=NAME]'
    type(fix_t), allocatable :: grown(:)
    type(fix_t) :: fix
    logical :: seen(6), ok
    type(text_t) :: val(6)

    associate (body => deck%bodies(s%cur))
      fix%line = st%line
      fix%boundary = ''
      if (st%nword == 0) then
        call report(s, st%line, 'missing boundary name (expected ' // usage // ')')
      else
        call check_name(s, st, st%word(1)%s, 'boundary', ok)
        if (ok) fix%boundary = st%word(1)%s
        call check_extra_words(s, st, 1, usage)
      end if
      call match_keys(s, st, st%names, st%forms, 'FIX', seen, val)
      call get_component_pair(s, st, seen, val, ['ux', 'uy', 'un', 'ut'], fix%local, fix%ux, fix%uy)
      if (fix%local) seen(1:2) = seen(5:6)             ! ux, uy hold un, ut
      call get_ramp(s, st, val(3), fix%ramp)
      call get_curve_name(s, st, val(4), val(3), fix%curve_name)
      fix%has_ux = seen(1)
      fix%has_uy = seen(2)
      if (.not. (seen(1) .or. seen(2))) then          ! FIX boundary [ramp=]: clamp both
        fix%has_ux = .true.
        fix%has_uy = .true.
      end if
      ! capacity doubles: 1e5 FIX statements cost 1e5 copies in all, not 5e9
      if (body%nfix == size(body%fixes)) then
        allocate(grown(max(8, 2 * size(body%fixes))))
        grown(1:body%nfix) = body%fixes(1:body%nfix)
        call move_alloc(grown, body%fixes)
      end if
      body%nfix = body%nfix + 1
      body%fixes(body%nfix) = fix
    end associate
  end subroutine do_fix

  !> TRACTION boundary tx= ty= [ramp=] | PRESSURE boundary p= [ramp=]
  subroutine do_load(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=:), allocatable :: usage, kw
    type(load_t), allocatable :: grown(:)
    type(load_t) :: load
    logical :: seen(6), ok
    type(text_t) :: val(6)
    integer :: nerr0

    kw = upper(st%keyword)
    associate (body => deck%bodies(s%cur))
      if (kw == 'TRACTION') then
        usage = 'TRACTION boundary tx=number ty=number | tn=number tt=number [ramp=k0:k1|curve=NAME]'
        load%kind = load_traction
      else
        usage = 'PRESSURE boundary p=number [ramp=k0:k1|curve=NAME]'
        load%kind = load_pressure
      end if
      load%line = st%line
      load%boundary = ''
      nerr0 = s%nerr
      if (st%nword == 0) then
        call report(s, st%line, 'missing boundary name (expected ' // usage // ')')
      else
        call check_name(s, st, st%word(1)%s, 'boundary', ok)
        if (ok) load%boundary = st%word(1)%s
        call check_extra_words(s, st, 1, usage)
      end if
      if (kw == 'TRACTION') then
        call match_keys(s, st, st%names, st%forms, 'TRACTION', seen, val)
        if (.not. any(seen([1, 2, 5, 6]))) call report(s, st%line, 'missing tx= and ty= (expected ' // usage // ')')
        call get_component_pair(s, st, seen, val, ['tx', 'ty', 'tn', 'tt'], load%local, load%tx, load%ty)
        call get_ramp(s, st, val(3), load%ramp)
        call get_curve_name(s, st, val(4), val(3), load%curve_name)
      else
        call match_keys(s, st, st%names, st%forms, 'PRESSURE', seen(1:3), val(1:3))
        call require_key(s, st, seen(1), 'p', 'PRESSURE', usage)
        call get_real(s, st, val(1), 'p', load%p, ok)
        call get_ramp(s, st, val(2), load%ramp)
        call get_curve_name(s, st, val(3), val(2), load%curve_name)
      end if
      if (s%nerr /= nerr0) return
      if (body%nload == size(body%loads)) then        ! capacity doubles, as for FIX
        allocate(grown(max(8, 2 * size(body%loads))))
        grown(1:body%nload) = body%loads(1:body%nload)
        call move_alloc(grown, body%loads)
      end if
      body%nload = body%nload + 1
      body%loads(body%nload) = load
    end associate
  end subroutine do_load

  !> BODYFORCE fx= fy= [ramp=|curve=]
  subroutine do_bodyforce(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    associate (body => deck%bodies(s%cur))
      body%bodyforce_line = st%line
      call read_vector_statement(s, st, 'BODYFORCE fx=number fy=number [ramp=k0:k1|curve=NAME]', body%fx, body%fy, &
                                 body%has_bodyforce, body%bodyforce_ramp, body%bodyforce_curve_name)
    end associate
  end subroutine do_bodyforce

  !> THERMAL alpha= dT= [region=NAME]
  subroutine do_thermal(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'THERMAL alpha=number dT=number [region=NAME] [curve=NAME]'
    type(thermal_t), allocatable :: grown(:)
    type(thermal_t) :: th
    logical :: seen(4), ok1, ok2, okn
    type(text_t) :: val(4), no_ramp
    integer :: k

    associate (body => deck%bodies(s%cur))
      call check_extra_words(s, st, 0, usage)
      call match_keys(s, st, st%names, st%forms, 'THERMAL', seen, val)
      call get_curve_name(s, st, val(4), no_ramp, th%curve_name)
      call require_key(s, st, seen(1), 'alpha', 'THERMAL', usage)
      call require_key(s, st, seen(2), 'dT', 'THERMAL', usage)
      call get_real(s, st, val(1), 'alpha', th%alpha, ok1)
      call get_real(s, st, val(2), 'dT', th%dt, ok2)
      th%region = ''
      okn = .true.
      if (allocated(val(3)%s)) then
        call check_name(s, st, val(3)%s, 'region', okn)
        if (okn) th%region = val(3)%s
      end if
      if (.not. (ok1 .and. ok2 .and. okn)) return
      do k = 1, size(body%thermals)
        if (body%thermals(k)%region == th%region) then
          if (len(th%region) == 0) then
            call report(s, st%line, 'second THERMAL for the whole of BODY ' // quoted(body%name) // ' (first at line ' // &
                        int_to_str(body%thermals(k)%line) // '; expected one, or one per region=)')
          else
            call report(s, st%line, 'second THERMAL for region ' // quoted(th%region) // ' (first at line ' // &
                        int_to_str(body%thermals(k)%line) // '; expected one per region)')
          end if
          return
        end if
      end do
      th%line = st%line
      allocate(grown(size(body%thermals) + 1))
      grown(1:size(body%thermals)) = body%thermals
      grown(size(grown)) = th
      call move_alloc(grown, body%thermals)
    end associate
  end subroutine do_thermal

  !> OFFSET dx= dy=: a rigid shift of the body's geometry (mesh) before anything else
  subroutine do_offset(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    associate (body => deck%bodies(s%cur))
      body%offset_line = st%line
      call read_vector_statement(s, st, 'OFFSET dx=number dy=number', body%dx, body%dy, body%has_offset)
    end associate
  end subroutine do_offset

  !> GRAVITY gx= gy= [ramp=|curve=]
  subroutine do_gravity(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    deck%gravity_line = st%line
    call read_vector_statement(s, st, 'GRAVITY gx=number gy=number [ramp=k0:k1|curve=NAME]', deck%gx, deck%gy, &
                               deck%has_gravity, deck%gravity_ramp, deck%gravity_curve_name)
  end subroutine do_gravity

  !> A statement of a vector (GRAVITY, BODYFORCE, OFFSET): no words, the keys
  !> of its row, its two components first (at least one given), then ramp= and
  !> curve= when it takes a load path.
  !>   usage       (in)    the statement's form, for messages
  !>   a, b        (inout) the components as given (unchanged when absent)
  !>   given       (out)   at least one component given, and every one given a number
  !>   ramp, curve_name (out, optional) the load path (get_ramp, get_curve_name)
  subroutine read_vector_statement(s, st, usage, a, b, given, ramp, curve_name)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    character(len=*), intent(in) :: usage
    real(dp), intent(inout) :: a, b
    logical, intent(out) :: given
    integer, intent(out), optional :: ramp(2)
    character(len=:), allocatable, intent(out), optional :: curve_name
    logical :: seen(4), ok1, ok2
    type(text_t) :: val(4)
    integer :: nkey

    nkey = size(st%names)
    call check_extra_words(s, st, 0, usage)
    call match_keys(s, st, st%names, st%forms, upper(st%keyword), seen(1:nkey), val(1:nkey))
    if (.not. (seen(1) .or. seen(2))) call report(s, st%line, 'missing ' // trim(st%names(1)) // '= and ' // &
                                                  trim(st%names(2)) // '= (expected ' // usage // ')')
    call get_real(s, st, val(1), trim(st%names(1)), a, ok1)
    call get_real(s, st, val(2), trim(st%names(2)), b, ok2)
    if (present(ramp)) call get_ramp(s, st, val(3), ramp)
    if (present(curve_name)) call get_curve_name(s, st, val(4), val(3), curve_name)
    given = (ok1 .or. .not. seen(1)) .and. (ok2 .or. .not. seen(2)) .and. (seen(1) .or. seen(2))
  end subroutine read_vector_statement

  !> CONTACT slave=body:boundary master=body:boundary [gap=geometry|zero] [mu=number | tresca=number]
  !>         [interference=allow|reject]
  subroutine do_contact(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'CONTACT slave=body:boundary master=body:boundary [gap=geometry|zero] ' // &
                                           '[mu=number|tresca=number] [interference=allow|reject]'
    logical :: seen(6), ok_s, ok_m, ok
    type(text_t) :: val(6)
    type(contact_deck_t) :: c
    type(contact_deck_t), allocatable :: grown(:)
    type(text_t), allocatable :: gs(:), gm(:)
    character(len=:), allocatable :: sbody, mbody, gap
    integer :: nerr0, i

    nerr0 = s%nerr
    call check_extra_words(s, st, 0, usage)
    call match_keys(s, st, st%names, st%forms, 'CONTACT', seen, val)
    call require_key(s, st, seen(1), 'slave', 'CONTACT', usage)
    call require_key(s, st, seen(2), 'master', 'CONTACT', usage)
    call split_side(s, st, val(1), 'slave', sbody, c%slave_boundary, ok_s)
    if (allocated(val(2)%s) .and. index(val(2)%s, ':') == 0 .and. is_name(val(2)%s)) then
      mbody = val(2)%s                               ! master=RIGIDNAME: resolved after the deck
      c%master_boundary = ''
      ok_m = .false.
    else
      call split_side(s, st, val(2), 'master', mbody, c%master_boundary, ok_m)
    end if
    if (ok_s .and. ok_m) then
      if (sbody == mbody .and. c%slave_boundary == c%master_boundary) &
        call report(s, st%line, 'slave and master must be different boundaries (both are ' // &
                    cut(sbody // ':' // c%slave_boundary) // ')')
    end if
    gap = 'geometry'
    if (allocated(val(3)%s)) gap = get_choice(s, st, val(3), 'gap', ['geometry', 'zero    '])
    c%gap_zero = gap == 'zero'
    ! an initial penetration deeper than a slave element is an input error unless allowed
    if (allocated(val(6)%s)) c%interference = get_choice(s, st, val(6), 'interference', ['allow ', 'reject']) == 'allow'
    ! friction (beyond the paper): |tau| <= mu p (Coulomb) or |tau| <= tresca
    c%friction = 'none'
    if (seen(4) .and. seen(5)) &
      call report(s, st%line, 'mu= and tresca= together (expected one friction law per CONTACT)')
    call get_real(s, st, val(4), 'mu', c%mu, ok)
    if (ok) then
      if (c%mu >= 0 .and. c%mu <= max_mu) then
        c%friction = 'coulomb'
      else
        call report(s, st%line, 'bad value mu=' // cut(val(4)%s) // ' (expected 0 <= mu <= 1000)')
      end if
    end if
    call get_real(s, st, val(5), 'tresca', c%tresca, ok)
    if (ok) then
      if (c%tresca >= 0) then
        c%friction = 'tresca'
      else
        call report(s, st%line, 'bad value tresca=' // cut(val(5)%s) // ' (expected tresca >= 0, a shear stress)')
      end if
    end if
    c%line = st%line
    if (s%nerr /= nerr0) then
      s%contact_bad = .true.
      return
    end if
    allocate(grown(s%ncontact + 1))
    do i = 1, s%ncontact
      grown(i) = deck%contacts(i)
    end do
    grown(s%ncontact + 1) = c
    call move_alloc(grown, deck%contacts)
    if (s%ncontact + 1 > size(s%slave_name)) then
      allocate(gs(2 * size(s%slave_name)), gm(2 * size(s%slave_name)))
      do i = 1, s%ncontact
        call move_alloc(s%slave_name(i)%s, gs(i)%s)
        call move_alloc(s%master_name(i)%s, gm(i)%s)
      end do
      call move_alloc(gs, s%slave_name)
      call move_alloc(gm, s%master_name)
    end if
    s%ncontact = s%ncontact + 1
    s%slave_name(s%ncontact)%s = sbody
    s%master_name(s%ncontact)%s = mbody
  end subroutine do_contact

  !> Split 'body:boundary'; report a bad form.  ok false when absent or bad.
  subroutine split_side(s, st, val, name, body, boundary, ok)
    type(state_t), intent(inout) :: s
    type(stmt_t), intent(in) :: st
    type(text_t), intent(in) :: val
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: body
    character(len=:), allocatable, intent(inout) :: boundary
    logical, intent(out) :: ok
    integer :: colon
    body = ''
    boundary = ''
    ok = .false.
    if (.not. allocated(val%s)) return
    colon = index(val%s, ':')
    if (colon > 1 .and. colon < len(val%s)) then
      body = val%s(1:colon - 1)
      boundary = val%s(colon + 1:)
      ok = is_name(body) .and. is_name(boundary)
    end if
    if (.not. ok) call report(s, st%line, 'bad value ' // name // '=' // cut(val%s) // ' (expected ' // name // &
                              '=body:boundary, names made of letters, digits, _ . -)')
  end subroutine split_side

  !> SOLVER [lcp=] [tol=] [maxit=] [omega=] [ordering=] [condense=] [cut=]
  subroutine do_solver(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'SOLVER [lcp=auto|lemke|pgs|pdas] [tol=number] [maxit=integer] ' // &
                                           '[omega=number] [ordering=auto|metis|amd] [condense=auto|solve|inverse] ' // &
                                           '[cut=auto|off]'
    logical :: seen(7), ok
    type(text_t) :: val(7)
    character(len=:), allocatable :: lcp, ordering, condense, halves

    deck%solver%line = st%line
    call check_extra_words(s, st, 0, usage)
    call match_keys(s, st, st%names, st%forms, 'SOLVER', seen, val)
    if (allocated(val(1)%s)) then
      lcp = get_choice(s, st, val(1), 'lcp', ['auto ', 'lemke', 'pgs  ', 'pdas '])
      if (len(lcp) > 0) deck%solver%lcp = lcp
    end if
    if (allocated(val(5)%s)) then
      ordering = get_choice(s, st, val(5), 'ordering', ['auto ', 'metis', 'amd  '])
      if (len(ordering) > 0) deck%solver%ordering = ordering
    end if
    if (allocated(val(6)%s)) then
      condense = get_choice(s, st, val(6), 'condense', ['auto   ', 'solve  ', 'inverse'])
      if (len(condense) > 0) deck%solver%condense = condense
    end if
    if (allocated(val(7)%s)) then
      halves = get_choice(s, st, val(7), 'cut', ['auto', 'off '])
      if (len(halves) > 0) deck%solver%cut = halves
    end if
    call get_real(s, st, val(2), 'tol', deck%solver%tol, ok, positive=.true.)
    call get_integer(s, st, val(3), 'maxit', 0, deck%solver%maxit, ok)
    call get_real(s, st, val(4), 'omega', deck%solver%omega, ok)
    if (ok .and. .not. (deck%solver%omega > 0 .and. deck%solver%omega < 2)) &
      call report(s, st%line, 'bad value omega=' // cut(val(4)%s) // ' (expected 0 < omega < 2)')
  end subroutine do_solver

  !> STEPS n: the number of load steps (the ramps run over steps 0..n)
  subroutine do_steps(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'STEPS n with an integer 1 <= n <= 100000'
    integer :: n, nerr0
    logical :: ok

    deck%steps_line = st%line
    nerr0 = s%nerr
    if (st%nword == 0) then
      if (st%npair == 0) call report(s, st%line, 'missing number of load steps (expected ' // usage // ')')
    else
      call parse_integer(st%word(1)%s, n, ok)
      if (ok) ok = n >= 1 .and. n <= max_steps
      if (ok) then
        deck%steps = n
      else
        call report(s, st%line, 'bad number of load steps ' // quoted(st%word(1)%s) // ' (expected ' // usage // ')')
      end if
      call check_extra_words(s, st, 1, usage)
    end if
    if (st%npair > 0) call report(s, st%line, 'unexpected ' // quoted(st%key(1)%s // '=' // st%value(1)%s) // &
                                  ' (expected ' // usage // ')')
    s%steps_bad = s%nerr /= nerr0
  end subroutine do_steps

  !> CURVE name t0:v0 t1:v1 ...: a piecewise-linear load factor against the
  !> step number, at least one point, t strictly increasing (numbers, not
  !> necessarily integers).
  subroutine do_curve(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'CURVE name t0:v0 t1:v1 ... with step numbers t0 < t1 < ... and ' // &
                                           'load factors v'
    type(curve_t) :: c
    type(curve_t), allocatable :: grown(:)
    integer :: k, colon, nerr0
    logical :: ok, ok1, ok2
    character(len=:), allocatable :: w

    nerr0 = s%nerr
    c%line = st%line
    if (st%npair > 0) call report(s, st%line, 'unexpected ' // quoted(st%key(1)%s // '=' // st%value(1)%s) // &
                                  ' (expected ' // usage // ')')
    if (st%nword == 0) then
      call report(s, st%line, 'missing curve name (expected ' // usage // ')')
      return
    end if
    call check_name(s, st, st%word(1)%s, 'curve', ok)
    if (.not. ok) return
    c%name = st%word(1)%s
    do k = 1, size(deck%curves)
      if (deck%curves(k)%name == c%name .and. len(deck%curves(k)%name) == len(c%name)) then
        call report(s, st%line, 'second CURVE ' // quoted(c%name) // ' (first at line ' // &
                    int_to_str(deck%curves(k)%line) // '; expected unique curve names)')
        return
      end if
    end do
    if (st%nword == 1) then
      call report(s, st%line, 'curve ' // quoted(c%name) // ' has no points (expected ' // usage // ')')
      return
    end if
    allocate(c%t(st%nword - 1), c%v(st%nword - 1))
    do k = 2, st%nword
      w = st%word(k)%s
      colon = index(w, ':')
      ok1 = .false.
      ok2 = .false.
      if (colon > 1 .and. colon < len(w)) then
        call parse_real(w(1:colon - 1), c%t(k - 1), ok1)
        call parse_real(w(colon + 1:), c%v(k - 1), ok2)
      end if
      if (.not. (ok1 .and. ok2)) then
        call report(s, st%line, 'bad curve point ' // quoted(cut(w)) // ' (expected t:v, two numbers: the step ' // &
                    'and the load factor)')
        return
      end if
      if (k > 2) then
        if (.not. c%t(k - 1) > c%t(k - 2)) then
          call report(s, st%line, 'curve ' // quoted(c%name) // ': step ' // quoted(w(1:colon - 1)) // &
                      ' not after the previous point''s (expected increasing steps t0 < t1 < ...)')
          return
        end if
      end if
    end do
    if (s%nerr /= nerr0) return
    allocate(grown(size(deck%curves) + 1))
    grown(1:size(deck%curves)) = deck%curves
    grown(size(grown)) = c
    call move_alloc(grown, deck%curves)
  end subroutine do_curve

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

  !> OUTPUT [vtk=] [contact=] [summary=]
  subroutine do_output(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'OUTPUT [vtk=NAME] [contact=NAME] [summary=NAME] [fields=LIST] ' // &
                                           '[steps=last|all]'
    character(len=16), parameter :: field_names(5) = [character(len=16) :: 'displacement', 'contact_pressure', &
                                                      'gap', 'stress', 'von_mises']
    logical :: seen(5)
    type(text_t) :: val(5)
    integer :: k, p, q, f
    character(len=:), allocatable :: item

    deck%output%line = st%line
    call check_extra_words(s, st, 0, usage)
    call match_keys(s, st, st%names, st%forms, 'OUTPUT', seen, val)
    if (allocated(val(5)%s)) then
      select case (lower(val(5)%s))
      case ('last')
        deck%output%steps_all = .false.
      case ('all')
        deck%output%steps_all = .true.
      case default
        call report(s, st%line, 'bad value ' // quoted(cut(val(5)%s)) // ' for steps= (expected steps=last or ' // &
                    'steps=all)')
      end select
    end if
    if (allocated(val(4)%s)) then
      ! fields=a,b,c (or all, or none): the arrays of the VTK file
      deck%output%fields = .false.
      p = 1
      do while (p <= len(val(4)%s) + 1)
        q = index(val(4)%s(p:), ',')
        if (q == 0) then
          q = len(val(4)%s) + 1
        else
          q = p + q - 1
        end if
        item = lower(val(4)%s(p:q - 1))
        f = find_key(item, field_names)
        if (item == 'all') then
          deck%output%fields = .true.
        else if (item == 'none') then
          continue
        else if (f == 0) then
          call report(s, st%line, 'unknown field ' // quoted(cut(item)) // ' in fields= (expected a comma-separated ' // &
                      'list of ' // join_list(field_names, ', ') // ', or all, or none)')
          exit
        else
          deck%output%fields(f) = .true.
        end if
        p = q + 1
      end do
    end if
    do k = 1, 3
      if (.not. allocated(val(k)%s)) cycle
      if (.not. is_name(val(k)%s) .or. val(k)%s == '.' .or. val(k)%s == '..') then
        call report(s, st%line, 'bad file name ' // trim(st%names(k)) // '=' // cut(val(k)%s) // ' (expected a ' // &
                    'name in the output folder: letters, digits, _ . - only, no /)')
        cycle
      end if
      select case (k)
      case (1)
        deck%output%vtk = val(k)%s
        if (.not. ends_with_ci(val(k)%s, '.vtk')) deck%output%vtk = val(k)%s // '.vtk'
      case (2)
        deck%output%contact = val(k)%s
      case (3)
        deck%output%summary = val(k)%s
      end select
    end do
  end subroutine do_output

  ! ================================================================ whole-deck checks

  !> Checks that need the whole deck: open block, bodies complete, rect boundary
  !> names, plane-strain compliance, CONTACT bodies, rigid-body modes, ramps within
  !> STEPS, lcp=pdas without friction, output names.
  subroutine finish_checks(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    integer :: b, i
    logical :: resolved

    if (s%block /= '' .and. .not. s%end_hinted) &
      call report(s, s%nline, 'missing END for ' // trim(s%block) // ' ' // quoted(s%block_name) // &
                  ' opened at line ' // int_to_str(s%block_line) // &
                  ' (expected END before the end of the file)', echo=.false.)
    if (s%nbody == 0) then
      call report(s, 0, 'deck has no BODY (at least one BODY ... END block expected)')
      return
    end if

    do b = 1, s%nbody
      associate (body => deck%bodies(b))
        if (.not. is_name(body%name)) cycle
        if (body%mesh%line == 0) call report(s, body%line, 'body ' // quoted(body%name) // &
                                             ' has no MESH (expected a MESH statement in its BODY block)')
        if (body%material%line == 0) call report(s, body%line, 'body ' // quoted(body%name) // &
                                                 ' has no MATERIAL (expected a MATERIAL statement in its BODY block)')
        if (.not. deck%plane_stress .and. allocated(body%material%kind)) then
          if (body%material%kind == 'orthotropic') then
            if (plane_compliance_ok(body%material) .and. .not. strain_compliance_ok(body%material)) &
              call report(s, body%material%line, 'orthotropic compliance not positive definite for PLANE ' // &
                          'strain (expected 1 - nu12^2 E2/E1 - nu23^2 E3/E2 - nu13^2 E3/E1 - ' // &
                          '2 nu12 nu23 nu13 E3/E1 > 0)')
          end if
        end if
        if (allocated(body%mesh%kind)) then
          if (body%mesh%kind == 'rect') then
            do i = 1, size(body%fixes)
              call check_rect_boundary(s, body, body%fixes(i)%boundary, body%fixes(i)%line)
            end do
            do i = 1, size(body%loads)
              call check_rect_boundary(s, body, body%loads(i)%boundary, body%loads(i)%line)
            end do
          end if
        end if
      end associate
    end do

    call resolve_contacts(s, deck, resolved)
    if (resolved .and. .not. s%contact_bad) call check_rigid_modes(s, deck)
    call check_ramps(s, deck)
    call resolve_curves(s, deck)
    call check_rigids(s, deck)
    call check_friction_solver(s, deck)
    call check_output_names(s, deck)
    if (deck%axisymmetric) call check_axisymmetric(s, deck)
  end subroutine finish_checks

  !> What PLANE axisymmetric cannot take: gravity off the axis (a load that
  !> depends on the angle theta, not a solid of revolution's).  The bodies'
  !> r >= 0 is checked with their meshes (scene).
  subroutine check_axisymmetric(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    if (deck%gravity_line > 0 .and. deck%gx /= 0.0_dp) &
      call report(s, deck%gravity_line, 'GRAVITY gx= ' // trim(format_number(deck%gx)) // ' across the axis in ' // &
                  'PLANE axisymmetric (line ' // int_to_str(deck%plane_line) // ') (gravity along the axis z ' // &
                  'expected: gx=0, gy=...)')
  end subroutine check_axisymmetric

  !> Every ramp=k0:k1 given ends at step STEPS at the latest (k0 < k1 and k0 >= 0
  !> were checked with the statement).  Nothing is said when STEPS itself was bad.
  subroutine check_ramps(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer :: b, i

    if (s%steps_bad) return
    do b = 1, s%nbody
      associate (body => deck%bodies(b))
        do i = 1, size(body%fixes)
          call check_ramp_end(s, deck, body%fixes(i)%ramp, body%fixes(i)%line)
        end do
        do i = 1, size(body%loads)
          call check_ramp_end(s, deck, body%loads(i)%ramp, body%loads(i)%line)
        end do
        if (body%bodyforce_line > 0) call check_ramp_end(s, deck, body%bodyforce_ramp, body%bodyforce_line)
      end associate
    end do
    if (deck%gravity_line > 0) call check_ramp_end(s, deck, deck%gravity_ramp, deck%gravity_line)
  end subroutine check_ramps

  !> Every curve=NAME names a CURVE of the deck (index into deck%curves).
  subroutine resolve_curves(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    integer :: b, i
    do b = 1, s%nbody
      associate (body => deck%bodies(b))
        do i = 1, size(body%fixes)
          call resolve(body%fixes(i)%curve_name, body%fixes(i)%line, body%fixes(i)%curve)
        end do
        do i = 1, size(body%loads)
          call resolve(body%loads(i)%curve_name, body%loads(i)%line, body%loads(i)%curve)
        end do
        do i = 1, size(body%thermals)
          call resolve(body%thermals(i)%curve_name, body%thermals(i)%line, body%thermals(i)%curve)
        end do
        call resolve(body%bodyforce_curve_name, body%bodyforce_line, body%bodyforce_curve)
      end associate
    end do
    call resolve(deck%gravity_curve_name, deck%gravity_line, deck%gravity_curve)
  contains
    subroutine resolve(name, line, curve)
      character(len=:), allocatable, intent(in) :: name
      integer, intent(in) :: line
      integer, intent(out) :: curve
      character(len=:), allocatable :: known
      integer :: c
      curve = 0
      if (.not. allocated(name)) return
      if (len(name) == 0) return
      do c = 1, size(deck%curves)
        if (deck%curves(c)%name == name .and. len(deck%curves(c)%name) == len(name)) then
          curve = c
          return
        end if
      end do
      known = ''
      do c = 1, size(deck%curves)
        if (c > 1) known = known // ', '
        known = known // deck%curves(c)%name
      end do
      if (size(deck%curves) == 0) then
        known = 'a CURVE statement of that name; the deck has none'
      else
        known = 'one of ' // known
      end if
      call report(s, line, 'unknown curve ' // quoted(name) // ' (expected ' // known // ')')
    end subroutine resolve
  end subroutine resolve_curves

  !> Report ramp(2) > STEPS at the line of the statement holding the ramp.
  subroutine check_ramp_end(s, deck, ramp, line)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: ramp(2), line
    character(len=:), allocatable :: text

    if (ramp(2) <= deck%steps) return
    text = 'ramp=' // int_to_str(ramp(1)) // ':' // int_to_str(ramp(2)) // ' ends after the last load step'
    if (deck%steps_line > 0) then
      call report(s, line, text // ' (expected k1 <= ' // int_to_str(deck%steps) // ', the STEPS value at line ' // &
                  int_to_str(deck%steps_line) // ')')
    else
      call report(s, line, text // ' (expected k1 <= 1, as STEPS defaults to 1 when absent)')
    end if
  end subroutine check_ramp_end

  !> lcp=pdas solves the frictionless LCP only: refuse it when some CONTACT has a
  !> friction bound that is not identically zero (mu=0 and tresca=0 are frictionless).
  subroutine check_friction_solver(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer :: i

    if (.not. allocated(deck%solver%lcp)) return
    if (deck%solver%lcp /= 'pdas') return
    do i = 1, s%ncontact
      if (deck%contacts(i)%mu > 0 .or. deck%contacts(i)%tresca > 0) then
        call report(s, deck%solver%line, 'lcp=pdas solves frictionless contact only (expected lcp=auto, ' // &
                    'lemke or pgs with friction)')
        return
      end if
    end do
  end subroutine check_friction_solver

  !> A rect mesh names its boundaries left, right, bottom, top.
  subroutine check_rect_boundary(s, body, name, line)
    type(state_t), intent(inout) :: s
    type(body_deck_t), intent(in) :: body
    character(len=*), intent(in) :: name
    integer, intent(in) :: line
    if (len(name) == 0) return
    select case (name)
    case ('left', 'right', 'bottom', 'top')
    case default
      call report(s, line, 'unknown boundary ' // quoted(name) // ' of BODY ' // quoted(body%name) // &
                  ' (expected one of left, right, bottom, top for MESH rect)')
    end select
  end subroutine check_rect_boundary

  !> Body indices of the CONTACT statements; duplicates; rect boundary names.
  subroutine resolve_contacts(s, deck, resolved)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    logical, intent(out) :: resolved
    integer :: i, j, b
    character(len=:), allocatable :: known

    resolved = .true.
    known = ''
    do b = 1, s%nbody
      if (.not. is_name(deck%bodies(b)%name)) cycle
      if (len(known) > 0) known = known // ', '
      known = known // deck%bodies(b)%name
    end do
    if (len(known) > 200) known = known(1:200) // ' ...'
    do i = 1, s%ncontact
      associate (c => deck%contacts(i))
        c%slave_body = find_body(deck, s%nbody, s%slave_name(i)%s)
        if (len(c%master_boundary) == 0) then         ! master=RIGIDNAME
          do j = 1, size(deck%rigids)
            if (deck%rigids(j)%name == s%master_name(i)%s .and. &
                len(deck%rigids(j)%name) == len(s%master_name(i)%s)) c%master_rigid = j
          end do
          if (c%master_rigid == 0) call report(s, c%line, 'unknown RIGID ' // quoted(s%master_name(i)%s) // &
            ' in CONTACT master= (expected master=body:boundary or the name of a RIGID block)')
          if (c%slave_body == 0) call report(s, c%line, 'unknown body ' // quoted(s%slave_name(i)%s) // &
                                             ' in CONTACT (expected one of ' // known // ')')
          if (c%slave_body == 0 .or. c%master_rigid == 0) then
            resolved = .false.
          else
            call check_contact_side(s, deck%bodies(c%slave_body), c%slave_boundary, c%line)
            do j = 1, i - 1
              if (deck%contacts(j)%master_rigid == c%master_rigid .and. deck%contacts(j)%slave_body == c%slave_body &
                  .and. deck%contacts(j)%slave_boundary == c%slave_boundary) &
                call report(s, c%line, 'duplicate CONTACT (same slave boundary and RIGID as at line ' // &
                            int_to_str(deck%contacts(j)%line) // '; expected each pair once)')
            end do
          end if
          cycle
        end if
        c%master_body = find_body(deck, s%nbody, s%master_name(i)%s)
        if (c%slave_body == 0) call report(s, c%line, 'unknown body ' // quoted(s%slave_name(i)%s) // &
                                           ' in CONTACT (expected one of ' // known // ')')
        if (c%master_body == 0 .and. s%master_name(i)%s /= s%slave_name(i)%s) &
          call report(s, c%line, 'unknown body ' // quoted(s%master_name(i)%s) // ' in CONTACT (expected one of ' // &
                      known // ')')
        if (c%slave_body == 0 .or. c%master_body == 0) then
          resolved = .false.
          cycle
        end if
        call check_contact_side(s, deck%bodies(c%slave_body), c%slave_boundary, c%line)
        call check_contact_side(s, deck%bodies(c%master_body), c%master_boundary, c%line)
        do j = 1, i - 1
          if (same_pair(c, deck%contacts(j))) then
            call report(s, c%line, 'duplicate CONTACT (same two boundaries as at line ' // &
                        int_to_str(deck%contacts(j)%line) // '; expected each pair once)')
            exit
          end if
        end do
      end associate
    end do
  end subroutine resolve_contacts

  subroutine check_contact_side(s, body, boundary, line)
    type(state_t), intent(inout) :: s
    type(body_deck_t), intent(in) :: body
    character(len=*), intent(in) :: boundary
    integer, intent(in) :: line
    if (.not. allocated(body%mesh%kind)) return
    if (body%mesh%kind == 'rect') call check_rect_boundary(s, body, boundary, line)
  end subroutine check_contact_side

  !> Two CONTACTs join the same two boundaries (in either role).
  pure logical function same_pair(a, b)
    type(contact_deck_t), intent(in) :: a, b
    same_pair = .false.
    if (a%master_rigid > 0 .or. b%master_rigid > 0) return
    same_pair = (a%slave_body == b%slave_body .and. a%slave_boundary == b%slave_boundary .and. &
                 a%master_body == b%master_body .and. a%master_boundary == b%master_boundary) .or. &
                (a%slave_body == b%master_body .and. a%slave_boundary == b%master_boundary .and. &
                 a%master_body == b%slave_body .and. a%master_boundary == b%slave_boundary)
  end function same_pair

  pure integer function find_body(deck, nbody, name) result(b)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: nbody
    character(len=*), intent(in) :: name
    do b = 1, nbody
      if (deck%bodies(b)%name == name .and. len(deck%bodies(b)%name) == len(name)) return
    end do
    b = 0
  end function find_body

  !> Every body must be held: a FIX of its own, or a CONTACT chain to a body with a
  !> FIX.  A body with neither FIX nor CONTACT, and a group of bodies joined by
  !> CONTACT none of which has a FIX, has rigid-body modes.
  subroutine check_rigid_modes(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    integer, allocatable :: group(:)
    logical, allocatable :: in_contact(:), on_rigid(:)
    integer :: b, i, g, a, c, nmem
    logical :: held, changed
    character(len=:), allocatable :: members

    allocate(group(s%nbody), in_contact(s%nbody))
    in_contact = .false.
    do b = 1, s%nbody
      group(b) = b
    end do
    allocate(on_rigid(s%nbody), source=.false.)
    do i = 1, s%ncontact
      in_contact(deck%contacts(i)%slave_body) = .true.
      if (deck%contacts(i)%master_rigid > 0) then
        on_rigid(deck%contacts(i)%slave_body) = .true.   ! a RIGID holds what touches it (checked when solved)
        cycle
      end if
      in_contact(deck%contacts(i)%master_body) = .true.
    end do
    changed = .true.                          ! label propagation: group = smallest member
    do while (changed)
      changed = .false.
      do i = 1, s%ncontact
        if (deck%contacts(i)%master_rigid > 0) cycle
        a = deck%contacts(i)%slave_body
        c = deck%contacts(i)%master_body
        if (group(a) /= group(c)) then
          group(a) = min(group(a), group(c))
          group(c) = group(a)
          changed = .true.
        end if
      end do
    end do
    do b = 1, s%nbody
      if (.not. is_name(deck%bodies(b)%name)) cycle
      if (size(deck%bodies(b)%fixes) > 0) cycle
      if (.not. in_contact(b)) then
        call report(s, deck%bodies(b)%line, 'body ' // quoted(deck%bodies(b)%name) // ' has no FIX and is in no ' // &
                    'CONTACT (rigid-body modes: expected FIX on a boundary, or a CONTACT that holds the body)')
        cycle
      end if
      g = group(b)
      if (g /= b) cycle                      ! report each group once, at its first body
      held = .false.
      members = ''
      nmem = 0
      do a = 1, s%nbody
        if (group(a) /= g) cycle
        if (size(deck%bodies(a)%fixes) > 0 .or. on_rigid(a)) held = .true.
        nmem = nmem + 1
        if (nmem > 1) members = members // ', '
        members = members // quoted(deck%bodies(a)%name)
      end do
      if (.not. held) call report(s, deck%bodies(b)%line, 'no FIX on any of the bodies ' // members // &
                                  ' held together by CONTACT (rigid-body modes: expected FIX on a boundary ' // &
                                  'of at least one of them)')
    end do
  end subroutine check_rigid_modes

  !> The three output files must have different names.
  subroutine check_output_names(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    character(len=:), allocatable :: v, c, m
    integer :: line
    call fill_defaults(deck)
    v = deck%output%vtk
    c = deck%output%contact
    m = deck%output%summary
    line = deck%output%line
    if (v == c .and. len(v) == len(c)) then
      call report(s, line, 'OUTPUT files must differ (vtk and contact are both ' // quoted(v) // ')')
    else if (v == m .and. len(v) == len(m)) then
      call report(s, line, 'OUTPUT files must differ (vtk and summary are both ' // quoted(v) // ')')
    else if (c == m .and. len(c) == len(m)) then
      call report(s, line, 'OUTPUT files must differ (contact and summary are both ' // quoted(c) // ')')
    else if (deck%output%steps_all) then
      ! steps=all adds STEM.pvd and STEM_steps.csv (STEM: the vtk name without .vtk)
      v = v(1:len(v) - 4)
      if (c == v // '.pvd' .or. m == v // '.pvd' .or. c == v // '_steps.csv' .or. m == v // '_steps.csv') &
        call report(s, line, 'OUTPUT files must differ (steps=all writes ' // quoted(v // '.pvd') // ' and ' // &
                    quoted(v // '_steps.csv') // ', which contact= or summary= names too)')
    end if
    ! each is written as NAME.part first, then renamed: 5 bytes kept for that
    if (len(path_too_long(v, 5)) > 0) call report(s, line, 'OUTPUT vtk: ' // path_too_long(v, 5))
    if (len(path_too_long(c, 5)) > 0) call report(s, line, 'OUTPUT contact: ' // path_too_long(c, 5))
    if (len(path_too_long(m, 5)) > 0) call report(s, line, 'OUTPUT summary: ' // path_too_long(m, 5))
  end subroutine check_output_names

  !> '' when the system can take path as a file name, else what is wrong: a
  !> component longer than NAME_MAX (255 bytes) or a path longer than PATH_MAX
  !> (4096), which open() refuses with ENAMETOOLONG whatever the folder.
  !>   path    (in) the name, as it will be opened
  !>   reserve (in) bytes the program adds to the last name (a temporary suffix)
  function path_too_long(path, reserve) result(msg)
    character(len=*), intent(in) :: path
    integer, intent(in) :: reserve
    character(len=:), allocatable :: msg
    integer, parameter :: name_max = 255, path_max = 4096
    integer :: i, first, limit
    msg = ''
    if (len(path) + reserve >= path_max) then
      msg = 'the path is ' // int_to_str(len(path)) // ' characters long (fewer than ' // &
            int_to_str(path_max - reserve) // ' expected: PATH_MAX)'
      return
    end if
    first = 1
    do i = 1, len(path) + 1
      if (i <= len(path)) then
        if (path(i:i) /= '/') cycle
      end if
      limit = name_max - merge(reserve, 0, i > len(path))
      if (i - first > limit) then
        msg = 'the name "' // path(first:first + 19) // '..." is ' // int_to_str(i - first) // &
              ' characters long (at most ' // int_to_str(limit) // ' expected: NAME_MAX'
        if (limit < name_max) msg = msg // ' is 255, less ' // int_to_str(reserve) // ' for the temporary suffix .part'
        msg = msg // ')'
        return
      end if
      first = i + 1
    end do
  end function path_too_long

  !> Cut each body's FIX and load lists, grown by doubling while reading, to the
  !> statements they hold: from here on size() is the count.
  subroutine cut_statement_lists(s, deck)
    type(state_t), intent(in) :: s
    type(deck_t), intent(inout) :: deck
    integer :: b
    type(fix_t), allocatable :: fixes(:)
    type(load_t), allocatable :: loads(:)

    if (.not. allocated(deck%bodies)) return
    do b = 1, min(s%nbody, size(deck%bodies))
      associate (body => deck%bodies(b))
        if (allocated(body%fixes)) then
          if (size(body%fixes) /= body%nfix) then
            fixes = body%fixes(1:body%nfix)
            call move_alloc(fixes, body%fixes)
          end if
        end if
        if (allocated(body%loads)) then
          if (size(body%loads) /= body%nload) then
            loads = body%loads(1:body%nload)
            call move_alloc(loads, body%loads)
          end if
        end if
      end associate
    end do
  end subroutine cut_statement_lists

  !> Allocate every character component left unset; resolve the ramps not given
  !> (or not valid) to [0, steps].
  subroutine fill_defaults(deck)
    type(deck_t), intent(inout) :: deck
    integer :: b, i
    if (.not. allocated(deck%title)) deck%title = ''
    if (.not. allocated(deck%solver%lcp)) deck%solver%lcp = 'auto'
    if (.not. allocated(deck%solver%ordering)) deck%solver%ordering = 'auto'
    if (.not. allocated(deck%solver%condense)) deck%solver%condense = 'auto'
    if (.not. allocated(deck%solver%cut)) deck%solver%cut = 'auto'
    if (.not. allocated(deck%output%vtk)) deck%output%vtk = deck%name // '.vtk'
    if (.not. allocated(deck%output%contact)) deck%output%contact = deck%name // '_contact.csv'
    if (.not. allocated(deck%output%summary)) deck%output%summary = deck%name // '.summary'
    do b = 1, size(deck%bodies)
      associate (body => deck%bodies(b), m => deck%bodies(b)%mesh)
        if (.not. allocated(body%name)) body%name = ''
        if (.not. allocated(m%kind)) m%kind = ''
        if (.not. allocated(m%elem)) m%elem = ''
        if (.not. allocated(m%diag)) m%diag = ''
        if (.not. allocated(m%file)) m%file = ''
        if (.not. allocated(m%path)) m%path = ''
        if (.not. allocated(m%set_names)) allocate(m%set_names(0))
        if (.not. allocated(m%set_values)) allocate(m%set_values(0))
        if (.not. allocated(body%material%kind)) body%material%kind = ''
        if (.not. allocated(body%fixes)) allocate(body%fixes(0))
        if (.not. allocated(body%loads)) allocate(body%loads(0))
        if (.not. allocated(body%thermals)) allocate(body%thermals(0))
        do i = 1, size(body%fixes)
          if (.not. allocated(body%fixes(i)%boundary)) body%fixes(i)%boundary = ''
          if (body%fixes(i)%ramp(2) == ramp_unset(2)) body%fixes(i)%ramp = [0, deck%steps]
        end do
        do i = 1, size(body%loads)
          if (body%loads(i)%ramp(2) == ramp_unset(2)) body%loads(i)%ramp = [0, deck%steps]
        end do
        if (body%bodyforce_line == 0 .or. body%bodyforce_ramp(2) == ramp_unset(2)) &
          body%bodyforce_ramp = [0, deck%steps]
      end associate
    end do
    if (deck%gravity_line == 0 .or. deck%gravity_ramp(2) == ramp_unset(2)) deck%gravity_ramp = [0, deck%steps]
    do i = 1, size(deck%rigids)
      associate (rg => deck%rigids(i))
        if (.not. allocated(rg%name)) rg%name = ''
        if (.not. allocated(rg%shape)) rg%shape = ''
        if (.not. allocated(rg%points)) allocate(rg%points(2, 0))
        if (.not. allocated(rg%fixes)) allocate(rg%fixes(0))
        if (.not. allocated(rg%forces)) allocate(rg%forces(0))
        do b = 1, size(rg%fixes)
          if (rg%fixes(b)%ramp(2) == ramp_unset(2)) rg%fixes(b)%ramp = [0, deck%steps]
        end do
        do b = 1, size(rg%forces)
          if (rg%forces(b)%ramp(2) == ramp_unset(2)) rg%forces(b)%ramp = [0, deck%steps]
        end do
      end associate
    end do
    do i = 1, size(deck%contacts)
      if (.not. allocated(deck%contacts(i)%slave_boundary)) deck%contacts(i)%slave_boundary = ''
      if (.not. allocated(deck%contacts(i)%master_boundary)) deck%contacts(i)%master_boundary = ''
      if (.not. allocated(deck%contacts(i)%friction)) deck%contacts(i)%friction = 'none'
    end do
  end subroutine fill_defaults

  ! ================================================================ RIGID blocks

  !> RIGID name: opens a rigid obstacle's block (SHAPE, REF, FIX, FORCE, END).
  subroutine do_rigid(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'RIGID name'
    type(rigid_deck_t), allocatable :: grown(:)
    integer :: r, nr
    logical :: ok

    nr = size(deck%rigids)
    allocate(grown(nr + 1))
    do r = 1, nr
      grown(r) = deck%rigids(r)
    end do
    call move_alloc(grown, deck%rigids)
    s%block_line = st%line
    s%block_name = ''
    if (st%nword > 0) s%block_name = st%word(1)%s
    associate (rg => deck%rigids(nr + 1))
      rg%line = st%line
      rg%name = ''
      rg%shape = ''
      allocate(rg%points(2, 0), rg%fixes(0), rg%forces(0))
      if (st%nword == 0) then
        call report(s, st%line, 'missing rigid obstacle name (expected ' // usage // ')')
      else
        call check_name(s, st, st%word(1)%s, 'rigid obstacle', ok)
        if (ok) rg%name = st%word(1)%s
        call check_extra_words(s, st, 1, usage)
        do r = 1, nr
          if (ok .and. deck%rigids(r)%name == rg%name .and. len(deck%rigids(r)%name) == len(rg%name)) &
            call report(s, st%line, 'duplicate RIGID name ' // quoted(rg%name) // ' (first at line ' // &
                        int_to_str(deck%rigids(r)%line) // '; expected a new name)')
        end do
      end if
      if (st%npair > 0) call report(s, st%line, 'unexpected ' // quoted(st%key(1)%s // '=' // st%value(1)%s) // &
                                    ' (expected ' // usage // ')')
    end associate
  end subroutine do_rigid

  !> The statements of the open RIGID block (the last RIGID read).
  subroutine rigid_shape_row(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    call do_rigid_shape(s, deck%rigids(size(deck%rigids)), st)
  end subroutine rigid_shape_row

  subroutine rigid_ref_row(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    call do_rigid_ref(s, deck%rigids(size(deck%rigids)), st)
  end subroutine rigid_ref_row

  subroutine rigid_fix_row(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    call do_rigid_load(s, deck%rigids(size(deck%rigids)), st, .true.)
  end subroutine rigid_fix_row

  subroutine rigid_force_row(s, deck, st)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    type(stmt_t), intent(in) :: st
    call do_rigid_load(s, deck%rigids(size(deck%rigids)), st, .false.)
  end subroutine rigid_force_row

  !> SHAPE line x0= y0= x1= y1= | circle xc= yc= r= [solid=inside|outside] | polyline points=x1:y1,x2:y2,...
  subroutine do_rigid_shape(s, rg, st)
    type(state_t), intent(inout) :: s
    type(rigid_deck_t), intent(inout) :: rg
    type(stmt_t), intent(in) :: st
    character(len=*), parameter :: usage = 'SHAPE line x0= y0= x1= y1= | SHAPE circle xc= yc= r= ' // &
                                           '[solid=inside|outside] | SHAPE polyline points=x1:y1,x2:y2,...'
    character(len=6), parameter :: names(9) = [character(len=6) :: 'x0', 'y0', 'x1', 'y1', 'xc', 'yc', 'r', &
                                               'solid', 'points']
    character(len=15), parameter :: forms(9) = [character(len=15) :: 'number', 'number', 'number', 'number', &
                                                'number', 'number', 'number', 'inside|outside', 'x1:y1,x2:y2,...']
    logical :: seen(9), ok, allowed(9)
    type(text_t) :: val(9)
    character(len=:), allocatable :: kind
    integer :: k

    if (rg%shape_line > 0) then
      call report(s, st%line, 'second SHAPE in RIGID ' // quoted(rg%name) // ' (first at line ' // &
                  int_to_str(rg%shape_line) // '; expected one SHAPE per RIGID)')
      return
    end if
    rg%shape_line = st%line
    if (st%nword == 0) then
      call report(s, st%line, 'missing shape kind (expected ' // usage // ')')
      return
    end if
    call check_extra_words(s, st, 1, usage)
    kind = lower(st%word(1)%s)
    call match_keys(s, st, names, forms, 'SHAPE', seen, val)
    allowed = .false.
    select case (kind)
    case ('line')
      allowed(1:4) = .true.
      do k = 1, 4
        call require_key(s, st, seen(k), trim(names(k)), 'SHAPE line', 'SHAPE line x0= y0= x1= y1=')
      end do
      rg%points = reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2])
      call get_real(s, st, val(1), 'x0', rg%points(1, 1), ok)
      call get_real(s, st, val(2), 'y0', rg%points(2, 1), ok)
      call get_real(s, st, val(3), 'x1', rg%points(1, 2), ok)
      call get_real(s, st, val(4), 'y1', rg%points(2, 2), ok)
      if (all(rg%points(:, 1) == rg%points(:, 2)) .and. all(seen(1:4))) &
        call report(s, st%line, 'SHAPE line of zero length (expected two different end points)')
    case ('circle')
      allowed(5:8) = .true.
      do k = 5, 7
        call require_key(s, st, seen(k), trim(names(k)), 'SHAPE circle', 'SHAPE circle xc= yc= r=')
      end do
      call get_real(s, st, val(5), 'xc', rg%centre(1), ok)
      call get_real(s, st, val(6), 'yc', rg%centre(2), ok)
      call get_real(s, st, val(7), 'r', rg%radius, ok, positive=.true.)
      if (allocated(val(8)%s)) rg%outside = get_choice(s, st, val(8), 'solid', ['inside ', 'outside']) == 'outside'
    case ('polyline')
      allowed(9) = .true.
      call require_key(s, st, seen(9), 'points', 'SHAPE polyline', 'SHAPE polyline points=x1:y1,x2:y2,...')
      if (allocated(val(9)%s)) call get_points(val(9)%s)
    case default
      call report(s, st%line, 'unknown shape ' // quoted(st%word(1)%s) // ' (expected line, circle or polyline)')
      return
    end select
    rg%shape = kind
    do k = 1, 9
      if (seen(k) .and. .not. allowed(k)) call report(s, st%line, 'key ' // quoted(trim(names(k))) // &
        ' does not belong to SHAPE ' // kind // ' (expected ' // usage // ')')
    end do
  contains
    !> points=x1:y1,x2:y2,...: at least two points, consecutive ones different.
    subroutine get_points(text)
      character(len=*), intent(in) :: text
      integer :: p, q, colon, n, j
      real(dp) :: x, y
      logical :: okx, oky
      real(dp), allocatable :: pts(:,:)
      allocate(pts(2, 0))
      p = 1
      n = 0
      do while (p <= len(text))
        q = index(text(p:), ',')
        if (q == 0) then
          q = len(text) + 1
        else
          q = p + q - 1
        end if
        colon = index(text(p:q - 1), ':')
        okx = .false.
        oky = .false.
        if (colon > 1) then
          call parse_real(text(p:p + colon - 2), x, okx)
          call parse_real(text(p + colon:q - 1), y, oky)
        end if
        if (.not. (okx .and. oky)) then
          call report(s, st%line, 'bad point ' // quoted(text(p:q - 1)) // ' in points= (expected x:y with ' // &
                      'two finite numbers, points separated by commas)')
          return
        end if
        n = n + 1
        pts = reshape([pts, x, y], [2, n])
        p = q + 1
      end do
      if (n < 2) then
        call report(s, st%line, 'SHAPE polyline with ' // int_to_str(n) // ' point (expected at least two points)')
        return
      end if
      do j = 1, n - 1
        if (all(pts(:, j) == pts(:, j + 1))) then
          call report(s, st%line, 'SHAPE polyline repeats point ' // int_to_str(j) // ' (expected consecutive ' // &
                      'points to differ)')
          return
        end if
      end do
      rg%points = pts
    end subroutine get_points
  end subroutine do_rigid_shape

  !> REF x= y=: the reference point (default: the circle's centre, the first point)
  subroutine do_rigid_ref(s, rg, st)
    type(state_t), intent(inout) :: s
    type(rigid_deck_t), intent(inout) :: rg
    type(stmt_t), intent(in) :: st
    logical :: seen(2), ok
    type(text_t) :: val(2)
    if (rg%ref_line > 0) then
      call report(s, st%line, 'second REF in RIGID ' // quoted(rg%name) // ' (expected one REF per RIGID)')
      return
    end if
    rg%ref_line = st%line
    call check_extra_words(s, st, 0, 'REF x=number y=number')
    call match_keys(s, st, ['x', 'y'], ['number', 'number'], 'REF', seen, val)
    call require_key(s, st, seen(1), 'x', 'REF', 'REF x=number y=number')
    call require_key(s, st, seen(2), 'y', 'REF', 'REF x=number y=number')
    call get_real(s, st, val(1), 'x', rg%ref(1), ok)
    call get_real(s, st, val(2), 'y', rg%ref(2), ok)
    rg%has_ref = .true.
  end subroutine do_rigid_ref

  !> FIX [ux=] [uy=] [rz=] [ramp=|curve=] (none given: all three 0) or
  !> FORCE [fx=] [fy=] [m=] [ramp=|curve=] (at least one) of a RIGID; each
  !> direction in one FIX or one FORCE at most.
  subroutine do_rigid_load(s, rg, st, is_fix)
    type(state_t), intent(inout) :: s
    type(rigid_deck_t), intent(inout) :: rg
    type(stmt_t), intent(in) :: st
    logical, intent(in) :: is_fix
    character(len=5) :: names(5)
    character(len=:), allocatable :: what, usage
    logical :: seen(5), ok
    type(text_t) :: val(5)
    integer :: k, j
    type(rigid_load_t) :: ld

    if (is_fix) then
      names = [character(len=5) :: 'ux', 'uy', 'rz', 'ramp', 'curve']
      what = 'FIX'
      usage = 'FIX [ux=number] [uy=number] [rz=radians] [ramp=k0:k1|curve=NAME]'
    else
      names = [character(len=5) :: 'fx', 'fy', 'm', 'ramp', 'curve']
      what = 'FORCE'
      usage = 'FORCE [fx=number] [fy=number] [m=number] [ramp=k0:k1|curve=NAME]'
    end if
    call check_extra_words(s, st, 0, usage)
    call match_keys(s, st, names, [character(len=6) :: 'number', 'number', 'number', 'k0:k1', 'NAME'], what, seen, val)
    do k = 1, 3
      call get_real(s, st, val(k), trim(names(k)), ld%value(k), ok)
    end do
    call get_ramp(s, st, val(4), ld%ramp)
    call get_curve_name(s, st, val(5), val(4), ld%curve_name)
    ld%line = st%line
    ld%has = seen(1:3)
    if (is_fix .and. .not. any(seen(1:3))) ld%has = .true.        ! FIX alone: held fixed
    if (.not. is_fix .and. .not. any(seen(1:3))) call report(s, st%line, 'FORCE without a component (expected ' // &
                                                             usage // ')')
    ! a direction is prescribed by one FIX or loaded by one FORCE
    do j = 1, size(rg%fixes)
      if (any(ld%has .and. rg%fixes(j)%has)) call report(s, st%line, what // ' names a direction that the FIX at ' // &
        'line ' // int_to_str(rg%fixes(j)%line) // ' prescribes (expected each of ux/fx, uy/fy, rz/m in one ' // &
        'FIX or FORCE of the RIGID)')
    end do
    do j = 1, size(rg%forces)
      if (any(ld%has .and. rg%forces(j)%has)) call report(s, st%line, what // ' names a direction that the FORCE ' // &
        'at line ' // int_to_str(rg%forces(j)%line) // ' loads (expected each of ux/fx, uy/fy, rz/m in one ' // &
        'FIX or FORCE of the RIGID)')
    end do
    if (is_fix) then
      rg%fixes = [rg%fixes, ld]
    else
      rg%forces = [rg%forces, ld]
    end if
  end subroutine do_rigid_load

  !> After the whole deck: every RIGID has a SHAPE and a name no BODY has; the
  !> RIGIDs' ramps end by STEPS and their curves exist.
  subroutine check_rigids(s, deck)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(inout) :: deck
    integer :: r, b
    do r = 1, size(deck%rigids)
      associate (rg => deck%rigids(r))
        if (len(rg%name) == 0) cycle
        if (rg%shape_line == 0) call report(s, rg%line, 'RIGID ' // quoted(rg%name) // ' has no SHAPE (expected ' // &
                                            'SHAPE line|circle|polyline in its block)')
        do b = 1, s%nbody
          if (deck%bodies(b)%name == rg%name .and. len(deck%bodies(b)%name) == len(rg%name)) &
            call report(s, rg%line, 'RIGID ' // quoted(rg%name) // ' has the name of the BODY at line ' // &
                        int_to_str(deck%bodies(b)%line) // ' (expected a name of its own)')
        end do
        do b = 1, size(rg%fixes)
          call finish_load(rg%fixes(b))
        end do
        do b = 1, size(rg%forces)
          call finish_load(rg%forces(b))
        end do
      end associate
    end do
  contains
    subroutine finish_load(ld)
      type(rigid_load_t), intent(inout) :: ld
      call check_ramp_end(s, deck, ld%ramp, ld%line)
      if (ld%ramp(2) == ramp_unset(2)) ld%ramp = [0, deck%steps]
      if (allocated(ld%curve_name)) call resolve_curve(s, deck, ld%curve_name, ld%line, ld%curve)
    end subroutine finish_load
  end subroutine check_rigids

  !> The index into deck%curves of curve=NAME ('': 0), reported when unknown.
  subroutine resolve_curve(s, deck, name, line, curve)
    type(state_t), intent(inout) :: s
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: name
    integer, intent(in) :: line
    integer, intent(out) :: curve
    integer :: c
    curve = 0
    if (len(name) == 0) return
    do c = 1, size(deck%curves)
      if (deck%curves(c)%name == name .and. len(deck%curves(c)%name) == len(name)) then
        curve = c
        return
      end if
    end do
    call report(s, line, 'unknown curve ' // quoted(name) // ' (expected a CURVE statement of that name)')
  end subroutine resolve_curve

  ! ================================================================ numbers and text

  !> Read an integer: [sign] digits, at most 9 significant digits.
  subroutine parse_integer(str, k, ok)
    character(len=*), intent(in) :: str
    integer, intent(out) :: k
    logical, intent(out) :: ok
    integer(int64) :: v
    k = 0
    ok = scan_integer(str, v)
    if (ok) ok = abs(v) < 1000000000_int64
    if (ok) k = int(v)
  end subroutine parse_integer

  !> Names: [A-Za-z0-9_.-]+
  pure logical function is_name(s)
    character(len=*), intent(in) :: s
    integer :: i
    is_name = len(s) > 0
    do i = 1, len(s)
      if (.not. (is_digit(s(i:i)) .or. is_letter(s(i:i)) .or. index('_.-', s(i:i)) > 0)) then
        is_name = .false.
        return
      end if
    end do
  end function is_name

  !> .geo variable: [A-Za-z_][A-Za-z0-9_]*, at most 64 characters.
  pure logical function is_identifier(s)
    character(len=*), intent(in) :: s
    integer :: i
    is_identifier = len(s) > 0 .and. len(s) <= 64
    if (.not. is_identifier) return
    is_identifier = is_letter(s(1:1)) .or. s(1:1) == '_'
    do i = 2, len(s)
      if (.not. (is_digit(s(i:i)) .or. is_letter(s(i:i)) .or. s(i:i) == '_')) is_identifier = .false.
    end do
  end function is_identifier

  !> No control characters (bytes >= 128 allowed).
  pure logical function is_printable(s)
    character(len=*), intent(in) :: s
    integer :: i
    is_printable = .true.
    do i = 1, len(s)
      if (iachar(s(i:i)) < 32 .or. iachar(s(i:i)) == 127) is_printable = .false.
    end do
  end function is_printable

  pure logical function ends_with_ci(s, suffix)
    character(len=*), intent(in) :: s, suffix
    ends_with_ci = .false.
    if (len(s) < len(suffix)) return
    ends_with_ci = lower(s(len(s) - len(suffix) + 1:)) == lower(suffix)
  end function ends_with_ci

  !> User text for a message: control and non-ASCII bytes as '?', cut after quote_len.
  pure function cut(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    integer :: i
    if (len(s) > quote_len) then
      t = s(1:quote_len) // '...'
    else
      t = s
    end if
    do i = 1, len(t)
      if (iachar(t(i:i)) < 32 .or. iachar(t(i:i)) > 126) t(i:i) = '?'
    end do
  end function cut

  !> "text", printable and cut.
  pure function quoted(s) result(t)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    t = '"' // cut(s) // '"'
  end function quoted

end module deck_reader
