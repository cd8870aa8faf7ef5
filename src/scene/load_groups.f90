!> load_groups: the load history of a deck (STEPS n, ramp=k0:k1, curve=NAME)
!> as load groups, one per distinct ramp or CURVE.  The loads and prescribed
!> values are kept per group (fgroup, ugroup); step k's are the groups
!> weighted by their factors at k.  A part of scene, which fills the groups
!> from the deck's statements; the solver's step loops ask the factors here.
!>
!> Programming interface
!>   type(load_groups_t)                  steps, the groups' ramps or curves, their forces and values
!>   collect_groups(deck, ndof, lg)       the deck's distinct load paths, the default ramp
!>        [0, steps] first; fgroup and ugroup (ndof, ngroup) zero
!>   ramp_group(lg, r, c)                 the group of ramp r, or of curve c when c > 0
!>   group_factor(lg, g, t), group_factors(lg, t)   load factor of group g (of every group) at step t
!>        (t real: a whole step k, or a point between two when a step is split)
!>   group_name(lg, g)                    the group's name for tables: the curve's or ramp_K0_K1
!>   load_factor(ramp, t)                 factor of ramp k0:k1 at step t
module load_groups
  use kinds, only: dp
  use strings, only: int_to_str
  use deck_reader, only: deck_t, curve_t, curve_factor
  implicit none
  private
  public :: load_groups_t, collect_groups, ramp_group, group_factor, group_factors, group_name, load_factor

  !> The load groups of a scene; fext and ubar of step k are
  !> sum_g f_g(k) fgroup(:, g) and sum_g f_g(k) ugroup(:, g).
  type :: load_groups_t
    integer :: steps = 1                      !< load steps
    integer, allocatable :: ramp(:,:)         !< (2, ngroup) distinct ramps k0:k1 ([0, 0] for a curve's group)
    integer, allocatable :: group_curve(:)    !< (ngroup) the curve of each group, 0 for a ramp's
    type(curve_t), allocatable :: curves(:)   !< the deck's CURVE statements
    real(dp), allocatable :: fgroup(:,:)      !< (ndof, ngroup) external forces of each group
    real(dp), allocatable :: ugroup(:,:)      !< (ndof, ngroup) prescribed values of each group
  end type load_groups_t

contains

  !> The distinct load paths of the deck's loads and prescribed values: ramps
  !> k0:k1 and curves, the default ramp [0, steps] first, then in the order
  !> the statements name them (GRAVITY; each body's FIX, loads, THERMAL,
  !> BODYFORCE; each RIGID's FIX and FORCE).
  !>   deck  (in)  the deck
  !>   ndof  (in)  the scene's dofs
  !>   lg    (out) steps, curves, ramp and group_curve; fgroup, ugroup (ndof, ngroup) zero
  subroutine collect_groups(deck, ndof, lg)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: ndof
    type(load_groups_t), intent(out) :: lg
    integer :: b, k, n
    integer, allocatable :: list(:,:)
    n = 1
    allocate(list(3, 8))
    list(:, 1) = [0, deck%steps, 0]
    if (deck%has_gravity) call add_path(deck%gravity_ramp, deck%gravity_curve, list, n)
    do b = 1, size(deck%bodies)
      associate(bd => deck%bodies(b))
        call add_paths(bd%fixes%ramp(1), bd%fixes%ramp(2), bd%fixes%curve, list, n)
        call add_paths(bd%loads%ramp(1), bd%loads%ramp(2), bd%loads%curve, list, n)
        do k = 1, size(bd%thermals)
          call add_path([0, deck%steps], bd%thermals(k)%curve, list, n)
        end do
        if (bd%has_bodyforce) call add_path(bd%bodyforce_ramp, bd%bodyforce_curve, list, n)
      end associate
    end do
    do b = 1, size(deck%rigids)
      associate(rd => deck%rigids(b))
        call add_paths(rd%fixes%ramp(1), rd%fixes%ramp(2), rd%fixes%curve, list, n)
        call add_paths(rd%forces%ramp(1), rd%forces%ramp(2), rd%forces%curve, list, n)
      end associate
    end do
    lg%steps = deck%steps
    lg%curves = deck%curves
    lg%ramp = list(1:2, 1:n)
    lg%group_curve = list(3, 1:n)
    allocate(lg%fgroup(ndof, n), lg%ugroup(ndof, n), source=0.0_dp)
  end subroutine collect_groups

  !> The paths of a list of statements, ramp k0(i):k1(i) or curve c(i) > 0,
  !> each added unless listed already (add_path).
  subroutine add_paths(k0, k1, c, list, n)
    integer, intent(in) :: k0(:), k1(:), c(:)
    integer, allocatable, intent(inout) :: list(:,:)
    integer, intent(inout) :: n
    integer :: i
    do i = 1, size(c)
      call add_path([k0(i), k1(i)], c(i), list, n)
    end do
  end subroutine add_paths

  !> Ramp r, or curve c when c > 0, added to the load paths unless listed already.
  !>   r, c (in)    the path: ramp k0:k1, or curve c > 0
  !>   list (inout) (3, capacity) the paths: [k0, k1, 0] or [0, 0, c]; grown when full
  !>   n    (inout) the paths in list
  subroutine add_path(r, c, list, n)
    integer, intent(in) :: r(2), c
    integer, allocatable, intent(inout) :: list(:,:)
    integer, intent(inout) :: n
    integer :: i, key(3)
    integer, allocatable :: grown(:,:)
    key = [r, 0]
    if (c > 0) key = [0, 0, c]
    do i = 1, n
      if (all(list(:, i) == key)) return
    end do
    if (n == size(list, 2)) then
      allocate(grown(3, 2 * n))
      grown(:, 1:n) = list
      call move_alloc(grown, list)
    end if
    n = n + 1
    list(:, n) = key
  end subroutine add_path

  !> Column of fgroup / ugroup holding ramp r, or curve c when c > 0.
  pure integer function ramp_group(lg, r, c) result(g)
    class(load_groups_t), intent(in) :: lg
    integer, intent(in) :: r(2), c
    do g = 1, size(lg%ramp, 2)
      if (c > 0) then
        if (lg%group_curve(g) == c) return
      else if (lg%group_curve(g) == 0 .and. lg%ramp(1, g) == r(1) .and. lg%ramp(2, g) == r(2)) then
        return
      end if
    end do
    g = 1
  end function ramp_group

  !> Load factor of group g at step t: its curve's value, or its ramp's.
  !>   t (in) the step: a whole step k, or a point between two (a split step)
  pure real(dp) function group_factor(lg, g, t) result(f)
    class(load_groups_t), intent(in) :: lg
    integer, intent(in) :: g
    real(dp), intent(in) :: t
    if (lg%group_curve(g) > 0) then
      f = curve_factor(lg%curves(lg%group_curve(g)), t)
    else
      f = load_factor(lg%ramp(:, g), t)
    end if
  end function group_factor

  !> The load factors f_g(t) of every group at step t.
  pure function group_factors(lg, t) result(f)
    class(load_groups_t), intent(in) :: lg
    real(dp), intent(in) :: t
    real(dp) :: f(size(lg%ramp, 2))
    integer :: g
    do g = 1, size(f)
      f(g) = group_factor(lg, g, t)
    end do
  end function group_factors

  !> Name of group g's load path for tables: the curve's name or ramp_K0_K1.
  function group_name(lg, g) result(name)
    class(load_groups_t), intent(in) :: lg
    integer, intent(in) :: g
    character(len=:), allocatable :: name
    if (lg%group_curve(g) > 0) then
      name = lg%curves(lg%group_curve(g))%name
    else
      name = 'ramp_' // int_to_str(lg%ramp(1, g)) // '_' // int_to_str(lg%ramp(2, g))
    end if
  end function group_name

  !> Load factor of ramp k0:k1 at step t: 0 up to k0, linear to 1 at k1, then 1.
  !> (t - k0 is exact for a whole step: the same factor as in integers.)
  pure real(dp) function load_factor(ramp, t) result(f)
    integer, intent(in) :: ramp(2)
    real(dp), intent(in) :: t
    f = min(1.0_dp, max(0.0_dp, (t - real(ramp(1), dp)) / real(ramp(2) - ramp(1), dp)))
  end function load_factor

end module load_groups
