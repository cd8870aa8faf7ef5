!> run_log: what a run tells its user as it goes, and its clock.
!>
!> Every layer that does a step of the run may say what it did (a line of
!> the run log on stdout, nothing with -q) and give a warning (stderr and the
!> summary's `warning CODE text`); the clock charges the seconds and CPU
!> seconds since the last lap to a phase.  One log_t is made by the program
!> and handed down explicitly to whatever needs it, so that no layer below
!> the application knows the run's state and none keeps module variables.
!>
!> Programming interface
!>   type(log_t)                 quiet flag, clock, phase times, warnings
!>   ph_mesh .. ph_total         the phases (index into log%time, log%cpu)
!>   nphase, phase_names         their number and the summary's names
!>   say(log, text)              one line of the run log (nothing when quiet)
!>   add_warning(log, code, text)  a warning: stderr (unless quiet), and kept for the summary
!>   start_clock(log)            the run's time zero
!>   lap(log, ph)                seconds since the last lap go to phase ph
!>   lap_shared(log, ph, share)  the same, shared between phases in proportions
!>   clock_seconds(log)          seconds since the last lap (the lap not taken)
module run_log
  use kinds, only: dp, i8
  use text_scan, only: string_t
  use system_binding, only: c2d_cpu_seconds
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  implicit none
  private
  public :: log_t, say, add_warning, start_clock, lap, lap_shared, clock_seconds
  public :: ph_mesh, ph_assemble, ph_factor, ph_condense, ph_lcp, ph_recover, ph_estimate, ph_output, ph_total
  public :: nphase, phase_names

  integer, parameter :: ph_mesh = 1, ph_assemble = 2, ph_factor = 3, ph_condense = 4, ph_lcp = 5, &
                        ph_recover = 6, ph_estimate = 7, ph_output = 8, ph_total = 9
  integer, parameter :: nphase = 9
  character(len=8), parameter :: phase_names(nphase) = &
    [character(len=8) :: 'mesh', 'assemble', 'factor', 'condense', 'lcp', 'recover', 'estimate', 'output', 'total']

  type :: log_t
    logical :: quiet = .false.                     !< -q: no run log, no warning on stderr
    integer(i8) :: t_start = 0, t_phase = 0        !< the run's start, the last lap (system_clock counts)
    real(dp) :: c_phase = 0                        !< the process's CPU seconds at the last lap
    real(dp) :: time(nphase) = 0                   !< seconds per phase_names (total: since t_start)
    real(dp) :: cpu(nphase) = 0                    !< CPU seconds per phase_names, gmsh's included (total: the process's)
    type(string_t), allocatable :: warning(:)      !< (nwarn) 'CODE text' of each warning, in order
  end type log_t

contains

  !> A line of the run log, unless quiet.
  !>   log  (in) its quiet flag
  !>   text (in) the line
  subroutine say(log, text)
    type(log_t), intent(in) :: log
    character(len=*), intent(in) :: text
    if (.not. log%quiet) write(output_unit, '(a)') text
  end subroutine say

  !> A warning: the run goes on, but its answer rests on something the user
  !> must know (an assumption of the model it has left, a pair that cannot
  !> touch).  The one way warnings are given: on stderr as
  !> `contact2d: warning: TEXT [CODE]` (unless quiet: only errors there), and
  !> kept for the summary's `warning CODE TEXT`, so that a batch script finds
  !> it.  The same warning given again (a load step measured twice) is kept once.
  !>   log  (inout) its quiet flag; warning gains the line
  !>   code (in)    one word naming the kind: locking, large_strain, large_rotation, ...
  !>   text (in)    what is wrong and what to do, one line; FILE:LINE: first
  !>                when a deck statement is the cause
  subroutine add_warning(log, code, text)
    type(log_t), intent(inout) :: log
    character(len=*), intent(in) :: code, text
    type(string_t), allocatable :: grown(:)
    integer :: k, n
    if (.not. allocated(log%warning)) allocate(log%warning(0))
    n = size(log%warning)
    do k = 1, n
      if (log%warning(k)%s == code // ' ' // text) return
    end do
    allocate(grown(n + 1))
    do k = 1, n
      call move_alloc(log%warning(k)%s, grown(k)%s)
    end do
    grown(n + 1)%s = code // ' ' // text
    call move_alloc(grown, log%warning)
    if (.not. log%quiet) write(error_unit, '(a)') 'contact2d: warning: ' // text // ' [' // code // ']'
  end subroutine add_warning

  !> The run's time zero: the phases are measured from here.
  subroutine start_clock(log)
    type(log_t), intent(inout) :: log
    call system_clock(log%t_start)
    log%t_phase = log%t_start
    log%c_phase = c2d_cpu_seconds()
  end subroutine start_clock

  !> Seconds since the last lap go to phase ph; the total is kept up to date.
  subroutine lap(log, ph)
    type(log_t), intent(inout) :: log
    integer, intent(in) :: ph
    call lap_shared(log, [ph], [1.0_dp])
  end subroutine lap

  !> Seconds and CPU seconds since the last lap, shared between the phases
  !> ph in the given proportions (two phases that ran side by side); the
  !> totals are the run's and the process's.
  !>   ph    (in) (m) the phases
  !>   share (in) (m) their shares, summing to 1
  subroutine lap_shared(log, ph, share)
    type(log_t), intent(inout) :: log
    integer, intent(in) :: ph(:)
    real(dp), intent(in) :: share(:)
    integer(i8) :: now, rate
    real(dp) :: cpu
    call system_clock(now, rate)
    log%time(ph) = log%time(ph) + share * real(now - log%t_phase, dp) / real(rate, dp)
    log%time(ph_total) = real(now - log%t_start, dp) / real(rate, dp)
    log%t_phase = now
    cpu = c2d_cpu_seconds()
    log%cpu(ph) = log%cpu(ph) + share * (cpu - log%c_phase)
    log%cpu(ph_total) = cpu
    log%c_phase = cpu
  end subroutine lap_shared

  !> Seconds since the last lap (no lap taken).
  real(dp) function clock_seconds(log) result(s)
    type(log_t), intent(in) :: log
    integer(i8) :: now, rate
    call system_clock(now, rate)
    s = real(now - log%t_phase, dp) / real(rate, dp)
  end function clock_seconds

end module run_log
