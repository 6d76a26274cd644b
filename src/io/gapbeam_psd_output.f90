!> The response spectral density of a transient run with &turbulence psd_nodes
!> (docs/flow.md) under /statistics: its frequencies, the nodes and planes of its series, the
!> mean over the draws and its 95 % half-width at every frequency.
module gapbeam_psd_output
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_flow_results, only: response_psd_t
   implicit none
   private
   public :: write_response_psd

contains

   !> /statistics/psd* of `psd`.
   subroutine write_response_psd(h5, psd)
      type(h5_writer_t), intent(inout) :: h5             !! writer
      type(response_psd_t), intent(in) :: psd            !! the PSD over the draws
      call h5%put('/statistics/psd_method', trim(psd%method))
      call h5%put('/statistics/psd_frequency', psd%frequency_hz)
      call h5%put('/statistics/psd_node', psd%nodes)
      call h5%put('/statistics/psd_plane', psd%planes)
      call h5%put('/statistics/psd', psd%psd)
      call h5%put('/statistics/psd_ci', psd%half_width)
   end subroutine write_response_psd
end module gapbeam_psd_output
