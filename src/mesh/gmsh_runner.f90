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
module gmsh_runner
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp, i8
  use strings, only: int_to_str, real_to_str, printable
  use errors, only: error_t, set_error, error_input
  use system_binding, only: c2d_run_program, c_unlink, c2d_run_exited, c2d_run_signaled, &
                            c2d_run_timeout
  use safe_files, only: find_program, read_file, real_path, folder_of, file_kind, c2d_regular, file_stamp
  implicit none
  private
  public :: gmsh_options_t, mesh_geo_file, gmsh_identity, gmsh_arguments, real_to_text

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
    character(len=:), allocatable :: gmsh, bwrap, geo, out_folder, message
    type(argv_t) :: argv
    integer(c_int) :: how, status
    integer :: i
    logical :: found

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

    if (.not. opts%trust_geo) then
      call find_program('bwrap', bwrap, found)
      if (found) found = sandbox_works(bwrap, log_path)
      if (found) call sandbox_arguments(bwrap, gmsh, read_folder, geo, out_folder, argv)
    end if
    call push(argv, gmsh)
    do i = 1, size(gmsh_arguments)
      call push(argv, trim(gmsh_arguments(i)))
    end do
    call push(argv, '-order')
    call push(argv, int_to_str(order))
    do i = 1, size(names)
      call push(argv, '-setnumber')
      call push(argv, trim(names(i)))
      call push(argv, real_to_text(values(i)))
    end do
    if (present(background)) then
      call push(argv, '-string')
      call push(argv, 'Mesh.MeshSizeFromPoints=0;Mesh.MeshSizeExtendFromBoundary=0;Mesh.MeshSizeFromCurvature=0;')
      call push(argv, '-bgm')
      call push(argv, background)
    end if
    if (present(size_range)) then
      call push(argv, '-clmin')
      call push(argv, real_to_text(size_range(1)))
      call push(argv, '-clmax')
      call push(argv, real_to_text(size_range(2)))
    end if
    call push(argv, geo)
    call push(argv, '-o')
    call push(argv, out_folder // '/' // msh_path(index(msh_path, '/', back=.true.) + 1:))
    if (c2d_run_program(argv%packed, int(argv%n, c_int), log_path // c_null_char, real(opts%timeout, c_double), &
                        how, status) /= 0) continue
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

  !> bubblewrap can make its namespaces here (not in every container).
  logical function sandbox_works(bwrap, log_path)
    character(len=*), intent(in) :: bwrap, log_path
    type(argv_t) :: argv
    integer(c_int) :: how, status
    call push(argv, bwrap)
    call push(argv, '--unshare-all')
    call push(argv, '--die-with-parent')
    call push(argv, '--ro-bind')
    call push(argv, '/')
    call push(argv, '/')
    call push(argv, 'true')
    if (c2d_run_program(argv%packed, int(argv%n, c_int), log_path // '.probe' // c_null_char, 30.0_c_double, &
                        how, status) /= 0) continue
    if (c_unlink(log_path // '.probe' // c_null_char) /= 0) continue
    sandbox_works = how == c2d_run_exited .and. status == 0
  end function sandbox_works

  !> bwrap's arguments up to the program: a new namespace of every kind (no
  !> network, no other processes), a new session, the process dies with
  !> contact2d; the system read-only, the deck's folder and the .geo
  !> read-only, the output folder writable, the environment cleared.
  subroutine sandbox_arguments(bwrap, gmsh, read_folder, geo, out_folder, argv)
    character(len=*), intent(in) :: bwrap, gmsh, read_folder, geo, out_folder
    type(argv_t), intent(inout) :: argv
    character(len=:), allocatable :: deck_folder, prefix
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
    if (gmsh(1:min(5, len(gmsh))) /= '/usr/') then      ! a gmsh installed elsewhere: its prefix
      prefix = folder_of(folder_of(gmsh))
      call push(argv, '--ro-bind')
      call push(argv, prefix)
      call push(argv, prefix)
    end if
    call real_path(read_folder, deck_folder, found)
    if (found) then
      call push(argv, '--ro-bind')
      call push(argv, deck_folder)
      call push(argv, deck_folder)
    end if
    call push(argv, '--ro-bind')
    call push(argv, geo)
    call push(argv, geo)
    call push(argv, '--bind')
    call push(argv, out_folder)
    call push(argv, out_folder)
    call push(argv, '--chdir')
    call push(argv, out_folder)
    call push(argv, '--')
  end subroutine sandbox_arguments

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
