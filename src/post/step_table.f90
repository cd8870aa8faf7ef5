!> step_table: the columns of NAME_steps.csv, a load step's row and the
!> header that names it, built by one routine so that the two cannot drift
!> apart.  Every column name is unique and says what it holds (doc/outputs.md,
!> "Step table"): KEY_LABEL_COMPONENT after the summary line it matches,
!> reaction_BODY:BOUNDARY_fx for `reaction BODY:BOUNDARY Fx Fy`,
!> contact_force_PAIR_fx for `contact_force PAIR Fx Fy`, rigid_NAME_ux for
!> `rigid NAME ux uy rz fx fy m`, spring_BODY:BOUNDARY_fx for `spring
!> BODY:BOUNDARY Fx Fy`.  Two FIX (or SPRING) statements on one boundary give
!> it one pair of columns, their sum (the force the boundary takes).
!>
!> Why it exists: the application names and commits files; what a step's
!> row holds is a list of its own that grows with the results.
!>
!> Programming interface
!>   step_columns(prob, kstep, res, iterations, header, values, whole)
!>        step kstep's row from its results res (engineering_results done) and
!>        its LCP iterations, the header line and which columns are integers
!>   step_header(prob)
!>        the header line alone, from the scene before anything is solved
!>        (OUTPUT x= names one of its columns: checked before the solve)
module step_table
  use kinds, only: dp
  use strings, only: int_to_str
  use problem, only: problem_t
  use results_writer, only: results_t, string_t
  use load_groups, only: group_factor, group_name
  use post_processing, only: fix_boundaries
  use contact_zones, only: zone_t
  use contact_set, only: has_friction
  implicit none
  private
  public :: step_columns, step_header

contains

  !> Step kstep's row of NAME_steps.csv and its header.
  !>   prob   (in)  the scene and contact set
  !>   kstep  (in)  the step, 1 .. steps
  !>   res    (in)  the step's results: reactions, contact forces, rigid results, zones, boundary_u
  !>   iterations (in) the step's LCP iterations
  !>   header (out) the header line (the same for every step)
  !>   values (out) (ncol) the row
  !>   whole  (out) (ncol) the column holds integers (step, counts)
  subroutine step_columns(prob, kstep, res, iterations, header, values, whole)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep, iterations
    type(results_t), intent(in) :: res
    character(len=:), allocatable, intent(out) :: header
    real(dp), allocatable, intent(out) :: values(:)
    logical, allocatable, intent(out) :: whole(:)
    type(string_t), allocatable :: labels(:)
    integer, allocatable :: of_fix(:)
    integer :: g, j, ip, n
    character(len=:), allocatable :: p, name
    real(dp), allocatable :: reaction(:,:)
    character(len=2), parameter :: rigid_part(6) = ['ux', 'uy', 'rz', 'fx', 'fy', 'm ']

    header = ''
    allocate(values(0), whole(0))
    call add('step', real(kstep, dp), .true.)
    do g = 1, size(prob%sc%ramp, 2)
      call add('factor_' // group_name(prob%sc, g), group_factor(prob%sc, g, real(kstep, dp)), .false.)
    end do
    call fix_boundaries(prob, labels, of_fix)
    allocate(reaction(2, size(labels)), source=0.0_dp)
    do j = 1, size(of_fix)
      reaction(:, of_fix(j)) = reaction(:, of_fix(j)) + res%reaction(:, j)
    end do
    do j = 1, size(labels)
      call add('reaction_' // labels(j)%s // '_fx', reaction(1, j), .false.)
      call add('reaction_' // labels(j)%s // '_fy', reaction(2, j), .false.)
    end do
    do j = 1, size(labels)
      call add('displacement_' // labels(j)%s // '_ux', res%boundary_u(1, j), .false.)
      call add('displacement_' // labels(j)%s // '_uy', res%boundary_u(2, j), .false.)
    end do
    do ip = 1, prob%cs%npair
      p = int_to_str(ip)                      ! the pair's number, or its CONTACT name= (the summary's PAIR)
      if (ip <= size(prob%deck%contacts)) then
        if (allocated(prob%deck%contacts(ip)%name)) then
          if (len(prob%deck%contacts(ip)%name) > 0) p = prob%deck%contacts(ip)%name
        end if
      end if
      call add('contact_force_' // p // '_fx', res%contact_force(1, ip), .false.)
      call add('contact_force_' // p // '_fy', res%contact_force(2, ip), .false.)
      call add_zone('contact', p, res%zones(ip)%contact)
      call add('peak_pressure_' // p // '_p', res%zones(ip)%peak(1), .false.)
      call add('peak_pressure_' // p // '_x', res%zones(ip)%peak(2), .false.)
      call add('peak_pressure_' // p // '_y', res%zones(ip)%peak(3), .false.)
      call add('center_of_pressure_' // p // '_x', res%zones(ip)%centre(1), .false.)
      call add('center_of_pressure_' // p // '_y', res%zones(ip)%centre(2), .false.)
      if (has_friction(prob%cs%pair(ip)%spec)) call add_zone('stick', p, res%zones(ip)%stick)
    end do
    do j = 1, size(prob%sc%rigids)
      name = prob%sc%rigids(j)%name
      do n = 1, 6
        call add('rigid_' // name // '_' // trim(rigid_part(n)), res%rigid(n, j), .false.)
      end do
    end do
    call add_springs()
    call add('active_nodes', real(res%active_nodes, dp), .true.)
    call add('lcp_iterations', real(iterations, dp), .true.)
    call add('certificate_complementarity', res%certificate(1), .false.)
    call add('certificate_cone', res%certificate(2), .false.)
    call add('certificate_equilibrium', res%certificate(3), .false.)

  contains

    subroutine add(column, value, integral)
      character(len=*), intent(in) :: column
      real(dp), intent(in) :: value
      logical, intent(in) :: integral
      if (size(values) > 0) header = header // ','
      header = header // column
      values = [values, value]
      whole = [whole, integral]
    end subroutine add

    !> The SPRINGs' force on their bodies, spring_BODY:BOUNDARY_fx, _fy, in
    !> the order of the deck's SPRING statements; two statements on one
    !> boundary give it one pair of columns, their sum (as the reactions).
    subroutine add_springs()
      type(string_t), allocatable :: label(:)
      real(dp), allocatable :: force(:,:)
      character(len=:), allocatable :: this
      integer :: b, k, m, nl, j
      if (.not. allocated(res%spring_force)) return
      allocate(label(size(res%spring_force, 2)), force(2, size(res%spring_force, 2)))
      nl = 0
      m = 0
      do b = 1, size(prob%deck%bodies)
        do k = 1, size(prob%deck%bodies(b)%springs)
          m = m + 1
          this = prob%deck%bodies(b)%name // ':' // prob%deck%bodies(b)%springs(k)%boundary
          if (nl > 0) then
            if (any([(label(j)%s == this, j = 1, nl)])) then
              j = findloc([(label(j)%s == this, j = 1, nl)], .true., dim=1)
              force(:, j) = force(:, j) + res%spring_force(:, m)
              cycle
            end if
          end if
          nl = nl + 1
          label(nl)%s = this
          force(:, nl) = res%spring_force(:, m)
        end do
      end do
      do k = 1, nl
        call add('spring_' // label(k)%s // '_fx', force(1, k), .false.)
        call add('spring_' // label(k)%s // '_fy', force(2, k), .false.)
      end do
    end subroutine add_springs

    !> A zone's columns: KIND_zone_P_x0 .. _length, KIND_zones_P_count, _length.
    subroutine add_zone(kind, pair, z)
      character(len=*), intent(in) :: kind, pair
      type(zone_t), intent(in) :: z
      call add(kind // '_zone_' // pair // '_x0', z%x0(1), .false.)
      call add(kind // '_zone_' // pair // '_y0', z%x0(2), .false.)
      call add(kind // '_zone_' // pair // '_x1', z%x1(1), .false.)
      call add(kind // '_zone_' // pair // '_y1', z%x1(2), .false.)
      call add(kind // '_zone_' // pair // '_length', z%length, .false.)
      call add(kind // '_zones_' // pair // '_count', real(z%count, dp), .true.)
      call add(kind // '_zones_' // pair // '_length', z%total, .false.)
    end subroutine add_zone

  end subroutine step_columns

  !> The header of NAME_steps.csv from the scene alone: step_columns on
  !> zero results of the sizes the scene gives (the names do not depend on
  !> the values), so the two cannot differ.
  !>   prob (in) the scene and contact set, built
  function step_header(prob) result(header)
    type(problem_t), intent(in) :: prob
    character(len=:), allocatable :: header
    type(results_t) :: res
    type(string_t), allocatable :: labels(:)
    integer, allocatable :: of_fix(:)
    real(dp), allocatable :: values(:)
    logical, allocatable :: whole(:)
    integer :: b

    call fix_boundaries(prob, labels, of_fix)
    allocate(res%reaction(2, size(of_fix)), res%boundary_u(2, size(labels)), res%contact_force(2, prob%cs%npair), &
             res%rigid(6, size(prob%sc%rigids)), source=0.0_dp)
    allocate(res%spring_force(2, sum([(size(prob%deck%bodies(b)%springs), b = 1, size(prob%deck%bodies))])), &
             source=0.0_dp)
    allocate(res%zones(prob%cs%npair))
    call step_columns(prob, 1, res, 0, header, values, whole)
  end function step_header

end module step_table
