!> results_writer: the output files of DECK.md — the VTK legacy file, the
!> contact table (CSV) and the summary — written atomically: each goes to a
!> temporary name first, and commit_outputs renames them all only after every
!> one was written, so a failed run never leaves half-written files nor
!> overwrites the outputs of an earlier successful run.
!>
!> Programming interface
!>   type(results_t)      everything a run computed that the files report
!>   write_vtk(path, title, bodies, r, ok)
!>   write_contact_csv(path, cs, r, ok)
!>   write_summary(path, r, ok)
!>   commit_outputs(tmp, final, ok)      rename tmp(i) -> final(i)
!>   discard_outputs(tmp)                remove the temporary files
module results_writer
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use kinds, only: dp, i8
  use body, only: body_t
  use contact_set, only: contact_set_t
  use diagnostics, only: int_to_str
  implicit none
  private
  public :: results_t, write_vtk, write_contact_csv, write_summary, commit_outputs, discard_outputs
  public :: phase_names, nphase

  integer, parameter :: nphase = 8
  character(len=8), parameter :: phase_names(nphase) = &
    [character(len=8) :: 'mesh', 'assemble', 'factor', 'condense', 'lcp', 'recover', 'output', 'total']

  type :: results_t
    character(len=:), allocatable :: effects     !< effects simulated
    integer :: nfree = 0                         !< free equations
    real(dp), allocatable :: u(:)                !< (ndof) displacements
    real(dp), allocatable :: stress(:,:)         !< (3, nelem) sxx syy sxy per element
    real(dp), allocatable :: vm(:)               !< (nelem) von Mises
    real(dp), allocatable :: node_pressure(:)    !< (ndof/2) contact pressure at nodes (0 elsewhere)
    real(dp), allocatable :: node_gap(:)         !< (ndof/2) final gap at slave nodes (0 elsewhere)
    real(dp), allocatable :: mu(:)               !< (nrow) multipliers (nodal forces)
    real(dp), allocatable :: gap(:)              !< (nrow) final gaps
    real(dp), allocatable :: pressure(:)         !< (nrow) pressures mu / w
    integer, allocatable :: status(:)            !< (nrow) 1 contact, 0 open
    real(dp), allocatable :: reaction(:,:)       !< (2, nfix)
    character(len=:), allocatable :: fix_label(:) !< (nfix) BODY:BOUNDARY
    real(dp) :: energy = 0
    character(len=:), allocatable :: lcp_method
    integer :: lcp_iterations = 0
    real(dp) :: lcp_residual = 0
    real(dp) :: complementarity = 0, min_gap = 0, min_pressure = 0
    integer :: contact_nodes = 0, active_nodes = 0, redundant = 0
    integer(i8) :: factor_nnz = 0
    real(dp) :: time(nphase) = 0                 !< seconds per phase_names
  end type results_t

  interface
    integer(c_int) function c_rename(from, to) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: from(*), to(*)
    end function c_rename
  end interface

contains

  !> VTK legacy unstructured grid of every body (see DECK.md).
  subroutine write_vtk(path, title, bodies, r, ok)
    character(len=*), intent(in) :: path, title
    type(body_t), intent(in) :: bodies(:)
    type(results_t), intent(in) :: r
    logical, intent(out) :: ok
    integer :: u, ios, b, e, a, nnode, nelem, ncon, k, nen
    character(len=256) :: head

    nnode = 0; nelem = 0; ncon = 0
    do b = 1, size(bodies)
      nnode = nnode + bodies(b)%mesh%nnode
      nelem = nelem + bodies(b)%mesh%nelem
      ncon = ncon + bodies(b)%mesh%nelem + sum(bodies(b)%mesh%nen)
    end do
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    ok = ios == 0
    if (.not. ok) return
    head = title
    if (len_trim(head) == 0) head = 'contact2d'
    write(u, '(a)') '# vtk DataFile Version 3.0'
    write(u, '(a)') trim(head)
    write(u, '(a)') 'ASCII'
    write(u, '(a)') 'DATASET UNSTRUCTURED_GRID'
    write(u, '(a,i0,a)') 'POINTS ', nnode, ' double'
    do b = 1, size(bodies)
      do a = 1, bodies(b)%mesh%nnode
        write(u, '(2(1x,es17.9e3),a)') bodies(b)%mesh%x(:, a), ' 0'
      end do
    end do
    write(u, '(a,i0,1x,i0)') 'CELLS ', nelem, ncon
    k = 0
    do b = 1, size(bodies)
      do e = 1, bodies(b)%mesh%nelem
        nen = bodies(b)%mesh%nen(e)
        write(u, '(i0,4(1x,i0))') nen, bodies(b)%mesh%conn(1:nen, e) - 1 + k
      end do
      k = k + bodies(b)%mesh%nnode
    end do
    write(u, '(a,i0)') 'CELL_TYPES ', nelem
    do b = 1, size(bodies)
      do e = 1, bodies(b)%mesh%nelem
        write(u, '(i0)') merge(5, 9, bodies(b)%mesh%nen(e) == 3)
      end do
    end do
    write(u, '(a,i0)') 'POINT_DATA ', nnode
    write(u, '(a)') 'VECTORS displacement double'
    do a = 1, nnode
      write(u, '(2(1x,es17.9e3),a)') r%u(2 * a - 1:2 * a), ' 0'
    end do
    write(u, '(a)') 'SCALARS contact_pressure double 1'
    write(u, '(a)') 'LOOKUP_TABLE default'
    write(u, '(1x,es17.9e3)') r%node_pressure
    write(u, '(a)') 'SCALARS gap double 1'
    write(u, '(a)') 'LOOKUP_TABLE default'
    write(u, '(1x,es17.9e3)') r%node_gap
    write(u, '(a,i0)') 'CELL_DATA ', nelem
    write(u, '(a)') 'SCALARS body int 1'
    write(u, '(a)') 'LOOKUP_TABLE default'
    do b = 1, size(bodies)
      do e = 1, bodies(b)%mesh%nelem
        write(u, '(i0)') b
      end do
    end do
    write(u, '(a)') 'SCALARS stress double 3'
    write(u, '(a)') 'LOOKUP_TABLE default'
    write(u, '(3(1x,es17.9e3))') r%stress
    write(u, '(a)') 'SCALARS von_mises double 1'
    write(u, '(a)') 'LOOKUP_TABLE default'
    write(u, '(1x,es17.9e3)') r%vm
    close(u, iostat=ios)
    ok = ios == 0
  end subroutine write_vtk

  !> Contact table: one row per slave node of each pair, along the boundary.
  !> Slave nodes with no master opposite (outside the effective contact zone)
  !> have empty gap0 and gap fields and status -1.
  subroutine write_contact_csv(path, cs, r, ok)
    character(len=*), intent(in) :: path
    type(contact_set_t), intent(in) :: cs
    type(results_t), intent(in) :: r
    logical, intent(out) :: ok
    integer :: u, ios, ip, i, row
    character(len=32) :: sx(4)
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    ok = ios == 0
    if (.not. ok) return
    write(u, '(a)') 'pair,s,x,y,gap0,gap,pressure,status'
    do ip = 1, cs%npair
      associate(pr => cs%pair(ip), mo => cs%pair(ip)%mortar)
        do i = 1, size(pr%snode)
          write(sx(1), '(es24.16e3)') mo%arc(i)
          write(sx(2), '(es24.16e3)') pr%xs(1, i)
          write(sx(3), '(es24.16e3)') pr%xs(2, i)
          if (mo%first > 0 .and. i >= mo%first .and. i <= mo%last) then
            row = pr%row0 + i - mo%first + 1
            write(u, '(a,i0,a,i0)') int_to_str(ip) // ',' // trim(adjustl(sx(1))) // ',' // &
              trim(adjustl(sx(2))) // ',' // trim(adjustl(sx(3))) // ',' // num(mo%gap0(i)) // ',' // &
              num(r%gap(row)) // ',' // num(r%pressure(row)) // ',', r%status(row), ''
          else
            write(u, '(a)') int_to_str(ip) // ',' // trim(adjustl(sx(1))) // ',' // &
              trim(adjustl(sx(2))) // ',' // trim(adjustl(sx(3))) // ',,,0,-1'
          end if
        end do
      end associate
    end do
    close(u, iostat=ios)
    ok = ios == 0
  end subroutine write_contact_csv

  function num(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    write(buf, '(es24.16e3)') x
    s = trim(adjustl(buf))
  end function num

  !> The summary: one `key value...` per line (DECK.md), plus extra keys.
  subroutine write_summary(path, r, ok)
    character(len=*), intent(in) :: path
    type(results_t), intent(in) :: r
    logical, intent(out) :: ok
    integer :: u, ios, k
    open(newunit=u, file=path, status='replace', action='write', form='formatted', iostat=ios)
    ok = ios == 0
    if (.not. ok) return
    write(u, '(a)') 'effects ' // r%effects
    write(u, '(a,i0)') 'dofs ', size(r%u)
    write(u, '(a,i0)') 'free_dofs ', r%nfree
    write(u, '(a,i0)') 'contact_nodes ', r%contact_nodes
    write(u, '(a,i0)') 'active_nodes ', r%active_nodes
    write(u, '(a,i0)') 'redundant_constraints ', r%redundant
    write(u, '(a)') 'lcp_method ' // r%lcp_method
    write(u, '(a,i0)') 'lcp_iterations ', r%lcp_iterations
    write(u, '(a,a)') 'lcp_residual ', num(r%lcp_residual)
    write(u, '(a,a)') 'complementarity ', num(r%complementarity)
    write(u, '(a,a)') 'min_gap ', num(r%min_gap)
    write(u, '(a,a)') 'min_pressure ', num(r%min_pressure)
    write(u, '(a,a)') 'energy ', num(r%energy)
    do k = 1, size(r%fix_label)
      write(u, '(a)') 'reaction ' // trim(r%fix_label(k)) // ' ' // num(r%reaction(1, k)) // ' ' // num(r%reaction(2, k))
    end do
    write(u, '(a,i0)') 'factor_nnz ', r%factor_nnz
    do k = 1, nphase
      write(u, '(a,a)') 'time_' // trim(phase_names(k)) // ' ', num(r%time(k))
    end do
    close(u, iostat=ios)
    ok = ios == 0
  end subroutine write_summary

  !> Rename every tmp(i) to final(i); ok = .false. at the first failure.
  subroutine commit_outputs(tmp, final, ok)
    character(len=*), intent(in) :: tmp(:), final(:)
    logical, intent(out) :: ok
    integer :: i
    ok = .true.
    do i = 1, size(tmp)
      if (len_trim(tmp(i)) == 0) cycle
      if (c_rename(trim(tmp(i)) // c_null_char, trim(final(i)) // c_null_char) /= 0) then
        ok = .false.
        return
      end if
    end do
  end subroutine commit_outputs

  subroutine discard_outputs(tmp)
    character(len=*), intent(in) :: tmp(:)
    integer :: i, u, ios
    logical :: there
    do i = 1, size(tmp)
      if (len_trim(tmp(i)) == 0) cycle
      inquire(file=trim(tmp(i)), exist=there)
      if (.not. there) cycle
      open(newunit=u, file=trim(tmp(i)), status='old', iostat=ios)
      if (ios == 0) close(u, status='delete', iostat=ios)
    end do
  end subroutine discard_outputs

end module results_writer
