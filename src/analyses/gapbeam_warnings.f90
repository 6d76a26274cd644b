!> Warnings about a deck before it runs: values far outside the model's scale, and stops the
!> beam cannot reach. A warning does not stop a run (the deck may mean it); it is one line on
!> standard error and in /run/warnings of the run's file. The warnings that come from a run's
!> results (a stop never touched) are in core/gapbeam_warning_text.
!>
!> **Scales** (every threshold a multiple of the span L, none met by a deck of inputs/ or
!> test/decks/, each far from them; see docs/running.md):
!> - a stop's gap above 0.1 L (`gap_span_fraction`): to meet it the beam must deflect by more
!>   than a tenth of its span, where the small deflections of linear beam theory no longer
!>   hold (the shipped decks: at most 0.01 L);
!> - a base amplitude A_pp above 0.2 L (`amplitude_span_fraction`): above its first resonance
!>   a base-driven beam's tip stays nearly still while the base moves, a relative deflection
!>   of about A_pp / 2 = 0.1 L (the shipped decks: at most 0.02 L);
!> - a section wider than the span (`width_span_ratio`: a plate, not a beam) or deeper than
!>   0.2 L (`depth_span_fraction`; the depth of a general section is sqrt(12 I / A), that of
!>   a rectangle of the same I and A): Euler-Bernoulli theory needs a slender beam (L/h >= 5
!>   already leaves f1 a few per cent high; the shipped decks: h / L at most 0.02).
!>
!> **Reach** of a stop (`reach_bounds`): for the linear structure with its stops open,
!> M u'' + C u' + K u = F(t) with harmonic F and C positive semi-definite (Rayleigh damping
!> with beta, gamma >= 0), u = u_p + h with the steady response u_p(t) = Im(U e^{i Omega t}),
!> (K - Omega^2 M + i Omega C) U = F^, and h free vibration whose energy
!> E_h = h'K h / 2 + h''M h' / 2 never grows. By Cauchy-Schwarz in the K norm,
!> |e'h| <= sqrt(2 E_h e'K^-1 e) for any direction e, so at a stop's dof
!>    |u_s(t)| <= |U_s| + sqrt(2 E_h(0) (K^-1)_ss)     for all t,
!> with E_h(0) the energy of the deck's initial state less u_p(0), u_p'(0). A gap above this
!> bound is never met: the run is that of the linear beam, whatever it is labelled. The bound
!> is rigorous (no threshold to choose), needs a regular K (not a mechanism) and a damped or
!> off-resonance steady state, and is skipped otherwise. It holds until the beam meets a stop,
!> so it proves a stop is never met only when every stop is out of reach: the warnings are
!> given then, for every stop, or not at all (a stop the run never meets although another is
!> within reach gets the warning about a stop never touched, from the run's own counts).
!> It is sharper than the static deflection under the base motion's inertia (which a beam
!> near resonance exceeds many times): the steady amplitude includes the resonant gain.
module gapbeam_warnings
   use gapbeam_kinds, only: dp, pi
   use gapbeam_error, only: error_t, str
   use gapbeam_deck, only: deck_t
   use gapbeam_warning_text, only: warning_length
   use gapbeam_description, only: dof_name, stop_t, rigid_planes
   use gapbeam_model, only: model_t
   use gapbeam_model_builder, only: build_full_model, initial_vectors
   use gapbeam_linalg, only: dense_to_band, bandwidth
   use gapbeam_lapack, only: dgbtrf, dgbtrs, dpbtrf, dpbtrs
   implicit none
   private
   public :: deck_warnings, reach_bounds

   real(dp), parameter :: gap_span_fraction = 0.1_dp        !! gap / L that warns
   real(dp), parameter :: amplitude_span_fraction = 0.2_dp  !! A_pp / L that warns
   real(dp), parameter :: width_span_ratio = 1.0_dp         !! width / L that warns
   real(dp), parameter :: depth_span_fraction = 0.2_dp      !! depth / L that warns

contains

   !> Every warning about a deck before it runs: its scales, and for the analyses that
   !> integrate the deck's forcing from its initial state (transient, work_precision,
   !> model_size, and a sweep over the forcing's frequency and amplitude) the stops out of
   !> reach. A model that cannot be built gives no reach warning (the run reports why).
   function deck_warnings(deck) result(lines)
      type(deck_t), intent(in) :: deck                 !! validated deck
      character(len=warning_length), allocatable :: lines(:)
      character(len=warning_length), allocatable :: more(:)
      lines = scale_warnings(deck)
      more = mechanism_warnings(deck)
      if (size(more) > 0) lines = joined(lines, more)
      more = reach_warnings(deck)
      if (size(more) > 0) lines = joined(lines, more)
   end function deck_warnings

   !> A beam that is a mechanism held by its stops (the deck reader refuses one that no stop
   !> holds): a note that between impacts it moves freely.
   pure function mechanism_warnings(deck) result(lines)
      type(deck_t), intent(in) :: deck                 !! validated deck
      character(len=warning_length), allocatable :: lines(:)
      logical :: rigid(2), held(2)
      character(len=:), allocatable :: planes
      allocate(lines(0))
      if (.not. allocated(deck%stops)) return
      call rigid_planes(deck%structure, deck%stops, rigid, held)
      if (.not. any(rigid)) return
      planes = 'w plane'
      if (rigid(2)) planes = 'v plane'
      if (all(rigid)) planes = 'w and v planes'
      call add(lines, "the beam is a mechanism: &root condition = 'pinned' with a free tip " &
         // 'and no &springs leaves the rigid rotation about the root free in the ' // planes &
         // ' (f = 0), held only by the stops; between impacts it moves freely, and a ' &
         // 'one-sided stop holds it on one side only (the beam may leave it and drift)')
   end function mechanism_warnings

   !> Gaps, base amplitude and section far outside the model's scale (the span L).
   pure function scale_warnings(deck) result(lines)
      type(deck_t), intent(in) :: deck                 !! validated deck
      character(len=warning_length), allocatable :: lines(:)
      character(len=:), allocatable :: t
      real(dp) :: span, depth, amp, ratio
      integer :: j
      character(len=*), parameter :: meant = ' (a value in mm given in m?)'
      allocate(lines(0))
      associate (b => deck%structure%beam)
         span = b%length
         if (.not. (span > 0.0_dp)) return
         if (b%width > 0.0_dp) then
            if (b%width > width_span_ratio * span) call add(lines, &
               '&beam width = ' // str(b%width) // ' m is ' // str(b%width / span) // ' times ' &
               // 'the span L = ' // str(span) // ' m: a section wider than the span is a ' &
               // 'plate, not a beam' // meant)
            depth = b%thickness
            t = '&beam thickness = ' // str(b%thickness) // ' m'
         else
            depth = sqrt(12.0_dp * b%second_moment / b%area)
            t = '&beam area = ' // str(b%area) // ' m^2 and second_moment = ' &
               // str(b%second_moment) // ' m^4 give a section depth sqrt(12 I / A) = ' &
               // str(depth) // ' m, which'
         end if
         if (depth > depth_span_fraction * span) call add(lines, &
            t // ' is ' // str(depth / span) // ' of the span L = ' // str(span) // ' m (more ' &
            // 'than ' // str(depth_span_fraction) // '): Euler-Bernoulli theory needs a ' &
            // 'slender beam' // meant)
      end associate
      if (uses_forcing(deck)) then
         amp = deck%forcing%amplitude_pp
         if (deck%job%analysis == 'sweep' .and. allocated(deck%sweep%amplitude_pp) .and. &
             index(deck%sweep%y_variable, 'amplitude_pp') > 0) then
            if (size(deck%sweep%amplitude_pp) > 0) amp = maxval(abs(deck%sweep%amplitude_pp))
         end if
         ratio = amp / span
         if (ratio > amplitude_span_fraction) call add(lines, &
            '&forcing amplitude_pp = ' // str(amp) // ' m is ' // str(ratio) // ' times the ' &
            // 'span L = ' // str(span) // ' m (more than ' // str(amplitude_span_fraction) &
            // '): above resonance the beam deflects by about A_pp/2 relative to the base, ' &
            // 'beyond the small deflections of beam theory' // meant)
      end if
      if (.not. allocated(deck%stops)) return
      do j = 1, size(deck%stops)
         ! a circular hole: the clearance at rest is its radius less the centre's offset
         ratio = clearance(deck%stops(j)) / span
         if (ratio > gap_span_fraction) call add(lines, &
            'stop ' // str(j) // ' (&stops gap(' // str(j) // ') = ' // str(deck%stops(j)%gap) &
            // ' ' // gap_unit(deck%stops(j)%dof) // ') is ' // str(ratio) // ' times the ' &
            // 'span L = ' // str(span) // ' m (more than ' // str(gap_span_fraction) &
            // '): to meet it the beam must deflect beyond the small deflections of beam ' &
            // 'theory' // meant)
      end do
   end function scale_warnings

   !> The stops the beam cannot reach from the deck's initial state (reach_bounds), for the
   !> analyses that integrate the deck's own forcing.
   function reach_warnings(deck) result(lines)
      type(deck_t), intent(in) :: deck                 !! validated deck
      character(len=warning_length), allocatable :: lines(:)
      type(model_t) :: model
      type(error_t), allocatable :: err
      real(dp), allocatable :: u0(:), v0(:), omegas(:), bc(:), br(:), worst_c(:), worst_r(:)
      real(dp), allocatable :: steady_c(:), steady_r(:), sc(:), sr(:)
      real(dp) :: half
      integer :: k, j
      logical :: ok
      character(len=:), allocatable :: where
      allocate(lines(0))
      ! the bound knows the harmonic forcing only: turbulence and fluid-elastic forces (an
      ! unstable mode grows until a stop limits it) reach stops it would call out of reach
      if (deck%turbulence%spectrum /= 'none' .or. (deck%flow%velocity > 0.0_dp .and. &
          deck%flow%fluid_elastic /= 'none')) return
      select case (deck%job%analysis)
      case ('transient', 'work_precision', 'model_size')
         omegas = [2.0_dp * pi * deck%forcing%frequency_hz]
         half = 0.5_dp * deck%forcing%amplitude_pp
         where = ' at ' // str(deck%forcing%frequency_hz) // ' Hz'
      case ('sweep')
         if (index(deck%sweep%x_variable, '&forcing frequency_hz') /= 1 .or. &
             index(deck%sweep%y_variable, '&forcing amplitude_pp') /= 1 .or. &
             deck%sweep%mode /= 'independent') return
         if (.not. allocated(deck%sweep%frequency_hz) .or. &
             .not. allocated(deck%sweep%amplitude_pp)) return
         if (size(deck%sweep%frequency_hz) == 0 .or. size(deck%sweep%amplitude_pp) == 0) return
         omegas = 2.0_dp * pi * deck%sweep%frequency_hz
         half = 0.5_dp * maxval(abs(deck%sweep%amplitude_pp))
         where = ' at any of the sweep''s ' // str(size(omegas)) // ' frequencies (largest ' &
            // 'amplitude)'
      case default
         return
      end select
      if (.not. allocated(deck%stops)) return
      if (size(deck%stops) == 0) return
      call build_full_model(deck%structure, deck%stops, deck%damping, deck%forcing, model, err)
      if (allocated(err)) return
      call initial_vectors(model, deck%initial, u0, v0)
      model%half_amplitude = half
      allocate(worst_c(model%n_contacts), steady_c(model%n_contacts), source=0.0_dp)
      allocate(worst_r(model%n_rings), steady_r(model%n_rings), source=0.0_dp)
      do k = 1, size(omegas)
         model%omega = omegas(k)
         call reach_bounds(model, u0, v0, bc, br, sc, sr, ok)
         if (.not. ok) return
         worst_c = max(worst_c, bc);  worst_r = max(worst_r, br)
         steady_c = max(steady_c, sc);  steady_r = max(steady_r, sr)
      end do
      ! the bound holds while the beam is linear, that is until it meets some stop: it proves
      ! a stop is never met only when every stop is out of reach (a stop within reach may
      ! send the beam further than the linear bound; the run's own count then tells)
      do j = 1, size(deck%stops)
         call stop_out_of_reach(deck, model, j, worst_c, worst_r, steady_c, steady_r, where, &
                                lines)
      end do
      if (size(lines) < size(deck%stops)) deallocate(lines)
      if (.not. allocated(lines)) allocate(lines(0))
   end function reach_warnings

   !> Add the warning of stop j when every contact of it is out of reach.
   subroutine stop_out_of_reach(deck, model, j, bc, br, sc, sr, where, lines)
      type(deck_t), intent(in) :: deck
      type(model_t), intent(in) :: model
      integer, intent(in) :: j                             !! deck stop
      real(dp), intent(in) :: bc(:), br(:), sc(:), sr(:)   !! bounds, steady amplitudes
      character(len=*), intent(in) :: where                !! ' at 10 Hz'
      character(len=warning_length), allocatable, intent(inout) :: lines(:)
      real(dp) :: reach, steady, gap
      integer :: c
      logical :: any_contact
      reach = 0.0_dp;  steady = 0.0_dp;  any_contact = .false.
      do c = 1, model%n_contacts
         if (model%c_stop(c) /= j) cycle
         any_contact = .true.
         reach = max(reach, bc(c));  steady = max(steady, sc(c))
      end do
      do c = 1, model%n_rings
         if (model%r_stop(c) /= j) cycle
         any_contact = .true.
         reach = max(reach, br(c));  steady = max(steady, sr(c))
      end do
      gap = clearance(deck%stops(j))
      if (.not. any_contact .or. .not. (gap > reach * (1.0_dp + 1.0e-9_dp))) return
      call add(lines, 'stop ' // str(j) // ' (node ' &
         // str(deck%stops(j)%node) // ', ' // dof_name(deck%stops(j)%dof) // '): gap ' &
         // str(deck%stops(j)%gap) // ' ' // gap_unit(deck%stops(j)%dof) // ' is out of ' &
         // 'reach: with its stops open the beam moves at most ' // str(reach) // ' ' &
         // gap_unit(deck%stops(j)%dof) // ' there' // where // ' (steady amplitude ' &
         // str(steady) // ', plus the decaying start from the deck''s initial state: a ' &
         // 'bound for the linear damped beam), so the stop will never be met')
   end subroutine stop_out_of_reach

   !> Bounds of the displacement of the open structure at every contact (bc, along its dof;
   !> rings: bc of the radial displacement of a circular hole from the beam's axis, or along
   !> a flat ring's normal) for all t from the initial state (u0, v0) under the model's
   !> forcing, and the steady amplitudes (sc, sr) in them. `ok` false when no finite bound
   !> exists or it cannot be computed: negative damping, a singular K (a mechanism), an
   !> undamped resonance.
   subroutine reach_bounds(model, u0, v0, bc, br, sc, sr, ok)
      type(model_t), intent(in) :: model                 !! model (full, not modal)
      real(dp), intent(in) :: u0(:), v0(:)               !! initial state
      real(dp), allocatable, intent(out) :: bc(:), br(:) !! bounds per contact, per ring
      real(dp), allocatable, intent(out) :: sc(:), sr(:) !! steady amplitudes
      logical, intent(out) :: ok                         !! bounds computed
      real(dp), allocatable :: ur(:), ui(:), kfac(:, :), e(:), h(:), hv(:)
      real(dp) :: energy, a(2, 2)
      integer :: c, n, kd, info, w, v
      n = model%n
      allocate(bc(model%n_contacts), sc(model%n_contacts), source=0.0_dp)
      allocate(br(model%n_rings), sr(model%n_rings), source=0.0_dp)
      ok = model%beta >= 0.0_dp .and. model%gamma >= 0.0_dp .and. n > 0
      if (.not. ok) return
      call steady_response(model, ur, ui, ok)
      if (.not. ok) return
      kd = bandwidth(model%sys%k)
      call dense_to_band(model%sys%k, kd, kfac)
      call dpbtrf('U', n, kd, kfac, kd + 1, info)
      ok = info == 0
      if (.not. ok) return
      h = u0 - ui
      hv = v0 - model%omega * ur
      energy = 0.5_dp * (dot_product(h, matmul(model%sys%k, h)) &
                         + dot_product(hv, matmul(model%sys%m, hv)))
      do c = 1, model%n_contacts
         w = model%c_dof(c)
         e = unit(n, w)
         bc(c) = hypot(ur(w), ui(w)) + sqrt(2.0_dp * max(energy, 0.0_dp) * flex(e))
         sc(c) = hypot(ur(w), ui(w))
      end do
      do c = 1, model%n_rings
         w = model%r_dof(1, c);  v = model%r_dof(2, c)
         if (model%r_circular(c)) then
            ! |u| <= sqrt(B_w^2 + B_v^2), each B a bound along one axis
            a(1, 1) = hypot(ur(w), ui(w)) + sqrt(2.0_dp * max(energy, 0.0_dp) * flex(unit(n, w)))
            a(2, 1) = hypot(ur(v), ui(v)) + sqrt(2.0_dp * max(energy, 0.0_dp) * flex(unit(n, v)))
            br(c) = hypot(a(1, 1), a(2, 1))
            sr(c) = hypot(hypot(ur(w), ui(w)), hypot(ur(v), ui(v)))
         else
            e = model%r_normal(1, c) * unit(n, w) + model%r_normal(2, c) * unit(n, v)
            sr(c) = hypot(dot_product(e, ur), dot_product(e, ui))
            br(c) = sr(c) + sqrt(2.0_dp * max(energy, 0.0_dp) * flex(e))
         end if
      end do
   contains
      !> e' K^-1 e.
      real(dp) function flex(e)
         real(dp), intent(in) :: e(:)
         real(dp), allocatable :: x(:, :)
         integer :: info2
         x = reshape(e, [n, 1])
         call dpbtrs('U', n, kd, 1, kfac, kd + 1, x, n, info2)
         flex = max(0.0_dp, dot_product(e, x(:, 1)))
      end function flex
   end subroutine reach_bounds

   !> The steady response u_p(t) = ur sin(Omega t) + ui cos(Omega t) to the model's harmonic
   !> loads: (K - Omega^2 M + i Omega C)(ur + i ui) = F^, solved as the real system of twice
   !> the size, interleaved (ur_1, ui_1, ur_2, ...) so that it stays banded. `ok` false when
   !> the matrix is singular (an undamped resonance, or a mechanism at Omega = 0).
   subroutine steady_response(model, ur, ui, ok)
      type(model_t), intent(in) :: model                 !! model
      real(dp), allocatable, intent(out) :: ur(:), ui(:) !! sine and cosine parts
      logical, intent(out) :: ok                         !! solved
      real(dp), allocatable :: fr(:), fi(:), ab(:, :), x(:, :)
      integer, allocatable :: ipiv(:)
      real(dp) :: om, a, aij, bij
      integer :: n, kd, kl, i, j, info, r0
      n = model%n
      om = model%omega
      a = model%half_amplitude * om**2
      allocate(ur(n), ui(n), source=0.0_dp)
      fr = a * model%q
      allocate(fi(n), source=0.0_dp)
      if (allocated(model%q_v)) then
         fr = fr + a * cos(model%phase_v) * model%q_v
         fi = fi + a * sin(model%phase_v) * model%q_v
      end if
      if (allocated(model%p_sin)) then
         fr = fr + model%p_sin
         fi = fi + model%p_cos
      end if
      ok = .true.
      if (all(fr == 0.0_dp) .and. all(fi == 0.0_dp)) return
      kd = max(bandwidth(model%sys%k), bandwidth(model%sys%m), bandwidth(model%c))
      kl = 2 * kd + 1
      r0 = 2 * kl + 1                           ! row of the diagonal in LAPACK's storage
      allocate(ab(3 * kl + 1, 2 * n), source=0.0_dp)
      do j = 1, n
         do i = max(1, j - kd), min(n, j + kd)
            aij = model%sys%k(i, j) - om**2 * model%sys%m(i, j)
            bij = om * model%c(i, j)
            ab(r0 + (2 * i - 1) - (2 * j - 1), 2 * j - 1) = aij    ! real row, ur column
            ab(r0 + (2 * i - 1) - 2 * j, 2 * j) = -bij             ! real row, ui column
            ab(r0 + 2 * i - (2 * j - 1), 2 * j - 1) = bij          ! imaginary row, ur column
            ab(r0 + 2 * i - 2 * j, 2 * j) = aij                    ! imaginary row, ui column
         end do
      end do
      allocate(x(2 * n, 1), ipiv(2 * n))
      x(1:2 * n:2, 1) = fr
      x(2:2 * n:2, 1) = fi
      call dgbtrf(2 * n, 2 * n, kl, kl, ab, 3 * kl + 1, ipiv, info)
      ok = info == 0
      if (.not. ok) return
      call dgbtrs('N', 2 * n, kl, kl, 1, ab, 3 * kl + 1, ipiv, x, 2 * n, info)
      ur = x(1:2 * n:2, 1)
      ui = x(2:2 * n:2, 1)
      ok = all(abs(ur) <= huge(1.0_dp)) .and. all(abs(ui) <= huge(1.0_dp))
   end subroutine steady_response

   !> Whether the analysis integrates the deck's forcing (its amplitude matters).
   pure logical function uses_forcing(deck)
      type(deck_t), intent(in) :: deck
      select case (deck%job%analysis)
      case ('transient', 'sweep', 'work_precision', 'model_size', 'continuation')
         uses_forcing = .true.
      case default
         uses_forcing = .false.
      end select
   end function uses_forcing

   !> The clearance of a stop at rest: its gap, less the centre's offset for a circular hole.
   pure real(dp) function clearance(st)
      type(stop_t), intent(in) :: st                   !! deck stop
      clearance = st%gap
      if (st%shape == 'circular') clearance = st%gap - hypot(st%offset_w, st%offset_v)
   end function clearance

   !> 'm' or 'rad' for a stop dof.
   pure function gap_unit(dof) result(t)
      integer, intent(in) :: dof
      character(len=:), allocatable :: t
      t = 'm'
      if (dof == 2 .or. dof == 4) t = 'rad'
   end function gap_unit

   !> Unit vector e_i of length n.
   pure function unit(n, i) result(e)
      integer, intent(in) :: n, i
      real(dp) :: e(n)
      e = 0.0_dp
      e(i) = 1.0_dp
   end function unit

   !> Append one line to a list.
   pure subroutine add(lines, text)
      character(len=warning_length), allocatable, intent(inout) :: lines(:)   !! list
      character(len=*), intent(in) :: text                                    !! the line
      character(len=warning_length), allocatable :: more(:)
      allocate(more(size(lines) + 1))
      more(1:size(lines)) = lines
      more(size(lines) + 1) = text
      call move_alloc(more, lines)
   end subroutine add

   !> Two lists of lines as one.
   pure function joined(a, b) result(c)
      character(len=warning_length), intent(in) :: a(:), b(:)
      character(len=warning_length), allocatable :: c(:)
      integer :: k
      allocate(c(size(a) + size(b)))
      do k = 1, size(a)
         c(k) = a(k)
      end do
      do k = 1, size(b)
         c(size(a) + k) = b(k)
      end do
   end function joined
end module gapbeam_warnings
