!> Unit tests of scene's step routines, on tests/unit/data/scene_thermal.deck
!> (three bodies over STEPS 4: hot on the default ramp, curved on a CURVE,
!> cold without THERMAL).
!>
!> - step_thermal_strains: each element's alpha dT at each step against the
!>   closed form alpha dT f(k), f the ramp k/4 or the curve's value written
!>   in the deck; 0 in the body without THERMAL; the output order
!>   (elem0 + e) of the bodies.
!> - it leaves the scene as it was: the bodies keep their strains at load
!>   factor 1 (build_scene's), bit for bit, after every step was asked for.
!> - step_forces of the last step gives the scene's fext and ubar.
!> Run from the repository root.
program test_scene
  use kinds, only: dp
  use errors, only: diag_t, error_t
  use deck_reader, only: deck_t, read_deck
  use gmsh_runner, only: gmsh_options_t
  use scene, only: scene_t, build_scene, step_forces, step_thermal_strains
  use testing, only: check, check_small, finish_tests, tol_round
  implicit none
  character(len=*), parameter :: file = 'tests/unit/data/scene_thermal.deck'
  integer, parameter :: steps = 4
  ! alpha dT at load factor 1 of each body (0: no THERMAL), and each body's
  ! factor at steps 1..4: the ramp 0:4, CURVE swing 0:0 2:1 4:0.5, none
  real(dp), parameter :: adt1(3) = [1.0e-3_dp * 10.0_dp, 2.0e-5_dp * (-50.0_dp), 0.0_dp]
  real(dp), parameter :: factor(steps, 3) = reshape([0.25_dp, 0.5_dp, 0.75_dp, 1.0_dp, &
                                                     0.5_dp, 1.0_dp, 0.75_dp, 0.5_dp, &
                                                     0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [steps, 3])
  type(deck_t) :: deck
  type(diag_t) :: diag
  type(gmsh_options_t) :: gmsh
  type(scene_t) :: sc
  type(error_t), allocatable :: err
  real(dp), allocatable :: adt(:), fext(:), ubar(:)
  real(dp) :: worst
  integer :: k, b, e0, ne
  logical :: unchanged

  call read_deck(file, deck, diag)
  call check(diag%count == 0, 'the deck reads without errors')
  call build_scene(deck, gmsh, sc, diag, err)
  call check(diag%count == 0 .and. .not. allocated(err), 'the scene builds without errors')
  if (diag%count > 0 .or. allocated(err)) call finish_tests()
  call check(size(sc%bodies) == 3 .and. sc%steps == steps, 'three bodies, four steps')
  call check(all(sc%bodies(2:3)%elem0 == sc%bodies(1:2)%elem0 + sc%bodies(1:2)%mesh%nelem) .and. &
             sc%nelem == sum(sc%bodies%mesh%nelem), 'the bodies'' elements numbered one after the other')

  allocate(adt(sc%nelem), fext(sc%ndof), ubar(sc%ndof))
  unchanged = .true.
  do k = 1, steps
    call step_thermal_strains(sc, real(k, dp), adt)
    ! alpha dT f(k), each a product of two or three roundings
    worst = 0.0_dp
    do b = 1, 3
      e0 = sc%bodies(b)%elem0
      ne = sc%bodies(b)%mesh%nelem
      worst = max(worst, maxval(abs(adt(e0 + 1:e0 + ne) - adt1(b) * factor(k, b))) / abs(adt1(1)))
    end do
    call check_small(worst, tol_round(4), 'step ' // achar(48 + k) // ': alpha dT of every element is alpha dT f(k)')
    e0 = sc%bodies(3)%elem0
    call check(all(adt(e0 + 1:) == 0.0_dp), 'step ' // achar(48 + k) // ': 0 in the body without THERMAL')
    ! the scene's bodies still hold their strains at load factor 1
    do b = 1, 2
      unchanged = unchanged .and. all(sc%bodies(b)%adt == sc%thermal(b)%adt1)
    end do
    unchanged = unchanged .and. .not. allocated(sc%bodies(3)%adt)
    call step_forces(sc, real(k, dp), fext, ubar)
  end do
  call check(unchanged, 'step_thermal_strains leaves the bodies'' strains (at load factor 1) as they were')
  call check(all(ubar == sc%ubar) .and. all(fext == sc%fext), 'step_forces of the last step: the scene''s fext and ubar')
  deallocate(adt, fext, ubar)              ! finish_tests stops: nothing left for the leak check
  call finish_tests()
end program test_scene
