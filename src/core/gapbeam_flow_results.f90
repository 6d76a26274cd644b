!> Result types of the flow excitation (docs/flow.md): the fluid-elastic data of the modes of
!> the open structure, the statistics over random draws, and the wear depth over years.
!> Pure data; the model kernels (src/model) fill them, the writers (src/io) write them.
module gapbeam_flow_results
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: flow_modes_t, draw_statistics_t, wear_depth_t, n_draw_outputs, draw_output_names, &
      response_psd_t

   integer, parameter :: n_draw_outputs = 9
   !> the scalar outputs taken over random draws, as named under /statistics (per stop; the
   !> last, the tip's RMS displacement over the history samples, one value)
   character(len=*), parameter :: draw_output_names(n_draw_outputs) = [character(len=24) :: &
      'impact_rate', 'peak_force', 'rms_force', 'contact_fraction', 'work_rate', &
      'normal_work_rate', 'friction_work_rate', 'wear_volume_rate', 'tip_rms_displacement']

   !> Every mode of the open structure (supports inactive), ascending in frequency (two planes:
   !> the modes of each plane, merged; at equal frequency w first), with its fluid-elastic data.
   type :: flow_modes_t
      integer :: n_modes = 0                        !! modes
      real(dp), allocatable :: frequency_hz(:)      !! f_j [Hz]
      integer, allocatable :: plane(:)              !! 1: w, 2: v
      real(dp), allocatable :: structural_ratio(:)  !! zeta_s,j (Rayleigh and modal) [-]
      !> U_e,j^2 / U^2: the mode-shape-squared weighted square of the flow profile [-]
      real(dp), allocatable :: velocity_ratio(:)
      !> the reference velocity at which the mode's net damping vanishes (Connors), +huge
      !> where no fluid-elastic force acts on the mode [m/s]
      real(dp), allocatable :: critical_velocity(:)
      real(dp), allocatable :: fluid_ratio(:)       !! zeta_fe,j at the deck's velocity [-]
      real(dp), allocatable :: shapes(:, :)         !! (n_dof, n_modes) mass-normalised [-]
      real(dp), allocatable :: omega(:)             !! 2 pi f_j [rad/s]
   end type flow_modes_t

   !> A scalar output over independent draws: the mean and the half-width of its two-sided
   !> 95 % confidence interval (Student t with n - 1 degrees of freedom; 0 for one draw).
   type :: draw_statistics_t
      character(len=:), allocatable :: name         !! output name
      integer :: n_draws = 0                        !! draws
      real(dp), allocatable :: values(:, :)         !! (n_draws, n_items) per draw
      real(dp), allocatable :: mean(:)              !! (n_items) mean over the draws
      real(dp), allocatable :: half_width(:)        !! (n_items) 95 % half-width of the mean
   end type draw_statistics_t

   !> The one-sided displacement spectral density at chosen nodes, averaged over the draws.
   type :: response_psd_t
      integer :: n_draws = 0                        !! draws averaged
      character(len=16) :: method = ''              !! 'welch' or 'periodogram'
      integer, allocatable :: nodes(:)              !! (n_series) node of each series
      integer, allocatable :: planes(:)             !! (n_series) 1: w, 2: v
      real(dp), allocatable :: frequency_hz(:)      !! (n_freq) [Hz]
      real(dp), allocatable :: psd(:, :)            !! (n_freq, n_series) mean [m^2/Hz]
      real(dp), allocatable :: half_width(:, :)     !! (n_freq, n_series) its 95 % half-width
      real(dp), allocatable :: draws(:, :, :)       !! (n_freq, n_series, n_draws) each draw's
   end type response_psd_t

   !> Wear depth of each support's scar against time.
   type :: wear_depth_t
      real(dp), allocatable :: time_years(:)        !! (n_times) [a]
      real(dp), allocatable :: depth(:, :)          !! (n_times, n_stops) [m]
      real(dp), allocatable :: years_to_fraction(:) !! (n_stops) +huge where never [a]
   end type wear_depth_t
end module gapbeam_flow_results
