!> Result files of a continuation: PREFIX.h5 and gnuplot-ready text tables, one output set
!> (gapbeam_output_set): written under temporary names unique to the process and put in place
!> together, or not at all; /run/files lists them.
!>
!> HDF5: the root attributes, /deck, /parameters and /model of every result file, and under
!> /continuation (shapes in C order, as h5py shows them; units and long names from the output
!> catalogue, `gapbeam --help-outputs continuation`):
!>   title, parameter_name ('&forcing frequency_hz'), parameter2_name ('' or the second
!>   variable of the curves), parameter2_value; per point (n): parameter, period, branch,
!>   stable, located, arclength, iterations, grazing, impacts; state (n, n_state) with
!>   state_dofs; multipliers/real, imag, modulus (n, n_state), by decreasing modulus;
!>   poincare/strain, strain_rate, tip (n, max_period, NaN beyond a point's period);
!>   branches/period, parent, first, last, ended; bifurcations/kind ('saddle_node',
!>   'period_doubling', 'neimark_sacker', 'grazing', 'branch_point'), parameter, period, branch,
!>   point, multiplier_real, multiplier_imag, grazing, note; curves/kind, period, ended and
!>   curves/curve_NNN/parameter, parameter2; seconds, map_evaluations, periods_integrated.
!> Text: PREFIX.branches.dat (blocks per branch and section point, a new block wherever the
!> stability changes, a located bifurcation point ending one block and starting the next:
!> parameter, strain, strain rate, tip, stable (1 stable, 0 unstable), branch, period),
!> PREFIX.bifurcations.dat, PREFIX.multipliers.dat, PREFIX.curves.dat (one block per curve).
!> Their first comment lines name the overlay sweep for scripts/plot.sh.
module gapbeam_continuation_output
   use, intrinsic :: iso_fortran_env, only: int64
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, str
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_output_set, only: output_set_t
   use gapbeam_files, only: append => append_text
   use gapbeam_model, only: model_t
   use gapbeam_parameters, only: parameter_set_t
   use gapbeam_file_info, only: write_parameter_set, write_model, udunits
   use gapbeam_continuation_types, only: continuation_result_t
   implicit none
   private
   public :: write_continuation

contains

   !> 1 period doubling, 2 saddle-node, 3 grazing, 4 other.
   pure integer function curve_kind_code(kind)
      character(len=*), intent(in) :: kind
      select case (trim(kind))
      case ('period_doubling');  curve_kind_code = 1
      case ('saddle_node');  curve_kind_code = 2
      case ('grazing');  curve_kind_code = 3
      case default;  curve_kind_code = 4
      end select
   end function curve_kind_code

   !> PREFIX.h5 and the text tables (with `write_text`), as one output set; with the run's
   !> parameters and model when given.
   subroutine write_continuation(prefix, title, deck_text, overlay, res, write_text, err, &
                                 params, model, stiffness_units, warnings)
      character(len=*), intent(in) :: prefix             !! output prefix
      character(len=*), intent(in) :: title              !! job title
      character(len=*), intent(in) :: deck_text          !! effective deck
      character(len=*), intent(in) :: overlay            !! sweep prefix for the charts
      type(continuation_result_t), intent(in) :: res     !! results
      logical, intent(in) :: write_text                  !! also the .dat tables
      type(error_t), allocatable, intent(out) :: err     !! I/O failure; no file changed then
      type(parameter_set_t), intent(in), optional :: params   !! /parameters
      type(model_t), intent(in), optional :: model       !! /model: the deck's model
      character(len=*), intent(in), optional :: stiffness_units   !! of its stop stiffnesses
      character(len=*), intent(in), optional :: warnings(:)   !! /run/warnings, one line each
      type(output_set_t) :: set
      type(h5_writer_t) :: h5
      if (write_text) then
         call set%begin(prefix, [character(len=18) :: '.h5', '.branches.dat', &
                        '.bifurcations.dat', '.multipliers.dat', '.curves.dat'])
      else
         call set%begin(prefix, ['.h5'])
      end if
      call set%open_h5(h5, 'continuation', deck_text, warnings)
      if (present(params)) call write_parameter_set(h5, params)
      if (present(model) .and. present(stiffness_units)) call write_model(h5, model, &
                                                                          stiffness_units)
      call write_h5(h5, title, res)
      call set%close_h5(h5)
      if (write_text) call write_tables(set, title, overlay, res)
      call set%finish(err)
   end subroutine write_continuation

   !> The /continuation datasets.
   subroutine write_h5(h5, title, res)
      type(h5_writer_t), intent(inout) :: h5             !! writer, file created
      character(len=*), intent(in) :: title              !! job title
      type(continuation_result_t), intent(in) :: res     !! results
      character(len=*), parameter :: c = '/continuation/'
      character(len=:), allocatable :: u, u2
      character(len=256), allocatable :: ended(:)
      character(len=16), allocatable :: kinds(:)
      integer :: k, nb, nc
      u = udunits(res%parameter_units)
      u2 = udunits(res%parameter2_units)
      call h5%put(c // 'title', title)
      call h5%put(c // 'parameter_name', res%parameter_name)
      call h5%put(c // 'parameter2_name', res%parameter2_name)
      call h5%put(c // 'parameter2_value', res%parameter2_value, units=u2)
      call h5%put(c // 'parameter', res%parameter, units=u)
      call h5%put(c // 'state', res%state)
      call h5%put(c // 'state_dofs', res%dofs)
      call h5%put(c // 'period', res%period)
      call h5%put(c // 'branch', res%branch)
      call h5%put(c // 'multipliers/real', real(res%multipliers, dp))
      call h5%put(c // 'multipliers/imag', aimag(res%multipliers))
      call h5%put(c // 'multipliers/modulus', abs(res%multipliers))
      call h5%put(c // 'stable', merge(1, 0, res%stable))
      call h5%put(c // 'located', merge(1, 0, res%located))
      call h5%put(c // 'arclength', res%arclength)
      call h5%put(c // 'iterations', res%iterations)
      call h5%put(c // 'grazing', res%grazing)
      call h5%put(c // 'impacts', res%impacts)
      call h5%put(c // 'poincare/strain', res%p_strain)
      call h5%put(c // 'poincare/strain_rate', res%p_rate)
      call h5%put(c // 'poincare/tip', res%p_tip)
      nb = size(res%branches)
      ended = [character(len=256) :: (res%branches(k)%ended, k = 1, nb)]
      call h5%put(c // 'branches/period', [(res%branches(k)%period, k = 1, nb)])
      call h5%put(c // 'branches/parent', [(res%branches(k)%parent, k = 1, nb)])
      call h5%put(c // 'branches/first', [(res%branches(k)%first, k = 1, nb)])
      call h5%put(c // 'branches/last', [(res%branches(k)%last, k = 1, nb)])
      call h5%put(c // 'branches/ended', ended)
      call h5%put(c // 'bifurcations/kind', res%bif_kind)
      call h5%put(c // 'bifurcations/parameter', res%bif_parameter, units=u)
      call h5%put(c // 'bifurcations/period', res%bif_period)
      call h5%put(c // 'bifurcations/branch', res%bif_branch)
      call h5%put(c // 'bifurcations/point', res%bif_point)
      call h5%put(c // 'bifurcations/multiplier_real', real(res%bif_multiplier, dp))
      call h5%put(c // 'bifurcations/multiplier_imag', aimag(res%bif_multiplier))
      call h5%put(c // 'bifurcations/grazing', res%bif_grazing)
      call h5%put(c // 'bifurcations/note', res%bif_note)
      nc = size(res%curves)
      kinds = [character(len=16) :: (res%curves(k)%kind, k = 1, nc)]
      ended = [character(len=256) :: (res%curves(k)%ended, k = 1, nc)]
      call h5%put(c // 'curves/kind', kinds)
      call h5%put(c // 'curves/period', [(res%curves(k)%period, k = 1, nc)])
      call h5%put(c // 'curves/ended', ended)
      do k = 1, nc
         call h5%put(c // 'curves/curve_' // pad3(k) // '/parameter', res%curves(k)%parameter, &
                     units=u)
         call h5%put(c // 'curves/curve_' // pad3(k) // '/parameter2', &
                     res%curves(k)%parameter2, units=u2)
      end do
      call h5%put(c // 'seconds', res%seconds)
      call h5%put(c // 'map_evaluations', res%map_evaluations)
      call h5%put(c // 'periods_integrated', res%periods_integrated)
   end subroutine write_h5

   pure function pad3(k) result(s)
      integer, intent(in) :: k
      character(len=3) :: s
      write(s, '(i3.3)') k
   end function pad3

   !> The four text tables.
   subroutine write_tables(set, title, overlay, res)
      type(output_set_t), intent(inout) :: set
      character(len=*), intent(in) :: title, overlay
      type(continuation_result_t), intent(in) :: res
      character(len=:), allocatable :: t, head
      integer :: nt
      integer :: b, j, k, m
      real(dp) :: s, last
      head = '# ' // title // new_line('a') // '# overlay: ' // trim(overlay) // new_line('a') &
         // '# parameter: ' // res%parameter_name // ' [' // res%parameter_units // ']' &
         // new_line('a')
      if (len(res%parameter2_name) > 0) head = head // '# branches at: ' &
         // res%parameter2_name // ' = ' // trim(adjustl(real_text(res%parameter2_value))) &
         // new_line('a')
      ! branches: one block per (branch, section point)
      nt = 0
      call append(t, nt, head)
      call append(t, nt, '# columns: parameter [' // res%parameter_units // '], strain [-], ' &
         // 'strain_rate [1/s], tip [m], stable [1 stable, 0 unstable], ' &
         // 'branch [-], period [forcing periods]' // new_line('a'))
      do b = 1, size(res%branches)
         do k = 1, res%branches(b)%period
            ! a new block wherever the stability changes: a located point ends the block
            ! before it (with that block's flag) and starts the next (with the next's), so that
            ! gnuplot draws each block in one style
            last = -1.0_dp
            do j = res%branches(b)%first, res%branches(b)%last
               s = merge(1.0_dp, 0.0_dp, res%stable(j))
               if (res%located(j) .and. j < res%branches(b)%last) &
                  s = merge(1.0_dp, 0.0_dp, res%stable(j + 1))
               if (res%located(j) .and. last >= 0.0_dp) then
                  call append(t, nt, row([res%parameter(j), res%p_strain(k, j), &
                     res%p_rate(k, j), res%p_tip(k, j), last, real(b, dp), &
                     real(res%period(j), dp)]))
                  call append(t, nt, new_line('a'))
               else if (last >= 0.0_dp .and. s /= last) then
                  call append(t, nt, new_line('a'))
               end if
               call append(t, nt, row([res%parameter(j), res%p_strain(k, j), res%p_rate(k, j), &
                  res%p_tip(k, j), s, real(b, dp), real(res%period(j), dp)]))
               last = s
            end do
            call append(t, nt, new_line('a') // new_line('a'))
         end do
      end do
      call set%text('.branches.dat', t(1:nt))
      ! bifurcations
      nt = 0
      call append(t, nt, head)
      call append(t, nt, '# columns: kind, parameter [' // res%parameter_units // '], strain [-] ' &
         // '(first section point), period [forcing periods], branch [-], multiplier_real ' &
         // '[-], multiplier_imag [-], grazing [m], kind_code [1 PD, 2 SN, 3 grazing, 4 ' &
         // 'other]' // new_line('a'))
      do j = 1, res%n_bif
         m = res%bif_point(j)
         call append(t, nt, trim(res%bif_kind(j)) // row([res%bif_parameter(j), &
            res%p_strain(1, m), real(res%bif_period(j), dp), real(res%bif_branch(j), dp), &
            real(res%bif_multiplier(j), dp), aimag(res%bif_multiplier(j)), res%bif_grazing(j), &
            real(curve_kind_code(res%bif_kind(j)), dp)]))
      end do
      call set%text('.bifurcations.dat', t(1:nt))
      ! multipliers
      nt = 0
      call append(t, nt, head)
      call append(t, nt, '# columns: parameter [' // res%parameter_units // '], real [-], ' &
         // 'imag [-], modulus [-], branch [-], period [forcing periods]' // new_line('a'))
      do j = 1, res%n
         do k = 1, res%n_state
            call append(t, nt, row([res%parameter(j), real(res%multipliers(k, j), dp), &
               aimag(res%multipliers(k, j)), abs(res%multipliers(k, j)), real(res%branch(j), dp), &
               real(res%period(j), dp)]))
         end do
      end do
      call set%text('.multipliers.dat', t(1:nt))
      ! curves
      nt = 0
      call append(t, nt, head)
      call append(t, nt, '# parameter2: ' // res%parameter2_name // ' [' // res%parameter2_units &
         // ']' // new_line('a') // '# columns: parameter [' // res%parameter_units &
         // '], parameter2 [' // res%parameter2_units // '], kind_code [1 PD, 2 SN, 3 ' &
         // 'grazing], period [forcing periods], curve [-]' // new_line('a'))
      do b = 1, size(res%curves)
         do j = 1, size(res%curves(b)%parameter)
            call append(t, nt, row([res%curves(b)%parameter(j), res%curves(b)%parameter2(j), &
               real(curve_kind_code(res%curves(b)%kind), dp), real(res%curves(b)%period, dp), &
               real(b, dp)]))
         end do
         call append(t, nt, new_line('a') // new_line('a'))
      end do
      call set%text('.curves.dat', t(1:nt))
   end subroutine write_tables

   pure function real_text(x) result(s)
      real(dp), intent(in) :: x
      character(len=26) :: s
      write(s, '(es26.16e3)') x
   end function real_text

   !> One table row.
   pure function row(v) result(s)
      real(dp), intent(in) :: v(:)
      character(len=:), allocatable :: s
      character(len=26) :: buf
      integer :: i
      s = ''
      do i = 1, size(v)
         if (v(i) /= v(i)) then
            buf = '  NaN'
         else
            write(buf, '(es26.16e3)') v(i)
         end if
         s = s // ' ' // trim(adjustl(buf))
      end do
      s = s // new_line('a')
   end function row
end module gapbeam_continuation_output
