!> What a run gives back: its cost estimate and its results per speed (and
!> per position with `series`). Types only: the time loop
!> (pavefric_simulate) fills them; the table of outputs (pavefric_outputs),
!> the NetCDF writer and the interfaces read them.
module pavefric_results
   use pavefric_kinds, only: wp, i8
   implicit none
   private

   public :: cost_estimate_type, sim_result_type

   !> What a run will cost, known before it starts: printed by the program
   !> before the run and recorded in the output, so that a user sees the
   !> price of a knob (substeps, elements_per_sample) before paying it.
   type :: cost_estimate_type
      !> Element updates of one pass at the scene's knobs, per speed and for
      !> all speeds: (spin-up + averaged positions) x pad elements, exactly
      !> (`memory_updates` counts the same on a viscous scene).
      integer(i8) :: element_steps = 0, total_element_steps = 0
      !> Peak memory of the run (bytes): geometry, per-speed state, series
      !> and the output built in memory.
      real(wp) :: bytes = 0.0_wp
      !> Seconds on one thread at the calibrated rates below, with the
      !> error estimate's pass (step_passes); with &numerics tolerance, of
      !> the first pass (each refinement doubles it); with the passes that
      !> will refine the pad where a probe found it on few elements.
      real(wp) :: seconds = 0.0_wp
      !> Of `seconds`, those refining the pad (add_refinement_cost), and the
      !> speeds (km/h) the probe found standing on too few elements.
      real(wp) :: refine_seconds = 0.0_wp
      real(wp), allocatable :: refine_speeds(:)
      !> With &numerics tolerance: a guess of the substeps the refinement
      !> will reach, of the seconds of all its passes to there and of the
      !> bytes of its last pass (tolerance_guess), 0 without a tolerance.
      integer :: tolerance_substeps = 0
      real(wp) :: tolerance_seconds = 0.0_wp, tolerance_bytes = 0.0_wp
   end type cost_estimate_type


   !> Results of one scene, per speed (and per position with `series`).
   type :: sim_result_type
      !> Pad elements N.
      integer :: n_elements = 0
      !> Averaged positions per speed M.
      integer :: n_positions = 0
      !> Spin-up positions before averaging (closed profiles).
      integer :: n_spinup = 0
      !> The rubber thickness (m), to compare max_compression with.
      real(wp) :: thickness = 0.0_wp
      !> The cost estimated before the run (of its first pass).
      type(cost_estimate_type) :: estimate
      !> Speeds (m s-1) and (km h-1).
      real(wp), allocatable :: speed(:), speed_kmh(:)
      !> The spacing of the profile the pad slid over (m): &pad
      !> element_length (adjusted to a whole number round a closed profile),
      !> or the profile's own.
      real(wp) :: element_spacing = 0.0_wp
      !> Mean friction coefficient over the profile (Eq. 12).
      real(wp), allocatable :: mu(:)
      !> Its parts: the rubber's dissipation (hysteresis) and the facets'
      !> local friction (adhesion), each per unit load and distance slid.
      real(wp), allocatable :: mu_hysteresis(:), mu_adhesion(:)
      !> Share of averaged positions where no element touched.
      real(wp), allocatable :: hydroplaning_fraction(:)
      !> Share of averaged positions where the film carried load.
      real(wp), allocatable :: wet_fraction(:)
      !> Largest |sum F + Wh - W| / W over the averaged positions.
      real(wp), allocatable :: max_balance_residual(:)
      !> Mean load carried by the film (N), and as a share of the pad's load.
      real(wp), allocatable :: mean_hydro_load(:), film_load_share(:)
      !> Share of the pad's elements in contact, averaged over positions.
      real(wp), allocatable :: contact_fraction(:)
      !> The film's water between the pad and the road per unit of pad area
      !> (m), averaged over positions (0 for films that do not resolve it).
      real(wp), allocatable :: mean_water_thickness(:)
      !> Averaged positions where the film's solution did not settle.
      integer(i8), allocatable :: film_unsettled(:)
      !> Averaged positions where the wet balance's root jumped (a film
      !> whose load is not monotone; film_root_jumps).
      integer(i8), allocatable :: film_root_jumps(:)
      !> The same, the largest over every pass the run made for the speed
      !> (the reported one, &numerics tolerance's and min_contacts' passes,
      !> the error estimate's): where only another pass had them, the
      !> reported mu still rests on a balance that can jump (one warning).
      integer(i8), allocatable :: root_jumps_seen(:)
      !> Largest compression of an element (m), to compare with the thickness.
      real(wp), allocatable :: max_compression(:)
      !> Contacts on facets steeper than theta_max, summed over positions.
      integer(i8), allocatable :: n_clamped(:)
      !> Evaluations of the film's load (0 when it did not run).
      integer(i8), allocatable :: bearing_evaluations(:)
      !> Element-steps that updated the rubber's memory (0 for an elastic scene).
      integer(i8), allocatable :: memory_updates(:)
      !> Whether the elements carried memory at this speed.
      logical, allocatable :: viscous_memory_ran(:)
      !> Whether the speed ran the exact Kelvin-Voigt integrator.
      logical, allocatable :: exact_integrator_ran(:)
      !> Whether a load-carrying film took part in the balance at this speed.
      logical, allocatable :: bearing_ran(:)
      !> Whether a friction-changing film ran at this speed.
      logical, allocatable :: friction_film_ran(:)
      !> With &numerics tolerance: the estimated error of mu (the change
      !> from the previous time step) and the substeps that met it.
      real(wp), allocatable :: mu_error(:)
      integer, allocatable :: substeps_used(:)
      !> With the error estimate at tolerance = 0: the elements_per_sample
      !> of its pass (twice the run's where the pad stood on few elements
      !> and the pass refined them too); else the run's.
      integer, allocatable :: estimate_elements_per_sample(:)
      !> With the error estimate at tolerance = 0, where the pad stood on few
      !> elements: the elements_per_sample at which its levels stopped, the
      !> elements in contact and mu there (the run's own elsewhere).
      integer, allocatable :: refined_elements_per_sample(:)
      real(wp), allocatable :: refined_mu(:), refined_contacts(:)
      !> The elements_per_sample of each speed's reported run: the value
      !> given, or more where &numerics min_contacts refined the pad; and
      !> the pad's elements there (n_elements at the value given).
      integer, allocatable :: elements_per_sample_used(:), speed_n_elements(:)
      !> Whether mu is the Richardson value of the last two passes (per speed).
      logical, allocatable :: extrapolated(:)
      !> Mean local friction over the contacts (force-weighted) with a
      !> friction-changing film, and the mean film under the pad (m).
      real(wp), allocatable :: mean_local_friction(:), mean_film_thickness(:)
      !> Distance slid from the first averaged position (m), with series.
      real(wp), allocatable :: position(:)
      !> Per position and speed, with series: instantaneous friction (Eq. 11),
      !> film load (N), pad penetration delta (m), elements in contact; with a
      !> friction-changing film also the mean film thickness under the pad (m)
      !> and the force-weighted local friction.
      real(wp), allocatable :: mu_inst(:,:), hydro_load(:,:), penetration(:,:)
      integer, allocatable :: contact_elements(:,:)
      real(wp), allocatable :: film_thickness(:,:), local_friction(:,:)
      !> Per position and speed, with series and a film that reports its
      !> solution (the Reynolds film): its largest pressure (Pa) and its
      !> water per unit of pad area (m) at the balance's root.
      real(wp), allocatable :: film_pressure_max(:,:), water_thickness(:,:)
      !> The effects that ran, comma-separated (the output's `effects`).
      character(len=:), allocatable :: effects
      !> Warnings about suspicious results, one a line ('' = none).
      character(len=:), allocatable :: warnings
   end type sim_result_type

end module pavefric_results
