!> The resolved parameters of a run, as a list of named values, for the `/parameters` group of
!> every result file: what the deck gave and what the program derived from it (EI, rho A,
!> kappa = k_theta L / EI, the stop stiffness from the paper's rule, f1 with the stops open,
!> the highest frequency, the forcing period), everything needed to rebuild the model (end
!> conditions, springs, masses, planes and added mass, stop laws and shapes, friction, hole
!> offsets, wear coefficients, the forcing's direction and phase, point forces), so that a
!> file says which model produced it without its deck being parsed.
!>
!> Units and long names are those of the output catalogue (core/gapbeam_output_catalogue, under
!> /parameters); a value carries its units only where the deck decides them (a stop's gap in
!> m or rad), and the part of its long name that depends on the deck (`fill`).
module gapbeam_parameters
   use gapbeam_kinds, only: dp
   use gapbeam_error, only: str
   use gapbeam_deck, only: deck_t
   use gapbeam_laws, only: law_caps_of
   use gapbeam_law, only: law_caps_t
   use gapbeam_description, only: beam_ei, beam_rho_a, beam_fibre_distance, beam_mass, &
      dof_w, dof_v, dof_name, law_code, forcing_omega, beam_is_timoshenko, &
      beam_shear_coefficient, beam_shear_stiffness
   implicit none
   private
   public :: parameter_set_t, run_parameters, stiffness_units, forcing_text

   !> One named value (a number, a list of numbers, or a text).
   type :: parameter_t
      character(len=:), allocatable :: path        !! under /parameters, e.g. 'beam/length'
      real(dp), allocatable :: values(:)           !! the number(s); unallocated for a text
      logical :: is_array = .false.                !! a list (one value per stop, ...)
      character(len=:), allocatable :: text        !! a text value, else unallocated
      character(len=:), allocatable :: units       !! UDUNITS-2, where the deck decides them
      character(len=:), allocatable :: fill        !! the deck's part of the long name
   end type parameter_t

   !> The parameters of a run.
   type :: parameter_set_t
      type(parameter_t), allocatable :: items(:)   !! in the order they are written
   contains
      procedure :: add_real, add_list, add_text
   end type parameter_set_t

contains

   !> Add a scalar.
   subroutine add_real(self, path, value, units, fill)
      class(parameter_set_t), intent(inout) :: self    !! set
      character(len=*), intent(in) :: path             !! under /parameters
      real(dp), intent(in) :: value                    !! value
      character(len=*), intent(in), optional :: units  !! units, where the deck decides them
      character(len=*), intent(in), optional :: fill   !! the deck's part of the long name
      type(parameter_t) :: p
      p%path = path;  p%values = [value]
      if (present(units)) p%units = units
      if (present(fill)) p%fill = fill
      call append(self, p)
   end subroutine add_real

   !> Add a list of numbers (one per stop, per spring, ...).
   subroutine add_list(self, path, values, units)
      class(parameter_set_t), intent(inout) :: self    !! set
      character(len=*), intent(in) :: path             !! under /parameters
      real(dp), intent(in) :: values(:)                !! values
      character(len=*), intent(in), optional :: units  !! units, where the deck decides them
      type(parameter_t) :: p
      p%path = path;  p%values = values;  p%is_array = .true.
      if (present(units)) p%units = units
      call append(self, p)
   end subroutine add_list

   !> Add a text.
   subroutine add_text(self, path, text)
      class(parameter_set_t), intent(inout) :: self    !! set
      character(len=*), intent(in) :: path             !! under /parameters
      character(len=*), intent(in) :: text             !! value
      type(parameter_t) :: p
      p%path = path;  p%text = text
      call append(self, p)
   end subroutine add_text

   subroutine append(set, p)
      type(parameter_set_t), intent(inout) :: set
      type(parameter_t), intent(in) :: p
      if (.not. allocated(set%items)) allocate(set%items(0))
      set%items = [set%items, p]
   end subroutine append

   !> The parameters of a run of `deck`: the deck's values and what was resolved from them.
   !> The resolved values the caller knows are optional: the stop stiffnesses (the paper's rule
   !> applied), f1 with the stops open, the highest natural frequency and the number of dofs.
   function run_parameters(deck, stop_stiffness, f1_open_hz, f_max_hz, n_dof) result(set)
      type(deck_t), intent(in) :: deck                       !! validated deck
      real(dp), intent(in), optional :: stop_stiffness(:)    !! resolved, per deck stop
      real(dp), intent(in), optional :: f1_open_hz           !! first frequency, stops open [Hz]
      real(dp), intent(in), optional :: f_max_hz             !! highest frequency [Hz]
      integer, intent(in), optional :: n_dof                 !! dofs of the integrated model
      type(parameter_set_t) :: set
      allocate(set%items(0))
      call add_structure(set, deck)
      call add_stops(set, deck, stop_stiffness)
      call set%add_text('damping/model', trim(deck%damping%model))
      call set%add_real('damping/mass_coefficient', deck%damping%mass_coefficient)
      call set%add_real('damping/stiffness_coefficient', deck%damping%stiffness_coefficient)
      if (deck%damping%model == 'ratios') then
         call set%add_real('damping/frequency1_hz', deck%damping%frequency1_hz)
         call set%add_real('damping/ratio1', deck%damping%ratio1)
         call set%add_real('damping/frequency2_hz', deck%damping%frequency2_hz)
         call set%add_real('damping/ratio2', deck%damping%ratio2)
      end if
      if (deck%damping%model == 'modal') call set%add_list('damping/modal_ratios', &
                                                           deck%damping%modal_ratios)
      call add_forcing(set, deck)
      if (present(f1_open_hz)) call set%add_real('model/f1_open_hz', f1_open_hz)
      if (present(f_max_hz)) call set%add_real('model/f_max_hz', f_max_hz)
      if (present(n_dof)) call set%add_real('model/n_dof', real(n_dof, dp))
      call set%add_text('model/reduction', trim(deck%reduction%kind))
      if (deck%reduction%kind == 'modal') then
         call set%add_real('model/n_modes', real(deck%reduction%n_modes, dp))
         call set%add_real('model/static_correction', &
                           merge(1.0_dp, 0.0_dp, deck%reduction%static_correction))
      end if
   end function run_parameters

   !> The beam, its ends, the springs and point masses.
   subroutine add_structure(set, deck)
      type(parameter_set_t), intent(inout) :: set
      type(deck_t), intent(in) :: deck
      real(dp) :: ei
      integer :: ns, j
      logical :: rectangle
      associate (b => deck%structure%beam, root => deck%structure%root, &
                 tip => deck%structure%tip)
         ei = beam_ei(b)
         rectangle = b%width > 0.0_dp .and. b%thickness > 0.0_dp
         call set%add_real('beam/length', b%length)
         call set%add_real('beam/n_elem', real(b%n_elem, dp))
         call set%add_real('beam/element_length', b%length / real(b%n_elem, dp))
         call set%add_real('beam/youngs_modulus', b%youngs_modulus)
         call set%add_real('beam/density', b%density)
         if (rectangle) then
            call set%add_real('beam/width', b%width)
            call set%add_real('beam/thickness', b%thickness)
            call set%add_real('beam/area', b%width * b%thickness, fill=' = b h')
            call set%add_real('beam/second_moment', b%width * b%thickness**3 / 12.0_dp, &
                              fill=' = b h^3 / 12')
         else
            call set%add_real('beam/area', b%area, fill='')
            call set%add_real('beam/second_moment', b%second_moment, fill='')
         end if
         call set%add_real('beam/fibre_distance', beam_fibre_distance(b))
         call set%add_real('beam/bending_stiffness', ei)
         call set%add_real('beam/mass_per_length', beam_rho_a(b))
         call set%add_real('beam/mass', beam_mass(b))
         call set%add_text('beam/mass_matrix', trim(b%mass_matrix))
         call set%add_text('beam/rotary_inertia', trim(b%rotary_inertia))
         if (beam_is_timoshenko(b)) then
            call set%add_text('beam/theory', trim(b%theory))
            call set%add_real('beam/shear_modulus', b%shear_modulus)
            call set%add_real('beam/shear_coefficient', beam_shear_coefficient(b))
            call set%add_real('beam/shear_stiffness', beam_shear_stiffness(b))
            call set%add_real('beam/shear_parameter', 12.0_dp * ei / (beam_shear_stiffness(b) &
                              * (b%length / real(b%n_elem, dp))**2))
         end if
         call set%add_real('beam/planes', real(b%planes, dp))
         call set%add_real('beam/added_mass', b%added_mass)
         call set%add_text('root/condition', trim(root%condition))
         if (root%condition == 'spring') then
            call set%add_real('root/k_theta', root%k_theta)
            call set%add_real('root/kappa', root%k_theta * b%length / ei)
         end if
         call set%add_text('tip/condition', trim(tip%condition))
         if (tip%condition == 'spring') call set%add_real('tip/k_theta', tip%k_theta)
      end associate
      ns = 0
      if (allocated(deck%structure%springs)) ns = size(deck%structure%springs)
      call set%add_real('springs/count', real(ns, dp))
      if (ns > 0) then
         associate (sp => deck%structure%springs)
            call set%add_list('springs/node', [(real(sp(j)%node, dp), j = 1, ns)])
            call set%add_list('springs/dof', [(real(sp(j)%dof, dp), j = 1, ns)])
            call set%add_list('springs/stiffness', [sp%stiffness], &
                              units_of([sp%dof], 'N m-1', 'N m rad-1'))
         end associate
      end if
      ns = 0
      if (allocated(deck%structure%masses)) ns = size(deck%structure%masses)
      call set%add_real('masses/count', real(ns, dp))
      if (ns > 0) then
         associate (pm => deck%structure%masses)
            call set%add_list('masses/node', [(real(pm(j)%node, dp), j = 1, ns)])
            call set%add_list('masses/mass', [pm%mass])
            call set%add_list('masses/inertia', [pm%inertia])
         end associate
      end if
   end subroutine add_structure

   !> The stops: where, which law and shape, the contact constants.
   subroutine add_stops(set, deck, stop_stiffness)
      type(parameter_set_t), intent(inout) :: set
      type(deck_t), intent(in) :: deck
      real(dp), intent(in), optional :: stop_stiffness(:)
      integer :: ns, j
      ns = 0
      if (allocated(deck%stops)) ns = size(deck%stops)
      call set%add_real('stops/count', real(ns, dp))
      if (ns == 0) return
      associate (s => deck%stops)
         call set%add_list('stops/node', [(real(s(j)%node, dp), j = 1, ns)])
         call set%add_list('stops/gap', [s%gap], units_of([s%dof], 'm', 'rad'))
         if (present(stop_stiffness)) call set%add_list('stops/stiffness', stop_stiffness, &
                                                        stiffness_units(deck))
         call set%add_list('stops/damping', [s%damping], units_of([s%dof], 'N s m-1', &
                           'N m s rad-1'))
         call set%add_list('stops/exponent', [s%exponent])
         call set%add_list('stops/side', [(side_code(s(j)%side), j = 1, ns)])
         call set%add_list('stops/dof', [(real(s(j)%dof, dp), j = 1, ns)])
         call set%add_list('stops/law', [(real(law_code(s(j)%law), dp), j = 1, ns)])
         call set%add_list('stops/rule_factor', [s%rule_factor])
         call set%add_list('stops/rule_f1_ratio', [s%rule_f1_ratio])
         call set%add_list('stops/rule_f1_hz', [s%rule_f1_hz])
         call set%add_list('stops/circular', [(merge(1.0_dp, 0.0_dp, s(j)%shape == 'circular'), &
                                               j = 1, ns)])
         call set%add_list('stops/offset_w', [s%offset_w])
         call set%add_list('stops/offset_v', [s%offset_v])
         call set%add_list('stops/friction', [s%friction])
         call set%add_list('stops/tangential_stiffness', [s%tangential_stiffness])
         call set%add_list('stops/wear_coefficient', [s%wear_coefficient])
      end associate
   end subroutine add_stops

   !> The base motion and the point forces.
   subroutine add_forcing(set, deck)
      type(parameter_set_t), intent(inout) :: set
      type(deck_t), intent(in) :: deck
      integer :: nf, j
      associate (f => deck%forcing)
         call set%add_real('forcing/frequency_hz', f%frequency_hz)
         call set%add_real('forcing/amplitude_pp', f%amplitude_pp)
         call set%add_real('forcing/period', 1.0_dp / f%frequency_hz)
         call set%add_real('forcing/omega', forcing_omega(f))
         call set%add_real('forcing/direction_deg', f%direction_deg)
         call set%add_real('forcing/phase_v_deg', f%phase_v_deg)
         nf = 0
         if (allocated(f%forces)) nf = size(f%forces)
         call set%add_real('point_forces/count', real(nf, dp))
         if (nf == 0) return
         call set%add_list('point_forces/node', [(real(f%forces(j)%node, dp), j = 1, nf)])
         call set%add_list('point_forces/dof', [(real(f%forces(j)%dof, dp), j = 1, nf)])
         call set%add_list('point_forces/amplitude', [f%forces%amplitude], &
                           units_of([f%forces%dof], 'N', 'N m'))
         call set%add_list('point_forces/phase_deg', [f%forces%phase_deg])
      end associate
   end subroutine add_forcing

   !> Units of a quantity per dof: `displacement` when every dof is w or v, `rotation` when
   !> every one is a rotation, '1' (see the long name) when they are mixed.
   pure function units_of(dofs, displacement, rotation) result(u)
      integer, intent(in) :: dofs(:)                        !! dof codes
      character(len=*), intent(in) :: displacement, rotation
      character(len=:), allocatable :: u
      if (all(dofs == dof_w .or. dofs == dof_v)) then
         u = displacement
      else if (all(dofs /= dof_w .and. dofs /= dof_v)) then
         u = rotation
      else
         u = '1'
      end if
   end function units_of

   !> Units of the stop stiffnesses: N m-1 or N m rad-1 for laws with a linear stiffness
   !> (bilinear) at stops of one kind of dof; '1' (see the long name) otherwise (Hertz stops:
   !> N m-p, with p per stop).
   function stiffness_units(deck) result(u)
      type(deck_t), intent(in) :: deck                      !! the deck
      character(len=:), allocatable :: u
      type(law_caps_t) :: lc
      integer :: j
      u = '1'
      do j = 1, size(deck%stops)
         lc = law_caps_of(deck%stops(j)%law)
         if (.not. lc%linear_stiffness) return
      end do
      u = units_of([deck%stops%dof], 'N m-1', 'N m rad-1')
   end function stiffness_units

   !> What drives the structure, in words: the forcing frequency, the base motion (unless
   !> point forces alone drive it) and every point force, e.g. '8 Hz; point forces 1.5 N at
   !> node 4 (w), 1.5 N at node 4 (v, phase 90 deg); no base motion'.
   function forcing_text(deck) result(t)
      type(deck_t), intent(in) :: deck                      !! the deck
      character(len=:), allocatable :: t
      integer :: j, nf
      nf = 0
      if (allocated(deck%forcing%forces)) nf = size(deck%forcing%forces)
      t = str(deck%forcing%frequency_hz) // ' Hz'
      if (deck%forcing%amplitude_pp > 0.0_dp .or. nf == 0) then
         t = t // ', ' // str(deck%forcing%amplitude_pp * 1.0e3_dp) // ' mm peak to peak'
         if (deck%structure%beam%planes > 1) t = t // ' at ' &
            // str(deck%forcing%direction_deg) // ' deg from w'
      end if
      do j = 1, nf
         associate (pf => deck%forcing%forces(j))
            t = t // trim(merge('; point forces', ',             ', j == 1)) // ' ' &
               // str(pf%amplitude) // ' ' // trim(merge('N  ', 'N m', pf%dof == dof_w &
               .or. pf%dof == dof_v)) // ' at node ' // str(pf%node) // ' (' // dof_name(pf%dof)
            if (pf%phase_deg /= 0.0_dp) t = t // ', phase ' // str(pf%phase_deg) // ' deg'
            t = t // ')'
         end associate
      end do
      if (nf > 0 .and. .not. (deck%forcing%amplitude_pp > 0.0_dp)) t = t // '; no base motion'
   end function forcing_text

   pure real(dp) function side_code(word)
      character(len=*), intent(in) :: word
      select case (trim(word))
      case ('negative')
         side_code = -1.0_dp
      case ('both')
         side_code = 2.0_dp
      case default
         side_code = 1.0_dp
      end select
   end function side_code
end module gapbeam_parameters
