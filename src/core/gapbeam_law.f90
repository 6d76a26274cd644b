!> The contact (stop) law interface: what a law computes and what it states it can do.
!>
!> A one-sided contact acts at one dof with a direction s = +1 or -1; its penetration is
!> d = s u - gap (d > 0: in contact) and the force on the structure is -s f, with f >= 0 the
!> magnitude a law returns. Every law takes the three parameters a deck gives a stop
!> (&stops stiffness k, damping c, exponent p) and reads them its own way.
!>
!> A law is one type extending `contact_law_t` in its own module, and one line in the law
!> registry (gapbeam_laws). It states once, in its `caps`, what it can do; the deck reader,
!> the integrators' refusals, `method = 'auto'`, `--help` and the capability table of
!> docs/methods.md read that and nothing else. Integrators, event location, the recorder and
!> the energy meter call its procedures through this interface only: no code tests a law's
!> name.
!>
!> Laws live in core/ because the deck reader (io/, which uses core/ only) must ask them what
!> they allow. They are pure kernels of a few scalars, like the linear algebra kernels here.
module gapbeam_law
   use gapbeam_kinds, only: dp
   implicit none
   private
   public :: contact_law_t, law_caps_t, law_slot_t

   !> What a contact law can do and which deck parameters it reads.
   type :: law_caps_t
      character(len=16) :: name = ''              !! the deck's word (&stops law)
      character(len=16) :: title = ''             !! how a sentence names it ('Hertz')
      character(len=96) :: force_text = ''        !! its force, in words (docs, --help)
      !> the force is k d + c d' while in contact and 0 outside (bilinear in (d, d')): the
      !> exact integrator, its flow Jacobian (continuation) and the amplitude scaling of a
      !> zero gap rely on this form
      logical :: piecewise_linear = .false.
      logical :: uses_damping = .false.           !! reads &stops damping (a contact damper)
      logical :: uses_exponent = .false.          !! reads &stops exponent
      real(dp) :: exponent_min = 1.0_dp           !! smallest exponent allowed
      real(dp) :: exponent_max = 1.0_dp           !! largest exponent allowed
      logical :: rings = .false.                  !! normal law of ring supports (circular, friction)
      !> k is a linear stiffness [N/m, N m/rad]: the units of the stop stiffness outputs, and
      !> with friction tangential_stiffness defaults to it (else it must be given)
      logical :: linear_stiffness = .false.
   end type law_caps_t

   !> A contact law: force, its condensed implicit solve, its energy.
   type, abstract :: contact_law_t
   contains
      procedure(caps_interface), deferred :: caps          !! what it can do
      procedure(force_interface), deferred :: force        !! f(d, d')
      procedure(force_interface), deferred :: extended     !! smooth extension (Newton)
      procedure(rate_interface), deferred :: rate          !! df/dt from d, d', d''
      procedure(elastic_interface), deferred :: elastic    !! elastic part of f
      procedure(elastic_interface), deferred :: energy     !! stored elastic energy
      procedure(solve_interface), deferred :: solve        !! exact condensed solve
      procedure(flag_interface), deferred :: releases_early  !! f can vanish with d > 0
      procedure(flag_interface), deferred :: jumps         !! f jumps at a contact onset
      procedure(onset_interface), deferred :: onset_rate   !! df/dt just after an onset
      procedure :: name => law_name                        !! caps%name, trimmed
   end type contact_law_t

   !> A law in an array (one per law code of a model).
   type :: law_slot_t
      class(contact_law_t), allocatable :: law   !! the law
   end type law_slot_t

   abstract interface
      !> What the law can do.
      pure function caps_interface(self) result(c)
         import :: contact_law_t, law_caps_t
         class(contact_law_t), intent(in) :: self   !! law
         type(law_caps_t) :: c
      end function caps_interface

      !> Force magnitude f >= 0 at penetration d and rate d' (0 for d <= 0); `extended`: a
      !> smooth extension beyond the contact (any sign) for a Newton iteration.
      pure real(dp) function force_interface(self, k, c, p, d, dd) result(f)
         import :: contact_law_t, dp
         class(contact_law_t), intent(in) :: self   !! law
         real(dp), intent(in) :: k, c, p            !! stiffness, damping, exponent
         real(dp), intent(in) :: d, dd              !! penetration [m], its rate [m/s]
      end function force_interface

      !> Rate of the force df/dt in contact from d, d' and d'' [N/s].
      pure real(dp) function rate_interface(self, k, c, p, d, dd, ddd) result(r)
         import :: contact_law_t, dp
         class(contact_law_t), intent(in) :: self   !! law
         real(dp), intent(in) :: k, c, p            !! stiffness, damping, exponent
         real(dp), intent(in) :: d, dd, ddd         !! penetration, rate, its rate
      end function rate_interface

      !> Elastic part of the force (f less the damper's share) [N], or the elastic energy
      !> stored at penetration d [J]; 0 for d <= 0.
      pure real(dp) function elastic_interface(self, k, c, p, d) result(e)
         import :: contact_law_t, dp
         class(contact_law_t), intent(in) :: self   !! law
         real(dp), intent(in) :: k, c, p            !! stiffness, damping, exponent
         real(dp), intent(in) :: d                  !! penetration [m]
      end function elastic_interface

      !> The exact contact force inside an implicit step: d = d_star - h f and
      !> d' = v_star - kappa h f (h > 0 the step's compliance at the contact, kappa =
      !> d(rate)/d(displacement) of the scheme); the unique f >= 0 with f = force(d, d').
      pure real(dp) function solve_interface(self, k, c, p, d_star, v_star, h, kappa) result(f)
         import :: contact_law_t, dp
         class(contact_law_t), intent(in) :: self   !! law
         real(dp), intent(in) :: k, c, p            !! stiffness, damping, exponent
         real(dp), intent(in) :: d_star             !! penetration with zero force [m]
         real(dp), intent(in) :: v_star             !! its rate with zero force [m/s]
         real(dp), intent(in) :: h                  !! compliance [m/N]
         real(dp), intent(in) :: kappa              !! [1/s]
      end function solve_interface

      !> A property of the law with these parameters.
      pure logical function flag_interface(self, k, c, p) result(yes)
         import :: contact_law_t, dp
         class(contact_law_t), intent(in) :: self   !! law
         real(dp), intent(in) :: k, c, p            !! stiffness, damping, exponent
      end function flag_interface

      !> Growth rate of the force just after an onset (d = 0) at penetration rate d' > 0 [N/s].
      pure real(dp) function onset_interface(self, k, c, p, dd) result(r)
         import :: contact_law_t, dp
         class(contact_law_t), intent(in) :: self   !! law
         real(dp), intent(in) :: k, c, p            !! stiffness, damping, exponent
         real(dp), intent(in) :: dd                 !! penetration rate [m/s]
      end function onset_interface
   end interface

contains

   !> The law's name (its caps%name).
   pure function law_name(self) result(name)
      class(contact_law_t), intent(in) :: self   !! law
      character(len=:), allocatable :: name
      type(law_caps_t) :: c
      c = self%caps()
      name = trim(c%name)
   end function law_name
end module gapbeam_law
