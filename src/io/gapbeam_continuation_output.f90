!> Result files of a continuation (issue 14): PREFIX.h5 and gnuplot-ready text tables.
!>
!> HDF5 (every dataset with `units`; Fortran shapes, so h5py shows 2-D arrays transposed):
!>   /deck                              the effective deck text
!>   /continuation/title, parameter_name ('&forcing frequency_hz'), parameter2_name ('' or
!>                                      the second variable of the curves), parameter2_value
!>   /continuation/parameter   (n)      the continued variable, in its own unit (Hz, m, ...)
!>   /continuation/state       (n_state, n)  section state x = (u_r, v_r) of each orbit
!>   /continuation/state_dofs  (n_state/2)   global dof of each u_r entry (v_r: the same dofs)
!>   /continuation/period      (n)      forcing periods of the orbit
!>   /continuation/branch      (n)      branch of the point (1 = the start branch)
!>   /continuation/multipliers/real, /imag, /modulus  (n_state, n)  Floquet multipliers, by
!>                                      decreasing modulus (complex: real and imaginary parts)
!>   /continuation/stable      (n)      1: every |multiplier| < 1, 0: unstable
!>   /continuation/located     (n)      1: a located bifurcation point
!>   /continuation/arclength, /iterations, /grazing (extremum of a stop penetration nearest
!>                                      0 [m]), /impacts (contact intervals per orbit)
!>   /continuation/poincare/strain, strain_rate, tip  (max_period, n)  at the p section points
!>                                      of each orbit (NaN beyond its period)
!>   /continuation/branches/period, parent, first, last, ended   one entry per branch
!>   /continuation/bifurcations/kind   ('saddle_node', 'period_doubling', 'neimark_sacker',
!>                                      'grazing', 'branch_point'), parameter, period, branch,
!>                                      point, multiplier_real, multiplier_imag, grazing, note
!>   /continuation/curves/kind, period, ended (per curve); curve_NNN/parameter, parameter2
!>   /continuation/seconds, map_evaluations, periods_integrated
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
   use gapbeam_files, only: make_parent_directory, write_text_file
   use gapbeam_continuation_types, only: continuation_result_t
   implicit none
   private
   public :: write_continuation, curve_kind_code

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

   !> PREFIX.h5 and the text tables.
   subroutine write_continuation(prefix, title, deck_text, overlay, res, write_text, err)
      character(len=*), intent(in) :: prefix             !! output prefix
      character(len=*), intent(in) :: title              !! job title
      character(len=*), intent(in) :: deck_text          !! effective deck
      character(len=*), intent(in) :: overlay            !! sweep prefix for the charts
      type(continuation_result_t), intent(in) :: res     !! results
      logical, intent(in) :: write_text                  !! also the .dat tables
      type(error_t), allocatable, intent(out) :: err     !! I/O failure
      call make_parent_directory(prefix // '.h5', err);  if (allocated(err)) return
      call write_h5(prefix // '.h5', title, deck_text, res, err);  if (allocated(err)) return
      if (.not. write_text) return
      call write_tables(prefix, title, overlay, res, err)
   end subroutine write_continuation

   subroutine write_h5(path, title, deck_text, res, err)
      character(len=*), intent(in) :: path, title, deck_text
      type(continuation_result_t), intent(in) :: res
      type(error_t), allocatable, intent(out) :: err
      type(h5_writer_t) :: h5
      character(len=:), allocatable :: u, su
      character(len=256), allocatable :: ended(:)
      character(len=16), allocatable :: kinds(:)
      integer :: k, nb, nc
      u = res%parameter_units
      su = 'm, rad (u); m/s, rad/s (v)'
      call h5%create(path, err);  if (allocated(err)) return
      call h5%write_text('/deck', deck_text, err);  if (failed()) return
      call h5%write_text('/continuation/title', title, err);  if (failed()) return
      call h5%write_text('/continuation/parameter_name', res%parameter_name, err)
      if (failed()) return
      call h5%write_text('/continuation/parameter2_name', res%parameter2_name, err)
      if (failed()) return
      call h5%write('/continuation/parameter2_value', res%parameter2_value, &
                    unit_or_dash(res%parameter2_units), err);  if (failed()) return
      call h5%write('/continuation/parameter', res%parameter, u, err);  if (failed()) return
      call h5%write('/continuation/state', res%state, su, err);  if (failed()) return
      call h5%write('/continuation/state_dofs', res%dofs, '-', err);  if (failed()) return
      call h5%write('/continuation/period', res%period, 'forcing periods', err)
      if (failed()) return
      call h5%write('/continuation/branch', res%branch, '-', err);  if (failed()) return
      call h5%write('/continuation/multipliers/real', real(res%multipliers, dp), '-', err)
      if (failed()) return
      call h5%write('/continuation/multipliers/imag', aimag(res%multipliers), '-', err)
      if (failed()) return
      call h5%write('/continuation/multipliers/modulus', abs(res%multipliers), '-', err)
      if (failed()) return
      call h5%write('/continuation/stable', merge(1, 0, res%stable), '1: stable, 0: unstable', &
                    err);  if (failed()) return
      call h5%write('/continuation/located', merge(1, 0, res%located), &
                    '1: a located bifurcation point', err);  if (failed()) return
      call h5%write('/continuation/arclength', res%arclength, '-', err);  if (failed()) return
      call h5%write('/continuation/iterations', res%iterations, '-', err);  if (failed()) return
      call h5%write('/continuation/grazing', res%grazing, 'm', err);  if (failed()) return
      call h5%write('/continuation/impacts', res%impacts, 'contact intervals per orbit', err)
      if (failed()) return
      call h5%write('/continuation/poincare/strain', res%p_strain, '-', err)
      if (failed()) return
      call h5%write('/continuation/poincare/strain_rate', res%p_rate, '1/s', err)
      if (failed()) return
      call h5%write('/continuation/poincare/tip', res%p_tip, 'm', err);  if (failed()) return
      nb = size(res%branches)
      allocate(ended(max(nb, 0)))
      do k = 1, nb
         ended(k) = res%branches(k)%ended
      end do
      call h5%write('/continuation/branches/period', [(res%branches(k)%period, k = 1, nb)], &
                    'forcing periods', err);  if (failed()) return
      call h5%write('/continuation/branches/parent', [(res%branches(k)%parent, k = 1, nb)], &
                    '-', err);  if (failed()) return
      call h5%write('/continuation/branches/first', [(res%branches(k)%first, k = 1, nb)], &
                    '-', err);  if (failed()) return
      call h5%write('/continuation/branches/last', [(res%branches(k)%last, k = 1, nb)], &
                    '-', err);  if (failed()) return
      call h5%write('/continuation/branches/ended', ended, '-', err);  if (failed()) return
      call h5%write('/continuation/bifurcations/kind', res%bif_kind, '-', err)
      if (failed()) return
      call h5%write('/continuation/bifurcations/parameter', res%bif_parameter, u, err)
      if (failed()) return
      call h5%write('/continuation/bifurcations/period', res%bif_period, 'forcing periods', err)
      if (failed()) return
      call h5%write('/continuation/bifurcations/branch', res%bif_branch, '-', err)
      if (failed()) return
      call h5%write('/continuation/bifurcations/point', res%bif_point, '-', err)
      if (failed()) return
      call h5%write('/continuation/bifurcations/multiplier_real', real(res%bif_multiplier, dp), &
                    '-', err);  if (failed()) return
      call h5%write('/continuation/bifurcations/multiplier_imag', aimag(res%bif_multiplier), &
                    '-', err);  if (failed()) return
      call h5%write('/continuation/bifurcations/grazing', res%bif_grazing, 'm', err)
      if (failed()) return
      call h5%write('/continuation/bifurcations/note', res%bif_note, '-', err)
      if (failed()) return
      nc = size(res%curves)
      allocate(kinds(nc))
      deallocate(ended);  allocate(ended(nc))
      do k = 1, nc
         kinds(k) = res%curves(k)%kind
         ended(k) = res%curves(k)%ended
      end do
      call h5%write('/continuation/curves/kind', kinds, '-', err);  if (failed()) return
      call h5%write('/continuation/curves/period', [(res%curves(k)%period, k = 1, nc)], &
                    'forcing periods', err);  if (failed()) return
      call h5%write('/continuation/curves/ended', ended, '-', err);  if (failed()) return
      do k = 1, nc
         call h5%write('/continuation/curves/curve_' // pad3(k) // '/parameter', &
                       res%curves(k)%parameter, u, err);  if (failed()) return
         call h5%write('/continuation/curves/curve_' // pad3(k) // '/parameter2', &
                       res%curves(k)%parameter2, unit_or_dash(res%parameter2_units), err)
         if (failed()) return
      end do
      call h5%write('/continuation/seconds', res%seconds, 's', err);  if (failed()) return
      call h5%write('/continuation/map_evaluations', res%map_evaluations, '-', err)
      if (failed()) return
      call h5%write('/continuation/periods_integrated', res%periods_integrated, &
                    'forcing periods', err);  if (failed()) return
      call h5%close(err)
   contains
      logical function failed()
         failed = allocated(err)
         if (failed) call h5%abort()
      end function failed
   end subroutine write_h5

   pure function unit_or_dash(u) result(s)
      character(len=*), intent(in) :: u
      character(len=:), allocatable :: s
      s = trim(u)
      if (len(s) == 0) s = '-'
   end function unit_or_dash

   pure function pad3(k) result(s)
      integer, intent(in) :: k
      character(len=3) :: s
      write(s, '(i3.3)') k
   end function pad3

   !> The four text tables.
   subroutine write_tables(prefix, title, overlay, res, err)
      character(len=*), intent(in) :: prefix, title, overlay
      type(continuation_result_t), intent(in) :: res
      type(error_t), allocatable, intent(out) :: err
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
      call write_text_file(prefix // '.branches.dat', t(1:nt), err);  if (allocated(err)) return
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
      call write_text_file(prefix // '.bifurcations.dat', t(1:nt), err);  if (allocated(err)) return
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
      call write_text_file(prefix // '.multipliers.dat', t(1:nt), err);  if (allocated(err)) return
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
      call write_text_file(prefix // '.curves.dat', t(1:nt), err)
   end subroutine write_tables

   !> Append text to a buffer t of used length nt (capacity doubles).
   pure subroutine append(t, nt, x)
      character(len=:), allocatable, intent(inout) :: t
      integer, intent(inout) :: nt
      character(len=*), intent(in) :: x
      character(len=:), allocatable :: tmp
      if (.not. allocated(t)) allocate(character(len=max(4096, 2 * len(x))) :: t)
      if (nt + len(x) > len(t)) then
         allocate(character(len=max(2 * len(t), nt + len(x))) :: tmp)
         tmp(1:nt) = t(1:nt)
         call move_alloc(tmp, t)
      end if
      t(nt + 1:nt + len(x)) = x
      nt = nt + len(x)
   end subroutine append

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
