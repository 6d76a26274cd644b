!> Calibration of one model parameter so that the first natural frequency equals a target.
!>
!> f1 is monotone in each supported parameter (a spring stiffness, the root spring, the
!> section thickness or width), so a bracket is grown geometrically around the current value
!> and Brent's method (on the logarithm of the parameter) finds the root. A target outside
!> the reachable range is an error that states the range (e.g. above the pinned limit of a
!> tip spring).
module gapbeam_calibration
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_description, only: structure_t, spring_t, stop_t, beam_ei, dof_w, dof_name, &
      rigid_planes
   use gapbeam_model, only: system_t
   use gapbeam_assembly, only: assemble
   use gapbeam_eigen, only: lowest_frequency
   implicit none
   private
   public :: first_frequency, calibrate_parameter, calibrate_spring

   real(dp), parameter :: span = 1.0e12_dp     ! parameter searched in [p0/span, p0*span]
   real(dp), parameter :: calibration_rtol = 1.0e-8_dp   ! |f1 - target| / target accepted

contains

   !> First natural frequency of a structure [Hz].
   subroutine first_frequency(st, f1, err, certify, accuracy)
      type(structure_t), intent(in) :: st             !! validated structure
      real(dp), intent(out) :: f1                     !! first natural frequency [Hz]
      type(error_t), allocatable, intent(out) :: err  !! set on eigen failure
      logical, intent(in), optional :: certify        !! Sturm check of f1 (default: yes)
      real(dp), intent(out), optional :: accuracy     !! relative accuracy of f1^2
      type(system_t) :: sys
      logical :: rigid(2), held(2)
      call assemble(st, sys, dense=.false.)
      call rigid_planes(st, [stop_t ::], rigid, held)    ! a mechanism: f1 = 0
      call lowest_frequency(sys, f1, err, certify, accuracy, mechanism=any(rigid))
   end subroutine first_frequency

   !> Value of a spring from (node, dof) to ground that makes f1 = target_hz.
   !>
   !> Because f1 grows with the stiffness, the root is the lowest stiffness that raises f1 to
   !> the target (the paper's rule for the stop stiffness multiplies it by a factor).
   subroutine calibrate_spring(st, node, dof, target_hz, k, err)
      type(structure_t), intent(in) :: st             !! structure without the spring
      integer, intent(in) :: node                     !! node of the spring
      integer, intent(in) :: dof                      !! dof_w or dof_theta
      real(dp), intent(in) :: target_hz               !! target first frequency [Hz]
      real(dp), intent(out) :: k                      !! calibrated stiffness [N/m or N m/rad]
      type(error_t), allocatable, intent(out) :: err  !! set when out of reach
      type(structure_t) :: work
      integer :: ns
      work = st
      if (allocated(work%springs)) then
         ns = size(work%springs)
         work%springs = [work%springs, spring_t(node=node, dof=dof, stiffness=0.0_dp)]
      else
         ns = 0
         work%springs = [spring_t(node=node, dof=dof, stiffness=0.0_dp)]
      end if
      call calibrate_parameter(work, 'spring', ns + 1, target_hz, k, err)
      if (allocated(err)) err%message = err%message // ' (spring at node ' // str(node) &
         // ', dof ' // dof_name(dof) // ')'
   end subroutine calibrate_spring

   !> Value of `parameter` (see calibration_words; `index` picks the spring) giving f1 = target.
   subroutine calibrate_parameter(st, parameter, index, target_hz, value, err)
      type(structure_t), intent(in) :: st             !! structure (current value: the seed)
      character(len=*), intent(in) :: parameter       !! which parameter
      integer, intent(in) :: index                    !! spring index for 'spring'
      real(dp), intent(in) :: target_hz               !! target first frequency [Hz]
      real(dp), intent(out) :: value                  !! calibrated value [SI]
      type(error_t), allocatable, intent(out) :: err  !! set when out of reach
      real(dp) :: x0, xa, xb, xc, fa, fb, fc, f0, step, lo, hi, flo, fhi
      real(dp) :: d, e, p, q, r, s, tol, xm, accuracy
      integer :: it
      character(len=*), parameter :: where = 'gapbeam_calibration:calibrate_parameter: '

      value = 0.0_dp
      x0 = log(seed_value(st, parameter, index))
      call residual(x0, f0);  if (allocated(err)) return
      if (f0 == 0.0_dp) then
         value = exp(x0);  return
      end if
      ! grow a bracket around x0 geometrically in log space
      lo = x0;  hi = x0;  flo = f0;  fhi = f0
      step = log(2.0_dp)
      do
         if (hi - x0 < log(span)) then
            hi = min(x0 + log(span), hi + step)
            call residual(hi, fhi);  if (allocated(err)) return
            if (sign(1.0_dp, fhi) /= sign(1.0_dp, f0)) then
               xa = hi - step;  xb = hi
               if (xa < x0) xa = x0
               exit
            end if
         end if
         if (x0 - lo < log(span)) then
            lo = max(x0 - log(span), lo - step)
            call residual(lo, flo);  if (allocated(err)) return
            if (sign(1.0_dp, flo) /= sign(1.0_dp, f0)) then
               xa = lo;  xb = lo + step
               if (xb > x0) xb = x0
               exit
            end if
         end if
         if (hi - x0 >= log(span) .and. x0 - lo >= log(span)) then
            call fatal_error(err, where // 'target f1 = ' // str(target_hz) // ' Hz is out of ' &
               // 'reach: varying ' // trim(parameter) // ' from ' // str(exp(lo)) // ' to ' &
               // str(exp(hi)) // ' gives f1 from ' // str(flo + target_hz) // ' to ' &
               // str(fhi + target_hz) // ' Hz')
            return
         end if
         step = 2.0_dp * step
      end do
      ! Brent's method on [xa, xb]
      call residual(xa, fa);  if (allocated(err)) return
      call residual(xb, fb);  if (allocated(err)) return
      xc = xb;  fc = fb;  d = xb - xa;  e = d
      do it = 1, 200
         if ((fb > 0.0_dp .and. fc > 0.0_dp) .or. (fb < 0.0_dp .and. fc < 0.0_dp)) then
            xc = xa;  fc = fa;  d = xb - xa;  e = d
         end if
         if (abs(fc) < abs(fb)) then
            xa = xb;  xb = xc;  xc = xa
            fa = fb;  fb = fc;  fc = fa
         end if
         tol = 4.0_dp * epsilon(1.0_dp) * max(1.0_dp, abs(xb))
         xm = 0.5_dp * (xc - xb)
         if (abs(xm) <= tol .or. fb == 0.0_dp .or. abs(fb) <= 1.0e-13_dp * target_hz) exit
         if (abs(e) >= tol .and. abs(fa) > abs(fb)) then
            s = fb / fa
            if (xa == xc) then
               p = 2.0_dp * xm * s;  q = 1.0_dp - s
            else
               q = fa / fc;  r = fb / fc
               p = s * (2.0_dp * xm * q * (q - r) - (xb - xa) * (r - 1.0_dp))
               q = (q - 1.0_dp) * (r - 1.0_dp) * (s - 1.0_dp)
            end if
            if (p > 0.0_dp) q = -q
            p = abs(p)
            if (2.0_dp * p < min(3.0_dp * xm * q - abs(tol * q), abs(e * q))) then
               e = d;  d = p / q
            else
               d = xm;  e = d
            end if
         else
            d = xm;  e = d
         end if
         xa = xb;  fa = fb
         if (abs(d) > tol) then
            xb = xb + d
         else
            xb = xb + sign(tol, xm)
         end if
         call residual(xb, fb);  if (allocated(err)) return
      end do
      value = exp(xb)
      ! the answer is checked, not assumed: f1 at the value found, certified, is the target
      call residual(xb, fb, .true.);  if (allocated(err)) return
      if (abs(fb) > max(calibration_rtol, accuracy) * target_hz) then
         call fatal_error(err, where // 'no value of ' // trim(parameter) // ' gives f1 = ' &
            // str(target_hz) // ' Hz to ' // str(calibration_rtol) // ': the search ended at ' &
            // str(value) // ' with f1 = ' // str(fb + target_hz) // ' Hz (f1 is not ' &
            // 'continuous in it here)')
         return
      end if

   contains

      subroutine residual(x, g, certify)
         real(dp), intent(in) :: x
         real(dp), intent(out) :: g
         logical, intent(in), optional :: certify
         type(structure_t) :: trial
         real(dp) :: f1
         trial = st
         call set_value(trial, parameter, index, exp(x))
         call first_frequency(trial, f1, err, merge(.true., .false., present(certify)), &
                              accuracy)
         if (allocated(err)) then
            err%message = where // 'at ' // trim(parameter) // ' = ' // str(exp(x)) // ': ' &
               // err%message
            g = 0.0_dp
            return
         end if
         g = f1 - target_hz
      end subroutine residual
   end subroutine calibrate_parameter

   !> Starting value of the search: the current value, or a characteristic one if unset.
   pure function seed_value(st, parameter, index) result(v)
      type(structure_t), intent(in) :: st
      character(len=*), intent(in) :: parameter
      integer, intent(in) :: index
      real(dp) :: v, ei, l
      ei = beam_ei(st%beam);  l = st%beam%length
      select case (parameter)
      case ('root_k_theta')
         v = st%root%k_theta
         if (v <= 0.0_dp) v = ei / l
      case ('spring')
         v = st%springs(index)%stiffness
         if (v <= 0.0_dp) then
            if (st%springs(index)%dof == dof_w) then
               v = 3.0_dp * ei / l**3
            else
               v = ei / l
            end if
         end if
      case ('thickness')
         v = st%beam%thickness
      case ('width')
         v = st%beam%width
      case default
         error stop 'gapbeam_calibration:seed_value: unknown parameter'
      end select
   end function seed_value

   !> Set the calibrated parameter in a structure.
   pure subroutine set_value(st, parameter, index, v)
      type(structure_t), intent(inout) :: st
      character(len=*), intent(in) :: parameter
      integer, intent(in) :: index
      real(dp), intent(in) :: v
      select case (parameter)
      case ('root_k_theta')
         st%root%k_theta = v
      case ('spring')
         st%springs(index)%stiffness = v
      case ('thickness')
         st%beam%thickness = v
      case ('width')
         st%beam%width = v
      case default
         error stop 'gapbeam_calibration:set_value: unknown parameter'
      end select
   end subroutine set_value
end module gapbeam_calibration
