!> mesh_cache: the meshes gmsh made of .geo files, kept for the runs that ask
!> for the same mesh again — the cases of a sweep that vary a load, not the
!> geometry, and the re-runs of a deck.  gmsh takes seconds on a .geo that
!> the rest of a small run solves in less (doc/performance.md, "Meshes kept
!> across a sweep").
!>
!> The key of a mesh is what it depends on, written out: the gmsh that makes
!> it (gmsh_identity: its path, size and modification time), its options and
!> -order, each -setnumber NAME VALUE as passed, and the .geo's bytes.  A
!> .geo that reads another file (Include, Merge, MergeWithBoundingBox,
!> ShapeFromFile) has no key: the other file's bytes are not in it, so such a
!> mesh is never kept.  An entry is two files in the cache folder, named after
!> a 64-bit hash of the key: geo-HASH.msh and geo-HASH.key, the key itself.
!> An entry is used only when its .key file holds exactly the key asked for,
!> so a hash collision costs a run of gmsh, never a wrong mesh.
!>
!> Decks are untrusted: the entries' names are the hash's hex digits, never
!> a name a deck chose, and they go only into the cache folder the program
!> names (inside the run's output folder).  A cache folder that is a symbolic
!> link (or under one made since) is neither read nor written: no link the
!> run did not make is followed.  Runs side by side (a sweep on
!> GNU parallel) write each entry to temporaries of their own and rename them
!> into place under the folder's lock (safe_files), the mesh before its key:
!> a run that reads a key finds its mesh complete.
!>
!> Programming interface
!>   type(mesh_entry_t)                              a key and the mesh made for it
!>   geo_key(geo_path, order, names, values, key)   the key of a .geo's mesh ('' when it has none)
!>   find_cached_mesh(folder, key, msh_path, found)  the kept mesh of key, when there is one
!>   keep_mesh(folder, key, msh_path, err)           keep the mesh msh_path under key
module mesh_cache
  use kinds, only: dp, i8
  use strings, only: int_to_str
  use errors, only: error_t, set_error, error_input
  use safe_files, only: read_file, file_kind, c2d_regular, c2d_missing, make_folders, temporary_t, create_temporary, &
                        close_temporary, commit_temporaries, discard_temporaries, real_path, folder_of
  use gmsh_runner, only: gmsh_identity, gmsh_arguments, real_to_text
  implicit none
  private
  public :: mesh_entry_t, geo_key, find_cached_mesh, keep_mesh

  !> A mesh gmsh made, to keep once the run has succeeded.
  type :: mesh_entry_t
    character(len=:), allocatable :: key        !< its key (geo_key)
    character(len=:), allocatable :: msh_path   !< the mesh gmsh wrote (the run's private folder)
  end type mesh_entry_t

  !> gmsh statements that read another file: a .geo with one has no key
  character(len=20), parameter :: reads_files(4) = [character(len=20) :: 'Include', 'Merge', &
                                                    'MergeWithBoundingBox', 'ShapeFromFile']

contains

  !> The key of the mesh gmsh makes of a .geo (module header).
  !>   geo_path (in)  the .geo file
  !>   order    (in)  element order (gmsh -order)
  !>   names    (in)  (n) the -setnumber names;  values (in) (n) their values
  !>   key      (out) the key; '' when the mesh cannot be kept (the .geo reads
  !>                  other files, or gmsh or the .geo cannot be read)
  subroutine geo_key(geo_path, order, names, values, key)
    character(len=*), intent(in) :: geo_path
    integer, intent(in) :: order
    character(len=*), intent(in) :: names(:)
    real(dp), intent(in) :: values(:)
    character(len=:), allocatable, intent(out) :: key
    character(len=:), allocatable :: geo, gmsh
    integer :: status, i
    logical :: found
    key = ''
    call gmsh_identity(gmsh, found)
    if (.not. found) return
    call read_file(geo_path, geo, status)
    if (status /= 0) return
    do i = 1, size(reads_files)
      if (index(geo, trim(reads_files(i))) > 0) return
    end do
    key = 'contact2d mesh cache 1' // achar(10) // 'gmsh ' // gmsh // achar(10) // 'options'
    do i = 1, size(gmsh_arguments)
      key = key // ' ' // trim(gmsh_arguments(i))
    end do
    key = key // ' -order ' // int_to_str(order) // achar(10)
    do i = 1, size(names)
      key = key // '-setnumber ' // trim(names(i)) // ' ' // real_to_text(values(i)) // achar(10)
    end do
    key = key // 'geo ' // int_to_str(len(geo)) // ' bytes' // achar(10) // geo
  end subroutine geo_key

  !> The kept mesh of key in folder, when its entry is there and holds that key.
  !>   folder   (in)  the cache folder
  !>   key      (in)  the mesh's key (geo_key), not ''
  !>   msh_path (out) folder/geo-HASH.msh
  !>   found    (out) the entry is there, its key is key
  subroutine find_cached_mesh(folder, key, msh_path, found)
    character(len=*), intent(in) :: folder, key
    character(len=:), allocatable, intent(out) :: msh_path
    logical, intent(out) :: found
    character(len=:), allocatable :: stored
    integer :: status
    msh_path = folder // '/' // entry_name(key) // '.msh'
    found = .false.
    if (len(key) == 0 .or. .not. own_folder(folder)) return
    if (file_kind(folder // '/' // entry_name(key) // '.key') /= c2d_regular) return
    call read_file(folder // '/' // entry_name(key) // '.key', stored, status)
    if (status /= 0) return
    found = stored == key .and. len(stored) == len(key) .and. file_kind(msh_path) == c2d_regular
  end subroutine find_cached_mesh

  !> Keep the mesh msh_path under key in folder (made when missing): the mesh
  !> and its key to temporaries, renamed into place together.
  !>   folder   (in)  the cache folder
  !>   key      (in)  the mesh's key (geo_key), not ''
  !>   msh_path (in)  the mesh gmsh wrote
  !>   err      (out) allocated when the entry could not be written (nothing kept)
  subroutine keep_mesh(folder, key, msh_path, err)
    character(len=*), intent(in) :: folder, key, msh_path
    type(error_t), allocatable, intent(out) :: err
    type(temporary_t) :: t(2)
    character(len=:), allocatable :: msh
    integer :: status
    if (len(key) == 0) then
      call set_error(err, 'no key for the mesh', error_input)
      return
    end if
    call read_file(msh_path, msh, status)
    if (status /= 0) then
      call set_error(err, msh_path // ': cannot read the mesh', error_input)
      return
    end if
    if (.not. own_folder(folder)) then
      call set_error(err, folder // ': a symbolic link, not a folder of the run''s', error_input)
      return
    end if
    call make_folders(folder, err)
    if (allocated(err)) return
    call create_temporary(folder, entry_name(key) // '.msh', t(1), err)
    if (.not. allocated(err)) call create_temporary(folder, entry_name(key) // '.key', t(2), err)
    if (.not. allocated(err)) call write_bytes(t(1)%io_path, msh, err)
    if (.not. allocated(err)) call write_bytes(t(2)%io_path, key, err)
    call close_temporary(t(1))
    call close_temporary(t(2))
    if (.not. allocated(err)) call commit_temporaries(folder, t, err)
    if (allocated(err)) call discard_temporaries(t)
  end subroutine keep_mesh

  !> The cache folder is missing (make_folders makes a real one), or is a
  !> folder that is where its name says: its real path is its parent's real
  !> path and its own name, so neither it nor a link on the way was planted.
  logical function own_folder(folder) result(ok)
    character(len=*), intent(in) :: folder
    character(len=:), allocatable :: real, parent
    logical :: found
    ok = file_kind(folder) == c2d_missing
    if (ok) return
    call real_path(folder, real, found)
    if (found) call real_path(folder_of(folder), parent, found)
    if (found) ok = real == parent // '/' // folder(index(folder, '/', back=.true.) + 1:)
  end function own_folder

  !> The bytes of text to the file at path (a temporary's io_path).
  subroutine write_bytes(path, text, err)
    character(len=*), intent(in) :: path, text
    type(error_t), allocatable, intent(out) :: err
    integer :: u, ios
    open(newunit=u, file=path, access='stream', form='unformatted', status='old', action='write', iostat=ios)
    if (ios == 0) then
      write(u, iostat=ios) text
      close(u)
    end if
    if (ios /= 0) call set_error(err, path // ': cannot write', error_input)
  end subroutine write_bytes

  !> geo-HASH: HASH the 16 hex digits of two 31-bit polynomial hashes of key
  !> (the arithmetic stays below 2^62: no overflow in 64-bit integers).
  function entry_name(key) result(name)
    character(len=*), intent(in) :: key
    character(len=:), allocatable :: name
    integer(i8), parameter :: prime(2) = [2147483647_i8, 2147483629_i8], base(2) = [257_i8, 65599_i8]
    integer(i8) :: h(2)
    integer :: i
    character(len=16) :: hex
    h = 0
    do i = 1, len(key)
      h = mod(h * base + iachar(key(i:i)) + 1, prime)
    end do
    write(hex, '(z8.8,z8.8)') h(1), h(2)
    name = 'geo-' // hex
  end function entry_name

end module mesh_cache
