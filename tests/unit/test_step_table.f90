!> step_table: the zone columns of NAME_steps.csv when a pair's zone count
!> changes over the steps, on data built here:
!>   - zone_sets: one column set per pair at first, then the most zones any
!>     step had (contact and stick counted apart), never fewer;
!>   - widen_rows: rows written under a header moved under a wider one that
!>     holds its names in the same order with zone 2's columns among them;
!>     each value in its named column, the new columns 0 (a step with fewer
!>     zones), a header that only repeats the old one leaves the rows as they
!>     are.
program test_step_table
  use kinds, only: dp
  use step_table, only: zone_sets, widen_rows
  use results_writer, only: results_t
  use testing, only: check, finish_tests
  implicit none
  type(results_t) :: res
  integer, allocatable :: sets(:,:)
  real(dp), allocatable :: table(:,:), kept(:,:)
  character(len=*), parameter :: old = 'step,contact_zone_1_x0,contact_zone_1_length,contact_zones_1_count,' // &
    'peak_pressure_1_p,active_nodes'
  character(len=*), parameter :: new = 'step,contact_zone_1_x0,contact_zone_1_length,contact_zone_1_x0_2,' // &
    'contact_zone_1_length_2,contact_zones_1_count,peak_pressure_1_p,peak_pressure_1_p_2,active_nodes'

  ! zone_sets over three steps of two pairs
  allocate(res%zones(2))
  res%zones(1)%contact%count = 1
  res%zones(2)%contact%count = 0
  call zone_sets(res, sets)
  call check(all(shape(sets) == [2, 2]) .and. all(sets == 1), 'zone_sets: one column set per pair at first')
  res%zones(1)%contact%count = 3
  res%zones(2)%stick%count = 2
  call zone_sets(res, sets)
  call check(all(sets == reshape([3, 1, 1, 2], [2, 2])), 'zone_sets: raised to the step''s counts, contact and stick apart')
  res%zones(1)%contact%count = 2
  call zone_sets(res, sets)
  call check(sets(1, 1) == 3, 'zone_sets: never lowered by a step with fewer zones')

  ! two steps written under old, then widened
  allocate(table(6, 3), source=0.0_dp)
  table(:, 1) = [1.0_dp, -2.5_dp, 4.0_dp, 1.0_dp, 47.0_dp, 12.0_dp]
  table(:, 2) = [2.0_dp, -2.0_dp, 5.0_dp, 1.0_dp, 52.0_dp, 14.0_dp]
  kept = table
  call widen_rows(old, old, table)
  call check(all(table == kept), 'widen_rows: the same header leaves the rows as they are')
  call widen_rows(old, new, table)
  call check(all(shape(table) == [9, 3]), 'widen_rows: the new header''s columns, the rows kept')
  call check(all(table(:, 1) == [1.0_dp, -2.5_dp, 4.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 47.0_dp, 0.0_dp, 12.0_dp]), &
             'widen_rows: step 1 under its names, zone 2''s columns 0')
  call check(all(table(:, 2) == [2.0_dp, -2.0_dp, 5.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 52.0_dp, 0.0_dp, 14.0_dp]), &
             'widen_rows: step 2 likewise')
  call check(all(table(:, 3) == 0.0_dp), 'widen_rows: a row not yet written stays 0')
  ! the main program's arrays outlive finish_tests' stop: freed here for the leak check
  deallocate(sets, table, kept, res%zones)
  call finish_tests()
end program test_step_table
