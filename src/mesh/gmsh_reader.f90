!> gmsh_reader: read a gmsh mesh file (MSH ASCII, format 2.2 or 4.1) into a
!> mesh_t (gmsh_runner runs gmsh on a .geo file).
!>
!> Layers, each in its file:
!>   msh_text       the file in memory, its lines and items, numbers, messages
!>   msh_sections   the sections ($MeshFormat, $PhysicalNames, $Entities,
!>                  $PartitionedEntities, $Nodes; unknown ones skipped) into msh_data_t
!>   msh_elements   the $Elements section
!>   msh_data       what the sections hold, as read
!>   msh_mesh       the mesh_t built from it: repeated elements merged, boundaries
!>                  from physical curves and points, regions from physical surfaces
!>
!> What is read
!>   - nodes (any tags, z = 0 up to 1e-10 of the extent); 2D elements: 3-node
!>     triangles and 4-node quadrangles, or second order: 6-node triangles, 8-
!>     and 9-node quadrangles, with the mid-side nodes where gmsh put them
!>     (curved edges); 2- and 3-node lines and points of physical groups;
!>   - the mesh is left as read: compaction of unused nodes, orientation and
!>     quality checks are the caller's (finalize_mesh of module mesh).
!>
!> Errors
!>   The first defect found is reported to diag as `FILE:LINE: what is wrong
!>   (what was expected)` with the line echoed, and reading stops; the mesh is
!>   then returned empty.  Memory that runs out while the file is read or the
!>   mesh built is `out of memory while reading the mesh file FILE (about N MB
!>   needed)`, in err (exit 1), not a defect of the file.
!>
!> Speed
!>   Reading costs O(file size): items are parsed in place, node tags looked
!>   up in a table tag -> node when they are dense, repeated elements found by
!>   a counting sort on their lowest node; the file is split into lines on the
!>   threads, and so are the data lines of a block (doc/performance.md,
!>   "Reading the mesh file").
!>
!> Programming interface
!>   read_gmsh_file(path, mesh, diag [, err])
!>        read the MSH file path into mesh; errors go to diag, out of memory to
!>        err (to diag, as a file-level message, when err is absent)
module gmsh_reader
  use kinds, only: i8
  use errors, only: diag_t, add_error, error_t, set_out_of_memory
  use mesh, only: mesh_t
  use msh_text, only: msh_text_t, load_text
  use msh_data, only: msh_data_t
  use msh_sections, only: read_sections
  use msh_mesh, only: build_mesh
  implicit none
  private
  public :: read_gmsh_file

contains

  !> Read a gmsh MSH ASCII file (format 2.2 or 4.1) into a mesh.
  !>   path (in)    file to open; also the name used in messages
  !>   mesh (out)   nodes, elements, named boundaries and regions as in the file;
  !>                empty (nnode = nelem = 0) when an error was found
  !>   diag (inout) receives one message for the first defect of the file
  !>   err  (out, optional) allocated when memory ran out (error_numerical); when
  !>                absent, that is a file-level message of diag
  subroutine read_gmsh_file(path, mesh, diag, err)
    character(len=*), intent(in) :: path
    type(mesh_t), intent(out) :: mesh
    type(diag_t), intent(inout) :: diag
    type(error_t), allocatable, intent(out), optional :: err
    type(msh_text_t) :: t
    type(msh_data_t) :: d
    type(error_t), allocatable :: e
    integer(i8) :: bytes

    t%path = path
    call load_text(t, e)
    if (.not. allocated(e)) call read_sections(t, d, e)
    if (.not. allocated(e)) call build_mesh(d, mesh, e)
    if (.not. allocated(e)) return
    if (.not. e%no_memory) then                ! a defect of the file: FILE:LINE, the line echoed
      if (allocated(e%echo)) then
        call add_error(diag, path, e%line, e%message, echo=e%echo)
      else
        call add_error(diag, path, e%line, e%message)
      end if
      return
    end if
    ! the layers below say what ran out; the message names the file
    bytes = e%bytes                            ! (e is remade: not e%bytes itself as the argument)
    call set_out_of_memory(e, 'reading the mesh file ' // path, bytes)
    if (present(err)) then
      call move_alloc(e, err)
    else
      call add_error(diag, path, 0, e%message)
    end if
  end subroutine read_gmsh_file

end module gmsh_reader
