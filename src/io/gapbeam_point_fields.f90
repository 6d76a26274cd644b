!> The fields of a point (point_result_t) that the result files carry, listed once: their
!> names (the dataset names under /sweep of a sweep file, one value or one array per point,
!> and under /diagnostics of a transient file) and their values in that order, read and set.
!> The sweep file's writer and reader and the transient file's /diagnostics loop over these
!> lists: a field added here reaches them all (and its catalogue entries say what it is).
module gapbeam_point_fields
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_results, only: point_result_t
   implicit none
   private
   public :: int_names, real_names, text_names, int_fields, set_int_fields, real_fields, &
      set_real_fields, text_field, set_text_field, array_names, array_extent, array_type, &
      array_late, array_field, set_array_field

   !> Integer fields per point (see point_result_t), /sweep/<name> and /diagnostics/<name>.
   character(len=*), parameter :: int_names(17) = [character(len=20) :: 'period', 'label', &
      'status', 'certificate', 'lyapunov_periods', 'lyapunov_converged', 'period_max_tested', &
      'closest_period', 'transient_periods', 'settle_windows', 'settled', 'accuracy_label', &
      'perturbed_label', 'n_attractors', 'lyapunov_dropped', 'lyapunov_rerun', 'lyapunov_starts']
   !> Real fields per point, /sweep/<name> and /diagnostics/<name>.
   character(len=*), parameter :: real_names(19) = [character(len=24) :: 'lyapunov', &
      'lyapunov_error', 'seconds', 'steps', 'f1_open_hz', 'period_tolerance', &
      'repeat_distance', 'window_difference', 'strain_range', 'strain_rate_range', &
      'seconds_label', 'seconds_certify', 'accuracy_lyapunov', 'accuracy_lyapunov_error', &
      'accuracy_distance', 'perturbed_lyapunov', 'perturbed_lyapunov_error', &
      'perturbed_distance', 'lyapunov_spread']
   !> Texts per point, /sweep/<name> and /diagnostics/<name>.
   character(len=*), parameter :: text_names(4) = [character(len=20) :: 'method', &
      'certificate_reason', 'accuracy_method', 'message']
   !> Arrays per point, /sweep/<name> (n, points): per stop, per recorded period (the Poincare
   !> points, then the running Lyapunov estimate), per start (the starts' and the attractors'
   !> results, /diagnostics/<name> of a transient file too).
   character(len=*), parameter :: array_names(21) = [character(len=34) :: 'impacts/count', &
      'impacts/peak_force', 'impacts/rms_force', 'impacts/contact_fraction', &
      'impacts/impulse_per_period', 'impacts/work_rate', 'wear/normal_work_rate', &
      'wear/sliding_distance', 'wear/friction_work_rate', 'wear/wear_volume_rate', &
      'poincare/strain', 'poincare/strain_rate', 'lyapunov_running', 'starts/label', &
      'starts/attractor', 'starts/lyapunov', 'attractors/label', 'attractors/fraction', &
      'attractors/lyapunov', 'starts/transient_periods', 'attractors/mean_transient_periods']
   !> The length n of each array: 1 stops, 2 recorded periods, 3 Lyapunov periods, 4 starts.
   integer, parameter :: array_extent(21) = [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 3, 4, 4, 4, &
      4, 4, 4, 4, 4]
   !> The type of each array in the files: 'r' reals, NaN past a point's own values; 'z' reals,
   !> 0 past them (counts); 'i' integers, 0 past them.
   character(len=*), parameter :: array_type = 'zrrrrrrrrrrrriirirrir'
   !> The arrays that files of an older gapbeam lack (the wear outputs, the starts' transients).
   logical, parameter :: array_late(21) = [.false., .false., .false., .false., .false., &
      .false., .true., .true., .true., .true., .false., .false., .false., .false., .false., &
      .false., .false., .false., .false., .true., .true.]
contains

   !> The integer fields of a point, in the order of int_names.
   pure function int_fields(pr) result(v)
      type(point_result_t), intent(in) :: pr   !! point
      integer :: v(size(int_names))
      v = [pr%period, pr%label, pr%status, pr%certificate, pr%lyapunov_periods, &
           pr%lyapunov_converged, pr%period_max_tested, pr%closest_period, &
           pr%transient_periods, pr%settle_windows, pr%settled, pr%accuracy_label, &
           pr%perturbed_label, pr%n_attractors, pr%lyapunov_dropped, pr%lyapunov_rerun, &
           pr%lyapunov_starts]
   end function int_fields

   !> Set the integer fields of a point (int_names order).
   pure subroutine set_int_fields(pr, v)
      type(point_result_t), intent(inout) :: pr   !! point
      integer, intent(in) :: v(:)                 !! values
      pr%period = v(1);  pr%label = v(2);  pr%status = v(3);  pr%certificate = v(4)
      pr%lyapunov_periods = v(5);  pr%lyapunov_converged = v(6)
      pr%period_max_tested = v(7);  pr%closest_period = v(8);  pr%transient_periods = v(9)
      pr%settle_windows = v(10);  pr%settled = v(11);  pr%accuracy_label = v(12)
      pr%perturbed_label = v(13);  pr%n_attractors = v(14);  pr%lyapunov_dropped = v(15)
      pr%lyapunov_rerun = v(16);  pr%lyapunov_starts = v(17)
   end subroutine set_int_fields

   !> The real fields of a point, in the order of real_names.
   pure function real_fields(pr) result(v)
      type(point_result_t), intent(in) :: pr   !! point
      real(dp) :: v(size(real_names))
      v = [pr%lyapunov, pr%lyapunov_error, pr%seconds, real(pr%steps, dp), pr%f1_open_hz, &
           pr%period_tolerance, pr%repeat_distance, pr%window_difference, pr%strain_range, &
           pr%strain_rate_range, pr%seconds_label, pr%seconds_certify, pr%accuracy_lyapunov, &
           pr%accuracy_lyapunov_error, pr%accuracy_distance, pr%perturbed_lyapunov, &
           pr%perturbed_lyapunov_error, pr%perturbed_distance, pr%lyapunov_spread]
   end function real_fields

   !> Set the real fields of a point (real_names order).
   pure subroutine set_real_fields(pr, v)
      type(point_result_t), intent(inout) :: pr   !! point
      real(dp), intent(in) :: v(:)                !! values
      pr%lyapunov = v(1);  pr%lyapunov_error = v(2);  pr%seconds = v(3)
      pr%steps = nint(v(4), int64);  pr%f1_open_hz = v(5);  pr%period_tolerance = v(6)
      pr%repeat_distance = v(7);  pr%window_difference = v(8);  pr%strain_range = v(9)
      pr%strain_rate_range = v(10);  pr%seconds_label = v(11);  pr%seconds_certify = v(12)
      pr%accuracy_lyapunov = v(13);  pr%accuracy_lyapunov_error = v(14)
      pr%accuracy_distance = v(15);  pr%perturbed_lyapunov = v(16)
      pr%perturbed_lyapunov_error = v(17);  pr%perturbed_distance = v(18)
      pr%lyapunov_spread = v(19)
   end subroutine set_real_fields

   !> Text field j (text_names) of a point ('' when unset).
   pure function text_field(pr, j) result(t)
      type(point_result_t), intent(in) :: pr   !! point
      integer, intent(in) :: j                 !! field
      character(len=:), allocatable :: t
      t = ''
      select case (j)
      case (1);  if (allocated(pr%method)) t = pr%method
      case (2);  if (allocated(pr%certificate_reason)) t = pr%certificate_reason
      case (3);  if (allocated(pr%accuracy_method)) t = pr%accuracy_method
      case default;  if (allocated(pr%message)) t = pr%message
      end select
   end function text_field

   !> Set text field j of a point.
   pure subroutine set_text_field(pr, j, t)
      type(point_result_t), intent(inout) :: pr   !! point
      integer, intent(in) :: j                    !! field
      character(len=*), intent(in) :: t           !! text
      select case (j)
      case (1);  pr%method = t
      case (2);  pr%certificate_reason = t
      case (3);  pr%accuracy_method = t
      case default;  pr%message = t
      end select
   end subroutine set_text_field

   !> Array k (array_names) of a point, as reals; empty when the point has none.
   pure function array_field(pr, k) result(v)
      type(point_result_t), intent(in) :: pr   !! point
      integer, intent(in) :: k                 !! field
      real(dp), allocatable :: v(:)
      allocate(v(0))
      select case (k)
      case (1);  if (allocated(pr%n_impacts)) v = real(pr%n_impacts, dp)
      case (2);  if (allocated(pr%peak_force)) v = pr%peak_force
      case (3);  if (allocated(pr%rms_force)) v = pr%rms_force
      case (4);  if (allocated(pr%contact_fraction)) v = pr%contact_fraction
      case (5);  if (allocated(pr%impulse_per_period)) v = pr%impulse_per_period
      case (6);  if (allocated(pr%work_rate)) v = pr%work_rate
      case (7);  if (allocated(pr%normal_work_rate)) v = pr%normal_work_rate
      case (8);  if (allocated(pr%sliding_distance)) v = pr%sliding_distance
      case (9);  if (allocated(pr%friction_work_rate)) v = pr%friction_work_rate
      case (10);  if (allocated(pr%wear_volume_rate)) v = pr%wear_volume_rate
      case (11);  if (allocated(pr%p_strain)) v = pr%p_strain
      case (12);  if (allocated(pr%p_strain_rate)) v = pr%p_strain_rate
      case (13);  if (allocated(pr%lyapunov_running)) v = pr%lyapunov_running
      case (14);  if (allocated(pr%start_label)) v = real(pr%start_label, dp)
      case (15);  if (allocated(pr%start_attractor)) v = real(pr%start_attractor, dp)
      case (16);  if (allocated(pr%start_lyapunov)) v = pr%start_lyapunov
      case (17);  if (allocated(pr%attractor_label)) v = real(pr%attractor_label, dp)
      case (18);  if (allocated(pr%attractor_fraction)) v = pr%attractor_fraction
      case (19);  if (allocated(pr%attractor_lyapunov)) v = pr%attractor_lyapunov
      case (20);  if (allocated(pr%start_transient)) v = real(pr%start_transient, dp)
      case default;  if (allocated(pr%attractor_transient)) v = pr%attractor_transient
      end select
   end function array_field

   !> Set array k of a point.
   pure subroutine set_array_field(pr, k, v)
      type(point_result_t), intent(inout) :: pr   !! point
      integer, intent(in) :: k                    !! field
      real(dp), intent(in) :: v(:)                !! values
      select case (k)
      case (1);  pr%n_impacts = nint(v)
      case (2);  pr%peak_force = v
      case (3);  pr%rms_force = v
      case (4);  pr%contact_fraction = v
      case (5);  pr%impulse_per_period = v
      case (6);  pr%work_rate = v
      case (7);  pr%normal_work_rate = v
      case (8);  pr%sliding_distance = v
      case (9);  pr%friction_work_rate = v
      case (10);  pr%wear_volume_rate = v
      case (11);  pr%p_strain = v
      case (12);  pr%p_strain_rate = v
      case (13);  pr%lyapunov_running = v
      case (14);  pr%start_label = nint(v)
      case (15);  pr%start_attractor = nint(v)
      case (16);  pr%start_lyapunov = v
      case (17);  pr%attractor_label = nint(v)
      case (18);  pr%attractor_fraction = v
      case (19);  pr%attractor_lyapunov = v
      case (20);  pr%start_transient = nint(v)
      case default;  pr%attractor_transient = v
      end select
   end subroutine set_array_field
end module gapbeam_point_fields
