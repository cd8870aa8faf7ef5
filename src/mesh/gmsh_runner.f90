!> gmsh_runner: mesh a .geo file by running gmsh, as an untrusted program.
!>
!> gmsh is started without a shell (an argument vector, src/sys/process_runner.c),
!> found on PATH, in a process group of its own that is killed when the time
!> limit passes or contact2d ends.  A .geo is a program: gmsh's language has
!> SystemCall, Printf > FILE, Save, Include of any path.  Unless the user
!> trusts the .geo (--trust-geo), gmsh runs under bubblewrap when this
!> machine lets it make namespaces: no network, no other processes, the
!> filesystem read-only and reduced to the system's programs and libraries,
!> the deck's folder and the .geo, with one writable folder, where the mesh
!> goes (the run's private folder).  The static screen of geo_screen runs
!> before, sandbox or not, and is what refuses such a .geo with FILE:LINE.
!>
!> The mesher.  Starting gmsh costs some 0.12 s of CPU before it reads its
!> .geo (the dynamic linker binds libgmsh and the ninety libraries it
!> needs): a two-body run paid it twice, a two-body ADAPT run four to six
!> times.  So when the gmsh on PATH is Debian's (/usr/bin/gmsh) and
!> contact2d-mesher (src/mesher/gmsh_mesher.c) lies beside the program, the
!> first mesh of a run starts the mesher, in the same sandbox as gmsh (its
!> .geo files those of the run), and each mesh is one request to it: it
!> forks and runs libgmsh's batch program with gmsh's argument vector, so
!> the mesh is byte for byte gmsh's and no state passes from one .geo to the
!> next.  It runs until stop_mesher (the run's meshes made), a program run
!> (it is stopped first) or the run's end; a mesher that cannot start or
!> ends without an answer leaves the mesh to gmsh, run as above.  Its CPU
!> time is the run's (c2d_cpu_seconds).
!>
!> Programming interface
!>   type(gmsh_options_t)    trust_geo, timeout (seconds), the mesh cache's folder
!>   gmsh_identity(identity, found)   'PATH SIZE MTIME' of the gmsh on PATH (mesh_cache's key)
!>   mesh_geo_file(geo_path, order, names, values, opts, read_folder, msh_path, log_path, err
!>                 [, background, size_range])
!>        gmsh -2 -format msh41 -v 2 -order ORDER [-setnumber NAME VALUE]... GEO -o MSH,
!>        its output to LOG (which must not exist); err unless gmsh exits 0 and wrote
!>        MSH, its message saying why (gmsh's first error lines, the time limit).
!>        With a background (a .pos view in MSH's folder): the sizes are the view's
!>        alone, within size_range (an adaptive re-mesh, module size_field)
!>   stop_mesher()    stop the mesher, when it runs
!>   gmsh_runs(served, alone, sandboxed)   the run's meshes: by the mesher, by gmsh
!>        processes of their own; all in the sandbox
module gmsh_runner
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str, printable
  use errors, only: error_t, set_error, error_input
  use system_binding, only: c2d_run_program, c_unlink, c2d_run_exited, c2d_run_signaled, &
                            c2d_run_timeout, c2d_server_start, c2d_server_running, c2d_server_call, c2d_server_stop
  use safe_files, only: find_program, read_file, real_path, folder_of, file_kind, c2d_regular, file_stamp
  implicit none
  private
  public :: gmsh_options_t, mesh_geo_file, gmsh_identity, gmsh_arguments, real_to_text, stop_mesher, gmsh_runs

  type :: gmsh_options_t
    logical :: trust_geo = .false.       !< run gmsh as it is: no screen, no sandbox (--trust-geo)
    real(dp) :: timeout = 600.0_dp       !< seconds gmsh may take per .geo (--gmsh-timeout)
    character(len=:), allocatable :: cache   !< folder of the mesh cache (mesh_cache); unallocated or
                                             !< '' when meshes are not kept (--no-mesh-cache)
  end type gmsh_options_t

  !> the options of every gmsh run besides -order and -setnumber (a mesh
  !> depends on them: they are part of mesh_cache's key)
  character(len=7), parameter :: gmsh_arguments(5) = [character(len=7) :: '-2', '-format', 'msh41', '-v', '2']

  !> an argument vector: NUL-terminated strings one after the other
  type :: argv_t
    character(len=:), allocatable :: packed
    integer :: n = 0
  end type argv_t

  !> the gmsh program of the Debian package whose libgmsh the mesher runs
  character(len=*), parameter :: debian_gmsh = '/usr/bin/gmsh'

  !> the run's mesher and sandbox, process state as the mesher's process is
  type :: mesher_t
    character(len=:), allocatable :: bwrap        !< bwrap when it works here, '' when not (probed once)
    character(len=:), allocatable :: program      !< contact2d-mesher beside the program, '' when none or off
    character(len=:), allocatable :: read_folder, deck_folder, out_folder   !< the running mesher's
    character(len=:), allocatable :: geos(:)      !< the .geo files its sandbox shows besides the deck's folder
    integer :: served = 0                         !< meshes the mesher made
    integer :: alone = 0                          !< meshes a gmsh process of their own made
    logical :: sandboxed = .true.                 !< every mesh so far made in the sandbox
  end type mesher_t
  type(mesher_t), save :: mesher

  !> what the sandbox shows of the system, read-only (when present)
  character(len=*), parameter :: system_paths(9) = [character(len=24) :: '/usr', '/bin', '/sbin', '/lib', &
    '/lib32', '/lib64', '/libx32', '/etc/ld.so.cache', '/etc/alternatives']

contains

  !> Mesh a .geo file with gmsh (2D, MSH 4.1 ASCII).
  !>   geo_path    (in)  the .geo file
  !>   order       (in)  element order, 1 or 2 (gmsh -order: second-order
  !>                     elements with the mid-side nodes on the curves)
  !>   names       (in)  (n) names given to -setnumber (n may be 0)
  !>   values      (in)  (n) their values
  !>   opts        (in)  trust and time limit
  !>   read_folder (in)  a folder the .geo may read (the deck's)
  !>   msh_path    (in)  the mesh to write, in a folder of the run's own (the only
  !>                     folder the sandbox lets gmsh write)
  !>   log_path    (in)  where gmsh's output goes (made here: must not exist)
  !>   err         (out) unallocated when gmsh exited with status 0 and wrote msh_path;
  !>                     else its message says what went wrong (error_input)
  !>   background  (in, optional) a gmsh view of the sizes wanted (gmsh -bgm), in
  !>                     msh_path's folder; the .geo's own sizes (points, boundary,
  !>                     curvature) are turned off, so that the view may coarsen too
  !>   size_range  (in, optional) (2) the smallest and largest size (-clmin, -clmax):
  !>                     a point of a curved boundary just outside the view's
  !>                     polygon gets no size of its own
  subroutine mesh_geo_file(geo_path, order, names, values, opts, read_folder, msh_path, log_path, err, &
                           background, size_range)
    character(len=*), intent(in) :: geo_path, read_folder, msh_path, log_path
    integer, intent(in) :: order
    character(len=*), intent(in) :: names(:)
    real(dp), intent(in) :: values(:)
    type(gmsh_options_t), intent(in) :: opts
    type(error_t), allocatable, intent(out) :: err
    character(len=*), intent(in), optional :: background
    real(dp), intent(in), optional :: size_range(2)
    character(len=:), allocatable :: gmsh, bwrap, geo, out_folder, message, shown
    type(argv_t) :: argv, gmsh_argv
    integer(c_int) :: how, status
    integer :: i
    logical :: found, served

    if (size(names) /= size(values)) then
      call set_error(err, 'gmsh parameters: ' // int_to_str(size(names)) // ' names but ' // int_to_str(size(values)) // &
        ' values (one value per name expected)', error_input)
      return
    end if
    do i = 1, size(names)
      if (len_trim(names(i)) == 0) then
        call set_error(err, 'gmsh parameter ' // int_to_str(i) // ' has an empty name (a name for -setnumber expected)', &
          error_input)
        return
      end if
      if (.not. ieee_is_finite(values(i))) then
        call set_error(err, 'gmsh parameter ' // trim(names(i)) // ' is not finite (a finite number expected)', error_input)
        return
      end if
    end do
    call find_program('gmsh', gmsh, found)
    if (.not. found) then
      call set_error(err, 'gmsh not found on PATH (install the Debian package gmsh)', error_input)
      return
    end if
    ! absolute paths: the same inside the sandbox, and never taken for an option
    call real_path(geo_path, geo, found)
    if (.not. found) then
      call set_error(err, 'cannot find "' // geo_path // '"', error_input)
      return
    end if
    call real_path(folder_of(msh_path), out_folder, found)
    if (.not. found) then
      call set_error(err, 'no folder for the mesh "' // msh_path // '"', error_input)
      return
    end if
    if (c_unlink(msh_path // c_null_char) /= 0) continue    ! a mesh there afterwards is gmsh's

    call push(gmsh_argv, gmsh)
    do i = 1, size(gmsh_arguments)
      call push(gmsh_argv, trim(gmsh_arguments(i)))
    end do
    call push(gmsh_argv, '-order')
    call push(gmsh_argv, int_to_str(order))
    do i = 1, size(names)
      call push(gmsh_argv, '-setnumber')
      call push(gmsh_argv, trim(names(i)))
      call push(gmsh_argv, real_to_text(values(i)))
    end do
    if (present(background)) then
      call push(gmsh_argv, '-string')
      call push(gmsh_argv, 'Mesh.MeshSizeFromPoints=0;Mesh.MeshSizeExtendFromBoundary=0;Mesh.MeshSizeFromCurvature=0;')
      call push(gmsh_argv, '-bgm')
      call push(gmsh_argv, background)
    end if
    if (present(size_range)) then
      call push(gmsh_argv, '-clmin')
      call push(gmsh_argv, real_to_text(size_range(1)))
      call push(gmsh_argv, '-clmax')
      call push(gmsh_argv, real_to_text(size_range(2)))
    end if
    call push(gmsh_argv, geo)
    call push(gmsh_argv, '-o')
    call push(gmsh_argv, out_folder // '/' // msh_path(index(msh_path, '/', back=.true.) + 1:))

    served = .false.
    if (mesher_serves(gmsh)) call serve(gmsh_argv, opts, read_folder, geo, out_folder, log_path, served, how, status)
    if (served) then
      mesher%served = mesher%served + 1
    else
      mesher%alone = mesher%alone + 1
      bwrap = sandbox_for(opts, log_path)
      shown = ''                                ! a gmsh installed outside /usr: its prefix (libraries, share/)
      if (gmsh(1:min(5, len(gmsh))) /= '/usr/') shown = folder_of(folder_of(gmsh))
      if (len(bwrap) > 0) call sandbox_arguments(bwrap, shown, read_folder, [geo], out_folder, argv)
      if (.not. allocated(argv%packed)) argv%packed = ''
      argv%packed = argv%packed // gmsh_argv%packed
      argv%n = argv%n + gmsh_argv%n
      if (c2d_run_program(argv%packed, int(argv%n, c_int), log_path // c_null_char, real(opts%timeout, c_double), &
                          how, status) /= 0) continue
    end if
    select case (how)
    case (c2d_run_timeout)
      call set_error(err, 'gmsh did not finish within ' // real_to_str(opts%timeout) // ' s (--gmsh-timeout): stopped ' // &
                '(a .geo that ends expected; an endless loop?)', error_input)
      return
    case (c2d_run_signaled)
      call set_error(err, 'gmsh was killed by signal ' // int_to_str(int(status)) // gmsh_errors(log_path, '; '), error_input)
      return
    case (c2d_run_exited)
    case default
      call set_error(err, 'cannot run ' // gmsh // ' (error ' // int_to_str(int(status)) // ')', error_input)
      return
    end select
    if (file_kind(msh_path) == c2d_regular .and. status == 0) return
    message = gmsh_errors(log_path, '')
    if (len(message) == 0) then
      if (status /= 0) then
        message = 'gmsh failed with exit status ' // int_to_str(int(status))
      else
        message = 'gmsh wrote no mesh file'
      end if
    end if
    call set_error(err, message, error_input)
  end subroutine mesh_geo_file

  !> The gmsh that mesh_geo_file runs, as a stamp: its real path, size and
  !> modification time ('PATH SIZE MTIME_NS'), which change when gmsh is
  !> upgraded or replaced.  Not its --version: starting gmsh to ask costs
  !> a third of a second, a good part of meshing a small .geo.
  !>   identity (out) the stamp ('' when not found)
  !>   found    (out) gmsh is on PATH
  subroutine gmsh_identity(identity, found)
    character(len=:), allocatable, intent(out) :: identity
    logical, intent(out) :: found
    character(len=:), allocatable :: gmsh, real, stamp
    identity = ''
    call find_program('gmsh', gmsh, found)
    if (.not. found) return
    call real_path(gmsh, real, found)
    if (found) call file_stamp(real, stamp, found)
    if (found) identity = real // ' ' // stamp
  end subroutine gmsh_identity

  !> bwrap for a gmsh run (the mesher's or a process of its own), '' when the
  !> run has none (--trust-geo, or bubblewrap cannot run here: then
  !> gmsh_runs says so).
  function sandbox_for(opts, log_path) result(bwrap)
    type(gmsh_options_t), intent(in) :: opts
    character(len=*), intent(in) :: log_path
    character(len=:), allocatable :: bwrap
    bwrap = ''
    if (.not. opts%trust_geo) bwrap = sandbox_program(log_path)
    mesher%sandboxed = mesher%sandboxed .and. len(bwrap) > 0
  end function sandbox_for

  !> bubblewrap's path when it can make its namespaces here (not in every
  !> container), else ''; probed once per run (the probe is a program run,
  !> which would stop a running mesher).
  function sandbox_program(log_path) result(bwrap)
    character(len=*), intent(in) :: log_path
    character(len=:), allocatable :: bwrap
    type(argv_t) :: argv
    integer(c_int) :: how, status
    logical :: found
    if (.not. allocated(mesher%bwrap)) then
      call find_program('bwrap', mesher%bwrap, found)
      if (found) then
        call push(argv, mesher%bwrap)
        call push(argv, '--unshare-all')
        call push(argv, '--die-with-parent')
        call push(argv, '--ro-bind')
        call push(argv, '/')
        call push(argv, '/')
        call push(argv, 'true')
        if (c2d_run_program(argv%packed, int(argv%n, c_int), log_path // '.probe' // c_null_char, 30.0_c_double, &
                            how, status) /= 0) continue
        if (c_unlink(log_path // '.probe' // c_null_char) /= 0) continue
        found = how == c2d_run_exited .and. status == 0
      end if
      if (.not. found) mesher%bwrap = ''
    end if
    bwrap = mesher%bwrap
  end function sandbox_program

  !> bwrap's arguments up to the program: a new namespace of every kind (no
  !> network, no other processes), a new session, the process dies with
  !> contact2d; the system read-only, shown (when not ''; the program's
  !> files outside the system's folders), the deck's folder and the .geo
  !> files read-only, the output folder writable, the environment cleared.
  subroutine sandbox_arguments(bwrap, shown, read_folder, geos, out_folder, argv)
    character(len=*), intent(in) :: bwrap, shown, read_folder, geos(:), out_folder
    type(argv_t), intent(inout) :: argv
    character(len=:), allocatable :: deck_folder
    logical :: found
    integer :: i
    call push(argv, bwrap)
    call push(argv, '--unshare-all')
    call push(argv, '--die-with-parent')
    call push(argv, '--new-session')
    call push(argv, '--clearenv')
    call push(argv, '--setenv')
    call push(argv, 'PATH')
    call push(argv, '/usr/bin:/bin')
    call push(argv, '--setenv')
    call push(argv, 'HOME')
    call push(argv, out_folder)
    do i = 1, size(system_paths)
      call push(argv, '--ro-bind-try')
      call push(argv, trim(system_paths(i)))
      call push(argv, trim(system_paths(i)))
    end do
    call push(argv, '--proc')
    call push(argv, '/proc')
    call push(argv, '--dev')
    call push(argv, '/dev')
    call push(argv, '--tmpfs')
    call push(argv, '/tmp')
    if (len(shown) > 0) then
      call push(argv, '--ro-bind')
      call push(argv, shown)
      call push(argv, shown)
    end if
    call real_path(read_folder, deck_folder, found)
    if (found) then
      call push(argv, '--ro-bind')
      call push(argv, deck_folder)
      call push(argv, deck_folder)
    end if
    do i = 1, size(geos)
      call push(argv, '--ro-bind')
      call push(argv, trim(geos(i)))
      call push(argv, trim(geos(i)))
    end do
    call push(argv, '--bind')
    call push(argv, out_folder)
    call push(argv, out_folder)
    call push(argv, '--chdir')
    call push(argv, out_folder)
    call push(argv, '--')
  end subroutine sandbox_arguments

  !> The mesher (contact2d-mesher, beside the running program) can make this
  !> run's meshes: it runs libgmsh's batch program, so it stands for the gmsh
  !> on PATH only when that is the gmsh of the same Debian package
  !> (/usr/bin/gmsh).  CONTACT2D_MESHER=0 turns it off (a gmsh per mesh).
  logical function mesher_serves(gmsh)
    character(len=*), intent(in) :: gmsh
    character(len=:), allocatable :: self
    character(len=8) :: setting
    integer :: length, status
    logical :: found
    if (.not. allocated(mesher%program)) then
      mesher%program = ''
      call get_environment_variable('CONTACT2D_MESHER', setting, length, status)
      if (status /= 0 .or. setting /= '0') then
        call real_path('/proc/self/exe', self, found)
        if (found) then
          if (file_kind(folder_of(self) // '/contact2d-mesher') == c2d_regular) &
            mesher%program = folder_of(self) // '/contact2d-mesher'
        end if
      end if
    end if
    mesher_serves = len(mesher%program) > 0 .and. gmsh == debian_gmsh
  end function mesher_serves

  !> Mesh through the mesher: started on the first request, and again when a
  !> request needs a folder or a .geo its sandbox does not show.  served is
  !> .false. when it could not start or ended without an answer (the caller
  !> then runs gmsh itself); else how and status are gmsh's run's.
  subroutine serve(gmsh_argv, opts, read_folder, geo, out_folder, log_path, served, how, status)
    type(argv_t), intent(in) :: gmsh_argv
    type(gmsh_options_t), intent(in) :: opts
    character(len=*), intent(in) :: read_folder, geo, out_folder, log_path
    logical, intent(out) :: served
    integer(c_int), intent(out) :: how, status
    type(argv_t) :: request
    integer(c_int) :: got
    served = .false.
    if (c2d_server_running() == 1) then
      if (mesher%out_folder /= out_folder .or. mesher%read_folder /= read_folder .or. &
          .not. any(mesher%geos == geo) .and. index(geo, mesher%deck_folder // '/') /= 1) call stop_mesher()
    end if
    if (c2d_server_running() == 0) then
      if (.not. allocated(mesher%geos)) allocate(character(len=0) :: mesher%geos(0))
      if (.not. any(mesher%geos == geo)) mesher%geos = [character(len=max(len(geo), len(mesher%geos))) :: &
                                                            mesher%geos, geo]
      call start_mesher(opts, read_folder, out_folder, log_path)
      if (c2d_server_running() == 0) then
        mesher%program = ''
        return
      end if
    end if
    call push(request, int_to_str(gmsh_argv%n))
    call push(request, real_to_text(opts%timeout))
    call push(request, log_path)
    got = c2d_server_call(request%packed // gmsh_argv%packed, int(len(request%packed) + len(gmsh_argv%packed), c_int), &
                          real(opts%timeout, c_double) + 30.0_c_double, how, status)
    select case (got)
    case (0)
      served = .true.
    case (1)                                   ! no answer in time: the mesher itself is stuck
      call stop_mesher()
      served = .true.
      how = c2d_run_timeout
      status = 0
    case default                               ! it ended: gmsh runs as a program of its own, from now on
      call stop_mesher()
      mesher%program = ''
      if (c_unlink(log_path // c_null_char) /= 0) continue
    end select
  end subroutine serve

  !> Start the mesher, sandboxed as gmsh is (its .geo files those seen so far).
  subroutine start_mesher(opts, read_folder, out_folder, log_path)
    type(gmsh_options_t), intent(in) :: opts
    character(len=*), intent(in) :: read_folder, out_folder, log_path
    type(argv_t) :: argv
    character(len=:), allocatable :: bwrap, deck_folder, server_log
    integer(c_int) :: status
    logical :: found
    bwrap = sandbox_for(opts, log_path)
    if (len(bwrap) > 0) call sandbox_arguments(bwrap, mesher%program, read_folder, mesher%geos, out_folder, argv)
    call push(argv, mesher%program)
    server_log = out_folder // '/contact2d-mesher.log'
    if (c_unlink(server_log // c_null_char) /= 0) continue
    if (c2d_server_start(argv%packed, int(argv%n, c_int), server_log // c_null_char, status) /= 0) return
    call real_path(read_folder, deck_folder, found)
    if (.not. found) deck_folder = read_folder
    mesher%deck_folder = deck_folder
    mesher%read_folder = read_folder
    mesher%out_folder = out_folder
  end subroutine start_mesher

  !> How this run's .geo files were meshed: how many meshes the mesher
  !> made, how many gmsh processes of their own, and whether all of them ran
  !> in the sandbox (the run log says so).
  subroutine gmsh_runs(served, alone, sandboxed)
    integer, intent(out) :: served, alone
    logical, intent(out) :: sandboxed
    served = mesher%served
    alone = mesher%alone
    sandboxed = mesher%sandboxed
  end subroutine gmsh_runs

  !> Stop the mesher when it runs (module header): once a run's meshes are
  !> made, so that it holds no memory while the run solves.
  subroutine stop_mesher()
    call c2d_server_stop()
  end subroutine stop_mesher

  !> Append one argument.
  subroutine push(argv, arg)
    type(argv_t), intent(inout) :: argv
    character(len=*), intent(in) :: arg
    if (.not. allocated(argv%packed)) argv%packed = ''
    argv%packed = argv%packed // arg // c_null_char
    argv%n = argv%n + 1
  end subroutine push

  !> The first two lines of gmsh's log starting with "Error", joined by "; "
  !> (else its first line: bwrap's own message), after lead when any.
  function gmsh_errors(log_path, lead) result(text)
    character(len=*), intent(in) :: log_path, lead
    character(len=:), allocatable :: text
    character(len=:), allocatable :: buf, line, first
    integer :: status, nfound
    integer(i8) :: p, q, n

    text = ''
    first = ''
    call read_file(log_path, buf, status)
    if (status /= 0) return
    n = len(buf, kind=i8)
    nfound = 0
    p = 1
    do while (p <= n .and. nfound < 2)
      q = index(buf(p:), achar(10), kind=i8)
      if (q == 0) then
        line = buf(p:n)
        p = n + 1
      else
        line = buf(p:p + q - 2)
        p = p + q
      end if
      line = trim(adjustl(printable(line)))
      if (len(line) > 300) line = line(1:300) // ' ...'
      if (len(first) == 0) first = line
      if (len(line) >= 5) then
        if (line(1:5) == 'Error') then
          if (nfound > 0) text = text // '; '
          text = text // line
          nfound = nfound + 1
        end if
      end if
    end do
    if (nfound == 0) text = first
    if (len(text) > 0) text = lead // text
  end function gmsh_errors

  !> A real number as text that reads back exactly: an integer when it is
  !> one, else 17 significant digits.
  function real_to_text(v) result(s)
    real(dp), intent(in) :: v
    character(len=:), allocatable :: s
    character(len=32) :: buf
    if (abs(v) < 1.0e15_dp .and. v == aint(v)) then
      write(buf, '(i0)') int(v, i8)
    else
      write(buf, '(es25.16e3)') v
    end if
    s = trim(adjustl(buf))
  end function real_to_text

end module gmsh_runner
