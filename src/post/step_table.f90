!> step_table: the columns of NAME_steps.csv, a load step's row and the
!> header that names it, built by one routine so that the two cannot drift
!> apart.  Every column name is unique and says what it holds (doc/outputs.md,
!> "Step table"): KEY_LABEL_COMPONENT after the summary line it matches,
!> reaction_BODY:BOUNDARY_fx for `reaction BODY:BOUNDARY Fx Fy`,
!> contact_force_PAIR_fx for `contact_force PAIR Fx Fy`, rigid_NAME_ux for
!> `rigid NAME ux uy rz fx fy m`, spring_BODY:BOUNDARY_fx for `spring
!> BODY:BOUNDARY Fx Fy`.  Two FIX (or SPRING) statements on one boundary give
!> it one pair of columns, their sum (the force the boundary takes).  A pair
!> with several zones has, as the sweep table names repeated summary lines,
!> the first zone's columns under the one-zone names and zone k's with `_k`
!> after them (contact_zone_PAIR_x0_2, peak_pressure_PAIR_p_2, ...), as many
!> as the pair's largest count over the steps so far (zone_sets), 0 where a
!> step has fewer: the header stays one for every step.
!>
!> Why it exists: the application names and commits files; what a step's
!> row holds is a list of its own that grows with the results.
!>
!> Programming interface
!>   step_columns(prob, kstep, res, iterations, sets, header, values, whole)
!>        step kstep's row from its results res (engineering_results done) and
!>        its LCP iterations, the header line and which columns are integers
!>   step_header(prob)
!>        the header line alone, from the scene before anything is solved
!>        (OUTPUT x= names one of its columns: checked before the solve),
!>        one zone's columns per pair
!>   zone_sets(res, sets)   the zone columns each pair needs: the most zones so far
!>   widen_rows(old, new, table)   a table's rows under header old moved to the columns of header new
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
  public :: step_columns, step_header, zone_sets, widen_rows

contains

  !> Step kstep's row of NAME_steps.csv and its header.
  !>   prob   (in)  the scene and contact set
  !>   kstep  (in)  the step, 1 .. steps
  !>   res    (in)  the step's results: reactions, contact forces, rigid results, zones, boundary_u
  !>   iterations (in) the step's LCP iterations
  !>   sets   (in)  (2, npair) how many contact zones (1, :) and stick zones (2, :)
  !>                each pair has columns for (zone_sets; at least 1)
  !>   header (out) the header line (the same for every step with the same sets)
  !>   values (out) (ncol) the row
  !>   whole  (out) (ncol) the column holds integers (step, counts)
  subroutine step_columns(prob, kstep, res, iterations, sets, header, values, whole)
    type(problem_t), intent(in) :: prob
    integer, intent(in) :: kstep, iterations, sets(:,:)
    type(results_t), intent(in) :: res
    character(len=:), allocatable, intent(out) :: header
    real(dp), allocatable, intent(out) :: values(:)
    logical, allocatable, intent(out) :: whole(:)
    type(string_t), allocatable :: labels(:)
    integer, allocatable :: of_fix(:)
    integer :: g, j, ip, n, k
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
      associate(z => res%zones(ip))
        call add_zone('contact', p, z%contact, sets(1, ip))
        do k = 1, sets(1, ip)
          call add('peak_pressure_' // p // '_p' // nth(k), zone_value(z%peak, 1, k), .false.)
          call add('peak_pressure_' // p // '_x' // nth(k), zone_value(z%peak, 2, k), .false.)
          call add('peak_pressure_' // p // '_y' // nth(k), zone_value(z%peak, 3, k), .false.)
        end do
        do k = 1, sets(1, ip)
          call add('center_of_pressure_' // p // '_x' // nth(k), zone_value(z%centre, 1, k), .false.)
          call add('center_of_pressure_' // p // '_y' // nth(k), zone_value(z%centre, 2, k), .false.)
        end do
        if (has_friction(prob%cs%pair(ip)%spec)) call add_zone('stick', p, z%stick, sets(2, ip))
      end associate
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
    ! finite strain: the step's Newton iterations (the solve's iterations above are these)
    if (allocated(res%newton)) call add('newton_iterations', res%newton(2, size(res%newton, 2)), .true.)
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

    !> A pair's zone columns: KIND_zone_P_x0 .. _length for each of its m
    !> zones, then KIND_zones_P_count, _length.
    subroutine add_zone(kind, pair, z, m)
      character(len=*), intent(in) :: kind, pair
      type(zone_t), intent(in) :: z
      integer, intent(in) :: m
      integer :: k
      do k = 1, m
        call add(kind // '_zone_' // pair // '_x0' // nth(k), zone_value(z%x0, 1, k), .false.)
        call add(kind // '_zone_' // pair // '_y0' // nth(k), zone_value(z%x0, 2, k), .false.)
        call add(kind // '_zone_' // pair // '_x1' // nth(k), zone_value(z%x1, 1, k), .false.)
        call add(kind // '_zone_' // pair // '_y1' // nth(k), zone_value(z%x1, 2, k), .false.)
        if (k <= z%count) then
          call add(kind // '_zone_' // pair // '_length' // nth(k), z%length(k), .false.)
        else
          call add(kind // '_zone_' // pair // '_length' // nth(k), 0.0_dp, .false.)
        end if
      end do
      call add(kind // '_zones_' // pair // '_count', real(z%count, dp), .true.)
      call add(kind // '_zones_' // pair // '_length', z%total, .false.)
    end subroutine add_zone

  end subroutine step_columns

  !> The header of NAME_steps.csv from the scene alone: step_columns on
  !> zero results of the sizes the scene gives (the names do not depend on
  !> the values), so the two cannot differ; one zone's columns per pair
  !> (the zones a step finds add columns COLUMN_k after them).
  !>   prob (in) the scene and contact set, built
  function step_header(prob) result(header)
    type(problem_t), intent(in) :: prob
    character(len=:), allocatable :: header
    type(results_t) :: res
    type(string_t), allocatable :: labels(:)
    integer, allocatable :: of_fix(:)
    real(dp), allocatable :: values(:)
    logical, allocatable :: whole(:)
    integer, allocatable :: sets(:,:)
    integer :: b

    call fix_boundaries(prob, labels, of_fix)
    allocate(res%reaction(2, size(of_fix)), res%boundary_u(2, size(labels)), res%contact_force(2, prob%cs%npair), &
             res%rigid(6, size(prob%sc%rigids)), source=0.0_dp)
    allocate(res%spring_force(2, sum([(size(prob%deck%bodies(b)%springs), b = 1, size(prob%deck%bodies))])), &
             source=0.0_dp)
    allocate(res%zones(prob%cs%npair))
    allocate(sets(2, prob%cs%npair), source=1)
    call step_columns(prob, 1, res, 0, sets, header, values, whole)
  end function step_header

  !> The suffix of zone k's columns: none for the first, `_k` after.
  pure function nth(k) result(suffix)
    integer, intent(in) :: k
    character(len=:), allocatable :: suffix
    suffix = ''
    if (k > 1) suffix = '_' // int_to_str(k)
  end function nth

  !> Entry (i, k) of a per-zone array, 0 past its zones (a step with fewer).
  pure real(dp) function zone_value(a, i, k) result(v)
    real(dp), allocatable, intent(in) :: a(:,:)
    integer, intent(in) :: i, k
    v = 0.0_dp
    if (.not. allocated(a)) return
    if (k <= size(a, 2)) v = a(i, k)
  end function zone_value

  !> The zone columns each pair needs: sets raised to the step's counts.
  !>   res  (in)    the step's results (zones)
  !>   sets (inout) (2, npair) the contact (1, :) and stick (2, :) zones each
  !>                pair has columns for; allocated with 1 each on the first call
  subroutine zone_sets(res, sets)
    type(results_t), intent(in) :: res
    integer, allocatable, intent(inout) :: sets(:,:)
    integer, allocatable :: grown(:,:)
    integer :: ip, npair
    npair = 0
    if (allocated(res%zones)) npair = size(res%zones)
    if (.not. allocated(sets)) allocate(sets(2, 0))
    if (size(sets, 2) < npair) then
      allocate(grown(2, npair), source=1)
      grown(:, 1:size(sets, 2)) = sets
      call move_alloc(grown, sets)
    end if
    do ip = 1, npair
      sets(1, ip) = max(sets(1, ip), res%zones(ip)%contact%count)
      sets(2, ip) = max(sets(2, ip), res%zones(ip)%stick%count)
    end do
  end subroutine zone_sets

  !> The rows of a table written under header old moved to the columns of
  !> header new, which holds each of old's names (more zone columns); a new
  !> column is 0 in them.
  !>   old   (in)    the table's header, names separated by commas
  !>   new   (in)    the wider header
  !>   table (inout) (ncol, nrow) the rows: ncol = the names of old on entry, of new on exit
  subroutine widen_rows(old, new, table)
    character(len=*), intent(in) :: old, new
    real(dp), allocatable, intent(inout) :: table(:,:)
    real(dp), allocatable :: wide(:,:)
    type(string_t), allocatable :: from(:), to(:)
    integer :: c, j
    call split_names(old, from)
    call split_names(new, to)
    allocate(wide(size(to), size(table, 2)), source=0.0_dp)
    do c = 1, size(from)
      do j = 1, size(to)
        if (to(j)%s == from(c)%s) then
          wide(j, :) = table(c, :)
          exit
        end if
      end do
    end do
    call move_alloc(wide, table)
  end subroutine widen_rows

  !> The names of a header line, split at its commas.
  subroutine split_names(header, names)
    character(len=*), intent(in) :: header
    type(string_t), allocatable, intent(out) :: names(:)
    integer :: a, b, n
    allocate(names(count([(header(a:a) == ',', a = 1, len(header))]) + 1))
    a = 1
    do n = 1, size(names)
      b = index(header(a:), ',')
      if (b == 0) then
        names(n)%s = header(a:)
      else
        names(n)%s = header(a:a + b - 2)
        a = a + b
      end if
    end do
  end subroutine split_names

end module step_table
