!> The output catalogue's entries of the flow excitation's statistics (docs/flow.md) that
!> the sweep writes: part of the catalogue (gapbeam_output_catalogue states the conventions).
module gapbeam_output_flow
   use gapbeam_output_studies, only: dataset_t
   implicit none
   private
   public :: sweep_draw_sets, psd_sets

   type(dataset_t), parameter :: sweep_draw_sets(*) = [ &
      dataset_t('/sweep/statistics/draws', '1', 'm', 'random draws (&turbulence draws) the ' &
                // 'statistics of the point are taken over (0: none)'), &
      dataset_t('/sweep/statistics/impact_rate', 's-1', 'point=m stop=n_stops', &
                'impacts per second of each stop: mean over the point''s draws (NaN: none)'), &
      dataset_t('/sweep/statistics/impact_rate_ci', 's-1', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/impact_rate (Student t)'), &
      dataset_t('/sweep/statistics/peak_force', 'N', 'point=m stop=n_stops', &
                'peak contact force of each stop: mean over the point''s draws (NaN: none)'), &
      dataset_t('/sweep/statistics/peak_force_ci', 'N', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/peak_force (Student t)'), &
      dataset_t('/sweep/statistics/rms_force', 'N', 'point=m stop=n_stops', &
                'RMS contact force of each stop: mean over the point''s draws (NaN: none)'), &
      dataset_t('/sweep/statistics/rms_force_ci', 'N', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/rms_force (Student t)'), &
      dataset_t('/sweep/statistics/contact_fraction', '1', 'point=m stop=n_stops', &
                'fraction of the record each stop is in contact: mean over the point''s ' &
                // 'draws (NaN: none)'), &
      dataset_t('/sweep/statistics/contact_fraction_ci', '1', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/contact_fraction (Student t)'), &
      dataset_t('/sweep/statistics/work_rate', 'W', 'point=m stop=n_stops', &
                'impact work rate of each stop: mean over the point''s draws (NaN: none)'), &
      dataset_t('/sweep/statistics/work_rate_ci', 'W', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/work_rate (Student t)'), &
      dataset_t('/sweep/statistics/normal_work_rate', 'W', 'point=m stop=n_stops', &
                'normal work rate of each support: mean over the point''s draws (NaN: none)'), &
      dataset_t('/sweep/statistics/normal_work_rate_ci', 'W', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/normal_work_rate (Student t)'), &
      dataset_t('/sweep/statistics/friction_work_rate', 'W', 'point=m stop=n_stops', &
                'friction work rate of each support: mean over the point''s draws (NaN: none)'), &
      dataset_t('/sweep/statistics/friction_work_rate_ci', 'W', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/friction_work_rate (Student t)'), &
      dataset_t('/sweep/statistics/wear_volume_rate', 'm3 s-1', 'point=m stop=n_stops', &
                'Archard wear volume rate of each support: mean over the point''s draws ' &
                // '(NaN: none)'), &
      dataset_t('/sweep/statistics/wear_volume_rate_ci', 'm3 s-1', 'point=m stop=n_stops', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/wear_volume_rate (Student t)'), &
      dataset_t('/sweep/statistics/tip_rms_displacement', 'm', 'm', &
                'RMS tip displacement over the record: mean over the point''s draws (NaN: none)'), &
      dataset_t('/sweep/statistics/tip_rms_displacement_ci', 'm', 'm', &
                'half-width of the 95 % confidence interval of ' &
                // '/sweep/statistics/tip_rms_displacement (Student t)')]

   type(dataset_t), parameter :: psd_sets(*) = [ &
      dataset_t('/statistics/psd_method', '1', '', 'how each draw''s spectrum was estimated ' &
                // '(&turbulence psd_method: welch or periodogram)'), &
      dataset_t('/statistics/psd_frequency', 'Hz', 'n_freq', 'frequencies of the response ' &
                // 'spectral density'), &
      dataset_t('/statistics/psd_node', '1', 'n_series', 'node of each series of the ' &
                // 'response spectral density (&turbulence psd_nodes)'), &
      dataset_t('/statistics/psd_plane', '1', 'n_series', 'plane of each series: 1 w, 2 v'), &
      dataset_t('/statistics/psd', 'm2 Hz-1', 'series=n_series frequency=n_freq', &
                'one-sided spectral density of the displacement of each series over the ' &
                // 'history samples: mean over the draws'), &
      dataset_t('/statistics/psd_ci', 'm2 Hz-1', 'series=n_series frequency=n_freq', &
                'half-width of the 95 % confidence interval of /statistics/psd (Student t)')]
end module gapbeam_output_flow
