!> Unit test of results_writer: the strings of results_t (the deck's
!> parameters, the FIX labels, the RIGID names, the unheld modes, the
!> effects, the method and the ordering) survive every way the program copies
!> a results_t: intrinsic assignment both ways (a load step's results start
!> from an empty one), an intent(out) argument (a step's solve returns its
!> results so) and a function result; and the
!> summary written from a copy holds each of them on its line.
program test_results_writer
  use kinds, only: dp
  use results_writer, only: results_t, string_t, write_summary
  use errors, only: error_t
  use testing, only: check, finish_tests
  implicit none
  type(results_t) :: r, saved, passed, returned
  ! lengths that differ, the longest not first: a deferred-length character
  ! array would hold them all at one length
  character(len=*), parameter :: params(3) = [character(len=24) :: 'mu 0.3', 'thickness 2.5e-3', 'g 9.81']
  character(len=*), parameter :: labels(3) = [character(len=24) :: 'slab:bottom', 'punch:top_edge', 'b:x']
  character(len=*), parameter :: rigids(2) = [character(len=24) :: 'floor', 'die_of_the_press']
  character(len=*), parameter :: modes(2) = [character(len=48) :: 'slab translation 1 0', &
                                             'punch rotation 0.5 -1.25']
  character(len=*), parameter :: path = 'test_results_writer.summary'
  integer :: k

  call fill(r)
  call check(holds(r), 'results_t strings as set')

  saved = r                                             ! a copy ...
  call check(holds(saved), 'assignment: every string survives')
  r%effects = 'changed'
  r%parameter(1)%s = 'changed'
  r%fix_label(2)%s = 'changed'
  call check(holds(saved), 'assignment: the copy owns its strings')
  r = saved                                             ! ... and back
  call check(holds(r), 'assignment back: every string survives')

  call copy_out(saved, passed)
  call check(holds(passed), 'intent(out) argument: every string survives')
  returned = copied(passed)
  call check(holds(returned), 'function result: every string survives')
  r = copied(returned)
  call check(holds(r), 'function result assigned over an allocated one: every string survives')

  call write_summary_of(copied(r), path)
  do k = 1, size(params)
    call check(has_line(path, 'parameter ' // trim(params(k))), 'summary line parameter ' // trim(params(k)))
  end do
  do k = 1, size(labels)
    call check(has_line(path, 'reaction ' // trim(labels(k)) // ' ', prefix=.true.), 'summary line reaction ' // trim(labels(k)))
  end do
  do k = 1, size(rigids)
    call check(has_line(path, 'rigid ' // trim(rigids(k)) // ' ', prefix=.true.), 'summary line rigid ' // trim(rigids(k)))
  end do
  do k = 1, size(modes)
    call check(has_line(path, 'unheld_mode ' // trim(modes(k))), 'summary line unheld_mode ' // trim(modes(k)))
  end do
  call check(has_line(path, 'effects elasticity contact rigid_obstacle'), 'summary line effects')
  call remove(path)
  call finish_tests()

contains

  !> A results_t with every string set and the arrays the summary reads.
  subroutine fill(r)
    type(results_t), intent(out) :: r
    r%effects = 'elasticity contact rigid_obstacle'
    r%lcp_method = 'lemke'
    r%ordering = 'amd(nodes)+last'
    r%parameter = strings(params)
    r%fix_label = strings(labels)
    r%rigid_name = strings(rigids)
    r%unheld_mode = strings(modes)
    allocate(r%u(4), source=0.0_dp)
    allocate(r%reaction(2, size(labels)), source=1.0_dp)
    allocate(r%rigid(6, size(rigids)), source=0.5_dp)
  end subroutine fill

  !> Each of list, its trailing blanks trimmed.
  function strings(list) result(s)
    character(len=*), intent(in) :: list(:)
    type(string_t), allocatable :: s(:)
    integer :: k
    allocate(s(size(list)))
    do k = 1, size(list)
      s(k)%s = trim(list(k))
    end do
  end function strings

  !> Every string of r as fill set it, at its own length.
  logical function holds(r)
    type(results_t), intent(in) :: r
    holds = same(r%parameter, params) .and. same(r%fix_label, labels) .and. same(r%rigid_name, rigids) .and. &
            same(r%unheld_mode, modes)
    if (.not. (allocated(r%effects) .and. allocated(r%lcp_method) .and. allocated(r%ordering))) then
      holds = .false.
      return
    end if
    holds = holds .and. r%effects == 'elasticity contact rigid_obstacle' .and. len(r%effects) == 33 .and. &
            r%lcp_method == 'lemke' .and. r%ordering == 'amd(nodes)+last'
  end function holds

  logical function same(got, expected)
    type(string_t), allocatable, intent(in) :: got(:)
    character(len=*), intent(in) :: expected(:)
    integer :: k
    same = allocated(got)
    if (.not. same) return
    same = size(got) == size(expected)
    if (.not. same) return
    do k = 1, size(got)
      if (.not. allocated(got(k)%s)) then
        same = .false.
        return
      end if
      same = same .and. len(got(k)%s) == len_trim(expected(k)) .and. got(k)%s == trim(expected(k))
    end do
  end function same

  subroutine copy_out(a, b)
    type(results_t), intent(in) :: a
    type(results_t), intent(out) :: b
    b = a
  end subroutine copy_out

  function copied(a) result(b)
    type(results_t), intent(in) :: a
    type(results_t) :: b
    b = a
  end function copied

  subroutine write_summary_of(r, path)
    type(results_t), intent(in) :: r
    character(len=*), intent(in) :: path
    type(error_t), allocatable :: err
    call write_summary(path, r, err)
    call check(.not. allocated(err), 'write_summary')
  end subroutine write_summary_of

  !> Whether the file has the line `text` (or a line that starts with it).
  logical function has_line(path, text, prefix)
    character(len=*), intent(in) :: path, text
    logical, intent(in), optional :: prefix
    character(len=1024) :: line
    integer :: u, ios
    logical :: starts
    starts = .false.
    if (present(prefix)) starts = prefix
    has_line = .false.
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (starts) then
        has_line = index(line, text) == 1
      else
        has_line = line == text
      end if
      if (has_line) exit
    end do
    close(u)
  end function has_line

  subroutine remove(path)
    character(len=*), intent(in) :: path
    integer :: u, ios
    open(newunit=u, file=path, status='old', iostat=ios)
    if (ios == 0) close(u, status='delete')
  end subroutine remove

end program test_results_writer
