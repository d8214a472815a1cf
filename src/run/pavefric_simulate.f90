!> The simulation driver: the pad slides over the profile, position after
!> position, at each speed (paper Fig. 4). It works through the rubber and
!> film components (pavefric_rubber, pavefric_film) and never branches on
!> which ones it has. Speeds are independent, so they run in parallel under
!> OpenMP with results identical to a serial run.
module pavefric_simulate
   use, intrinsic :: iso_c_binding, only: c_long_long, c_int
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use pavefric_kinds, only: wp, i8, kmh_to_ms
   use pavefric_error, only: error_type, fatal_error, add_warning, stat_memory, stat_internal
   use pavefric_format, only: to_str, round_sig
   use pavefric_model, only: model_type, validate_model, shape_code, max_substeps, &
      & max_elements_per_sample
   use pavefric_pad, only: pad_bottom
   use pavefric_heights, only: refine_profile, check_heights, resample_to_length, resampled_points, &
      & max_profile_height
   use pavefric_rubber, only: rubber_model, rubber_step_type, kelvin_voigt_rubber
   use pavefric_film, only: film_model, film_step_type, pseudo_bearing_film
   use pavefric_results, only: cost_estimate_type, sim_result_type
   use pavefric_components, only: make_components
   use pavefric_facet, only: facet_friction, facet_tangent
   use pavefric_balance, only: dry_roots, dry_roots_of_c, wet_roots, gap_field, engaged_lanes, &
      & engaged_by_level, lanes
   use pavefric_kv_exact, only: kv_exact_lane, kv_exact_type
   !$ use omp_lib, only: omp_get_max_threads
   implicit none
   private

   public :: sim_result_type, simulate, pad_elements, averaged_positions, effects_text
   public :: make_components, cost_estimate_type, estimate_cost, check_memory, element_grid
   public :: check_profile_scale
   public :: tolerance_guess
   public :: add_spinup_cost, add_refinement_cost, richardson

   !> Largest height a profile may have (m): far beyond any texture, small
   !> enough that no difference of heights can overflow.
   real(wp), parameter :: max_height = max_profile_height

   !> Phases of the pad's element grid on a resampled profile (&pad
   !> element_length): the grid starts at k / element_phases of an element,
   !> k = 0 .. element_phases - 1, and the results are averaged over them.
   !> Where the grid falls moves a profile's friction by several per cent
   !> (CAPTIF station 0: 0.433 to 0.459 over four phases, mu_loc = 0.3);
   !> four phases bring profiles given at 0.037 to 0.5 mm within 2 % of each
   !> other (docs/model.md).
   integer, parameter, public :: element_phases = 4

   !> Most laps of a closed profile a speed spins up over before averaging
   !> (lap_spinup).
   integer, parameter :: max_spin_laps = 4

   !> mu_hysteresis below -max(this, negative_share |mu|) is neither
   !> rounding (an elastic pad's is within 1e-9 of 0) nor the small
   !> difference of stored energy between an open profile's first and last
   !> positions (-4.5e-4 against mu 0.62 on a batch's segments): the warning
   !> that the pad's state did not repeat.
   real(wp), parameter :: negative_hysteresis = 1.0e-6_wp, negative_share = 0.01_wp

   interface
      function c_physical_memory() bind(C, name="pavefric_physical_memory") result(bytes)
         import :: c_long_long
         integer(c_long_long) :: bytes
      end function c_physical_memory
      !> 0 if this thread's OpenMP pool came through fork() (src/io/pavefric_files_lock.c).
      function parallel_ok() bind(C, name="pavefric_parallel_ok") result(ok)
         import :: c_int
         integer(c_int) :: ok
      end function parallel_ok
   end interface

   ! The cost model (one thread): a part per profile sample (reading,
   ! preprocessing, texture metrics, writing), a part per refined sample and
   ! pass (the geometry; the error estimate's pass counts), a part per pad
   ! position that the speeds' lanes share (the wet balance's iterations run until every
   ! lane has converged), and a part per element-step of each speed. Fitted
   ! on the "training" runs of `python -m pavefric bench`'s cost-estimate
   ! section (a 65,536-point open profile at 1 to 12 speeds, each model) on
   ! the 2-core AMD EPYC development machine; its "test" runs, which the fit
   ! did not see, judge it (docs/performance.md). The section prints the
   ! rates refitted on its own training runs (non-negative least squares on
   ! the relative error), which is how these were obtained (2026-11-26, with
   ! the error estimate's pass).
   !> Every rate below is that host's times hosts_scale: on 2026-12-06 the
   !> benchmark ran on an Intel Xeon host about twice as fast (estimated /
   !> measured 1.50-2.73 over the cost section's scenes, where the AMD
   !> host's last run read 0.73-1.65). The rates are scaled to the middle of
   !> the two (0.71: both hosts then within a factor 2, 1.07-1.94 and
   !> 0.52-1.17); a host more than about 1.4 times faster or slower than
   !> both reads outside it. The seconds are a host's, the element-steps and
   !> bytes are not. (Scaled here, the rates, so that every use of them,
   !> the run's, the spin-up's and the probe's, takes the same seconds.)
   real(wp), parameter :: hosts_scale = 0.71_wp
   real(wp), parameter :: sec_point = hosts_scale * 5.9e-7_wp, &
      & sec_step = hosts_scale * 9.3e-9_wp, sec_arm = hosts_scale * 1.2e-9_wp
   !> The paper's bearing: refitted on 2026-11-29 on the section's five
   !> kane2017 training runs alone, the other rates held (non-negative least
   !> squares on the relative error of what they leave), after its balance
   !> took the roots of its pieces without a checking pass (1.7e-8 and
   !> 7.1e-7 before; those runs' estimated / measured were 1.31-1.53).
   real(wp), parameter :: sec_bearing_step = hosts_scale * 8.1e-9_wp, &
      & sec_bearing_position = hosts_scale * 5.0e-7_wp
   real(wp), parameter :: sec_squeeze_step = hosts_scale * 4.1e-8_wp, &
      & sec_squeeze_position = 0.0_wp
   !> The drainage film's update per road sample under an element (a vector
   !> add over the footprint, substeps samples an element): set on
   !> 2026-12-06 from a 256-point profile at substeps 64-1024 (1024: 2.0 s
   !> measured, 0.45 s estimated without it), where it is the larger part;
   !> below about 100 substeps it is under half of sec_squeeze_step.
   real(wp), parameter :: sec_squeeze_sample = hosts_scale * 1.5e-10_wp
   !> The Reynolds film (wet_model = 'reynolds'; before 2026-11-27 it was
   !> costed as the paper's bearing, 25 times too cheap): the section's
   !> refit of 2026-11-27 on its two Reynolds training runs (9.5e-7; the
   !> other rates kept from 2026-11-26), divided by 1.74 on 2026-11-28, the
   !> mean estimated / measured of those two runs after the film's balance
   !> took fewer and cheaper evaluations (1.56 and 1.92; the other models'
   !> rows 0.79-1.59 in the same run).
   real(wp), parameter :: sec_reynolds_step = hosts_scale * 5.5e-7_wp, &
      & sec_reynolds_position = 0.0_wp
   real(wp), parameter :: sec_run = hosts_scale * 1.0e-3_wp, &
      & sec_point_pass = hosts_scale * 4.5e-7_wp
   !> mu's estimated error from the time step, as a share of mu, above
   !> which a run at tolerance = 0 warns (&numerics error_estimate); an
   !> estimate below `estimate_floor` never warns (mu itself near 0).
   real(wp), parameter :: estimate_warning = 0.05_wp, estimate_floor = 1.0e-3_wp
   !> Elements in contact, averaged over the positions, below which the pad
   !> does not resolve its contacts (counted where any element touched):
   !> the shipped tread compound below 40 C stands on one to four of the 23
   !> default elements, and its friction then changes by up to a factor 2
   !> as the elements are refined, at any time step (docs/accuracy.md, "The
   !> pad's resolution"). The error estimate then halves the elements until
   !> the pad stands on this many (estimate_step_error), and a tolerance
   !> warns. (At 4.4 contacts the compound's time-step estimate still covers
   !> its error, 1.2 times; the paper's rubber stands on 4 to 15, where the
   !> elements change mu by a tenth of the step's error.)
   real(wp), parameter :: contacts_resolved = 4.0_wp
   !> The error estimate halves the elements at most this many times to
   !> bring the pad onto contacts_resolved of them (elements_per_sample up
   !> to 16 times the run's; the levels cost up to 4 + 16 + 64 + 256 times
   !> the run's element-steps, the last pass 2 or 4 times the last level's).
   integer, parameter :: pad_levels = 4
   !> Round a closed profile, a negative rubber part no larger than this
   !> share of the steps' mean |work| is the stored energy's rounding (the
   !> dissipation it stands for is >= 0 by construction; a dry road's path
   !> imbalance, docs/model.md "Friction", is far above this where it is
   !> not 0) and reads 0.
   real(wp), parameter :: rounding_share = 1.0e-10_wp


   !> One speed's averaged results (see sim_result_type for their meaning).
   type :: speed_summary_type
      real(wp) :: mu = 0, mu_hysteresis = 0, mu_adhesion = 0, hydroplaning_fraction = 0, wet_fraction = 0
      real(wp) :: max_balance_residual = 0, mean_hydro_load = 0, max_compression = 0
      real(wp) :: mean_local_friction = 0, mean_film_thickness = 0
      real(wp) :: contact_fraction = 0, mean_water_thickness = 0
      integer(i8) :: n_clamped = 0, bearing_evaluations = 0, memory_updates = 0
      integer(i8) :: film_unsettled = 0, film_root_jumps = 0
      !> Spin-up positions this speed ran, and whether its memory outlasted them.
      integer :: spinup = 0
      logical :: spin_short = .false.
      logical :: viscous_memory_ran = .false., bearing_ran = .false.
      logical :: friction_film_ran = .false.
      !> Whether the speed ran the exact Kelvin-Voigt integrator
      !> (time_scheme = 'exact'), and the position where its events ran away.
      logical :: exact_ran = .false.
      integer :: exact_bad_position = 0
      !> The exact integrator declined the speed under a film (its events
      !> ran away, or the film lifts the pad only all but closed): the
      !> driver runs it again with backward Euler.
      logical :: exact_declined = .false.
      !> stat_memory when the speed's work arrays could not be allocated,
      !> stat_internal when the exact integrator's events ran away.
      integer :: failed = 0
   end type speed_summary_type

   !> Everything about the profile and pad that does not depend on speed.
   type :: geometry_type
      real(wp), allocatable :: z(:), tan_theta(:), h(:)
      !> tan(theta) - tan(alpha) (both clamped): the local friction's part of
      !> a facet's tangent (Eq. 10 split into slope and local friction).
      real(wp), allocatable :: adhesion(:)
      !> Facet slopes tan(alpha), for films that change the local friction.
      real(wp), allocatable :: slope(:)
      logical, allocatable :: clamped(:)
      !> clamped as 1 or 0, for the vector loops.
      real(wp), allocatable :: clamped_at(:)
      integer :: n_el = 0, spacing = 1, stride = 1, n_avg = 0, n_spin = 0, npf = 0
      logical :: closed = .true.
      !> Element width (m) and pad advance per step (m).
      real(wp) :: dx_el = 0.0_wp, advance = 0.0_wp
   end type geometry_type

   !> The dry balance's first pass, taken in lane_free_gaps_from's: per lane,
   !> the guess g of the penetration going in; the count of the clearances
   !> below it, the sum of their c - g, the largest of them and the least of
   !> the others coming out (dry_roots_of_c).
   type :: dry_start_type
      real(wp), dimension(lanes) :: guess = 0.0_wp, sums = 0.0_wp, counts = 0.0_wp, &
         & below = 0.0_wp, above = 0.0_wp
   end type dry_start_type

contains

   !> Why the pad has no element: its length is under half the element's
   !> (dx_el: the spacing the pad's elements get, `resampled` when that is
   !> &pad element_length's grid), naming what set the element's length.
   pure subroutine no_element_message(m, dx_el, resampled, text)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: dx_el
      logical, intent(in) :: resampled
      character(len=:), allocatable, intent(out) :: text
      character(len=:), allocatable :: made
      if (resampled) then
         made = "&pad element_length = " // to_str(m%element_length) // " m"
      else
         made = "the profile's spacing dx = " // to_str(dx_el) // " m"
      end if
      if (m%elements_per_sample > 1) made = made // " / &numerics elements_per_sample = " // &
         & to_str(m%elements_per_sample)
      text = "&pad length = " // to_str(m%length) // " m is less than half an element (" // &
         & made // ": elements of " // to_str(round_sig(dx_el / m%elements_per_sample, 4)) // &
         & " m), so the pad would have no element; give a pad at least one element long " // &
         & "(&pad length >= " // to_str(round_sig(dx_el / m%elements_per_sample, 4)) // " m)"
      if (resampled) then
         text = text // " or a shorter &pad element_length"
      else
         text = text // " or a finer profile (or &numerics elements_per_sample)"
      end if
   end subroutine no_element_message

   !> A profile of np samples at spacing dx (the user's) a thousand times
   !> shorter than the pad (resampled to the pad's elements), or so short
   !> that the pad would need more than 2e9 elements at its spacing: said of
   !> &surface dx (a spacing in other units than metres is the likely
   !> cause), not of the resampled grid nor as a lack of memory.
   pure subroutine tiny_profile_message(m, np, dx, text)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np
      real(wp), intent(in) :: dx
      character(len=:), allocatable, intent(out) :: text
      text = "&surface dx = " // to_str(dx) // " m: the profile of " // to_str(np) // &
         & " points is " // to_str(round_sig(real(np, wp) * dx, 4)) // " m long, far " // &
         & "shorter than the pad (&pad length = " // to_str(m%length) // " m); give dx " // &
         & "in metres (or a profile at least as long as the pad)"
   end subroutine tiny_profile_message

   !> A profile of np samples at the user's spacing dx a thousand times
   !> shorter than the pad, or so fine that the pad would need more than 2e9
   !> elements at its spacing while the refined profile itself fits:
   !> refused naming &surface dx, before anything is estimated or resampled
   !> from it (tiny_profile_message). The one place this refusal is made
   !> (run_grids, the program's estimate, check_inputs).
   pure subroutine check_profile_scale(m, np, dx, error)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np
      real(wp), intent(in) :: dx
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: text
      if (.not. real(np, wp) * dx < 1.0e-3_wp * m%length) then
         if (pad_elements(m, dx) < huge(1)) return
         ! (a refined profile that would not fit is the knobs' refusal)
         if (real(np, wp) * real(m%elements_per_sample, wp) * real(m%substeps, wp) > &
            & 2.0e9_wp) return
      end if
      call tiny_profile_message(m, np, dx, text)
      call fatal_error(error, text)
   end subroutine check_profile_scale

   !> Pad elements N = nint(L / (dx / elements_per_sample)).
   pure function pad_elements(m, dx) result(n)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: dx
      integer :: n
      real(wp) :: r
      r = m%length / (dx / real(m%elements_per_sample, wp))
      if (.not. (r < 2.0e9_wp)) then
         n = huge(1)
         return
      end if
      n = nint(r)
   end function pad_elements

   !> Averaged positions for a profile of np samples (0 if the pad does not fit).
   pure function averaged_positions(m, np, dx, closed) result(n_avg)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np
      real(wp), intent(in) :: dx
      logical, intent(in) :: closed
      integer :: n_avg, n_el, s, npf, fine
      n_avg = 0
      n_el = pad_elements(m, dx)
      s = m%substeps
      fine = m%elements_per_sample * s
      if (n_el >= huge(1) / max(s, 1) - 1) return
      if (real(np, wp) * real(fine, wp) > 2.0e9_wp) return
      if (closed) then
         npf = np * fine
         n_avg = (npf + m%position_stride - 1) / m%position_stride
         if (npf < n_el * s .or. n_el < 1) n_avg = 0
      else
         npf = (np - 1) * fine + 1
         n_avg = max(0, (npf - (n_el - 1) * s - 1) / m%position_stride + 1)
         if (npf < (n_el - 1) * s + 1 .or. n_el < 1) n_avg = 0
      end if
   end function averaged_positions

   !> The averaged positions a run needs: on an open profile two, since
   !> friction is the work done over the distance the pad slides from its
   !> first position (one position is a pad that lands and never slides);
   !> a closed profile's one position has the whole loop behind it (the
   !> spin-up).
   pure integer function positions_needed(closed)
      logical, intent(in) :: closed
      positions_needed = merge(1, 2, closed)
   end function positions_needed

   !> Why a profile of np samples at spacing dx is too short for the pad at
   !> m's knobs (averaged_positions below positions_needed), and what would
   !> do: the fewest samples at that spacing, or the longest pad. `resampled`:
   !> the profile was resampled to that &pad element_length (m; 0: not).
   !> (A subroutine: a deferred-length function result costs a static
   !> length per call site, shared by threads; tests/test_threads.py.)
   pure subroutine short_profile_message(m, np, dx, closed, resampled, text)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np
      real(wp), intent(in) :: dx, resampled
      logical, intent(in) :: closed
      character(len=:), allocatable, intent(out) :: text
      character(len=:), allocatable :: pad, spacing
      real(wp) :: fine, s, stride, need, np_min, el_max, longest, unit
      integer :: n_el, n_avg
      n_el = pad_elements(m, dx)
      n_avg = averaged_positions(m, np, dx, closed)
      s = real(m%substeps, wp)
      fine = real(m%elements_per_sample, wp) * s
      stride = real(m%position_stride, wp)
      need = real(positions_needed(closed), wp)
      ! the fewest samples and the most elements that give `need` positions
      ! (averaged_positions solved for np, and for the pad's elements)
      if (closed) then
         np_min = ceiling(real(n_el, wp) * s / fine)
         el_max = floor(real(np, wp) * fine / s)
      else
         np_min = 1.0_wp + ceiling(((real(n_el, wp) - 1.0_wp) * s + stride * (need - 1.0_wp)) &
            & / fine)
         el_max = 1.0_wp + floor(((real(np, wp) - 1.0_wp) * fine - stride * (need - 1.0_wp)) / s)
      end if
      spacing = "dx = " // to_str(dx) // " m"
      if (m%elements_per_sample > 1) spacing = spacing // " / &numerics elements_per_sample = " // &
         & to_str(m%elements_per_sample)
      pad = "the pad's " // to_str(n_el) // " elements (&pad length = " // to_str(m%length) // &
         & " m at " // spacing // ")"
      if (resampled > 0.0_wp) then
         text = "the profile resampled to &pad element_length = " // to_str(resampled) // &
            & " m has " // to_str(np) // " points (" // to_str(round_sig(np * dx, 4)) // " m)"
      else
         text = "the profile has " // to_str(np) // " points (" // &
            & to_str(round_sig(np * dx, 4)) // " m)"
      end if
      if (n_avg < 1) then
         text = text // ", fewer than " // pad
      else
         text = text // ": " // pad // " stand on it at one averaged position only"
         if (m%position_stride > 1) text = text // " (&numerics position_stride = " // &
            & to_str(m%position_stride) // ")"
         text = text // ", and on an open profile friction needs two (it is the work " // &
            & "done over the distance the pad slides)"
      end if
      text = text // "; give a profile of at least " // to_str(nint(np_min)) // " points"
      if (resampled > 0.0_wp) text = text // " at that spacing (" // &
         & to_str(round_sig(np_min * dx, 4)) // " m)"
      if (el_max >= 1.0_wp) then
         ! three digits, rounded down: a longer pad would not fit
         longest = el_max * dx / real(m%elements_per_sample, wp)
         unit = 10.0_wp**(floor(log10(longest)) - 2)
         text = text // ", or &pad length <= " // &
            & to_str(round_sig(floor(longest / unit) * unit, 3)) // " m"
      end if
      if (m%position_stride > 1 .and. .not. closed .and. n_avg >= 1) text = text // &
         & ", or a smaller position_stride"
   end subroutine short_profile_message

   !> The profile the pad slides over: np points at spacing dx become npe at
   !> dxe with &pad element_length (resample_to_length, at the grid's first
   !> phase), else stay. `phases`: how many phases of the grid run
   !> (element_phases when resampled, else 1); `positions`: the averaged
   !> positions of all of them.
   pure subroutine element_grid(m, np, dx, closed, npe, dxe, phases, positions)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np
      real(wp), intent(in) :: dx
      logical, intent(in) :: closed
      integer, intent(out) :: npe
      real(wp), intent(out) :: dxe
      integer, intent(out), optional :: phases, positions
      integer :: k, n, total
      real(wp) :: d
      npe = np
      dxe = dx
      if (present(phases)) phases = 1
      if (present(positions)) positions = averaged_positions(m, np, dx, closed)
      if (.not. resamples(m, dx, np, closed)) return
      total = 0
      do k = 0, element_phases - 1
         n = resampled_points(np, dx, closed, m%element_length, &
            & real(k, wp) / real(element_phases, wp))
         if (n < 1) exit
         if (closed) then
            d = real(np, wp) * dx / real(n, wp)
         else
            d = m%element_length
         end if
         if (averaged_positions(m, n, d, closed) < positions_needed(closed) .and. k > 0) exit
         total = total + averaged_positions(m, n, d, closed)
         if (present(phases)) phases = k + 1
      end do
      if (present(positions)) positions = total
      npe = resampled_points(np, dx, closed, m%element_length, 0.0_wp)
      if (closed) then
         dxe = real(np, wp) * dx / real(max(npe, 1), wp)
      else
         dxe = m%element_length
      end if
   end subroutine element_grid

   !> Whether the profile of np points at spacing dx is resampled to &pad
   !> element_length: not where the pad's grid would be the profile's own
   !> (an open profile's element_length equal to dx; a closed one's whole
   !> number of elements round the loop equal to its points, the spacing
   !> then dx exactly: an element_length within about dx / (2 np) of dx gave
   !> the four phases of an interpolated grid, 0.8 % below the profile's
   !> own at 1e-7 from dx, an attack found).
   pure logical function resamples(m, dx, np, closed)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: dx
      integer, intent(in) :: np
      logical, intent(in) :: closed
      resamples = m%element_length > 0.0_wp .and. dx > 0.0_wp .and. dx <= huge(dx)
      if (.not. resamples) return
      if (closed) then
         resamples = resampled_points(np, dx, closed, m%element_length, 0.0_wp) /= np
      else
         resamples = abs(dx - m%element_length) > 1.0e-9_wp * m%element_length
      end if
   end function resamples

   !> Run the friction model on heights `z` (m) at spacing `dx` (m) for each
   !> speed in `speeds_kmh`. With &numerics tolerance > 0 the time step is
   !> refined until the estimated error of every speed's friction meets it
   !> (simulate_to_tolerance); otherwise the knobs are taken as given. With
   !> &numerics min_contacts the pad's elements are then refined speed by
   !> speed (resolve_pad); at tolerance = 0 the error estimate follows
   !> (estimate_step_error), made on the results as reported.
   subroutine simulate(m, z, dx, closed, speeds_kmh, want_series, res, error, refine_seconds)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed, want_series
      type(sim_result_type), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      !> The seconds the up-front estimate (scene_estimate) gave the passes
      !> that refine the pad, when the caller made it (>= 0): recorded as
      !> they are, so the probe behind them is not run a second time.
      !> Absent or < 0: the probe runs here (add_refinement_cost).
      real(wp), intent(in), optional :: refine_seconds
      logical :: given
      call run_grids(m, z, dx, closed, speeds_kmh, want_series, res, error)
      if (allocated(error)) return
      ! the estimate as the program printed it before the run (scene_estimate)
      given = present(refine_seconds)
      if (given) given = refine_seconds >= 0.0_wp
      if (given) then
         res%estimate%refine_seconds = refine_seconds
         res%estimate%seconds = res%estimate%seconds + refine_seconds
      else
         call add_refinement_cost(m, z, dx, closed, speeds_kmh, res%estimate)
      end if
      ! (a tolerance's passes run at every level the refinement takes)
      call tolerance_guess(m, res%estimate)
      allocate(res%elements_per_sample_used(size(speeds_kmh)), &
         & res%speed_n_elements(size(speeds_kmh)))
      res%elements_per_sample_used = m%elements_per_sample
      res%speed_n_elements = res%n_elements
      if (m%min_contacts > 0) call resolve_pad(m, z, dx, closed, speeds_kmh, want_series, res)
      if (m%tolerance <= 0.0_wp .and. m%error_estimate) &
         & call estimate_step_error(m, z, dx, closed, speeds_kmh, res)
      call warn_estimate(m, res)
      call root_jump_warning(res, speeds_kmh)
   end subroutine simulate

   !> The run at `mm` for `speeds` over the pad's grid(s): the profile as
   !> given, or resampled to &pad element_length at each phase of the pad's
   !> grid, the phases merged (no min_contacts, no error estimate: the
   !> caller's). The passes of min_contacts and of the error estimate are
   !> made by it too, so that they are made as the reported run was. (A
   !> module procedure, not one internal to simulate passed as an argument:
   !> that needs a trampoline, an executable stack, which newer C libraries
   !> refuse to load; tests/test_api.py checks the installed files.)
   subroutine run_grids(mm, z, dx, closed, speeds, series, out, err)
      type(model_type), intent(in) :: mm
      real(wp), intent(in) :: z(:), dx, speeds(:)
      logical, intent(in) :: closed, series
      type(sim_result_type), intent(out) :: out
      type(error_type), allocatable, intent(out) :: err
      type(model_type) :: me
      type(sim_result_type) :: r
      real(wp), allocatable :: ze(:)
      real(wp) :: dxe, phase
      integer :: stat, k, npe
      character(len=:), allocatable :: text
      if (.not. resamples(mm, dx, size(z), closed)) then
         call simulate_spaced(mm, z, dx, speeds, series, out, err)
         if (.not. allocated(err) .and. mm%tolerance > 0.0_wp) &
            & call tolerance_unmet_warning(mm%tolerance, out)
         return
      end if
      ! the pad's own elements: the profile filtered and resampled to them
      call validate_model(mm, err)
      if (allocated(err)) return
      call check_heights(z, err)
      if (allocated(err)) return
      if (resampled_points(size(z), dx, closed, mm%element_length, 0.0_wp) < 1) then
         call fatal_error(err, "&pad element_length = " // to_str(mm%element_length) // &
            & ": the profile resampled to it would have more than 2e9 points; give a " // &
            & "larger element_length (default 0.87e-3 m) or 0 for the profile's own " // &
            & "spacing", stat_memory)
         return
      end if
      me = mm
      me%element_length = 0.0_wp
      ! the first phase's grid too short for the pad: said of the resampled
      ! profile (the run's own check would name a spacing the user never gave)
      call element_grid(mm, size(z), dx, closed, npe, dxe)
      call check_profile_scale(mm, size(z), dx, err)
      if (allocated(err)) return
      if (pad_elements(me, dxe) < 1) then
         call no_element_message(mm, dxe, .true., text)
         call fatal_error(err, text)
         return
      end if
      if (averaged_positions(me, npe, dxe, closed) < positions_needed(closed) .and. &
            & pad_elements(me, dxe) < huge(1)) then
         call short_profile_message(me, npe, dxe, closed, mm%element_length, text)
         call fatal_error(err, text)
         return
      end if
      ! the pad's grid at each phase; an open profile too short for a phase
      ! (the last start beyond its end) has fewer phases
      do k = 0, element_phases - 1
         phase = real(k, wp) / real(element_phases, wp)
         if (resampled_points(size(z), dx, closed, mm%element_length, phase) < 1) exit
         call resample_to_length(z, dx, closed, mm%element_length, phase, ze, dxe, stat)
         if (stat /= 0) then
            call fatal_error(err, "not enough memory to resample a profile of " // &
               & to_str(size(z)) // " points to &pad element_length = " // &
               & to_str(mm%element_length) // " m", stat_memory)
            return
         end if
         if (k == 0) then
            call simulate_spaced(me, ze, dxe, speeds, series, out, err)
            if (allocated(err)) return
         else
            call simulate_spaced(me, ze, dxe, speeds, series, r, err)
            ! a later phase the pad does not fit (an open profile one
            ! element long): the phases before it stand
            if (allocated(err)) then
               if (err%stat == stat_memory .or. err%stat == stat_internal) return
               deallocate(err)
               exit
            end if
            call merge_phase(out, r, phase * dxe, stat)
            if (stat /= 0) then
               call fatal_error(err, "not enough memory to merge the series of " // &
                  & to_str(element_phases) // " phases of the pad's element grid (" // &
                  & to_str(out%n_positions) // " positions); run without &output " // &
                  & "series or on a shorter profile", stat_memory)
               return
            end if
         end if
      end do
      ! the speeds the tolerance was not met at, over the phases (their
      ! largest error, as mu_error)
      if (mm%tolerance > 0.0_wp) call tolerance_unmet_warning(mm%tolerance, out)
   contains
      subroutine simulate_spaced(mm, zz, dd, speeds, series, out, err)
         type(model_type), intent(in) :: mm
         real(wp), intent(in) :: zz(:), dd, speeds(:)
         logical, intent(in) :: series
         type(sim_result_type), intent(out) :: out
         type(error_type), allocatable, intent(out) :: err
         if (mm%tolerance > 0.0_wp) then
            ! (the speeds it does not meet: run_grids' one warning, over the
            ! phases)
            call simulate_to_tolerance(mm, zz, dd, closed, speeds, series, out, err)
         else
            call simulate_fixed(mm, zz, dd, closed, speeds, series, out, err)
         end if
         out%element_spacing = dd
      end subroutine simulate_spaced
   end subroutine run_grids

   !> Phase `r` of the pad's grid (its positions `offset` further along)
   !> into the results `acc` of the phases before it: per-speed means
   !> weighted by the positions averaged, largest values, sums of counts,
   !> effects that ran in any; the series merged in order of position.
   pure subroutine merge_phase(acc, r, offset, stat)
      type(sim_result_type), intent(inout) :: acc
      type(sim_result_type), intent(in) :: r
      real(wp), intent(in) :: offset
      !> 0, or the status of an allocation that failed (the caller's error)
      integer, intent(out) :: stat
      real(wp) :: wa, wr
      integer :: na, nr, i, ia, ir
      real(wp), allocatable :: pos(:), a2(:,:), b2(:,:), c2(:,:), d2(:,:), e2(:,:)
      integer, allocatable :: k2(:,:), from(:)
      character(len=:), allocatable :: line, rest
      stat = 0
      wa = real(acc%n_positions, wp)
      wr = real(r%n_positions, wp)
      call mean_in(acc%mu, r%mu)
      call mean_in(acc%mu_hysteresis, r%mu_hysteresis)
      call mean_in(acc%mu_adhesion, r%mu_adhesion)
      call mean_in(acc%hydroplaning_fraction, r%hydroplaning_fraction)
      call mean_in(acc%wet_fraction, r%wet_fraction)
      call mean_in(acc%mean_hydro_load, r%mean_hydro_load)
      call mean_in(acc%mean_local_friction, r%mean_local_friction)
      call mean_in(acc%mean_film_thickness, r%mean_film_thickness)
      call mean_in(acc%contact_fraction, r%contact_fraction)
      call mean_in(acc%film_load_share, r%film_load_share)
      call mean_in(acc%mean_water_thickness, r%mean_water_thickness)
      acc%film_unsettled = acc%film_unsettled + r%film_unsettled
      acc%film_root_jumps = acc%film_root_jumps + r%film_root_jumps
      acc%root_jumps_seen = acc%root_jumps_seen + r%root_jumps_seen
      acc%max_balance_residual = max(acc%max_balance_residual, r%max_balance_residual)
      acc%max_compression = max(acc%max_compression, r%max_compression)
      acc%n_clamped = acc%n_clamped + r%n_clamped
      acc%bearing_evaluations = acc%bearing_evaluations + r%bearing_evaluations
      acc%memory_updates = acc%memory_updates + r%memory_updates
      acc%viscous_memory_ran = acc%viscous_memory_ran .or. r%viscous_memory_ran
      acc%exact_integrator_ran = acc%exact_integrator_ran .and. r%exact_integrator_ran
      acc%bearing_ran = acc%bearing_ran .or. r%bearing_ran
      acc%friction_film_ran = acc%friction_film_ran .or. r%friction_film_ran
      if (allocated(acc%mu_error) .and. allocated(r%mu_error)) then
         acc%mu_error = max(acc%mu_error, r%mu_error)
         acc%substeps_used = max(acc%substeps_used, r%substeps_used)
         acc%estimate_elements_per_sample = max(acc%estimate_elements_per_sample, &
            & r%estimate_elements_per_sample)
         acc%extrapolated = acc%extrapolated .or. r%extrapolated
      end if
      acc%n_spinup = acc%n_spinup + r%n_spinup
      acc%estimate%element_steps = acc%estimate%element_steps + r%estimate%element_steps
      acc%estimate%total_element_steps = acc%estimate%total_element_steps + &
         & r%estimate%total_element_steps
      acc%estimate%seconds = acc%estimate%seconds + r%estimate%seconds
      acc%estimate%bytes = max(acc%estimate%bytes, r%estimate%bytes)
      if (len(r%effects) > len(acc%effects)) acc%effects = r%effects
      ! the later phase's warnings that the earlier ones did not give
      rest = r%warnings
      do while (len(rest) > 0)
         i = index(rest, achar(10))
         if (i == 0) then
            line = rest
            rest = ""
         else
            line = rest(1:i-1)
            rest = rest(i+1:)
         end if
         if (len(line) > 0 .and. index(acc%warnings, line) == 0) &
            & call add_warning(acc%warnings, line)
      end do
      if (allocated(acc%mu_inst) .and. allocated(r%mu_inst)) then
         ! both series in order of position: merge them
         na = size(acc%position)
         nr = size(r%position)
         allocate(pos(na + nr), from(na + nr), stat=stat)
         if (stat /= 0) return
         ia = 1
         ir = 1
         do i = 1, na + nr
            if (ir > nr) then
               from(i) = ia
               ia = ia + 1
            else if (ia > na) then
               from(i) = -ir
               ir = ir + 1
            else if (acc%position(ia) <= r%position(ir) + offset) then
               from(i) = ia
               ia = ia + 1
            else
               from(i) = -ir
               ir = ir + 1
            end if
            if (from(i) > 0) then
               pos(i) = acc%position(from(i))
            else
               pos(i) = r%position(-from(i)) + offset
            end if
         end do
         call merge_series(acc%mu_inst, r%mu_inst, a2, stat)
         if (stat == 0) call merge_series(acc%hydro_load, r%hydro_load, b2, stat)
         if (stat == 0) call merge_series(acc%penetration, r%penetration, c2, stat)
         if (stat == 0) allocate(k2(na + nr, size(acc%contact_elements, 2)), stat=stat)
         if (stat /= 0) return
         do i = 1, na + nr
            if (from(i) > 0) then
               k2(i, :) = acc%contact_elements(from(i), :)
            else
               k2(i, :) = r%contact_elements(-from(i), :)
            end if
         end do
         call move_alloc(a2, acc%mu_inst)
         call move_alloc(b2, acc%hydro_load)
         call move_alloc(c2, acc%penetration)
         call move_alloc(k2, acc%contact_elements)
         if (allocated(acc%film_thickness) .and. allocated(r%film_thickness)) then
            call merge_series(acc%film_thickness, r%film_thickness, d2, stat)
            if (stat == 0) call merge_series(acc%local_friction, r%local_friction, e2, stat)
            if (stat /= 0) return
            call move_alloc(d2, acc%film_thickness)
            call move_alloc(e2, acc%local_friction)
         end if
         if (allocated(acc%film_pressure_max) .and. allocated(r%film_pressure_max)) then
            call merge_series(acc%film_pressure_max, r%film_pressure_max, d2, stat)
            if (stat == 0) call merge_series(acc%water_thickness, r%water_thickness, e2, stat)
            if (stat /= 0) return
            call move_alloc(d2, acc%film_pressure_max)
            call move_alloc(e2, acc%water_thickness)
         end if
         call move_alloc(pos, acc%position)
      end if
      acc%n_positions = acc%n_positions + r%n_positions
   contains
      pure subroutine mean_in(a, b)
         real(wp), intent(inout) :: a(:)
         real(wp), intent(in) :: b(:)
         a = (wa * a + wr * b) / (wa + wr)
      end subroutine mean_in
      pure subroutine merge_series(a, b, c, st)
         real(wp), intent(in) :: a(:,:), b(:,:)
         real(wp), allocatable, intent(out) :: c(:,:)
         integer, intent(out) :: st
         integer :: q
         allocate(c(size(from), size(a, 2)), stat=st)
         if (st /= 0) return
         do q = 1, size(from)
            if (from(q) > 0) then
               c(q, :) = a(from(q), :)
            else
               c(q, :) = b(-from(q), :)
            end if
         end do
      end subroutine merge_series
   end subroutine merge_phase

   !> Accuracy on demand: the time step (substeps) halved until, for every
   !> speed, the estimated error of its friction is at most &numerics
   !> tolerance. The passes are backward Euler, of order 1. With the signed
   !> changes d1 = mu(s/2) - mu(s/4) and d2 = mu(s) - mu(s/2):
   !> - Euler's estimate of the error left in mu(s) is 2 max(|d1|, |d2|) (the
   !>   error of a first-order sequence equals its last change; the larger of
   !>   two and the factor 2 guard the coarse steps, where the sequence is
   !>   not yet monotone and one change can be accidentally small);
   !> - when the sequence is in its asymptotic range (d1 and d2 of one sign,
   !>   d1 / d2 within [1.5, 3], first order's 2 with a margin) and
   !>   `extrapolate` is set, the Richardson value 2 mu(s) - mu(s/2) removes
   !>   the first-order term; its error is estimated as
   !>   max(|2 d2 - d1|, |d2|): the change of the extrapolated value (three
   !>   times the error of a second-order sequence) and never less than the
   !>   last change. It is reported when that estimate is the smaller, with
   !>   mu_hysteresis and mu_adhesion extrapolated alike (their sum stays mu),
   !>   unless it would make a part negative that both passes had >= 0.
   !>   Measured on the 15 reference scenes (docs/accuracy.md): the same
   !>   tolerances met at half to a quarter of the substeps, no estimate below
   !>   the actual error down to tolerance 1e-4.
   !> A speed that meets the tolerance keeps its result and is not run again
   !> (with `series` every speed is refined together, so that the series
   !> share positions). The pad's elements (elements_per_sample) are a model
   !> choice, not refined here.
   subroutine simulate_to_tolerance(m, z, dx, closed, speeds_kmh, want_series, res, error)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed, want_series
      type(sim_result_type), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      type(model_type) :: mm
      type(sim_result_type) :: r
      real(wp), allocatable :: prev(:), last_change(:), prev_h(:), prev_a(:), last_ratio(:)
      logical, allocatable :: active(:)
      integer, allocatable :: idx(:)
      integer :: ns, k, j, level
      real(wp) :: change, est, est_r, rich, rich_h, rich_a
      logical :: extrapolate, usable
      ns = size(speeds_kmh)
      mm = m
      mm%tolerance = 0.0_wp            ! each pass runs its substeps as given
      ! ... as its own Euler pass ('richardson' at tolerance = 0 would ask for
      ! the error estimate's pass, which the passes here do not make)
      if (scheme_is(m, "richardson")) mm%time_scheme = "extrapolated"
      extrapolate = .true.
      if (allocated(m%time_scheme)) extrapolate = m%time_scheme == "extrapolated" .or. &
         & m%time_scheme == "auto" .or. m%time_scheme == "richardson"
      call simulate_fixed(mm, z, dx, closed, speeds_kmh, want_series, res, error)
      if (allocated(error)) return
      allocate(res%mu_error(ns), res%substeps_used(ns), res%extrapolated(ns), active(ns), &
         & res%estimate_elements_per_sample(ns))
      res%mu_error = huge(1.0_wp)
      res%substeps_used = mm%substeps
      res%estimate_elements_per_sample = m%elements_per_sample
      res%extrapolated = .false.
      prev = res%mu
      prev_h = res%mu_hysteresis
      prev_a = res%mu_adhesion
      allocate(last_change(ns), last_ratio(ns))
      last_change = huge(1.0_wp)
      last_ratio = 0.0_wp
      active = .true.
      level = 0
      do
         if (2 * mm%substeps > max_substeps) exit
         mm%substeps = 2 * mm%substeps
         level = level + 1
         if (want_series) then
            idx = [(j, j = 1, ns)]
         else
            idx = pack([(j, j = 1, ns)], active)
         end if
         call simulate_fixed(mm, z, dx, closed, speeds_kmh(idx), want_series, r, error)
         if (allocated(error)) return
         do k = 1, size(idx)
            j = idx(k)
            change = r%mu(k) - prev(j)
            call richardson(prev(j), prev_h(j), prev_a(j), r%mu(k), r%mu_hysteresis(k), &
               & r%mu_adhesion(k), rich, rich_h, rich_a, usable)
            prev(j) = r%mu(k)
            prev_h(j) = r%mu_hysteresis(k)
            prev_a(j) = r%mu_adhesion(k)
            if (.not. active(j) .and. .not. want_series) cycle
            call copy_speed(r, k, res, j)
            res%substeps_used(j) = mm%substeps
            res%extrapolated(j) = .false.
            if (.not. active(j)) cycle
            if (level == 1 .and. exact_in_time(r, k)) then
               ! exact in time: two grids give the same friction but for the
               ! roots' rounding, which this measures (twice the change)
               est = 2.0_wp * abs(change)
               res%mu_error(j) = est
               if (est <= m%tolerance) active(j) = .false.
            else if (level >= 2) then
               est = 2.0_wp * max(abs(change), abs(last_change(j)))
               if (r%exact_integrator_ran(k) .and. order_known(last_ratio(j), last_change(j), &
                  & change)) then
                  ! the exact integrator under the film: its error falls at
                  ! an order between 0.6 and 3 (about 2 once asymptotic);
                  ! two successive ratios in that band give the error of
                  ! the pass as the geometric tail of its changes, |d| /
                  ! (ratio - 1), taken twice
                  est = 2.0_wp * abs(change) / (last_change(j) / change - 1.0_wp)
               else if (extrapolate .and. asymptotic(last_change(j), change) .and. usable) then
                  est_r = max(abs(2.0_wp * change - last_change(j)), abs(change))
                  if (est_r < est) then
                     est = est_r
                     res%mu(j) = rich
                     res%mu_hysteresis(j) = rich_h
                     res%mu_adhesion(j) = rich_a
                     res%extrapolated(j) = .true.
                  end if
               end if
               res%mu_error(j) = est
               if (est <= m%tolerance) active(j) = .false.
            end if
            if (level >= 2 .and. change /= 0.0_wp) last_ratio(j) = last_change(j) / change
            last_change(j) = change
         end do
         res%n_elements = r%n_elements
         res%n_positions = max(res%n_positions, r%n_positions)
         res%n_spinup = max(res%n_spinup, r%n_spinup)
         if (len(r%effects) > len(res%effects)) res%effects = r%effects
         if (want_series) call move_series(r, res)
         call take_jumps_seen(res, idx, r)
         if (.not. any(active)) exit
      end do
   contains
      !> Two successive ratios of changes (the one before, and d1 / d2) each
      !> 1.5 to 8 (an order 0.6 to 3) and within a factor 2 of each other,
      !> the changes of one sign.
      pure logical function order_known(r1, d1, d2)
         real(wp), intent(in) :: r1, d1, d2
         real(wp) :: r2
         order_known = .false.
         if (abs(d1) >= huge(1.0_wp) .or. .not. (d1 * d2 > 0.0_wp)) return
         r2 = d1 / d2
         order_known = r1 >= 1.5_wp .and. r1 <= 8.0_wp .and. r2 >= 1.5_wp .and. &
            & r2 <= 8.0_wp .and. r2 <= 2.0_wp * r1 .and. r1 <= 2.0_wp * r2
      end function order_known

      !> Two successive changes of a first-order sequence in its asymptotic
      !> range: one sign, the earlier 1.5 to 3 times the later.
      pure logical function asymptotic(d1, d2)
         real(wp), intent(in) :: d1, d2
         asymptotic = .false.
         if (abs(d1) >= huge(1.0_wp) .or. .not. (d1 * d2 > 0.0_wp)) return
         asymptotic = abs(d1) >= 1.5_wp * abs(d2) .and. abs(d1) <= 3.0_wp * abs(d2)
      end function asymptotic
   end subroutine simulate_to_tolerance

   !> The warning for the speeds whose estimated error is above the
   !> tolerance after the last pass, each with its own error (3 significant
   !> digits) and the substeps it reached: "... not met at substeps = 4096 (the
   !> largest allowed); estimated error 1.17e-07 at 20 km/h, 4.22e-07 at 80 km/h".
   subroutine tolerance_unmet_warning(tolerance, res)
      real(wp), intent(in) :: tolerance
      type(sim_result_type), intent(inout) :: res
      character(len=:), allocatable :: text
      integer :: k, reached
      if (.not. allocated(res%mu_error)) return
      text = ""
      reached = 0
      do k = 1, size(res%mu_error)
         if (.not. (res%mu_error(k) > tolerance)) cycle
         if (len(text) > 0) text = text // ", "
         text = text // to_str(round_sig(res%mu_error(k), 3)) // " at " // &
            & to_str(res%speed_kmh(k)) // " km/h"
         reached = max(reached, res%substeps_used(k))
      end do
      if (len(text) == 0) return
      call add_warning(res%warnings, "&numerics tolerance = " // to_str(tolerance) // &
         & ": not met at substeps = " // to_str(reached) // " (the largest allowed); " // &
         & "estimated error " // text)
   end subroutine tolerance_unmet_warning

   !> &numerics min_contacts: where the pad stood on fewer than
   !> m%min_contacts elements in contact on average at a speed
   !> (contacts_touching: positions the film carried alone left out), the run
   !> is repeated with the elements halved (elements_per_sample doubled), at
   !> most pad_levels times (to 16 times the value given, and within
   !> max_elements_per_sample), and the refined run replaces that speed's
   !> results (copy_speed: mu, its parts and every per-speed output, with a
   !> tolerance its accuracy record too). With series each speed's series
   !> are its own run's (so that asking for them changes no mean), held on
   !> the finest run's positions (hold_series). A level that fails, or a
   !> speed still short at the last, keeps the finest run made, with a
   !> warning.
   subroutine resolve_pad(m, z, dx, closed, speeds_kmh, want_series, res)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed, want_series
      type(sim_result_type), intent(inout) :: res
      type(model_type) :: mc
      type(sim_result_type) :: r
      !> With series: each level's run, and the level and column of each
      !> speed's own run (level 0: the run given).
      type(sim_result_type) :: runs(pad_levels)
      integer, allocatable :: level_of(:), col_of(:)
      type(error_type), allocatable :: err
      integer, allocatable :: group(:), idx(:)
      logical, allocatable :: active(:)
      integer :: ns, j, k, level, eps, cap
      logical :: failed
      real(wp) :: target
      character(len=:), allocatable :: limit
      ns = size(speeds_kmh)
      target = real(m%min_contacts, wp)
      idx = [(j, j = 1, ns)]
      active = [(short_of(res, j), j = 1, ns)]
      level_of = [(0, j = 1, ns)]
      col_of = idx
      failed = .false.
      cap = min(max_elements_per_sample, m%elements_per_sample * 2**pad_levels)
      eps = m%elements_per_sample
      mc = inner_pass(m)
      do level = 1, pad_levels
         if (.not. any(active)) exit
         if (2 * eps > cap) exit
         eps = 2 * eps
         mc%elements_per_sample = eps
         group = pack(idx, active)
         call run_grids(mc, z, dx, closed, speeds_kmh(group), want_series, r, err)
         if (allocated(err)) then
            call add_warning(res%warnings, "&numerics min_contacts = " // &
               & to_str(m%min_contacts) // ": the pad's elements could not be refined " // &
               & "beyond elements_per_sample = " // to_str(eps / 2) // " at " // &
               & to_str(speeds_kmh(group(1))) // " km/h (a run with elements_per_sample = " &
               & // to_str(eps) // " could not be made on this profile; its check said: " // &
               & err%message // "); the results there are those at " // to_str(eps / 2))
            deallocate(err)
            failed = .true.
            exit
         end if
         do k = 1, size(group)
            j = group(k)
            call copy_speed(r, k, res, j)
            res%elements_per_sample_used(j) = eps
            res%speed_n_elements(j) = r%n_elements
            active(j) = short_of(r, k)
            level_of(j) = level
            col_of(j) = k
         end do
         if (len(r%effects) > len(res%effects)) res%effects = r%effects
         if (want_series) call move_series_whole(r, runs(level))
      end do
      if (want_series) call hold_series(res, runs, level_of, col_of)
      if (failed) return
      limit = "the largest allowed"
      if (cap == m%elements_per_sample * 2**pad_levels) &
         & limit = "the most it refines to: 16 times the value given"
      do j = 1, ns
         if (.not. active(j)) cycle
         call add_warning(res%warnings, "&numerics min_contacts = " // &
            & to_str(m%min_contacts) // " not reached at " // to_str(speeds_kmh(j)) // &
            & " km/h: at elements_per_sample = " // &
            & to_str(res%elements_per_sample_used(j)) // " (" // limit // &
            & ") the pad stood on " // to_str(round_sig(contacts_touching(res, j), 3)) // &
            & " elements in contact on average; give a larger elements_per_sample to " // &
            & "start from, or a smaller min_contacts")
      end do
   contains
      !> Whether the pad stood on fewer than the target at speed j of `rr`
      !> (a pad the film carried all along has no contacts to resolve).
      pure logical function short_of(rr, jj)
         type(sim_result_type), intent(in) :: rr
         integer, intent(in) :: jj
         real(wp) :: c
         c = contacts_touching(rr, jj)
         short_of = c > 0.0_wp .and. c < target
      end function short_of
   end subroutine resolve_pad

   !> The error estimate of a run at tolerance = 0 (&numerics
   !> error_estimate), made on the run `res` as reported (the pad's grid
   !> phases merged); the result reported stays the run's own.
   !> Where the pad stood on at least `contacts_resolved` elements in
   !> contact (Euler speeds): one more pass at half the step (substeps
   !> doubled, without series), and three times its change of mu as the
   !> estimate. An error falling as the step to the power p is 1 / (1 -
   !> 2^-p) times that change: 2 at first order, 3 at p = 0.59; measured
   !> orders are 0.65 to 1.3 (docs/accuracy.md), and on the reference
   !> surfaces the default run's error was at most two thirds of the
   !> estimate at 5 to 100 km/h, dry and wet (tests/test_error_estimate.py).
   !> A coarse pass (position_stride doubled) was measured and rejected: on
   !> ctm_wet at 20 km/h its change was 1/34 of the error (docs/accuracy.md).
   !> Where it stood on fewer (unresolved_contacts), its friction depends on
   !> how finely the elements resolve the contacts, and one halving of them
   !> does not show how much: friction rises along an S as the elements
   !> shrink, and three times the first halving's change was 0.19 to 1.66
   !> of the error on the paper's surfaces with the shipped compound at 0
   !> and 20 C (docs/accuracy.md, "The pad's resolution", second table). So the elements are halved (elements_per_sample
   !> doubled at the same substeps, which halves the step too) until the pad
   !> stands on `contacts_resolved` of them, at most `pad_levels` times
   !> (elements_per_sample up to 16 times the run's); from that level k one
   !> more pass at half the elements (or at half the step where it now
   !> stands on enough), and the estimate is |mu - mu_k| + 3 |mu_k - mu_k'|:
   !> how far the refinement took mu, plus the estimate of what is left.
   !> Speeds the exact integrator ran have no error from the step but one
   !> from the elements: their passes halve the elements, with the same
   !> integrator, at any number of contacts.
   !> estimate_elements_per_sample records the finest pass's elements;
   !> res%refined_* what the levels found (warn_estimate names it).
   !> With time_scheme 'richardson' (extrapolates), a speed whose last pass
   !> halved the step on the run's own elements reports the
   !> Richardson value 2 mu(s) - mu(s/2) of that pass and the run, its parts
   !> alike (their sum stays mu), unless a part both passes have >= 0 would
   !> turn negative; its estimate is then 2 |mu(s) - mu(s/2)|, twice the
   !> correction: the error of the Richardson value of an error falling as
   !> the step to the power p is |2^(1-p) - 1| / (1 - 2^-p) times the change,
   !> at most 1 for p >= 0.59 and 2 for p >= 0.42 (on the paper's surfaces it
   !> was 0.5 to 0.8 of the change, docs/accuracy.md).
   !> The passes' own warnings are not repeated. A level that fails stops
   !> the refinement there (a warning says so); a last pass that fails or
   !> cannot run (the step's beyond max_substeps, the elements' beyond
   !> max_elements_per_sample) is replaced by the other kind; if that fails
   !> too, the run has no estimate and a warning says why; warn_estimate
   !> warns where the estimate is large.
   subroutine estimate_step_error(m, z, dx, closed, speeds_kmh, res)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed
      type(sim_result_type), intent(inout) :: res
      type(model_type) :: mc
      type(sim_result_type) :: r
      type(error_type), allocatable :: err
      integer, allocatable :: group(:), idx(:)
      logical, allocatable :: active(:), by_elements(:), done(:), blocked(:), want(:)
      real(wp), allocatable :: pass_mu(:), pass_h(:), pass_a(:)
      logical, allocatable :: by_step(:)
      integer :: ns, j, k, e, level, cap
      real(wp) :: rich, rich_h, rich_a
      logical :: usable
      character(len=:), allocatable :: why, last_why
      ns = size(speeds_kmh)
      allocate(res%mu_error(ns), res%substeps_used(ns), res%extrapolated(ns), &
         & res%estimate_elements_per_sample(ns), res%refined_elements_per_sample(ns), &
         & res%refined_mu(ns), res%refined_contacts(ns))
      res%mu_error = 0.0_wp
      res%substeps_used = m%substeps
      res%extrapolated = .false.
      res%estimate_elements_per_sample = res%elements_per_sample_used
      res%refined_elements_per_sample = res%elements_per_sample_used
      res%refined_mu = res%mu
      res%refined_contacts = [(contacts_touching(res, j), j = 1, ns)]
      idx = [(j, j = 1, ns)]
      ! the levels: the elements halved while the pad stands on too few, each
      ! speed from its run's elements (min_contacts may have refined them),
      ! to at most pad_levels halvings of the value given in all
      active = [(unresolved_contacts(res, j), j = 1, ns)]
      allocate(blocked(ns), want(ns))
      blocked = .false.
      cap = min(max_elements_per_sample / 2, m%elements_per_sample * 2**pad_levels)
      mc = inner_pass(m)
      do level = 1, pad_levels
         want = active
         do while (any(want))
            e = minval(res%refined_elements_per_sample, mask=want)
            group = pack(idx, want .and. res%refined_elements_per_sample == e)
            want = want .and. res%refined_elements_per_sample /= e
            if (2 * e > cap) then
               active(group) = .false.
               cycle
            end if
            mc%elements_per_sample = 2 * e
            call run_grids(mc, z, dx, closed, speeds_kmh(group), .false., r, err)
            if (allocated(err)) then
               call add_warning(res%warnings, "&numerics error_estimate: the pad's elements " &
                  & // "could not be refined beyond elements_per_sample = " // to_str(e) // &
                  & " at " // to_str(speeds_kmh(group(1))) // " km/h (a run with elements_" // &
                  & "per_sample = " // to_str(2 * e) // " could not be made on this profile; " &
                  & // "its check said: " // err%message // "); the estimate is made from there")
               deallocate(err)
               blocked(group) = .true.
               active(group) = .false.
               cycle
            end if
            do k = 1, size(group)
               j = group(k)
               res%refined_mu(j) = r%mu(k)
               res%refined_elements_per_sample(j) = 2 * e
               res%refined_contacts(j) = contacts_touching(r, k)
               active(j) = unresolved_contacts(r, k)
            end do
            call take_jumps_seen(res, group, r)
         end do
      end do
      ! the last pass from each speed's level: half the elements where the pad
      ! still stands on too few, or the exact integrator ran; else half the step
      by_elements = [(exact_in_time(res, j) .or. (res%refined_contacts(j) > 0.0_wp .and. &
         & res%refined_contacts(j) < contacts_resolved), j = 1, ns)]
      allocate(pass_mu(ns), pass_h(ns), pass_a(ns), done(ns), by_step(ns))
      pass_mu = 0.0_wp
      pass_h = 0.0_wp
      pass_a = 0.0_wp
      by_step = .false.
      done = .false.
      ! first choice, then the other kind for the speeds it left
      by_elements = by_elements .and. .not. blocked
      call last_passes(by_elements)
      call last_passes(.not. by_elements)
      ! exact speeds whose elements could not be halved: the refinement's
      ! change alone (their step has no error), said
      do j = 1, ns
         if (done(j) .or. .not. exact_in_time(res, j)) cycle
         done(j) = .true.
         pass_mu(j) = res%refined_mu(j)
         call add_warning(res%warnings, "&numerics error_estimate at " // &
            & to_str(speeds_kmh(j)) // " km/h (the exact integrator's): no pass could " // &
            & "halve the pad's elements, so the estimate leaves out their resolution")
      end do
      if (.not. all(done)) then
         if (.not. allocated(why)) why = " (no pass could run)"
         call no_estimate(why)
         return
      end if
      do j = 1, ns
         res%mu_error(j) = abs(res%mu(j) - res%refined_mu(j)) + &
            & 3.0_wp * abs(res%refined_mu(j) - pass_mu(j))
      end do
      if (.not. extrapolates(m)) return
      ! the Richardson value of the run and its pass at half the step, where
      ! that pass was made on the run's own elements
      do j = 1, ns
         if (.not. by_step(j)) cycle
         if (res%refined_elements_per_sample(j) /= res%elements_per_sample_used(j)) cycle
         call richardson(res%mu(j), res%mu_hysteresis(j), res%mu_adhesion(j), pass_mu(j), &
            & pass_h(j), pass_a(j), rich, rich_h, rich_a, usable)
         if (.not. usable) cycle
         res%mu_error(j) = 2.0_wp * abs(pass_mu(j) - res%mu(j))
         res%mu(j) = rich
         res%mu_hysteresis(j) = rich_h
         res%mu_adhesion(j) = rich_a
         res%extrapolated(j) = .true.
      end do
   contains
      !> The last pass, for the speeds not yet done: halving the elements
      !> where `elements_for`, else the step (not for the exact integrator's
      !> speeds, which have none to halve), grouped by their level's
      !> elements_per_sample. A pass that cannot run or fails leaves its
      !> speeds to the next call (the other kind), with a warning.
      subroutine last_passes(elements_for)
         logical, intent(in) :: elements_for(:)
         logical :: want(ns), elements_kind
         integer :: q, e, q2
         do q = 1, 2
            elements_kind = q == 1
            want = .not. done .and. (elements_for .eqv. elements_kind)
            if (.not. elements_kind) want = want .and. .not. [(exact_in_time(res, q2), &
               & q2 = 1, ns)]
            if (elements_kind) want = want .and. .not. blocked
            do while (any(want))
               e = minval(res%refined_elements_per_sample, mask=want)
               group = pack(idx, want .and. res%refined_elements_per_sample == e)
               want = want .and. res%refined_elements_per_sample /= e
               mc = inner_pass(m)
               mc%elements_per_sample = e
               if (elements_kind) then
                  if (2 * e > max_elements_per_sample) then
                     call reason(" (elements_per_sample = " // to_str(e) // " cannot be doubled)")
                     cycle
                  end if
                  mc%elements_per_sample = 2 * e
               else
                  if (2 * m%substeps > max_substeps) then
                     call reason(" at substeps = " // to_str(m%substeps) // " (its pass at " // &
                        & "half the step would pass " // to_str(max_substeps) // ")")
                     cycle
                  end if
                  ! (backward Euler's own pass; the exact integrator's
                  ! under the film, where it ran)
                  mc%time_scheme = "euler"
                  if (exact_scheme(m)) mc%time_scheme = m%time_scheme
                  mc%substeps = 2 * m%substeps
               end if
               call run_grids(mc, z, dx, closed, speeds_kmh(group), .false., r, err)
               if (allocated(err)) then
                  if (elements_kind) then
                     call reason(": its pass with the pad's elements halved " // &
                        & "(elements_per_sample = " // to_str(mc%elements_per_sample) // &
                        & ") could not be made on this profile (its check said: " // &
                        & err%message // ")")
                     blocked(group) = .true.
                  else
                     call reason(": its pass at half the step (substeps = " // &
                        & to_str(mc%substeps) // ") could not be made (" // err%message // ")")
                  end if
                  call add_warning(res%warnings, "&numerics error_estimate at " // &
                     & to_str(speeds_kmh(group(1))) // " km/h" // last_why)
                  deallocate(err)
                  cycle
               end if
               do k = 1, size(group)
                  pass_mu(group(k)) = r%mu(k)
                  pass_h(group(k)) = r%mu_hysteresis(k)
                  pass_a(group(k)) = r%mu_adhesion(k)
                  by_step(group(k)) = .not. elements_kind
                  done(group(k)) = .true.
                  res%estimate_elements_per_sample(group(k)) = mc%elements_per_sample
               end do
               ! (the passes' own warnings are not repeated; a root that
               ! left its range in the estimate's pass is counted)
               call take_jumps_seen(res, group, r)
            end do
         end do
      end subroutine last_passes

      !> Why a pass could not be made: the last reason (its own warning's)
      !> and all of them (the no-estimate warning's), joined.
      subroutine reason(text)
         character(len=*), intent(in) :: text
         last_why = text
         if (.not. allocated(why)) then
            why = text
         else if (text(1:1) == ":") then
            why = why // ";" // text(2:)
         else
            why = why // ";" // text
         end if
      end subroutine reason

      subroutine no_estimate(text)
         character(len=*), intent(in) :: text
         deallocate(res%mu_error, res%substeps_used, res%extrapolated, &
            & res%estimate_elements_per_sample, res%refined_elements_per_sample, &
            & res%refined_mu, res%refined_contacts)
         call add_warning(res%warnings, "&numerics error_estimate: no estimate of mu's " // &
            & "error" // text)
      end subroutine no_estimate
   end subroutine estimate_step_error

   !> The Richardson value 2 b - a of two backward-Euler passes, a at a step
   !> and b at half of it, for mu and its parts alike (their sum stays mu);
   !> `usable` false where it would turn negative a part both passes have
   !> >= 0 (mu_loc = 0 keeps mu >= 0).
   pure subroutine richardson(mu_a, hyst_a, adh_a, mu_b, hyst_b, adh_b, rich, rich_h, &
      & rich_a, usable)
      real(wp), intent(in) :: mu_a, hyst_a, adh_a, mu_b, hyst_b, adh_b
      real(wp), intent(out) :: rich, rich_h, rich_a
      logical, intent(out) :: usable
      rich = 2.0_wp * mu_b - mu_a
      rich_h = 2.0_wp * hyst_b - hyst_a
      rich_a = 2.0_wp * adh_b - adh_a
      usable = .not. (hyst_a >= 0.0_wp .and. hyst_b >= 0.0_wp .and. rich_h < 0.0_wp) .and. &
         & .not. (adh_a >= 0.0_wp .and. adh_b >= 0.0_wp .and. rich_a < 0.0_wp)
   end subroutine richardson

   !> The scene of a pass the run makes for itself (the pad's levels, the
   !> error estimate's): no estimate of its own, no refinement, and its own
   !> Euler pass where the run asked for 'richardson' (which needs the
   !> estimate the pass does not make).
   pure function inner_pass(m) result(mc)
      type(model_type), intent(in) :: m
      type(model_type) :: mc
      mc = m
      mc%error_estimate = .false.
      mc%min_contacts = 0
      if (scheme_is(m, "richardson")) mc%time_scheme = "extrapolated"
   end function inner_pass

   !> Whether a run at tolerance = 0 reports the Richardson value of its
   !> error estimate's pass at half the step: time_scheme 'richardson'.
   pure logical function extrapolates(m)
      type(model_type), intent(in) :: m
      extrapolates = scheme_is(m, "richardson")
   end function extrapolates

   !> Whether speed j ran the exact integrator on a dry road: exact in time,
   !> its friction with no error from the step (under the paper's film the
   !> exact integrator's linearised film leaves one, second order).
   pure logical function exact_in_time(res, j)
      type(sim_result_type), intent(in) :: res
      integer, intent(in) :: j
      exact_in_time = res%exact_integrator_ran(j) .and. .not. res%bearing_ran(j)
   end function exact_in_time

   !> Whether the pad stood on fewer than `contacts_resolved` elements in
   !> contact at speed j (contacts_touching: a pad the film carries all
   !> along has no contacts to resolve).
   pure logical function unresolved_contacts(res, j)
      type(sim_result_type), intent(in) :: res
      integer, intent(in) :: j
      real(wp) :: contacts
      contacts = contacts_touching(res, j)
      unresolved_contacts = contacts > 0.0_wp .and. contacts < contacts_resolved
   end function unresolved_contacts

   !> The elements in contact at speed j, averaged over the positions where
   !> any touched (those where the film carried the pad alone, the
   !> hydroplaning_fraction, have no contacts to resolve); 0 where none did.
   pure real(wp) function contacts_touching(res, j) result(contacts)
      type(sim_result_type), intent(in) :: res
      integer, intent(in) :: j
      integer :: n
      contacts = 0.0_wp
      if (res%hydroplaning_fraction(j) >= 1.0_wp) return
      n = res%n_elements
      if (allocated(res%speed_n_elements)) n = res%speed_n_elements(j)
      contacts = res%contact_fraction(j) * real(n, wp) / &
         & (1.0_wp - res%hydroplaning_fraction(j))
   end function contacts_touching

   !> After a run (all of the pad's grid phases merged). At tolerance = 0:
   !> a warning where mu's estimated error exceeds `estimate_warning` of mu
   !> (and `estimate_floor`), at the speed where its share is largest,
   !> naming what the estimate's pass refined. With a tolerance (which
   !> refines the time step only): a warning where the pad stood on too
   !> few elements for the tolerance to mean mu's error.
   subroutine warn_estimate(m, res)
      type(model_type), intent(in) :: m
      type(sim_result_type), intent(inout) :: res
      integer :: worst, j, e, used
      real(wp) :: share, worst_share
      character(len=:), allocatable :: off, how
      if (.not. allocated(res%mu_error)) return
      if (size(res%mu_error) == 0) return
      if (m%tolerance > 0.0_wp) then
         do j = 1, size(res%mu_error)
            if (.not. unresolved_contacts(res, j)) cycle
            call add_warning(res%warnings, "&numerics tolerance = " // to_str(m%tolerance) // &
               & " bounds the error from the time step only: at " // &
               & to_str(res%speed_kmh(j)) // " km/h the pad stood on " // &
               & to_str(round_sig(contacts_touching(res, j), 3)) // &
               & " elements in contact on average (fewer than " // &
               & to_str(nint(contacts_resolved)) // "), where mu also depends on how " // &
               & "finely the elements resolve the contacts, which the tolerance does not " // &
               & "refine: set &numerics min_contacts = " // to_str(nint(contacts_resolved)) // &
               & ", or raise elements_per_sample (from " // &
               & to_str(res%elements_per_sample_used(j)) // ") until mu settles " // &
               & "(docs/accuracy.md, ""The pad's resolution"")")
            exit
         end do
         return
      end if
      worst = 0
      worst_share = estimate_warning
      do j = 1, size(res%mu_error)
         if (.not. (res%mu_error(j) > estimate_floor)) cycle
         ! (mu = 0 with an estimate above the floor: an infinite share)
         share = huge(1.0_wp)
         if (abs(res%mu(j)) > 0.0_wp) share = res%mu_error(j) / abs(res%mu(j))
         if (share > worst_share) then
            worst = j
            worst_share = share
         end if
      end do
      if (worst == 0) return
      off = "mu is estimated to be off by up to " // to_str(round_sig(res%mu_error(worst), 2)) &
         & // " (" // to_str(round_sig(100.0_wp * min(worst_share, 1.0e6_wp), 2)) // &
         & " % of mu " // to_str(round_sig(res%mu(worst), 3)) // ") at " // &
         & to_str(res%speed_kmh(worst)) // " km/h from the pad's "
      used = res%elements_per_sample_used(worst)
      if (res%refined_elements_per_sample(worst) > used) then
         e = res%refined_elements_per_sample(worst)
         call add_warning(res%warnings, off // "elements: it stood on " // &
            & to_str(round_sig(contacts_touching(res, worst), 3)) // &
            & " elements in contact on average; at elements_per_sample = " // to_str(e) // &
            & " (the elements " // to_str(e / used) // " times finer) it " // &
            & "stood on " // to_str(round_sig(res%refined_contacts(worst), 3)) // " and " // &
            & "gave mu = " // to_str(round_sig(res%refined_mu(worst), 4)) // &
            & " (mu_error_estimate: that change of mu plus three times the change of one " // &
            & "more halving): set &numerics min_contacts = " // to_str(nint(contacts_resolved)) &
            & // " to report the refined pad, or elements_per_sample to " // to_str(e) // &
            & " or more, and substeps, until mu settles (docs/accuracy.md, ""The pad's " // &
            & "resolution"")")
      else if (res%estimate_elements_per_sample(worst) > used) then
         call add_warning(res%warnings, off // "elements: it stood on " // &
            & to_str(round_sig(contacts_touching(res, worst), 3)) // &
            & " elements in contact on average (mu_error_estimate: three times the change " // &
            & "with the elements halved, elements_per_sample doubled): raise &numerics " // &
            & "elements_per_sample (e.g. to " // &
            & to_str(min(max_elements_per_sample, 4 * used)) // &
            & ") until mu settles (docs/accuracy.md, ""The pad's resolution"")")
      else
         how = "three times the change at half the step, substeps doubled"
         if (res%extrapolated(worst)) how = "mu is the Richardson value of the run and " // &
            & "its pass at half the step, substeps doubled; the estimate twice their difference"
         if (jumped(worst)) then
            ! (no advice to refine the step: it does not converge there)
            call add_warning(res%warnings, off // "step along " // &
               & "the road (mu_error_estimate: " // how // "), and more: the wet " // &
               & "balance's root left the range of the clearances' moves in this run " // &
               & "(film_root_jumps, its own warning), where neither the estimate nor " // &
               & "&numerics tolerance bounds mu's error (docs/accuracy.md)")
         else
            call add_warning(res%warnings, off // "step along " // &
               & "the road (mu_error_estimate: " // how // "): set &numerics " // &
               & "tolerance (e.g. 1e-3) to refine it, or time_scheme = 'exact' on a dry " // &
               & "road (docs/accuracy.md)")
         end if
      end if
   contains
      pure logical function jumped(jj)
         integer, intent(in) :: jj
         jumped = .false.
         if (allocated(res%root_jumps_seen)) jumped = res%root_jumps_seen(jj) > 0
      end function jumped
   end subroutine warn_estimate

   !> Speed k of `from` into speed j of `to` (every per-speed result).
   pure subroutine copy_speed(from, k, to, j)
      type(sim_result_type), intent(in) :: from
      integer, intent(in) :: k, j
      type(sim_result_type), intent(inout) :: to
      to%mu(j) = from%mu(k)
      to%mu_hysteresis(j) = from%mu_hysteresis(k)
      to%mu_adhesion(j) = from%mu_adhesion(k)
      to%hydroplaning_fraction(j) = from%hydroplaning_fraction(k)
      to%wet_fraction(j) = from%wet_fraction(k)
      to%max_balance_residual(j) = from%max_balance_residual(k)
      to%mean_hydro_load(j) = from%mean_hydro_load(k)
      to%max_compression(j) = from%max_compression(k)
      to%n_clamped(j) = from%n_clamped(k)
      to%bearing_evaluations(j) = from%bearing_evaluations(k)
      to%memory_updates(j) = from%memory_updates(k)
      to%viscous_memory_ran(j) = from%viscous_memory_ran(k)
      to%exact_integrator_ran(j) = from%exact_integrator_ran(k)
      to%bearing_ran(j) = from%bearing_ran(k)
      to%friction_film_ran(j) = from%friction_film_ran(k)
      to%mean_local_friction(j) = from%mean_local_friction(k)
      to%mean_film_thickness(j) = from%mean_film_thickness(k)
      to%contact_fraction(j) = from%contact_fraction(k)
      to%film_load_share(j) = from%film_load_share(k)
      to%mean_water_thickness(j) = from%mean_water_thickness(k)
      to%film_unsettled(j) = from%film_unsettled(k)
      to%film_root_jumps(j) = from%film_root_jumps(k)
      to%root_jumps_seen(j) = max(to%root_jumps_seen(j), from%root_jumps_seen(k))
      ! a tolerance's own accuracy record, where both runs have one
      if (allocated(from%mu_error) .and. allocated(to%mu_error)) then
         to%mu_error(j) = from%mu_error(k)
         to%substeps_used(j) = from%substeps_used(k)
         to%extrapolated(j) = from%extrapolated(k)
         to%estimate_elements_per_sample(j) = from%estimate_elements_per_sample(k)
      end if
   end subroutine copy_speed

   !> Speed k's series of `from` into speed j's column of `to` (the same
   !> positions).
   pure subroutine copy_series_column(from, k, to, j)
      type(sim_result_type), intent(in) :: from
      integer, intent(in) :: k, j
      type(sim_result_type), intent(inout) :: to
      to%mu_inst(:, j) = from%mu_inst(:, k)
      to%hydro_load(:, j) = from%hydro_load(:, k)
      to%penetration(:, j) = from%penetration(:, k)
      to%contact_elements(:, j) = from%contact_elements(:, k)
      if (allocated(from%film_thickness) .and. allocated(to%film_thickness)) then
         to%film_thickness(:, j) = from%film_thickness(:, k)
         to%local_friction(:, j) = from%local_friction(:, k)
      end if
      if (allocated(from%film_pressure_max) .and. allocated(to%film_pressure_max)) then
         to%film_pressure_max(:, j) = from%film_pressure_max(:, k)
         to%water_thickness(:, j) = from%water_thickness(:, k)
      end if
   end subroutine copy_series_column

   !> The series of the last level (every speed refined together).
   pure subroutine move_series(from, to)
      type(sim_result_type), intent(inout) :: from, to
      call move_alloc(from%position, to%position)
      call move_alloc(from%mu_inst, to%mu_inst)
      call move_alloc(from%hydro_load, to%hydro_load)
      call move_alloc(from%penetration, to%penetration)
      call move_alloc(from%contact_elements, to%contact_elements)
      if (allocated(from%film_thickness)) then
         call move_alloc(from%film_thickness, to%film_thickness)
         call move_alloc(from%local_friction, to%local_friction)
      end if
      if (allocated(from%film_pressure_max)) then
         call move_alloc(from%film_pressure_max, to%film_pressure_max)
         call move_alloc(from%water_thickness, to%water_thickness)
      end if
      to%n_positions = from%n_positions
   end subroutine move_series

   !> move_series, and the pad's element count and spin-up the series were
   !> made with.
   pure subroutine move_series_whole(from, to)
      type(sim_result_type), intent(inout) :: from, to
      call move_series(from, to)
      to%n_elements = from%n_elements
      to%n_spinup = from%n_spinup
   end subroutine move_series_whole

   !> The series of a run whose speeds &numerics min_contacts refined to
   !> different levels: each speed's own run's series (runs(level_of(j)),
   !> its column col_of(j); level 0: res's own), held on the positions of
   !> the finest level's run, whose positions, element count and spin-up res
   !> then reports. At each of those positions a speed's series has the
   !> value of its own run's last position at or before it: a closed
   !> profile's coarser run has every 2^k-th position of the finer, so each
   !> value is held 2^k times and the series' mean is its own run's.
   subroutine hold_series(res, runs, level_of, col_of)
      type(sim_result_type), intent(inout) :: res
      type(sim_result_type), intent(in) :: runs(:)
      integer, intent(in) :: level_of(:), col_of(:)
      type(sim_result_type) :: fine
      integer, allocatable :: at(:)
      integer :: top, j, n, ns, stat
      logical :: films, reports
      top = maxval(level_of)
      if (top == 0) return
      n = size(runs(top)%position)
      ns = size(level_of)
      films = allocated(runs(top)%film_thickness)
      reports = allocated(runs(top)%film_pressure_max)
      allocate(fine%mu_inst(n, ns), fine%hydro_load(n, ns), fine%penetration(n, ns), &
         & fine%contact_elements(n, ns), fine%position(n), at(n), stat=stat)
      if (stat == 0 .and. films) allocate(fine%film_thickness(n, ns), &
         & fine%local_friction(n, ns), stat=stat)
      if (stat == 0 .and. reports) allocate(fine%film_pressure_max(n, ns), &
         & fine%water_thickness(n, ns), stat=stat)
      if (stat /= 0) then
         call add_warning(res%warnings, "&numerics min_contacts: no memory for the series " // &
            & "on the refined pad's " // to_str(n) // " positions; the series are the run's " // &
            & "at the elements_per_sample given, the means the refined runs' " // &
            & "(elements_per_sample_used)")
         return
      end if
      do j = 1, ns
         if (level_of(j) == 0) then
            call take(res, col_of(j), j)
         else
            call take(runs(level_of(j)), col_of(j), j)
         end if
      end do
      fine%position(:) = runs(top)%position
      fine%n_positions = n
      call move_series(fine, res)
      res%n_elements = runs(top)%n_elements
      res%n_spinup = runs(top)%n_spinup
   contains
      !> Column c of `src`'s series, held on the finest positions, as speed j.
      subroutine take(src, c, j)
         type(sim_result_type), intent(in) :: src
         integer, intent(in) :: c, j
         integer :: i, q, nc
         real(wp) :: slack
         nc = size(src%position)
         slack = 1.0e-9_wp * (src%position(min(2, nc)) - src%position(1))
         q = 1
         do i = 1, n
            do while (q < nc)
               if (src%position(q + 1) > runs(top)%position(i) + slack) exit
               q = q + 1
            end do
            at(i) = q
         end do
         fine%mu_inst(:, j) = src%mu_inst(at, c)
         fine%hydro_load(:, j) = src%hydro_load(at, c)
         fine%penetration(:, j) = src%penetration(at, c)
         fine%contact_elements(:, j) = src%contact_elements(at, c)
         if (films .and. allocated(src%film_thickness)) then
            fine%film_thickness(:, j) = src%film_thickness(at, c)
            fine%local_friction(:, j) = src%local_friction(at, c)
         end if
         if (reports .and. allocated(src%film_pressure_max)) then
            fine%film_pressure_max(:, j) = src%film_pressure_max(at, c)
            fine%water_thickness(:, j) = src%water_thickness(at, c)
         end if
      end subroutine take
   end subroutine hold_series

   !> root_jumps_seen of another pass r into res: res's speed at(k), the
   !> pass's k-th, takes the larger of the two (copy_speed's rule).
   pure subroutine take_jumps_seen(res, at, r)
      type(sim_result_type), intent(inout) :: res
      integer, intent(in) :: at(:)
      type(sim_result_type), intent(in) :: r
      integer :: k
      do k = 1, size(at)
         res%root_jumps_seen(at(k)) = max(res%root_jumps_seen(at(k)), r%root_jumps_seen(k))
      end do
   end subroutine take_jumps_seen

   !> The run's one warning where a wet balance left the range of the
   !> clearances' moves (a film whose load is not monotone): in the reported
   !> pass (film_root_jumps), else in another pass the run made for the
   !> speed (root_jumps_seen: the tolerance's, min_contacts', the error
   !> estimate's), at the first speed with any.
   pure subroutine root_jump_warning(res, speeds_kmh)
      type(sim_result_type), intent(inout) :: res
      real(wp), intent(in) :: speeds_kmh(:)
      character(len=:), allocatable :: place
      integer :: j
      if (.not. allocated(res%root_jumps_seen)) return
      if (.not. any(res%root_jumps_seen > 0)) return
      if (any(res%film_root_jumps > 0)) then
         j = findloc(res%film_root_jumps > 0, .true., dim=1)
         call positions(res%film_root_jumps(j), place)
         place = place // " at " // to_str(speeds_kmh(j)) // " km/h (film_root_jumps)"
      else
         j = findloc(res%root_jumps_seen > 0, .true., dim=1)
         call positions(res%root_jumps_seen(j), place)
         place = place // " at " // to_str(speeds_kmh(j)) // &
            & " km/h in a pass the run made to refine or estimate its result (the " // &
            & "reported pass's film_root_jumps is 0)"
      end if
      call add_warning(res%warnings, "the wet balance's root left the range of the " // &
         & "elements' clearances' moves at " // place // ": the film's load is not " // &
         & "monotone in the penetration there, a lifted and a seated pad may both " // &
         & "balance, and a jump between them strikes the dashpots harder as the step " // &
         & "shrinks, so mu depends on the time step and may have no converged value " // &
         & "(mu_error_estimate and &numerics tolerance do not bound its error; " // &
         & "docs/model.md, ""The film's balance has more than one root"")")
   contains
      !> "k averaged position(s)" (a subroutine: a deferred-length function
      !> result would be a static length, shared by threads).
      pure subroutine positions(count, text)
         integer(i8), intent(in) :: count
         character(len=:), allocatable, intent(out) :: text
         text = to_str(int(count)) // " averaged position"
         if (count /= 1) text = text // "s"
      end subroutine positions
   end subroutine root_jump_warning


   !> The friction model at the knobs given.
   recursive subroutine simulate_fixed(m, z, dx, closed, speeds_kmh, want_series, res, error)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed, want_series
      type(sim_result_type), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      type(geometry_type) :: geo
      type(speed_summary_type), allocatable :: summaries(:)
      class(rubber_model), allocatable :: rubber
      class(film_model), allocatable :: film
      integer :: j, ns, stat, c, j0, j1, n_chunks, width, n_threads, k, n_parts
      integer, allocatable :: spinups(:), exact_bad(:)
      ! speeds the exact integrator declined under a film, run again by
      ! backward Euler
      logical, allocatable :: declined(:)
      type(model_type) :: mm
      type(sim_result_type) :: rr
      integer, allocatable :: idx(:)
      !> The chunks' first and last speeds, and whether each speed's film
      !> carries load (a chunk holds speeds of one kind only).
      integer, allocatable :: part_first(:), part_last(:)
      logical, allocatable :: load_on(:)
      type(film_step_type) :: fs
      logical, allocatable :: shorts(:), negative(:)
      logical :: friction_film, reporting_film, paper_scheme
      character(len=:), allocatable :: effect, others

      res%warnings = ""
      res%effects = ""
      call validate_model(m, error)
      if (allocated(error)) return
      call check_inputs(m, z, dx, closed, speeds_kmh, error)
      if (allocated(error)) return
      call make_components(m, rubber, film)
      friction_film = .false.
      reporting_film = .false.
      if (allocated(film)) then
         friction_film = film%changes_friction()
         reporting_film = film%carries_load() .and. film%reports()
      end if
      res%estimate = estimate_cost(m, size(z), dx, closed, size(speeds_kmh), want_series, &
         & friction_film, rubber%state_size())
      call add_spinup_cost(m, size(z), dx, closed, speeds_kmh, res%estimate)
      call tolerance_guess(m, res%estimate)
      call check_memory(res%estimate, m, want_series, error)
      if (allocated(error)) return
      call build_geometry(m, z, dx, closed, friction_film, geo, error)
      if (allocated(error)) return

      ns = size(speeds_kmh)
      res%n_elements = geo%n_el
      res%n_positions = geo%n_avg
      res%n_spinup = geo%n_spin
      res%thickness = m%thickness
      res%speed_kmh = speeds_kmh
      res%speed = speeds_kmh * kmh_to_ms
      allocate(res%mu(ns), res%mu_hysteresis(ns), res%mu_adhesion(ns), &
         & res%hydroplaning_fraction(ns), res%wet_fraction(ns), &
         & res%max_balance_residual(ns), res%mean_hydro_load(ns), res%max_compression(ns), &
         & res%n_clamped(ns), res%bearing_evaluations(ns), res%memory_updates(ns), &
         & res%viscous_memory_ran(ns), res%bearing_ran(ns), res%friction_film_ran(ns), &
         & res%exact_integrator_ran(ns), &
         & res%mean_local_friction(ns), res%mean_film_thickness(ns), spinups(ns), shorts(ns), &
         & exact_bad(ns), res%contact_fraction(ns), res%film_load_share(ns), &
         & res%mean_water_thickness(ns), res%film_unsettled(ns), res%film_root_jumps(ns), &
         & res%root_jumps_seen(ns), declined(ns), stat=stat)
      if (stat == 0) then
         exact_bad = 0
         declined = .false.
      end if
      if (stat == 0 .and. want_series) then
         allocate(res%mu_inst(geo%n_avg, ns), res%hydro_load(geo%n_avg, ns), &
            & res%penetration(geo%n_avg, ns), res%contact_elements(geo%n_avg, ns), &
            & res%position(geo%n_avg), stat=stat)
         if (stat == 0 .and. friction_film) allocate(res%film_thickness(geo%n_avg, ns), &
            & res%local_friction(geo%n_avg, ns), stat=stat)
         if (stat == 0 .and. reporting_film) then
            allocate(res%film_pressure_max(geo%n_avg, ns), res%water_thickness(geo%n_avg, ns), &
               & stat=stat)
            ! 0 where the film is off (no motion): slide writes where it reports
            if (stat == 0) res%film_pressure_max = 0.0_wp
            if (stat == 0) res%water_thickness = 0.0_wp
         end if
         if (stat == 0) res%position = [(real(j, wp) * geo%advance, j = 0, geo%n_avg - 1)]
      end if
      if (stat /= 0) then
         call fatal_error(error, "not enough memory for the results of " // to_str(ns) // &
            & " speeds and " // to_str(geo%n_avg) // " positions", stat_memory)
         return
      end if

      ! Speeds advance together in chunks of at most `lanes` (the element
      ! loops run over the lanes innermost and vectorise), as many chunks as
      ! threads when there are speeds enough, of equal width (no idle lane);
      ! each speed's arithmetic is the scalar one whatever chunk it is in, so
      ! neither the chunking nor the thread count can change a bit of the
      ! result.
      n_chunks = (ns + lanes - 1) / lanes
      !$ n_chunks = max(n_chunks, min(ns, omp_get_max_threads()))
      ! the exact integrator runs one speed at a time (its events are each
      ! speed's own)
      if (exact_scheme(m)) n_chunks = ns
      width = (ns + n_chunks - 1) / n_chunks
      n_chunks = (ns + width - 1) / width
      ! A chunk never mixes speeds whose film carries load with speeds whose
      ! film does not (no water, or no motion: a speed of 0): the dry pad's
      ! balance takes its clearances' pass alone (lane_gaps_from), which a
      ! chunk with a film cannot, and the two round differently; split, a
      ! speed's numbers are the same whichever speeds share its call.
      allocate(load_on(ns), part_first(ns), part_last(ns))
      do j = 1, ns
         load_on(j) = .false.
         if (.not. allocated(film)) cycle
         call film%prepare(res%speed(j), geo%advance, fs)
         load_on(j) = fs%active .and. film%carries_load()
      end do
      n_parts = 0
      do c = 1, n_chunks
         j0 = (c - 1) * width + 1
         j1 = min(ns, c * width)
         k = j0
         do j = j0 + 1, j1 + 1
            if (j <= j1) then
               if (load_on(j) .eqv. load_on(j - 1)) cycle
            end if
            n_parts = n_parts + 1
            part_first(n_parts) = k
            part_last(n_parts) = j - 1
            k = j
         end do
      end do
      ! one thread on a thread whose OpenMP pool came through fork() (it
      ! would wait for threads that are gone; src/io/pavefric_files_lock.c)
      n_threads = 1
      !$ if (parallel_ok() == 1) n_threads = omp_get_max_threads()
      !$omp parallel do schedule(dynamic, 1) default(shared) private(c, j0, j1, j, summaries) &
      !$omp & num_threads(n_threads)
      do c = 1, n_parts
         j0 = part_first(c)
         j1 = part_last(c)
         allocate(summaries(lanes))
         if (want_series) then
            if (friction_film) then
               call slide(geo, m, rubber, film, res%speed(j0:j1), summaries, &
                  & res%mu_inst(:, j0:j1), res%hydro_load(:, j0:j1), res%penetration(:, j0:j1), &
                  & res%contact_elements(:, j0:j1), res%film_thickness(:, j0:j1), &
                  & res%local_friction(:, j0:j1))
            else if (reporting_film) then
               call slide(geo, m, rubber, film, res%speed(j0:j1), summaries, &
                  & res%mu_inst(:, j0:j1), res%hydro_load(:, j0:j1), res%penetration(:, j0:j1), &
                  & res%contact_elements(:, j0:j1), &
                  & film_pressure_max=res%film_pressure_max(:, j0:j1), &
                  & water_thickness=res%water_thickness(:, j0:j1))
            else
               call slide(geo, m, rubber, film, res%speed(j0:j1), summaries, &
                  & res%mu_inst(:, j0:j1), res%hydro_load(:, j0:j1), res%penetration(:, j0:j1), &
                  & res%contact_elements(:, j0:j1))
            end if
         else
            call slide(geo, m, rubber, film, res%speed(j0:j1), summaries)
         end if
         do j = j0, j1
            associate(summary => summaries(j - j0 + 1))
               res%mu(j) = summary%mu
               res%mu_hysteresis(j) = summary%mu_hysteresis
               res%mu_adhesion(j) = summary%mu_adhesion
               res%hydroplaning_fraction(j) = summary%hydroplaning_fraction
               res%wet_fraction(j) = summary%wet_fraction
               res%max_balance_residual(j) = summary%max_balance_residual
               res%mean_hydro_load(j) = summary%mean_hydro_load
               res%max_compression(j) = summary%max_compression
               res%n_clamped(j) = summary%n_clamped
               res%bearing_evaluations(j) = summary%bearing_evaluations
               res%memory_updates(j) = summary%memory_updates
               res%viscous_memory_ran(j) = summary%viscous_memory_ran
               res%bearing_ran(j) = summary%bearing_ran
               res%friction_film_ran(j) = summary%friction_film_ran
               res%mean_local_friction(j) = summary%mean_local_friction
               res%mean_film_thickness(j) = summary%mean_film_thickness
               res%contact_fraction(j) = summary%contact_fraction
               ! a share: the mean of loads that each balance to W can round
               ! a few ulps past it (1 + 4e-15 on a flat road at 300 km/h)
               res%film_load_share(j) = min(1.0_wp, max(0.0_wp, &
                  & summary%mean_hydro_load / m%load))
               res%mean_water_thickness(j) = summary%mean_water_thickness
               res%film_unsettled(j) = summary%film_unsettled
               res%film_root_jumps(j) = summary%film_root_jumps
               res%memory_updates(j) = merge(-1_i8, res%memory_updates(j), &
                  & summary%failed == stat_memory .or. summary%failed == 1)
               if (summary%failed == stat_internal) exact_bad(j) = summary%exact_bad_position
               declined(j) = summary%exact_declined
               res%exact_integrator_ran(j) = summary%exact_ran
               spinups(j) = summary%spinup
               shorts(j) = summary%spin_short
            end associate
         end do
         deallocate(summaries)
      end do
      !$omp end parallel do
      if (any(res%memory_updates < 0)) then
         call fatal_error(error, "not enough memory for the work arrays of a speed", stat_memory)
         return
      end if
      if (any(exact_bad /= 0)) then
         j = findloc(exact_bad /= 0, .true., dim=1)
         call fatal_error(error, "&numerics time_scheme = 'exact': the contact events of one " // &
            & "step ran away at " // to_str(speeds_kmh(j)) // " km/h, position " // &
            & to_str(exact_bad(j)) // " of the pad's grid; run with time_scheme = " // &
            & "'extrapolated' (and report the scene: it is a bug)", stat_internal)
         return
      end if
      if (any(declined)) then
         ! backward Euler ('extrapolated': at tolerance = 0 its one pass)
         ! for the speeds the exact integrator declined, on the same grid
         idx = pack([(j, j = 1, ns)], declined)
         mm = m
         mm%time_scheme = "extrapolated"
         call simulate_fixed(mm, z, dx, closed, speeds_kmh(idx), want_series, rr, error)
         if (allocated(error)) return
         do k = 1, size(idx)
            j = idx(k)
            call copy_speed(rr, k, res, j)
            spinups(j) = rr%n_spinup
            if (want_series) call copy_series_column(rr, k, res, j)
         end do
      end if
      if (exact_scheme(m) .and. .not. scheme_is(m, "auto")) then
         do j = 1, ns
            if (res%exact_integrator_ran(j) .or. .not. res%viscous_memory_ran(j)) cycle
            call add_warning(res%warnings, "&numerics time_scheme = 'exact' integrates the " // &
               & "Kelvin-Voigt rubber on a dry road or under the paper's film (wet_model = " // &
               & "'kane2017'); at " // to_str(speeds_kmh(j)) // " km/h backward Euler ran at " // &
               & "substeps = " // to_str(m%substeps) // " (another rubber or film, or a film " // &
               & "too weak to lift the pad off a plateau it stands on, whose contact events " // &
               & "the exact integrator could not resolve; use tolerance > 0 for its error)")
            exit
         end do
      end if
      res%n_spinup = maxval(spinups)
      if (any(shorts)) call add_warning(res%warnings, "the rubber's memory outlasts " // &
         & to_str(max_spin_laps) // " laps of spin-up at " // &
         & to_str(speeds_kmh(findloc(shorts, .true., dim=1))) // " km/h: the pad's state " // &
         & "still drifts round the profile, and mu (mu_hysteresis) holds that drift " // &
         & "(a retardation time far beyond the time of a lap: is &rubber viscosity or " // &
         & "stiffness what you meant?)")

      if (any(res%film_unsettled > 0)) then
         j = findloc(res%film_unsettled > 0, .true., dim=1)
         call add_warning(res%warnings, "the water film's solution did not settle at " // &
            & to_str(int(res%film_unsettled(j))) // " of " // to_str(geo%n_avg) // &
            & " positions at " // to_str(speeds_kmh(j)) // " km/h (film_unsettled): its " // &
            & "last iterate was used there, and mu may be off by its share of the load")
      end if
      res%root_jumps_seen = res%film_root_jumps
      ! A closed profile's positions close the lap only when the stride
      ! divides the grid's points: else the last step runs past the start
      ! and the elements' stored energy is not returned over the positions
      ! averaged (with mu_loc = 0, mu can turn negative)
      if (geo%closed .and. modulo(geo%npf, geo%stride) /= 0) &
         & call add_warning(res%warnings, "&numerics position_stride = " // &
         & to_str(geo%stride) // " does not divide the " // to_str(geo%npf) // &
         & " points of the closed profile's grid: its " // to_str(geo%n_avg) // &
         & " positions do not close the lap (they run " // &
         & to_str(geo%n_avg * geo%stride - geo%npf) // " points past its start), so the " // &
         & "energy the elements store is not all returned over them and mu is off by " // &
         & "it (with mu_loc = 0 it can be negative); give a stride that divides " // &
         & to_str(geo%npf))
      ! The rubber's dissipation is never negative: a negative mu_hysteresis
      ! is a pad that has not reached a state that repeats round the profile
      ! (a very soft or very slow rubber creeping through the run), whose
      ! drift the energy balance counts. Finite, but not a friction: say so.
      negative = res%mu_hysteresis < -max(negative_hysteresis, negative_share * abs(res%mu))
      if (any(negative)) then
         j = findloc(negative, .true., dim=1)
         call others_negative(j, others)
      end if
      paper_scheme = .false.
      if (allocated(m%friction_scheme)) paper_scheme = m%friction_scheme == "paper"
      if (any(negative) .and. paper_scheme) then
         ! the paper's facet forces (Eq. 10) are not the rubber's energy
         ! balance: their work has no sign (attack22: an elastic pad on a
         ! sawtooth read -0.242, the warning blaming its viscosity)
         call add_warning(res%warnings, "mu_hysteresis = " // to_str(res%mu_hysteresis(j)) // &
            & " < 0 at " // to_str(speeds_kmh(j)) // " km/h under &numerics " // &
            & "friction_scheme = 'paper': the paper's facet forces (Eq. 10, tangents from " // &
            & "central differences) do not balance the energy the rubber stores and " // &
            & "dissipates, so their work can be negative, and mu = " // to_str(res%mu(j)) // &
            & " there is not a friction; friction_scheme = 'energy' (the default) measures " // &
            & "the rubber's dissipation (docs/model.md)" // others)
      else if (any(negative) .and. .not. geo%closed) then
         ! an open profile: its mean is the rubber's dissipation over the
         ! stretch (since 2026-12-07), >= 0 step by step in exact
         ! arithmetic; below the bound only through rounding of a stored
         ! energy far larger than the dissipation
         call add_warning(res%warnings, "mu_hysteresis = " // to_str(res%mu_hysteresis(j)) // &
            & " < 0 at " // to_str(speeds_kmh(j)) // " km/h on an open profile: the " // &
            & "rubber cannot dissipate less than nothing, so the energy the elements " // &
            & "store at the ends of its " // to_str(geo%n_avg) // " positions (or their " // &
            & "rounding) outweighs what it dissipated, and mu = " // to_str(res%mu(j)) // &
            & " there is not a friction (docs/model.md, 'Known limits'); a longer " // &
            & "profile, or &surface closed = .true. for a closed track, avoids it" // others)
      else if (any(negative)) then
         call add_warning(res%warnings, "mu_hysteresis = " // to_str(res%mu_hysteresis(j)) // &
            & " < 0 at " // to_str(speeds_kmh(j)) // " km/h: the rubber cannot dissipate " // &
            & "less than nothing, so the pad did not reach a state that repeats round the " // &
            & "profile (largest compression " // to_str(res%max_compression(j)) // " m; " // &
            & "its drift is in the energy balance) and mu = " // to_str(res%mu(j)) // &
            & " there is not a friction: check &rubber stiffness and viscosity " // &
            & "(docs/model.md, 'Known limits')" // others)
      end if
      res%effects = "elastic_contact,facet_friction"
      if (any(res%viscous_memory_ran)) then
         call rubber%memory_effect(effect)
         res%effects = res%effects // "," // effect
      end if
      if (allocated(film)) then
         if (any(res%bearing_ran) .or. any(res%friction_film_ran)) then
            call film%effect(effect)
            res%effects = res%effects // "," // effect
         end if
      end if
      call check_results(res, error)
   contains
      !> The other speeds after the j-th whose mu_hysteresis is negative
      !> beyond the warning's bound (`negative`), named ("" if none). (A
      !> subroutine: see short_profile_message.)
      subroutine others_negative(j, text)
         integer, intent(in) :: j
         character(len=:), allocatable, intent(out) :: text
         integer :: k
         text = ""
         do k = j + 1, size(negative)
            if (.not. negative(k)) cycle
            if (len(text) == 0) then
               text = "; also at "
            else
               text = text // ", "
            end if
            text = text // to_str(speeds_kmh(k)) // " km/h (mu_hysteresis = " // &
               & to_str(res%mu_hysteresis(k)) // ")"
         end do
      end subroutine others_negative
   end subroutine simulate_fixed

   !> Checks that need the profile and speeds as well as the parameters.
   subroutine check_inputs(m, z, dx, closed, speeds_kmh, error)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed
      type(error_type), allocatable, intent(out) :: error
      integer :: j, n_el
      character(len=:), allocatable :: text
      if (.not. (dx > 0.0_wp .and. dx <= huge(dx))) then
         call fatal_error(error, "&surface dx = " // to_str(dx) // ": must be finite and > 0")
         return
      end if
      if (size(speeds_kmh) < 1) then
         call fatal_error(error, "&operation speeds_kmh: no speed given")
         return
      end if
      do j = 1, size(speeds_kmh)
         if (.not. (speeds_kmh(j) >= 0.0_wp .and. speeds_kmh(j) <= 1.0e5_wp)) then
            call fatal_error(error, "&operation speeds_kmh(" // to_str(j) // ") = " // &
               & to_str(speeds_kmh(j)) // ": must be finite and >= 0 and <= 1e5")
            return
         end if
      end do
      call check_heights(z, error)
      if (allocated(error)) return
      if (maxval(abs(z)) > max_height) then
         j = maxloc(abs(z), dim=1)
         call fatal_error(error, "profile height " // to_str(j) // " = " // to_str(z(j)) // &
            & " m: beyond +-" // to_str(max_height) // " m, not a texture; are the heights " // &
            & "in the unit declared (&surface height_unit, or the file's header)?")
         return
      end if
      ! (a pad that would not fit in memory where the profile does: a
      ! profile far shorter than the pad)
      call check_profile_scale(m, size(z), dx, error)
      if (allocated(error)) return
      n_el = pad_elements(m, dx)
      if (n_el < 1) then
         call no_element_message(m, dx, .false., text)
         call fatal_error(error, text)
         return
      end if
      if (averaged_positions(m, size(z), dx, closed) < positions_needed(closed)) then
         if (n_el >= huge(1) .or. real(size(z), wp) * real(m%elements_per_sample, wp) * &
               & real(m%substeps, wp) > 2.0e9_wp) then
            call fatal_error(error, "&numerics elements_per_sample = " // &
               & to_str(m%elements_per_sample) // " and substeps = " // to_str(m%substeps) // &
               & ": the refined profile of " // to_str(size(z)) // " points would have more " // &
               & "than 2e9 samples, or the pad more than 2e9 elements", stat_memory)
         else
            call short_profile_message(m, size(z), dx, closed, 0.0_wp, text)
            call fatal_error(error, text)
         end if
         return
      end if
   end subroutine check_inputs

   !> The cost of a run at the model's knobs (cost_estimate_type), from the
   !> scene alone: np profile samples, ns speeds. `n_state`: the rubber's
   !> state values per element and speed (1 + Maxwell arms).
   pure function estimate_cost(m, np, dx, closed, ns, want_series, friction_film, n_state) &
      & result(c)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np, ns, n_state
      real(wp), intent(in) :: dx
      logical, intent(in) :: closed, want_series, friction_film
      type(cost_estimate_type) :: c
      real(wp) :: fine, n_ext, n_el, n_avg, n_spin, per_step, per_position
      fine = real(m%elements_per_sample, wp) * real(m%substeps, wp)
      n_el = real(pad_elements(m, dx), wp)
      n_ext = real(np, wp) * fine + n_el * real(m%substeps, wp)
      n_avg = real(averaged_positions(m, np, dx, closed), wp)
      n_spin = 0.0_wp
      if (closed) n_spin = real(ceiling(n_el * real(m%substeps, wp) / &
         & real(m%position_stride, wp)), wp)
      ! geometry: z, tan_theta, clamped (+ slopes), and the refinement's copies
      c%bytes = n_ext * (8.0_wp + 8.0_wp + 4.0_wp) * 2.0_wp
      ! the error estimate's pass at half the step: twice the geometry, once
      ! the first pass's is freed
      if (step_passes(m, n_state) > 2.5_wp) c%bytes = 2.0_wp * c%bytes
      if (friction_film) c%bytes = c%bytes + n_ext * 16.0_wp * real(min(ns, 64), wp)
      ! per speed (one per thread at most, counted for all): element arrays,
      ! the rubber's state and its coefficients per element (a Maxwell
      ! rubber of n arms: 1 + n state values and 2 + 6 n coefficients, here
      ! 5 + 7 n with room to spare; Kelvin-Voigt: 5)
      c%bytes = c%bytes + n_el * 8.0_wp * real(10 + 5 * n_state + 2 * (n_state - 1), wp) * &
         & real(ns, wp)
      ! series: the arrays, and again the output file built from them
      if (want_series) c%bytes = c%bytes + 2.0_wp * n_avg * real(ns, wp) * 8.0_wp * 6.0_wp
      if (n_avg > 0.0_wp .and. n_el > 0.0_wp .and. (n_avg + n_spin) * n_el < 9.0e18_wp) then
         c%element_steps = int((n_avg + n_spin) * n_el, i8)
         c%total_element_steps = c%element_steps * int(ns, i8)
      end if
      per_step = sec_step + sec_arm * real(n_state - 1, wp)
      per_position = 0.0_wp
      if (m%depth > 0.0_wp) then
         if (m%wet_model == "squeeze") then
            ! the film thins on every road sample under a touching element:
            ! substeps of them an element (its footprint on the refined road)
            per_step = per_step + sec_squeeze_step + sec_squeeze_sample * real(m%substeps, wp)
            per_position = sec_squeeze_position
         else if (m%wet_model == "reynolds") then
            per_step = per_step + sec_reynolds_step
            per_position = sec_reynolds_position
         else
            per_step = per_step + sec_bearing_step
            per_position = sec_bearing_position
         end if
      end if
      c%seconds = sec_run + sec_point * real(np, wp) + step_passes(m, n_state) * &
         & (sec_point_pass * real(np, wp) * fine + per_step * real(c%total_element_steps, wp))
      if (n_el > 0.0_wp) c%seconds = c%seconds + step_passes(m, n_state) * per_position * &
         & real(c%element_steps, wp) / n_el
   end function estimate_cost

   !> The cost of a run's element-steps in backward-Euler passes at its
   !> substeps: 2 for the exact integrator (1.1 to 3.7 one pass,
   !> docs/accuracy.md), 3 with the error estimate's pass at half the step
   !> (&numerics error_estimate at tolerance = 0), else 1. (Where the pad
   !> stands on few elements min_contacts and the estimate halve them until
   !> it stands on 4, up to hundreds of passes' worth: add_refinement_cost
   !> foresees them with a probe. The exact integrator's pass that halves
   !> the elements, 4 more, is not counted.)
   pure real(wp) function step_passes(m, n_state) result(passes)
      type(model_type), intent(in) :: m
      integer, intent(in) :: n_state
      passes = 1.0_wp
      if (exact_scheme(m) .and. m%depth <= 0.0_wp .and. n_state == 1) then
         passes = 2.0_wp
      else if (m%tolerance <= 0.0_wp .and. m%error_estimate) then
         passes = 3.0_wp
      end if
   end function step_passes

   !> The estimate `c` of a run at `speeds_kmh` (km/h) with each speed's own
   !> spin-up (lap_spinup: the energy scheme on a closed profile spins a
   !> speed up further when its rubber's memory is long), as the run will
   !> make it: every element-step counted, and the seconds they cost.
   subroutine add_spinup_cost(m, np, dx, closed, speeds_kmh, c)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np
      real(wp), intent(in) :: dx, speeds_kmh(:)
      logical, intent(in) :: closed
      type(cost_estimate_type), intent(inout) :: c
      class(rubber_model), allocatable :: rubber
      class(film_model), allocatable :: film
      type(rubber_step_type) :: rstep
      type(geometry_type) :: geo
      real(wp) :: extra, fine, kel, per_step
      integer :: j, spin, stat
      logical :: short, repeats
      if (.not. closed .or. c%element_steps <= 0) return
      if (allocated(m%friction_scheme)) then
         if (m%friction_scheme == "paper") return
      end if
      fine = real(m%elements_per_sample, wp) * real(m%substeps, wp)
      geo%n_el = pad_elements(m, dx)
      geo%stride = m%position_stride
      geo%npf = np * m%elements_per_sample * m%substeps
      geo%n_spin = (geo%n_el * m%substeps + geo%stride - 1) / geo%stride
      geo%advance = dx / fine * real(m%position_stride, wp)
      call make_components(m, rubber, film)
      call rubber%prepare(speeds_kmh * kmh_to_ms, geo%advance, geo%n_el, rstep, stat)
      if (stat /= 0) return     ! (the run itself will say that memory is short)
      extra = 0.0_wp
      do j = 1, size(speeds_kmh)
         if (.not. rstep%memory(j)) cycle
         kel = m%width * (dx / real(m%elements_per_sample, wp)) * rstep%k_eff(j)
         ! (with repeats, as the run asks: the spin then includes the
         ! extension that lets a lane repeat)
         call lap_spinup(rstep, j, geo, m%load / kel, spin, short, repeats)
         extra = extra + real(spin - geo%n_spin, wp) * real(geo%n_el, wp)
      end do
      if (.not. extra > 0.0_wp) return
      c%total_element_steps = c%total_element_steps + int(extra, i8)
      per_step = sec_step + sec_arm * real(rubber%state_size() - 1, wp)
      c%seconds = c%seconds + step_passes(m, rubber%state_size()) * per_step * extra
   end subroutine add_spinup_cost

   !> The passes the run will add where it finds the pad standing on fewer
   !> than contacts_resolved elements in contact (resolve_pad for
   !> min_contacts, estimate_step_error's levels and last pass), foreseen
   !> before the run by a probe: each speed run once on every `stride`-th
   !> position of the profile's first probe_window samples (about
   !> probe_positions of them, one step per position, no estimate, no
   !> refinement), whose contacts say how many halvings each
   !> speed will need, on the assumption that the contacts double with each
   !> halving of the elements. Each level is costed by estimate_cost at its
   !> elements_per_sample (about 4 times the level before: twice the
   !> elements at twice the positions). Added to c%seconds only (the
   !> element-steps stay the reported pass's). Runs of fewer than
   !> probe_runs_from * probe_positions positions (where the probe would cost
   !> more than half a pass, a sixth of the default run) unless their
   !> refinement could make them long (below), runs that refine nothing
   !> (neither min_contacts nor, at tolerance = 0, the error estimate)
   !> and probes that fail are left as they are: the probe is an estimate's
   !> helper, never an error. (At 256 positions the probe of a pad the film
   !> lifted at 80 km/h saw it touch at 2 of them, and missed the levels.)
   !> With a tolerance, min_contacts' levels each run the tolerance's
   !> passes: the levels' first passes are costed here, and tolerance_guess
   !> multiplies them with the rest. A short run is probed where every
   !> level, and a tolerance's passes to max_substeps, would take
   !> probe_worth seconds or more (the program announces a run from 1 s):
   !> a 128-point profile of the shipped compound at tolerance = 1e-9 ran
   !> 104 s where its estimate said 0.001 s.
   subroutine add_refinement_cost(m, z, dx, closed, speeds_kmh, c)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed
      type(cost_estimate_type), intent(inout) :: c
      integer, parameter :: probe_positions = 1024, probe_runs_from = 2
      integer, parameter :: probe_window = 65536
      real(wp), parameter :: probe_worth = 1.0_wp
      !> The most a probe may cost (seconds, bytes, as estimate_cost says).
      real(wp), parameter :: probe_budget = 1.0_wp, probe_bytes = 256.0_wp * 2.0_wp**20
      type(model_type) :: mp
      type(cost_estimate_type) :: probe
      type(sim_result_type) :: r
      type(error_type), allocatable :: err
      class(rubber_model), allocatable :: rubber
      class(film_model), allocatable :: film
      logical :: friction_film, estimate
      integer :: npe, phases, positions, j, k, levels, eps, nw, npw, phw
      real(wp) :: dxe, dxw, contacts, extra, fixed, worst
      estimate = m%error_estimate .and. .not. m%tolerance > 0.0_wp
      if (m%min_contacts <= 0 .and. .not. estimate) return
      call element_grid(m, size(z), dx, closed, npe, dxe, phases, positions)
      if (positions < probe_runs_from * probe_positions * phases) then
         ! the worst case: every level (about 4 times the one before) and
         ! the estimate's pass, or a tolerance's passes to max_substeps
         worst = c%seconds * (4.0_wp**(pad_levels + 1) - 1.0_wp) / 3.0_wp
         if (m%tolerance > 0.0_wp) then
            worst = worst * real(2 * (max_substeps / m%substeps) - 1, wp)
         else
            worst = 2.0_wp * worst
         end if
         if (worst < probe_worth) return
      end if
      mp = m
      mp%error_estimate = .false.
      mp%min_contacts = 0
      mp%substeps = 1
      mp%tolerance = 0.0_wp
      mp%time_scheme = "euler"
      ! a window of the profile at most probe_window samples long (its
      ! geometry is built for the probe as for a run: a 10-million-point
      ! profile would pay that twice), on every n-th of its positions
      nw = min(size(z), probe_window)
      call element_grid(m, nw, dx, closed .and. nw == size(z), npw, dxw, phw, positions)
      mp%position_stride = max(1, positions / (phw * probe_positions))
      call make_components(m, rubber, film)
      friction_film = .false.
      if (allocated(film)) friction_film = film%changes_friction()
      ! the probe's own cost bounded: its positions are few, but a pad of
      ! millions of elements (&pad element_length = 1e-9 m) made it run for
      ! minutes and take gigabytes before anything was announced or the
      ! memory checked (attack20). Beyond probe_budget the refinement is
      ! not foreseen: such a run is announced at its base cost, or refused
      ! for its memory, at once.
      probe = estimate_cost(mp, npw, dxw, closed .and. nw == size(z), size(speeds_kmh), &
         & .false., friction_film, rubber%state_size())
      if (probe%seconds > probe_budget .or. probe%bytes > probe_bytes) return
      call run_grids(mp, z(1:nw), dx, closed .and. nw == size(z), speeds_kmh, .false., r, err)
      if (allocated(err)) return
      fixed = sec_run + sec_point * real(npe, wp)
      extra = 0.0_wp
      allocate(c%refine_speeds(0))
      do j = 1, size(speeds_kmh)
         contacts = contacts_touching(r, j)
         if (.not. (contacts > 0.0_wp .and. contacts < contacts_resolved)) cycle
         c%refine_speeds = [c%refine_speeds, speeds_kmh(j)]
         levels = 0
         do while (contacts * 2.0_wp**levels < contacts_resolved .and. levels < pad_levels)
            levels = levels + 1
         end do
         eps = m%elements_per_sample
         do k = 1, levels
            if (2 * eps > max_elements_per_sample) exit
            eps = 2 * eps
            extra = extra + level_seconds(eps, m%substeps)
         end do
         if (.not. estimate) cycle
         ! the estimate's last pass: half the step where the levels reached
         ! the contacts, else half the elements once more
         if (contacts * 2.0_wp**levels >= contacts_resolved) then
            extra = extra + level_seconds(eps, 2 * m%substeps)
         else if (2 * eps <= max_elements_per_sample) then
            extra = extra + level_seconds(2 * eps, m%substeps)
         end if
      end do
      c%refine_seconds = extra * real(phases, wp)
      c%seconds = c%seconds + c%refine_seconds
   contains
      !> One speed's pass at elements_per_sample e and substeps s, without
      !> the run's fixed costs.
      real(wp) function level_seconds(e, s)
         integer, intent(in) :: e, s
         type(model_type) :: ml
         type(cost_estimate_type) :: cl
         ml = m
         ml%error_estimate = .false.
         ml%min_contacts = 0
         ml%elements_per_sample = e
         ml%substeps = s
         cl = estimate_cost(ml, npe, dxe, closed, 1, .false., friction_film, &
            & rubber%state_size())
         level_seconds = max(0.0_wp, cl%seconds - fixed)
      end function level_seconds
   end subroutine add_refinement_cost

   !> With &numerics tolerance, a guess of where its refinement stops, from
   !> how the default scenes converge (docs/performance.md, "The default
   !> scenes to tolerance"): backward Euler's error about err_euler / s at
   !> s steps a sample, the Richardson value's about err_richardson / s**2
   !> ('extrapolated', 'richardson', 'auto'), the exact integrator's met at
   !> the first two halvings. The substeps guessed: the power of two times
   !> the scene's substeps that meets the tolerance so, at least two
   !> halvings, at most max_substeps; the seconds: every pass to there, each
   !> twice the one before (c%seconds the first's); the bytes: the first
   !> pass's times the substeps' ratio (its profile on the refined grid and
   !> its series grow with them; at the scene's elements: a pass that
   !> min_contacts refined holds more). A guess: a rough profile
   !> or a stiff compound converges slower, and speeds that meet the
   !> tolerance early stop.
   pure subroutine tolerance_guess(m, c)
      type(model_type), intent(in) :: m
      type(cost_estimate_type), intent(inout) :: c
      real(wp), parameter :: err_euler = 0.03_wp, err_richardson = 0.25_wp
      real(wp) :: needed
      integer :: s
      c%tolerance_substeps = 0
      c%tolerance_seconds = 0.0_wp
      c%tolerance_bytes = 0.0_wp
      if (.not. (m%tolerance > 0.0_wp)) return
      needed = sqrt(err_richardson / m%tolerance)
      if (allocated(m%time_scheme)) then
         if (m%time_scheme == "euler") needed = err_euler / m%tolerance
         if (m%time_scheme == "exact") needed = 1.0_wp
      end if
      ! the Reynolds film's mu need not converge in the step (its balance's
      ! roots, docs/model.md): its ladder to the top (attack21: the shipped
      ! scene at 1e-3 was announced at substeps 16, 1.5 s, and ran to 4096,
      ! 92 s, without meeting it)
      if (allocated(m%wet_model) .and. m%depth > 0.0_wp) then
         if (m%wet_model == "reynolds") needed = real(max_substeps, wp)
      end if
      ! (the refinement's own ladder: doublings while they stay within
      ! max_substeps; validate_model leaves room for the first two)
      s = 4 * m%substeps
      do while (2 * s <= max_substeps .and. real(s, wp) < needed)
         s = 2 * s
      end do
      c%tolerance_substeps = s
      c%tolerance_seconds = c%seconds * real(2 * (s / m%substeps) - 1, wp)
      c%tolerance_bytes = c%bytes * real(s / m%substeps, wp)
   end subroutine tolerance_guess

   !> Refuse a run, before allocating, whose estimated memory exceeds what
   !> the machine has (a clear error instead of the process being killed).
   subroutine check_memory(c, m, series, error)
      type(cost_estimate_type), intent(in) :: c
      !> The scene's model and whether it writes series: the message names
      !> what the scene set that makes the run large.
      type(model_type), intent(in) :: m
      logical, intent(in) :: series
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: limit
      character(len=:), allocatable :: knobs
      limit = real(c_physical_memory(), wp)
      if (limit <= 0.0_wp) limit = 16.0_wp * 2.0_wp**30
      if (c%bytes > 0.8_wp * limit) then
         knobs = ""
         if (m%element_length > 0.0_wp) knobs = "a longer &pad element_length (now " // &
            & to_str(m%element_length) // " m), "
         if (m%elements_per_sample > 1) knobs = knobs // "a smaller &numerics " // &
            & "elements_per_sample (now " // to_str(m%elements_per_sample) // "), "
         if (m%substeps > 1) knobs = knobs // "fewer &numerics substeps (now " // &
            & to_str(m%substeps) // "), "
         if (series) knobs = knobs // "&output series = .false., "
         knobs = knobs // "fewer speeds or a shorter profile"
         call fatal_error(error, "the run needs about " // to_str(nint(c%bytes / 2.0_wp**20, i8)) &
            & // " MiB, more than the memory this process may use (" // &
            & to_str(nint(limit / 2.0_wp**20, i8)) // " MiB: the machine's, or the " // &
            & "limit of the job, ulimit or container): give " // knobs, stat_memory)
      end if
   end subroutine check_memory

   !> Every result finite: a non-finite number is never written.
   subroutine check_results(res, error)
      type(sim_result_type), intent(in) :: res
      type(error_type), allocatable, intent(out) :: error
      integer :: j
      do j = 1, size(res%mu)
         if (.not. (ieee_is_finite(res%mu(j)) .and. ieee_is_finite(res%max_balance_residual(j)) &
               & .and. ieee_is_finite(res%mean_hydro_load(j)) .and. &
               & ieee_is_finite(res%max_compression(j)))) then
            call fatal_error(error, "internal: a non-finite result at " // &
               & to_str(res%speed_kmh(j)) // " km/h (mu = " // to_str(res%mu(j)) // &
               & "); the inputs are within their ranges, please report this scene", &
               & stat_internal)
            return
         end if
      end do
      if (allocated(res%mu_inst)) then
         if (.not. all(ieee_is_finite(res%mu_inst)) .or. &
               & .not. all(ieee_is_finite(res%penetration)) .or. &
               & .not. all(ieee_is_finite(res%hydro_load))) then
            call fatal_error(error, "internal: a non-finite per-position result; please " // &
               & "report this scene", stat_internal)
            return
         end if
      end if
   end subroutine check_results

   !> Refine the profile, compute facet friction, lay out the pad, and extend
   !> a closed profile by wrapping so element indices never need a modulo.
   subroutine build_geometry(m, z, dx, closed, with_slopes, geo, error)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx
      logical, intent(in) :: closed, with_slopes
      type(geometry_type), intent(out) :: geo
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: zf(:), tf(:), t_fine(:), sf(:), af(:)
      logical, allocatable :: cf(:), c_fine(:)
      real(wp) :: dxf, tan_max
      integer :: fine, n_ext, k, i, stat

      fine = m%elements_per_sample * m%substeps
      dxf = dx / real(fine, wp)
      if (fine > 1) then
         call refine_profile(z, closed, fine, zf, stat)
      else
         allocate(zf, source=z, stat=stat)
      end if
      if (stat /= 0) then
         call no_memory(size(z), fine, error)
         return
      end if
      geo%npf = size(zf)
      geo%closed = closed
      geo%n_el = pad_elements(m, dx)
      geo%spacing = m%substeps
      geo%stride = m%position_stride
      geo%dx_el = dx / real(m%elements_per_sample, wp)
      geo%advance = dxf * real(m%position_stride, wp)
      geo%n_avg = averaged_positions(m, size(z), dx, closed)
      if (closed) then
         ! N spin-up positions in MODEL.md: enough steps to slide one pad length
         geo%n_spin = (geo%n_el * geo%spacing + geo%stride - 1) / geo%stride
      else
         geo%n_spin = 0
      end if

      ! Facets belong to the measured profile: tan(theta) from MODEL.md's
      ! central differences at the samples, interpolated linearly between
      ! them on a refined grid (a refined point counts as clamped when its
      ! nearest sample is). Refinement then changes the discretisation, not
      ! the surface's facet geometry.
      allocate(tf(size(z)), cf(size(z)), sf(size(z)), af(size(z)), stat=stat)
      if (stat /= 0) then
         call fatal_error(error, "not enough memory for the facets of " // to_str(size(z)) // &
            & " points", stat_memory)
         return
      end if
      call facet_friction(z, dx, closed, m%mu_loc, m%theta_max_deg, tf, cf, slopes=sf)
      ! the local friction's part of each tangent: tan(theta) - tan(alpha),
      ! both clamped at theta_max (>= 0 for mu_loc >= 0: the clamp is monotone)
      tan_max = tan(m%theta_max_deg * acos(-1.0_wp) / 180.0_wp)
      do k = 1, size(z)
         af(k) = adhesion_tangent(sf(k), tf(k), cf(k), m%mu_loc, tan_max)
      end do
      if (fine > 1) then
         call refine_profile(tf, closed, fine, t_fine, stat)
         call move_alloc(t_fine, tf)
         if (stat == 0) call refine_profile(af, closed, fine, t_fine, stat)
         if (stat == 0) call move_alloc(t_fine, af)
         if (with_slopes .and. stat == 0) then
            call refine_profile(sf, closed, fine, t_fine, stat)
            call move_alloc(t_fine, sf)
         end if
         if (stat == 0) allocate(c_fine(geo%npf), stat=stat)
         if (stat /= 0) then
            call no_memory(size(z), fine, error)
            return
         end if
         do k = 1, geo%npf
            c_fine(k) = cf(min(size(z), (k - 1 + fine / 2) / fine + 1))
            if (closed .and. (k - 1 + fine / 2) / fine + 1 > size(z)) c_fine(k) = cf(1)
         end do
         call move_alloc(c_fine, cf)
      end if
      if (closed) then
         n_ext = geo%npf + (geo%n_el - 1) * geo%spacing
         allocate(geo%z(n_ext), geo%tan_theta(n_ext), geo%clamped(n_ext), geo%adhesion(n_ext), &
            & stat=stat)
         if (stat == 0 .and. with_slopes) allocate(geo%slope(n_ext), stat=stat)
         if (stat /= 0) then
            call fatal_error(error, "not enough memory for a profile of " // to_str(n_ext) // &
               & " refined points", stat_memory)
            return
         end if
         do k = 1, n_ext
            i = modulo(k - 1, geo%npf) + 1
            geo%z(k) = zf(i)
            geo%tan_theta(k) = tf(i)
            geo%adhesion(k) = af(i)
            geo%clamped(k) = cf(i)
            if (with_slopes) geo%slope(k) = sf(i)
         end do
      else
         call move_alloc(zf, geo%z)
         call move_alloc(tf, geo%tan_theta)
         call move_alloc(af, geo%adhesion)
         call move_alloc(cf, geo%clamped)
         if (with_slopes) call move_alloc(sf, geo%slope)
      end if
      allocate(geo%clamped_at(size(geo%clamped)), stat=stat)
      if (stat /= 0) then
         call fatal_error(error, "not enough memory for a profile of " // &
            & to_str(size(geo%clamped)) // " refined points", stat_memory)
         return
      end if
      geo%clamped_at = merge(1.0_wp, 0.0_wp, geo%clamped)

      ! Undeformed pad bottom h_i above the reference plane.
      allocate(geo%h(geo%n_el), stat=stat)
      if (stat /= 0) then
         call fatal_error(error, "not enough memory for a pad of " // to_str(geo%n_el) // &
            & " elements (&numerics elements_per_sample = " // to_str(m%elements_per_sample) // &
            & ")", stat_memory)
         return
      end if
      call pad_bottom(shape_code(m%shape), m%radius, geo%dx_el, geo%h)
   end subroutine build_geometry

   !> A set of speeds (lanes) over the same positions: spin-up, then the
   !> averaged positions (Eqs. 2-12). The element loops run over the lanes
   !> innermost, so they vectorise, while each lane's arithmetic is the
   !> scalar algorithm's exactly (sums over elements in element order); the
   !> wet balance and the friction films run lane by lane.
   subroutine slide(geo, m, rubber, film, speeds, out, mu_inst, hydro_load, penetration, &
         & contact, film_thickness, local_friction, film_pressure_max, water_thickness)
      type(geometry_type), intent(in) :: geo
      type(model_type), intent(in) :: m
      class(rubber_model), intent(in) :: rubber
      class(film_model), allocatable, intent(in) :: film
      !> The chunk's speeds (at most `lanes`).
      real(wp), intent(in) :: speeds(:)
      !> A summary per lane (the first size(speeds) are the speeds').
      type(speed_summary_type), intent(out) :: out(lanes)
      real(wp), intent(out), optional :: mu_inst(:,:), hydro_load(:,:), penetration(:,:)
      integer, intent(out), optional :: contact(:,:)
      real(wp), intent(out), optional :: film_thickness(:,:), local_friction(:,:)
      !> With a film that reports its solution: its largest pressure (Pa) and
      !> water per unit of pad area (m) at each position (left as they are
      !> at the speeds where the film is off: the caller's zeros).
      real(wp), intent(inout), optional :: film_pressure_max(:,:), water_thickness(:,:)

      type(rubber_step_type) :: rstep
      !> The landing: a lane's first step, from relaxed elements, takes the
      !> time the road needs to move one element length whatever the
      !> substeps (and position_stride), so that every pass starts from the
      !> same state (docs/model.md, "The landing"); its coefficients, its
      !> stiffness kel_land and load s_land, and the run's (kel_run, s_run)
      !> to come back to. `land_differs`: the landing's step is not the
      !> run's (substeps or position_stride > 1, a rubber with memory).
      type(rubber_step_type) :: rstep_land
      real(wp), dimension(lanes) :: kel_land, s_land, kel_run, s_run
      logical :: land_differs, landing_step
      logical, dimension(lanes) :: landing
      !> Per lane, whether the spin-up left the pad's start below 1e-9 (as
      !> friction): the state repeats round the lap, and the mean on a
      !> closed profile is the elements' dissipation (lap_spinup).
      logical, dimension(lanes) :: repeats
      !> The lanes whose film may engage at the dry balance (engaged_lanes').
      logical, dimension(lanes) :: engage_mask
      real(wp), allocatable :: state_land(:,:,:)
      type(film_step_type), allocatable :: fstep(:)
      real(wp), allocatable :: c(:,:), d(:,:), state(:,:,:), u_free(:,:), push(:,:)
      real(wp), allocatable :: work(:), dl(:), gap(:), fstate(:,:,:), pressure(:), share(:)
      real(wp), allocatable :: thick(:)
      real(wp), allocatable :: tan_el(:), pl(:), gaps(:,:), u_prev(:,:), push_prev(:,:)
      real(wp), allocatable :: pmean(:,:)
      !> The film's workspace per lane (film%work_size(n), nl): zeroed when a
      !> lane's run (re)starts.
      real(wp), allocatable :: fwork(:,:)
      integer, allocatable :: samples(:)
      !> The penetration two positions back and the film's load at the
      !> previous position: the wet balance's warm start.
      real(wp), dimension(lanes) :: delta_prev2, wh_prev
      !> The previous two positions' dry roots (the dry balance's warm start,
      !> extrapolated: under a film the penetration taken, delta_prev, is the
      !> wet root, further from this position's dry root).
      real(wp), dimension(lanes) :: delta_dry_prev, delta_dry_prev2
      real(wp), dimension(lanes) :: guess
      type(dry_start_type) :: dry_start
      !> The dry pad's clearances and first balance pass in one pass
      !> (lane_free_gaps_from), d then unshifted: dref, subtracted from d
      !> where it is read after the balance (cmin there, else 0).
      logical :: one_pass
      real(wp), dimension(lanes) :: dref
      !> Per lane, the sum of the shifted clearances d (engaged_lanes' or
      !> engaged_by_level's; wet_roots takes it).
      real(wp), dimension(lanes) :: sum_d
      real(wp), dimension(lanes) :: kel, s_load, cmin, x, delta_prev, wh, sum_f, sum_ft, v
      real(wp), dimension(lanes) :: mu_sum, resid_max, wh_sum, u_max, local_sum
      real(wp), dimension(lanes) :: force_sum, film_mean_sum, contacts, clamps
      real(wp), dimension(lanes) :: sum_fa, hyst, hyst_sum, adh_sum, delta_last
      !> The rubber's mean against the push (rubber_step_type%push_slope; 0
      !> where the law gives none): lane_work_mean's contact ramp.
      real(wp), dimension(lanes) :: push_slope
      real(wp), dimension(lanes) :: film_work, push_total_prev, mean_total, hyst_abs_sum
      ! an open profile's stretch averaged: the elements' work in its steps
      ! (the pad's descent's added back), and the energy they store at its
      ! ends (open_dissipation)
      real(wp), dimension(lanes) :: open_work, stored_start, stored_end, step_descent
      logical :: open_energy, open_known
      !> Sums over averaged positions: the share of elements in contact, and
      !> the film's water per unit area (films that report it)
      real(wp), dimension(lanes) :: contact_share_sum, water_sum
      integer(i8), dimension(lanes) :: n_clamped, n_eval, n_unsettled, n_jumps
      !> A film whose load may not be monotone (film_model%load_monotone):
      !> each lane's clearances and wet root at its last position, to count
      !> the positions where the root left the range of their moves
      !> (count_jumps).
      logical :: track_jumps
      logical, dimension(lanes) :: have_jump_prev
      real(wp), dimension(lanes) :: delta_jump_prev
      real(wp), allocatable :: c_jump_prev(:,:)
      integer, dimension(lanes) :: n_contact, n_nocontact, n_wet, n_clamp_j
      logical, dimension(lanes) :: load_film, friction_film, wet_lane
      real(wp) :: mu_j, resid, tan_max, mu_eff, film_sum, hyst_j, adh_j, water, pmax
      integer :: t, k1, n, nl, j, stat, lead, lead_prev, ns_state, film_count
      logical :: series, clamped, any_memory, any_load, any_friction, energy, settled
      logical :: film_reports
      !> Whether the film's engagement may be decided without the dry roots
      !> (engaged_by_level: a load film whose sums suffice), and whether this
      !> position's wet lanes start without them.
      logical :: level_test, skip_dry
      !> Per lane: whether it takes the level's path at this position, and
      !> engaged_by_level's answers (engaged, the sum of d, the upper bound).
      logical, dimension(lanes) :: by_level, wet_level
      real(wp), dimension(lanes) :: sum_level, x_level
      !> The Kelvin-Voigt pad (the energy scheme; dry, under a film that
      !> carries load or one that changes the facets' friction): the rubber's
      !> free compression, the contacts, the work and the rubber's update
      !> each fused into the pass beside them (lane_free_gaps, lane_step_kv),
      !> the same numbers in fewer passes; a friction film's facets after.
      logical :: kv_fused
      !> Spin-up steps of each lane (closed profiles), and whether a lane has
      !> had a step since it started.
      integer, dimension(lanes) :: spin
      logical, dimension(lanes) :: have_prev
      !> Whether an element touched at the step before the first averaged one.
      logical, dimension(lanes) :: contact_before

      logical :: done

      done = .false.
      call prepare_lanes(done)
      if (done) return
      delta_prev = -huge(1.0_wp)
      delta_prev2 = -huge(1.0_wp)
      delta_dry_prev = -huge(1.0_wp)
      delta_dry_prev2 = -huge(1.0_wp)
      wh_prev = 0.0_wp
      have_prev = .false.
      contact_before = .false.
      spin = geo%n_spin
      ! (the paper's scheme keeps 0.1.0's spin-up of one pad length)
      repeats = .false.
      if (geo%closed .and. any_memory .and. energy) then
         do j = 1, nl
            if (rstep%memory(j)) call lap_spinup(rstep, j, geo, m%load / kel(j), spin(j), &
               & out(j)%spin_short, repeats(j))
         end do
      end if
      spin(nl+1:) = spin(nl)
      hyst = 0.0_wp
      film_work = 0.0_wp
      push_total_prev = 0.0_wp
      hyst_sum = 0.0_wp
      hyst_abs_sum = 0.0_wp
      open_work = 0.0_wp
      mean_total = 0.0_wp
      stored_start = 0.0_wp
      stored_end = 0.0_wp
      step_descent = 0.0_wp
      adh_sum = 0.0_wp
      mu_sum = 0.0_wp
      wh_sum = 0.0_wp
      resid_max = 0.0_wp
      u_max = 0.0_wp
      local_sum = 0.0_wp
      force_sum = 0.0_wp
      film_mean_sum = 0.0_wp
      contact_share_sum = 0.0_wp
      water_sum = 0.0_wp
      n_unsettled = 0
      n_jumps = 0
      have_jump_prev = .false.
      n_clamped = 0
      n_eval = 0
      n_nocontact = 0
      n_wet = 0
      lead_prev = -huge(1)
      do t = -maxval(spin(1:nl)), geo%n_avg - 1
         call restart_lanes(t)
         if (land_differs .and. t <= 1) then
            ! a lane's landing step takes the landing's stiffness (and the
            ! step after the last landing, the run's again)
            landing(1:nl) = t == -spin(1:nl)
            landing(nl+1:) = .false.
            landing_step = any(landing(1:nl))
            kel = merge(kel_land, kel_run, landing)
            s_load = merge(s_land, s_run, landing)
         end if
         if (geo%closed) then
            k1 = modulo(t * geo%stride + 1, geo%npf) + 1
         else
            k1 = t * geo%stride + 1
         end if
         ! c_i = h_i - z_k + u_free_i: the penetration at which element i
         ! starts to push (Eqs. 4, 8).
         ! A dry pad (one_pass): the clearances unshifted (dref = cmin: the
         ! balance and the step take d = c - cmin), the balance's first pass
         ! at the extrapolated penetration in the same pass.
         one_pass = .not. any_load
         if (one_pass) dry_start%guess = extrapolated(delta_dry_prev, delta_dry_prev2)
         if (one_pass .and. kv_fused) then
            call lane_free_gaps_from(nl, n, rstep%coef(:, 1), state, &
               & geo%z(k1 : k1 + (n-1) * geo%spacing : geo%spacing), geo%h, u_free, d, cmin, &
               & dry_start)
         else if (kv_fused) then
            call lane_free_gaps(nl, n, rstep%coef(:, 1), state, &
               & geo%z(k1 : k1 + (n-1) * geo%spacing : geo%spacing), geo%h, u_free, cmin, d)
         else
            if (any_memory) call rubber%free_compression(rstep, state, u_free)
            if (one_pass) then
               call lane_gaps_from(nl, n, geo%z(k1 : k1 + (n-1) * geo%spacing : geo%spacing), &
                  & geo%h, u_free, d, cmin, dry_start)
            else
               call lane_gaps(nl, n, geo%z(k1 : k1 + (n-1) * geo%spacing : geo%spacing), &
                  & geo%h, u_free, c, cmin, d)
            end if
         end if
         dref = merge(cmin, 0.0_wp, one_pass)
         ! Where a lane's film carried load at the previous position (and
         ! its sums suffice), whether it engages here is decided without its
         ! dry root (engaged_by_level); where it engages, its wet balance is
         ! bracketed by an upper bound of its dry root (engaged_by_level's),
         ! and the dry roots are computed only where another lane needs
         ! them. Each lane's path is its own (its numbers do not depend on
         ! the lanes beside it): the dry roots computed for the others are
         ! neither used nor remembered for a lane on the level's path.
         by_level = .false.
         if (level_test) then
            by_level(1:nl) = load_film(1:nl) .and. wh_prev(1:nl) > 0.0_wp .and. &
               & delta_prev(1:nl) > -huge(1.0_wp)
            if (any(by_level(1:nl))) then
               call engaged_by_level(nl, n, d, s_load, film, fstep, by_level, wet_level, &
                  & sum_level, x_level)
               by_level(1:nl) = by_level(1:nl) .and. wet_level(1:nl)
            end if
         end if
         skip_dry = all(by_level(1:nl))
         wh = 0.0_wp
         if (.not. skip_dry) then
            ! warm start from the previous position's dry root, extrapolated
            ! linearly from the two before where there are two (the start
            ! only: the root is the same, to rounding where dry_roots_of_c
            ! takes its first step as the root)
            if (one_pass) then
               call dry_roots_of_c(nl, n, d, cmin, s_load, dry_start%guess, dry_start%sums, &
                  & dry_start%counts, dry_start%below, dry_start%above, x, work, dl)
            else
               guess = extrapolated(delta_dry_prev, delta_dry_prev2)
               call dry_roots(nl, n, d, s_load, guess - cmin, x, work, dl)
            end if
            ! (loops, not WHERE on sections of nl: gfortran allocates a
            ! mask for those on the heap, at every position)
            do j = 1, nl
               if (by_level(j)) cycle
               delta_dry_prev2(j) = delta_dry_prev(j)
               delta_dry_prev(j) = cmin(j) + x(j)
            end do
         end if
         if (any_load) then
            ! the lanes whose film engages at the dry balance, then their wet
            ! balances together (the level's lanes: engaged, the level's
            ! upper bound their bracket's top)
            if (.not. skip_dry) then
               ! (the mask in a lanes-sized array: an expression of sections of
               ! nl would be a heap temporary at every position)
               engage_mask(1:nl) = load_film(1:nl) .and. .not. by_level(1:nl)
               call engaged_lanes(nl, n, d, x, film, fstep, engage_mask(1:nl), wet_lane, dl, &
                  & gap, sum_d)
            end if
            do j = 1, nl
               if (.not. by_level(j)) cycle
               wet_lane(j) = .true.
               sum_d(j) = sum_level(j)
               x(j) = x_level(j)
            end do
            ! Warm start where the film carried load at the previous position:
            ! from its wet penetration, extrapolated linearly from the two
            ! before. Elsewhere from the dry root, which is then the root to
            ! the bit when the film carries nothing (a film that never
            ! lifts gives the dry numbers exactly).
            do j = 1, nl
               guess(j) = -huge(1.0_wp)
               if (wh_prev(j) <= 0.0_wp .or. delta_prev(j) <= -huge(1.0_wp)) cycle
               guess(j) = extrapolated(delta_prev(j), delta_prev2(j)) - cmin(j)
            end do
            call wet_roots(nl, n, d, kel, m%load, film, fstep, wet_lane, m%wet_tolerance, &
               & guess, x, wh, n_eval, gaps, fwork, sum_d)
            ! what the film's solution at the root is (films that report it)
            if (film_reports .and. t >= 0) then
               do j = 1, nl
                  if (.not. load_film(j)) cycle
                  dl = d(j, :)
                  call gap_field(dl, x(j), gap)
                  call film%report(fstep(j), gap, settled, water, pmax, fwork(:, j))
                  water_sum(j) = water_sum(j) + water
                  if (.not. settled) n_unsettled(j) = n_unsettled(j) + 1
                  if (present(film_pressure_max)) film_pressure_max(t+1, j) = pmax
                  if (present(water_thickness)) water_thickness(t+1, j) = water
               end do
            end if
            if (track_jumps) call count_jumps(t)
         end if

         if (kv_fused) then
            ! lane_contacts, energy_step's lane_work_linear and kv_update in
            ! one pass (the first step's work, from no previous step, is
            ! discarded below as energy_step discards it)
            call lane_step_kv(nl, n, x, d, dref, u_free, &
               & geo%clamped_at(k1 : k1 + (n-1) * geo%spacing : geo%spacing), &
               & geo%adhesion(k1 : k1 + (n-1) * geo%spacing : geo%spacing), &
               & rstep%mean_weights, cmin + x - delta_last, push_prev, state, &
               & sum_f, contacts, clamps, u_max, sum_fa, hyst, mean_total)
            ! (the step's pushes are push_prev now; push itself only where a
            ! friction film or energy_step's first step reads it)
            if (any(friction_film(1:nl)) .or. .not. all(have_prev(1:nl))) push = push_prev
            n_contact = nint(contacts)
            n_clamp_j = nint(clamps)
            if (t == -1) contact_before = n_contact > 0
            ! a friction film's facets (its tangents, adhesion and clamps
            ! replace the ones above on its lanes; the work and the rubber's
            ! update do not depend on them)
            call friction_films(t, k1)
            ! the rest of energy_step, its work already done
            call energy_step(.true.)
         else
            sum_f = 0.0_wp
            call lane_contacts(nl, n, x, d, dref, u_free, &
               & geo%tan_theta(k1 : k1 + (n-1) * geo%spacing : geo%spacing), &
               & geo%clamped_at(k1 : k1 + (n-1) * geo%spacing : geo%spacing), &
               & geo%adhesion(k1 : k1 + (n-1) * geo%spacing : geo%spacing), push, sum_f, &
               & contacts, sum_ft, clamps, u_max, sum_fa)
            n_contact = nint(contacts)
            n_clamp_j = nint(clamps)
            if (t == -1) contact_before = n_contact > 0

            call friction_films(t, k1)
            if (energy) call energy_step(.false.)
            if (any_memory) then
               ! the landing lanes' state from the landing's step
               if (landing_step) then
                  state_land = state
                  call rubber%update(rstep_land, state_land, u_free, push)
               end if
               call rubber%update(rstep, state, u_free, push)
               if (landing_step) then
                  do j = 1, nl
                     if (landing(j)) state(j, :, :) = state_land(j, :, :)
                  end do
               end if
            end if
         end if
         delta_prev2 = merge(delta_prev, -huge(1.0_wp), delta_prev > -huge(1.0_wp))
         wh_prev = wh
         delta_prev = cmin + x
         if (t < 0) cycle                                    ! spin-up

         call accumulate(t)
         if (open_energy .and. (t == 0 .or. t == geo%n_avg - 1)) call stored_now(t)
      end do

      call summarise()
   contains
      !> The rubber's and the films' step coefficients per lane, and the
      !> work arrays; the exact Kelvin-Voigt integrator instead where it
      !> applies (`done`: it ran, or memory ran out: out%failed).
      subroutine prepare_lanes(done)
         logical, intent(out) :: done
         integer :: j
         logical :: exact_film
         done = .false.
         n = geo%n_el
         nl = size(speeds)
         ! the lanes' arrays are sized for `lanes`; those beyond the chunk's
         ! speeds repeat its last speed and are never used
         v(1:nl) = speeds
         v(nl+1:) = speeds(nl)
         series = present(mu_inst)
         call step_stiffness(geo%advance, rstep, kel, s_load)
         if (stat /= 0) then
            out%failed = 1
            done = .true.
            return
         end if
         kel_run = kel
         s_run = s_load
         push_slope = 0.0_wp
         if (allocated(rstep%push_slope)) push_slope(1:nl) = rstep%push_slope
         landing = .false.
         landing_step = .false.
         ! the landing's step: one element length of travel (the run's step
         ! at substeps = 1 and position_stride = 1, where nothing changes)
         land_differs = any(rstep%memory) .and. geo%advance /= geo%dx_el
         if (land_differs) then
            call step_stiffness(geo%dx_el, rstep_land, kel_land, s_land)
            if (stat /= 0) then
               out%failed = 1
               done = .true.
               return
            end if
         end if
         any_memory = any(rstep%memory)
         ! Simulate only the effects the scene calls for: a film needs water and
         ! motion (Sect. 3); the rubber's memory needs viscosity and motion.
         load_film = .false.
         friction_film = .false.
         allocate(fstep(lanes))
         if (allocated(film)) then
            do j = 1, nl
               call film%prepare(v(j), geo%advance, fstep(j))
               load_film(j) = fstep(j)%active .and. film%carries_load()
               friction_film(j) = fstep(j)%active .and. film%changes_friction()
            end do
         end if
         any_load = any(load_film)
         any_friction = any(friction_film)
         film_reports = .false.
         if (allocated(film)) film_reports = any_load .and. film%reports()
         level_test = .false.
         if (allocated(film)) level_test = any_load .and. film%sums_suffice()
         if (nl == 1 .and. exact_scheme(m) .and. .not. any_friction .and. rstep%memory(1)) then
            ! dry, or under the paper's pseudo-bearing (its load a function
            ! of the mean gap: pavefric_kv_exact)
            exact_film = .not. any_load
            if (any_load) then
               select type (film)
               type is (pseudo_bearing_film)
                  exact_film = .true.
               end select
            end if
            if (exact_film) then
               select type (rubber)
               type is (kelvin_voigt_rubber)
                  if (any_load) then
                     select type (film)
                     type is (pseudo_bearing_film)
                        call slide_exact(geo, m, rubber, v(1), out(1), mu_inst, hydro_load, &
                           & penetration, contact, film_thickness, local_friction, &
                           & fstep(1)%coef(1), film%depth)
                     end select
                     if (out(1)%failed == stat_internal) then
                        ! under the film the integrator declines a film that
                        ! lifts the pad only all but closed (a slow speed, a
                        ! heavy pad on flat tops), and its events can run
                        ! away there: simulate_fixed runs the speed again
                        ! with backward Euler, and the warning for speeds
                        ! 'exact' did not run says so
                        out(1)%failed = 0
                        out(1)%exact_bad_position = 0
                        out(1)%exact_ran = .false.
                        out(1)%exact_declined = .true.
                     end if
                     done = .true.
                     return
                  else
                     call slide_exact(geo, m, rubber, v(1), out(1), mu_inst, hydro_load, &
                        & penetration, contact, film_thickness, local_friction)
                     done = .true.
                     return
                  end if
               end select
            end if
         end if

         ns_state = rubber%state_size()
         ! the lane count as a run-time value: the lane loops then compile to
         ! vector loops (a constant count is unrolled into scalar code)
         energy = .true.
         if (allocated(m%friction_scheme)) energy = m%friction_scheme /= "paper"
         open_energy = energy .and. .not. geo%closed
         open_known = open_energy
         allocate(c(nl, n), d(nl, n), push(nl, n), u_free(nl, n), work(n), &
            & dl(n), gap(n), stat=stat)
         if (stat == 0 .and. energy) allocate(u_prev(nl, n), push_prev(nl, n), stat=stat)
         if (stat == 0 .and. energy .and. any_memory .and. .not. allocated(rstep%mean_weights)) &
            & allocate(pmean(nl, n), stat=stat)
         if (stat == 0 .and. any_memory) allocate(state(nl, ns_state, n), stat=stat)
         if (stat == 0 .and. any_load) allocate(gaps(nl, n), &
            & fwork(film%work_size(n), nl), source=0.0_wp, stat=stat)
         track_jumps = .false.
         if (any_load) track_jumps = .not. film%load_monotone()
         if (stat == 0 .and. track_jumps) allocate(c_jump_prev(nl, n), source=0.0_wp, stat=stat)
         if (stat == 0 .and. any_friction) allocate(fstate(film%state_size(), geo%npf, nl), &
            & pressure(n), share(n), thick(n), tan_el(n), pl(n), samples(n), &
            & stat=stat)
         if (stat /= 0) then
            out%failed = 1
            done = .true.
            return
         end if
         u_free = 0.0_wp
         if (any_memory) state = 0.0_wp
         kv_fused = .false.
         select type (rubber)
         type is (kelvin_voigt_rubber)
            kv_fused = any_memory .and. energy .and. allocated(rstep%mean_weights) .and. &
               & ns_state == 1
         end select
         if (kv_fused) then
            ! the first step's work is computed from these and discarded
            u_prev = 0.0_wp
            push_prev = 0.0_wp
            delta_last = 0.0_wp
         end if
         tan_max = tan(m%theta_max_deg * acos(-1.0_wp) / 180.0_wp)
         if (any_friction) then
            do j = 1, nl
               if (friction_film(j)) call film%reset(fstep(j), fstate(:, :, j))
            end do
         end if

      end subroutine prepare_lanes

      !> The rubber's coefficients for steps of `advance` (m) per lane, and
      !> the element's stiffness kl and the load's share sl = W / kl (Eq. 2:
      !> F = l dx p, p = K_eff (g - u_free)); stat as the rubber's prepare.
      subroutine step_stiffness(advance, step, kl, sl)
         real(wp), intent(in) :: advance
         type(rubber_step_type), intent(out) :: step
         real(wp), intent(out) :: kl(lanes), sl(lanes)
         call rubber%prepare(v(1:nl), advance, n, step, stat)
         if (stat /= 0) return
         kl(1:nl) = m%width * geo%dx_el * step%k_eff
         kl(nl+1:) = kl(nl)
         sl = m%load / kl
      end subroutine step_stiffness

      !> For a film whose load may not be monotone: per lane, whether the
      !> wet root moved from the lane's last position outside the range of
      !> the moves of the clearances c_i = d_i + cmin (beyond their
      !> rounding), counted at averaged positions (film_root_jumps). Where
      !> the load is monotone in the penetration and in each gap, the
      !> balance's root is a weighted mean of the clearances' moves, weights
      !> >= 0, and cannot leave their range (every c_i moved by the same
      !> amount moves the root by it; one moved further moves it less); a
      !> root that leaves it sits where the load is not monotone, and one
      !> that jumped to another root leaves it by a distance that does not
      !> shrink with the step.
      subroutine count_jumps(t)
         integer, intent(in) :: t
         real(wp) :: lo_c, hi_c, dc, move, excess, spread
         integer :: i, j
         do j = 1, nl
            if (.not. load_film(j)) cycle
            if (have_jump_prev(j) .and. t >= 0) then
               lo_c = huge(1.0_wp)
               hi_c = -huge(1.0_wp)
               spread = 0.0_wp
               do i = 1, n
                  dc = (d(j, i) + cmin(j)) - c_jump_prev(j, i)
                  lo_c = min(lo_c, dc)
                  hi_c = max(hi_c, dc)
                  spread = max(spread, d(j, i))
               end do
               move = (cmin(j) + x(j)) - delta_jump_prev(j)
               excess = max(0.0_wp, move - hi_c, lo_c - move)
               ! the rounding of the clearances (their spread, and the
               ! profile's height: a vertical shift changes no count)
               if (excess > 1.0e-9_wp * spread + 64.0_wp * epsilon(1.0_wp) * abs(cmin(j))) &
                  & n_jumps(j) = n_jumps(j) + 1
            end if
            do i = 1, n
               c_jump_prev(j, i) = d(j, i) + cmin(j)
            end do
            delta_jump_prev(j) = cmin(j) + x(j)
            have_jump_prev(j) = .true.
         end do
      end subroutine count_jumps

      !> A lane whose spin-up starts at step t begins from relaxed elements
      !> (what it did before is discarded): its numbers are its own,
      !> whichever speeds share its chunk.
      subroutine restart_lanes(t)
         integer, intent(in) :: t
         integer :: j, first
            ! (spin-ups start at t <= 0: none later)
            if (t > 0) return
            first = -maxval(spin(1:nl))
            do j = 1, nl
               if (t /= -spin(j) .or. t == first) cycle
               if (any_memory) state(j, :, :) = 0.0_wp
               u_free(j, :) = 0.0_wp
               delta_prev(j) = -huge(1.0_wp)
               delta_prev2(j) = -huge(1.0_wp)
               delta_dry_prev(j) = -huge(1.0_wp)
               delta_dry_prev2(j) = -huge(1.0_wp)
               wh_prev(j) = 0.0_wp
               if (allocated(fwork)) fwork(:, j) = 0.0_wp
               have_prev(j) = .false.
               have_jump_prev(j) = .false.
               n_jumps(j) = 0
               u_max(j) = 0.0_wp
               n_eval(j) = 0
               if (friction_film(j)) call film%reset(fstep(j), fstate(:, :, j))
            end do
      end subroutine restart_lanes

      !> The friction films (lane by lane): the water entering under the
      !> leading edge, the share of mu_loc each element keeps, the facets'
      !> tangents and work with it, and the film's series.
      subroutine friction_films(t, k1)
         integer, intent(in) :: t, k1
         integer :: i, j, k
            if (any_friction) then
               ! the film on the road samples entering under the leading edge
               ! (counted without wrapping round a closed profile)
               lead = t * geo%stride + n * geo%spacing + merge(1, 0, geo%closed)
               if (lead_prev == -huge(1)) lead_prev = lead
               ! the road sample under each element's start
               do i = 1, n
                  samples(i) = physical(k1 + (i-1) * geo%spacing)
               end do
               do j = 1, nl
                  if (.not. friction_film(j)) cycle
                  do k = lead_prev + 1, lead
                     call film%enter(fstep(j), fstate(:, :, j), physical(k))
                  end do
                  do i = 1, n
                     pl(i) = push(j, i)
                     pressure(i) = rstep%k_eff(j) * pl(i)
                  end do
                  ! (a landing step presses with the landing's stiffness)
                  if (landing(j)) pressure(1:n) = rstep_land%k_eff(j) * pl(1:n)
                  call film%friction(fstep(j), fstate(:, :, j), samples, geo%spacing, &
                     & geo%closed, pressure, geo%dx_el, share, thick)
                  film_sum = 0.0_wp
                  film_count = 0
                  sum_ft(j) = 0.0_wp
                  sum_fa(j) = 0.0_wp
                  n_clamp_j(j) = 0
                  do i = 1, n
                     ! an element out of contact adds nothing below (+0 to
                     ! each sum, and it has no film between): skipped
                     if (.not. pl(i) > 0.0_wp) cycle
                     k = k1 + (i-1) * geo%spacing
                     if (share(i) >= 1.0_wp) then
                        tan_el(i) = geo%tan_theta(k)
                        clamped = geo%clamped(k)
                        mu_eff = m%mu_loc
                     else
                        mu_eff = m%mu_loc * share(i)
                        call facet_tangent(geo%slope(k), mu_eff, tan_max, tan_el(i), clamped)
                     end if
                     sum_ft(j) = sum_ft(j) + pl(i) * tan_el(i)
                     if (share(i) >= 1.0_wp) then
                        sum_fa(j) = sum_fa(j) + pl(i) * geo%adhesion(k)
                     else
                        sum_fa(j) = sum_fa(j) + pl(i) * adhesion_tangent(geo%slope(k), &
                           & tan_el(i), clamped, mu_eff, tan_max)
                     end if
                     n_clamp_j(j) = n_clamp_j(j) + merge(1, 0, pl(i) > 0.0_wp .and. clamped)
                     if (t >= 0) local_sum(j) = local_sum(j) + pl(i) * mu_eff
                     ! the film where the rubber touches: the one between them
                     ! (as the film's step left it under the element)
                     if (pressure(i) > 0.0_wp) then
                        film_sum = film_sum + thick(i)
                        film_count = film_count + 1
                     end if
                  end do
                  if (film_count > 0) film_sum = film_sum / real(film_count, wp)
                  if (t >= 0) then
                     force_sum(j) = force_sum(j) + sum_f(j)
                     film_mean_sum(j) = film_mean_sum(j) + film_sum
                     if (series .and. present(film_thickness)) then
                        film_thickness(t+1, j) = film_sum
                        local_friction(t+1, j) = 0.0_wp
                        if (sum_f(j) > 0.0_wp) local_friction(t+1, j) = &
                           & local_partial(pl, share, m%mu_loc) / sum_f(j)
                     end if
                  end if
               end do
               lead_prev = lead
            end if
            if (t >= 0 .and. series .and. present(film_thickness)) then
               ! speeds where the film is off (no motion): no film, the full mu_loc
               do j = 1, nl
                  if (friction_film(j)) cycle
                  film_thickness(t+1, j) = 0.0_wp
                  local_friction(t+1, j) = merge(m%mu_loc, 0.0_wp, sum_f(j) > 0.0_wp)
               end do
            end if
      end subroutine friction_films

      !> The energy scheme's step: the work the facets did on the elements
      !> beyond the pad's own descent (lane_work), and the pad's descent
      !> against the film.
      subroutine energy_step(work_done)
         !> The step's work (hyst, mean_total) already made with the
         !> contacts (lane_step_kv): the rest only.
         logical, intent(in) :: work_done
         integer :: j
            ! the work of the step on the elements beyond the pad's own
            ! descent: what the facets did (lane_work)
            if (any(have_prev(1:nl))) then
               if (work_done) then
                  ! (lane_step_kv: lane_work_linear's sums, in its pass)
               else if (any_memory .and. allocated(rstep%mean_weights)) then
                  ! the same, for a law whose mean is linear in the step's two
                  ! compressions (u_prev is the step's start): in one pass
                  call lane_work_linear(nl, n, u_free, push, rstep%mean_weights, u_prev, &
                     & push_prev, cmin + x - delta_last, hyst, mean_total)
               else if (any_memory) then
                  ! each element's mean pressure over the step, exact for the
                  ! path the rubber integrates (the state is still the
                  ! step's start): the work is then the stored energy's
                  ! change plus a dissipation >= 0, element by element
                  call rubber%mean_push(rstep, state, u_free, push, pmean)
                  call lane_work_mean(nl, n, u_free, push, pmean, push_slope, u_prev, &
                     & push_prev, cmin + x - delta_last, hyst, mean_total)
               else
                  ! an elastic pad: the trapezoid is the exact mean
                  ! (lane_work also remembers this step for the next)
                  call lane_work(nl, n, u_free, push, u_prev, push_prev, &
                     & cmin + x - delta_last, hyst)
                  mean_total(1:nl) = 0.5_wp * (push_total_prev(1:nl) + sum_f(1:nl))
               end if
               ! what the pad's descent did beyond the elements' mean force:
               ! the load they did not carry on average over the step (W -
               ! their mean force) times the descent. With a film carrying
               ! load that is the film's work; on a dry road, the step's path
               ! between two balances (its elements' mean force adds up to W
               ! only at the ends). The mean counts it out on a closed
               ! profile whose spin-up brought the pad to a state that
               ! repeats: the load's own work W (delta - delta') returns
               ! round the lap there, so the mean is the elements'
               ! dissipation alone, >= 0 for every rubber (docs/model.md,
               ! "Which the mean takes"). Where the load's work does not
               ! return (an open profile; a memory or a creep that still
               ! shows after the spin-up, such as the shipped compound's slow
               ! arms) the term is counted out only where a film carries load
               ! at either end of the step, and elsewhere the friction is the
               ! facets' work (a flat road has none, whatever the pad's creep)
               do j = 1, nl
                  film_work(j) = 0.0_wp
                  if ((geo%closed .and. repeats(j)) .or. &
                     & (load_film(j) .and. (wh(j) > 0.0_wp .or. wh_prev(j) > 0.0_wp))) &
                     & film_work(j) = (m%load - kel(j) * mean_total(j)) * &
                     & (cmin(j) + x(j) - delta_last(j))
               end do
            end if
            where (.not. have_prev)
               hyst = 0.0_wp
               film_work = 0.0_wp
            end where
            push_total_prev(1:nl) = sum_f(1:nl)
            if (.not. all(have_prev(1:nl))) call lane_remember(nl, n, u_free, push, u_prev, &
               & push_prev)
            ! (a loop: merge on sections of nl would be a heap temporary)
            do j = 1, nl
               step_descent(j) = 0.0_wp
               if (have_prev(j)) step_descent(j) = cmin(j) + x(j) - delta_last(j)
            end do
            delta_last = cmin + x
            have_prev = .true.
      end subroutine energy_step

      !> An open profile's stored energy at the first and last averaged
      !> positions (after the rubber's update): the rubber's own, or an
      !> elastic pad's K u^2 / 2 over k_eff = K, u its push.
      subroutine stored_now(t)
         integer, intent(in) :: t
         real(wp) :: e(lanes)
         logical :: known
         integer :: i, j
         e = 0.0_wp
         if (any_memory) then
            call rubber%stored_energy(rstep, state, e(1:nl), known)
         else
            do i = 1, n
               do j = 1, nl
                  e(j) = e(j) + push(j, i) * push(j, i)
               end do
            end do
            e = 0.5_wp * e
            known = .true.
         end if
         open_known = open_known .and. known
         if (t == 0) stored_start(1:nl) = e(1:nl)
         if (t == geo%n_avg - 1) stored_end(1:nl) = e(1:nl)
      end subroutine stored_now

      !> The step's friction (Eq. 11, as the facets' work per distance: the
      !> rubber's part and the local friction's) and the means, counts and
      !> series of an averaged position t.
      subroutine accumulate(t)
         integer, intent(in) :: t
         integer :: j
         do j = 1, nl
            sum_f(j) = kel(j) * sum_f(j)
            ! Eq. 11 (divided by W), as the facets' work per distance: the
            ! rubber's part and the local friction's part
            adh_j = kel(j) * sum_fa(j) / m%load
            if (energy) then
               hyst_j = kel(j) * hyst(j) / (m%load * geo%advance)
            else
               hyst_j = kel(j) * (sum_ft(j) - sum_fa(j)) / m%load
            end if
            mu_j = hyst_j + adh_j
            ! the rubber's part of the mean: the facets' work less the film's
            ! (Eq. 15's lift is a function of the gap, not a dissipation: what
            ! it takes and gives back round the profile is not friction)
            if (energy) hyst_j = hyst_j - film_work(j) / (m%load * geo%advance)
            hyst_sum(j) = hyst_sum(j) + hyst_j
            hyst_abs_sum(j) = hyst_abs_sum(j) + abs(hyst_j)
            ! an open profile's: the elements' work, the descent's term added
            ! back (mean_total is its factor in hyst)
            if (open_energy) open_work(j) = open_work(j) + &
               & kel(j) * (hyst(j) + mean_total(j) * step_descent(j))
            adh_sum(j) = adh_sum(j) + adh_j
            resid = abs(sum_f(j) + wh(j) - m%load) / m%load
            mu_sum(j) = mu_sum(j) + mu_j
            wh_sum(j) = wh_sum(j) + wh(j)
            resid_max(j) = max(resid_max(j), resid)
            n_clamped(j) = n_clamped(j) + n_clamp_j(j)
            if (n_contact(j) == 0) n_nocontact(j) = n_nocontact(j) + 1
            contact_share_sum(j) = contact_share_sum(j) + real(n_contact(j), wp) / real(n, wp)
            if (wh(j) > 0.0_wp) n_wet(j) = n_wet(j) + 1
            if (series) then
               mu_inst(t+1, j) = mu_j
               hydro_load(t+1, j) = wh(j)
               penetration(t+1, j) = cmin(j) + x(j)
               contact(t+1, j) = n_contact(j)
            end if
         end do
      end subroutine accumulate

      !> Each lane's summary (Eq. 12 and the effects that ran).
      subroutine summarise()
         integer :: j
         do j = 1, nl
            out(j)%mu = mu_sum(j) / real(geo%n_avg, wp)                   ! Eq. 12
            out(j)%mu_hysteresis = hyst_sum(j) / real(geo%n_avg, wp)
            out(j)%mu_adhesion = adh_sum(j) / real(geo%n_avg, wp)
            if (energy) then
               ! mu is the dissipation: the rubber's and the local friction's
               ! (the mean of mu_inst, the facets' work, differs from it by the
               ! film's work round the profile over W and the distance)
               if (.not. geo%closed .and. geo%n_avg > 1) then
                  ! An open profile's first position has no step before it
                  ! (the pad lands there): its n_avg positions bound n_avg - 1
                  ! steps, and the work of those is over their distance (the
                  ! mean over n_avg read it (n_avg - 1) / n_avg of that: half
                  ! on a profile one sample longer than the pad)
                  out(j)%mu_hysteresis = hyst_sum(j) / real(geo%n_avg - 1, wp)
                  ! The steps' work holds the energy the elements store at
                  ! the stretch's ends and the load's work W (delta_end -
                  ! delta_start) (a closed profile's lap returns both): on a
                  ! stretch of the length of a few pads they were of the
                  ! order of a low-loss rubber's dissipation and of either
                  ! sign (a 100 mm segment: -6e-4 against 6e-5 closed). Where
                  ! the rubber says what it stores, its dissipation instead:
                  ! the elements' work, the descent's term added back, less
                  ! the stored energy's change, >= 0 step by step
                  if (open_known) out(j)%mu_hysteresis = (open_work(j) - kel_run(j) * &
                     & (stored_end(j) - stored_start(j))) / (m%load * geo%advance * &
                     & real(geo%n_avg - 1, wp))
                  ! an elastic rubber dissipates nothing (its work is the
                  ! stored energy's change, to rounding)
                  if (open_known .and. .not. rstep%memory(j)) out(j)%mu_hysteresis = 0.0_wp
               end if
               if (geo%closed .and. .not. rstep%memory(j)) then
                  ! An elastic rubber dissipates nothing: round a closed profile
                  ! its work returns exactly, and the sum of the steps' work
                  ! differs from 0 by rounding only (~1e-19).
                  out(j)%mu_hysteresis = 0.0_wp
               end if
               if (geo%closed .and. rstep%memory(j) .and. out(j)%mu_hysteresis < 0.0_wp &
                  & .and. out(j)%mu_hysteresis >= -rounding_share * hyst_abs_sum(j) &
                  & / real(geo%n_avg, wp)) then
                  ! Round a closed profile the rubber's part is the elements'
                  ! dissipation in contact (each step's >= 0, mean_push) plus
                  ! what they lose relaxing off the road (and, dry, the path
                  ! imbalance); the steps' work holds the stored energy too,
                  ! which returns, and what is left of it is rounding, below
                  ! zero only by that
                  out(j)%mu_hysteresis = 0.0_wp
               end if
               if (n_nocontact(j) == geo%n_avg .and. .not. contact_before(j)) then
                  ! nothing touched: no facet did any work, and what the film
                  ! did round the profile is not friction
                  out(j)%mu_hysteresis = 0.0_wp
               end if
               out(j)%mu = out(j)%mu_hysteresis + out(j)%mu_adhesion
            end if
            out(j)%hydroplaning_fraction = real(n_nocontact(j), wp) / real(geo%n_avg, wp)
            out(j)%wet_fraction = real(n_wet(j), wp) / real(geo%n_avg, wp)
            out(j)%max_balance_residual = resid_max(j)
            out(j)%mean_hydro_load = wh_sum(j) / real(geo%n_avg, wp)
            out(j)%contact_fraction = contact_share_sum(j) / real(geo%n_avg, wp)
            out(j)%mean_water_thickness = water_sum(j) / real(geo%n_avg, wp)
            out(j)%film_unsettled = n_unsettled(j)
            out(j)%film_root_jumps = n_jumps(j)
            out(j)%max_compression = u_max(j)
            out(j)%n_clamped = n_clamped(j)
            out(j)%bearing_evaluations = n_eval(j)
            if (rstep%memory(j)) out(j)%memory_updates = int(n, i8) * int(geo%n_avg + spin(j), i8)
            out(j)%spinup = spin(j)
            out(j)%viscous_memory_ran = rstep%memory(j)
            out(j)%bearing_ran = load_film(j)
            out(j)%friction_film_ran = friction_film(j)
            if (friction_film(j)) then
               if (force_sum(j) > 0.0_wp) out(j)%mean_local_friction = local_sum(j) / force_sum(j)
               out(j)%mean_film_thickness = film_mean_sum(j) / real(geo%n_avg, wp)
            else
               out(j)%mean_local_friction = m%mu_loc            ! no film: the full mu_loc
            end if
         end do
      end subroutine summarise

      !> The road sample an extended index stands for.
      pure integer function physical(kk)
         integer, intent(in) :: kk
         if (geo%closed) then
            physical = modulo(kk - 1, geo%npf) + 1
         else
            physical = min(kk, geo%npf)
         end if
      end function physical
   end subroutine slide

   !> The local friction's part of a facet's tangent, tan(theta) - tan(alpha)
   !> for a facet of slope s = tan(alpha), tangent t = tan(theta) (clamped
   !> when `clamped`) and local friction mu >= 0: unclamped, the addition
   !> formula's mu (1 + s^2) / (1 - s mu), exactly 0 for mu = 0 and never
   !> negative; clamped, t less the slope clamped at the same angle (>= 0: the
   !> clamp is monotone).
   elemental real(wp) function adhesion_tangent(s, t, clamped, mu, tan_max) result(a)
      real(wp), intent(in) :: s, t, mu, tan_max
      logical, intent(in) :: clamped
      if (.not. mu > 0.0_wp) then
         a = 0.0_wp
      else if (clamped) then
         a = max(0.0_wp, t - max(-tan_max, min(tan_max, s)))
      else
         a = mu * (1.0_wp + s * s) / (1.0_wp - s * mu)
      end if
   end function adhesion_tangent

   !> Spin-up steps of lane j on a closed profile: at least the pad's length
   !> (geo%n_spin), and as many more (at most a lap) as the rubber's memory
   !> needs before the state it started from (relaxed) stops changing from
   !> one lap to the next. A mode decaying by e a step, of weight w, leaves
   !> e^S of the start after S steps, which changes over a lap of L steps by
   !> e^S (1 - e^L); as friction (the stored energy it moves, about half the
   !> load times the mean push, over W and the lap's length) that is
   !> c e^S, c = w (1 - e^L) u / (2 L advance), kept below 1e-6 for every
   !> mode, at most max_spin_laps laps (`short`: not met within them). The
   !> paper's rubber (memory gone within a step) and the shipped compound
   !> (its slow arms soft next to k_eff: at most 16 steps at -20 to 60 C)
   !> need no more than the pad's length; a soft viscous pad (K = 1e4 N m-3,
   !> C = 100) several laps.
   pure subroutine lap_spinup(rstep, j, geo, push_total, spin, short, repeats)
      type(rubber_step_type), intent(in) :: rstep
      integer, intent(in) :: j
      type(geometry_type), intent(in) :: geo
      !> W / (l dx k_eff): the elements' pushes add up to it.
      real(wp), intent(in) :: push_total
      integer, intent(out) :: spin
      logical, intent(out) :: short
      !> Whether, after the spin, every mode's c e^S, and the pad's creep's
      !> (rubber_step_type's creep_decay, weight creep_weight), is below 1e-9: the
      !> start no longer shows and the state repeats round the lap (the
      !> paper's rubber forgets within a step; not the shipped compound,
      !> whose slow arms keep its creep alive). 1e-9, not the spin-up's
      !> 1e-6: the mean of a pad still creeping on a flat road would then
      !> read its lift-off (docs/model.md, "Which the mean takes").
      logical, intent(out), optional :: repeats
      real(wp), parameter :: tol = 1.0e-6_wp, tol_repeats = 1.0e-9_wp
      real(wp) :: e, w, lap_len, coef, need
      integer :: lap, k
      logical :: gone
      spin = geo%n_spin
      short = .false.
      if (present(repeats)) repeats = .false.
      if (.not. allocated(rstep%mode_decay)) return
      lap = (geo%npf + geo%stride - 1) / geo%stride
      lap_len = real(lap, wp) * geo%advance
      do k = 1, size(rstep%mode_decay, 2)
         e = rstep%mode_decay(j, k)
         w = rstep%mode_weight(j, k)
         if (.not. (e > 0.0_wp .and. e < 1.0_wp .and. w > 0.0_wp)) cycle
         coef = lap_change(e, w)
         if (.not. coef > tol) cycle
         need = log(tol / coef) / log(e)
         if (need > real(max_spin_laps, wp) * real(lap, wp)) then
            spin = max(spin, max_spin_laps * lap)
            short = .true.
         else
            spin = max(spin, ceiling(need))
         end if
      end do
      ! (the pad's creep under its load is not spun out: its bound below
      ! lumps every retardation mode into the longest, and spun
      ! out it took the shipped compound at 40 C and 1 km/h from 23
      ! positions to 3,819; docs/numerics.md, "Known gaps")
      if (.not. present(repeats)) return
      ! Where bringing every mode and the creep below tol_repeats costs at
      ! most a quarter lap more, spin that far: the lane then repeats, and
      ! its mean is the dissipation, free of the path's imbalance (a stiff,
      ! viscous pad under a tiny load whose creep, weighed by its size, was
      ! just short of it read -8.1e-5 against the exact integrator's 6.2e-5)
      if (.not. short) then
         need = real(spin, wp)
         do k = 1, size(rstep%mode_decay, 2)
            ! (a mode that does not decay within a step changes nothing over
            ! a lap, as below)
            if (rstep%mode_decay(j, k) < 1.0_wp) &
               & call need_below(rstep%mode_decay(j, k), rstep%mode_weight(j, k), need)
         end do
         if (allocated(rstep%creep_decay)) &
            & call need_below(rstep%creep_decay(j), creep_weight(), need)
         if (need <= real(spin, wp) + 0.25_wp * real(lap, wp)) spin = max(spin, ceiling(need))
      end if
      gone = .not. short
      do k = 1, size(rstep%mode_decay, 2)
         e = rstep%mode_decay(j, k)
         w = rstep%mode_weight(j, k)
         ! (a mode that does not decay within a step to rounding changes
         ! nothing over a lap: a Maxwell arm that is a spring over the run;
         ! a Kelvin-Voigt element that never recovers creeps, below)
         if (.not. w > 0.0_wp .or. .not. e < 1.0_wp) cycle
         gone = gone .and. left_below(e, w)
      end do
      ! and the pad's creep under its load, weighed by its size against the
      ! instant compression (rubber_step_type's creep_weight): one that does
      ! not decay never repeats
      gone = gone .and. allocated(rstep%creep_decay)
      if (gone) gone = left_below(rstep%creep_decay(j), creep_weight())
      repeats = gone
   contains
      !> The creep's weight against the instant compression
      !> (rubber_step_type's creep_weight; 1 for a rubber that gives none).
      pure real(wp) function creep_weight()
         creep_weight = 1.0_wp
         if (allocated(rstep%creep_weight)) creep_weight = rstep%creep_weight(j)
      end function creep_weight

      !> c = w (1 - e^L) u / (2 L advance): what a mode of weight w decaying
      !> by e a step changes over a lap, as friction, per unit of its start.
      pure real(wp) function lap_change(e, w)
         real(wp), intent(in) :: e, w
         lap_change = w * (-expm1_(real(lap, wp) * log(e))) * &
            & (push_total / real(geo%n_el, wp)) / (2.0_wp * lap_len)
      end function lap_change

      !> Whether a mode (decay e a step, weight w > 0) leaves c e^S below
      !> tol_repeats after the spin, as logarithms (e^S underflows long
      !> before it matters): one gone within a step (e = 0) does; one that
      !> does not decay (e >= 1) never does.
      pure logical function left_below(e, w)
         real(wp), intent(in) :: e, w
         real(wp) :: c
         left_below = .not. e > 0.0_wp
         if (left_below .or. .not. e < 1.0_wp) return
         c = lap_change(e, w)
         left_below = .not. c > 0.0_wp
         if (.not. left_below) left_below = log(c) + real(spin, wp) * log(e) <= log(tol_repeats)
      end function left_below

      !> The spin after which a mode (decay e a step, weight w) leaves c e^S
      !> below tol_repeats, into `need` where larger (huge where it never
      !> does; nothing for one without weight or gone within a step).
      pure subroutine need_below(e, w, need)
         real(wp), intent(in) :: e, w
         real(wp), intent(inout) :: need
         real(wp) :: c
         if (.not. (w > 0.0_wp .and. e > 0.0_wp)) return
         if (.not. e < 1.0_wp) then
            need = huge(1.0_wp)
            return
         end if
         c = lap_change(e, w)
         if (.not. c > tol_repeats) return
         need = max(need, log(tol_repeats / c) / log(e))
      end subroutine need_below

      !> exp(x) - 1 without cancellation near 0.
      pure real(wp) function expm1_(x)
         real(wp), intent(in) :: x
         if (abs(x) < 1.0e-5_wp) then
            expm1_ = x + 0.5_wp * x * x
         else
            expm1_ = exp(x) - 1.0_wp
         end if
      end function expm1_
   end subroutine lap_spinup

   !> sum_i push_i mu_eff_i at one position (mu_eff = mu_loc times the share).
   pure real(wp) function local_partial(push, share, mu_loc)
      real(wp), intent(in) :: push(:), share(:), mu_loc
      integer :: i
      local_partial = 0.0_wp
      do i = 1, size(push)
         local_partial = local_partial + push(i) * merge(mu_loc, mu_loc * share(i), &
            & share(i) >= 1.0_wp)
      end do
   end function local_partial

   !> The effects that ran, comma-separated: what the output's `effects`
   !> attribute says.
   pure function effects_text(res) result(text)
      type(sim_result_type), intent(in) :: res
      character(len=effects_text_len(res)) :: text
      character(len=:), allocatable :: deferred_text
      call effects_text_text(res, deferred_text)
      text = deferred_text
   end function effects_text

   !> The length of effects_text's text.
   pure integer function effects_text_len(res)
      type(sim_result_type), intent(in) :: res
      character(len=:), allocatable :: deferred_text
      call effects_text_text(res, deferred_text)
      effects_text_len = len(deferred_text)
   end function effects_text_len

   !> The text of effects_text, into a deferred-length argument.
   pure subroutine effects_text_text(res, text)
      type(sim_result_type), intent(in) :: res
      character(len=:), allocatable, intent(out) :: text
      text = res%effects
   end subroutine effects_text_text

   !> Per lane and element: c = h - z + u_free, the penetration at which the
   !> element starts to push (Eqs. 4, 8), its minimum over the pad, and d = c -
   !> cmin. The lane loops innermost on explicit run-time shapes compile to
   !> vector loops (measured: inside the driver they did not).
   pure subroutine lane_gaps(nl, n, z, h, u_free, c, cmin, d)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: z(:), h(n), u_free(nl, n)
      real(wp), intent(out) :: c(nl, n), cmin(nl), d(nl, n)
      integer :: i, j
      real(wp) :: low
      if (nl == 1) then
         ! one lane: plain loops (a lane loop of one trip costs more than the work)
         low = huge(1.0_wp)
         do i = 1, n
            c(1, i) = h(i) - z(i) + u_free(1, i)
            low = min(low, c(1, i))
         end do
         cmin(1) = low
         do i = 1, n
            d(1, i) = c(1, i) - low
         end do
         return
      end if
      cmin = huge(1.0_wp)
      do i = 1, n
         do j = 1, nl
            c(j, i) = h(i) - z(i) + u_free(j, i)
            cmin(j) = min(cmin(j), c(j, i))
         end do
      end do
      do i = 1, n
         do j = 1, nl
            d(j, i) = c(j, i) - cmin(j)
         end do
      end do
   end subroutine lane_gaps

   !> The dry Kelvin-Voigt pad's pass before its balance, once over the pad:
   !> the free compression u_free = b u (kv_free), the clearances c_i = h_i -
   !> z_i + u_free_i (not shifted by their least value cmin, which would take
   !> a second pass: the balance and the step take d = c - cmin as they go),
   !> cmin, and the dry balance's first pass at the guess g (dry_start_type's;
   !> dry_roots_of_c goes on from there).
   pure subroutine lane_free_gaps_from(nl, n, relax, state, z, h, u_free, c, cmin, start)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: relax(nl), state(nl, n), z(:), h(n)
      real(wp), intent(out) :: u_free(nl, n), c(nl, n), cmin(nl)
      type(dry_start_type), intent(inout) :: start
      integer :: i, j
      if (nl == 1) then
         ! one lane: lane_gaps_from's plain loops
         do i = 1, n
            u_free(1, i) = relax(1) * state(1, i)
         end do
         call lane_gaps_from(nl, n, z, h, u_free, c, cmin, start)
         return
      end if
      associate (g => start%guess, sums => start%sums, counts => start%counts, &
            & below => start%below, above => start%above)
         cmin = huge(1.0_wp)
         sums = 0.0_wp
         counts = 0.0_wp
         below = -huge(1.0_wp)
         above = huge(1.0_wp)
         do i = 1, n
            !GCC$ ivdep
            do j = 1, nl
               u_free(j, i) = relax(j) * state(j, i)
               c(j, i) = h(i) - z(i) + u_free(j, i)
               cmin(j) = min(cmin(j), c(j, i))
               sums(j) = sums(j) + merge(c(j, i) - g(j), 0.0_wp, c(j, i) < g(j))
               counts(j) = counts(j) + merge(1.0_wp, 0.0_wp, c(j, i) < g(j))
               below(j) = max(below(j), merge(c(j, i), -huge(1.0_wp), c(j, i) < g(j)))
               above(j) = min(above(j), merge(huge(1.0_wp), c(j, i), c(j, i) < g(j)))
            end do
         end do
      end associate
   end subroutine lane_free_gaps_from

   !> lane_gaps without the shift, and the dry balance's first pass at the
   !> guess in the same pass (lane_free_gaps_from's, for any rubber's u_free):
   !> c_i = h_i - z_i + u_free_i (lane_gaps' c, the same operations), its
   !> least value cmin, and the first pass at the guess (dry_start_type's).
   pure subroutine lane_gaps_from(nl, n, z, h, u_free, c, cmin, start)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: z(:), h(n), u_free(nl, n)
      real(wp), intent(out) :: c(nl, n), cmin(nl)
      type(dry_start_type), intent(inout) :: start
      integer :: i, j
      real(wp) :: low, total, counted, ci, lo, hi, gg
      associate (g => start%guess, sums => start%sums, counts => start%counts, &
            & below => start%below, above => start%above)
         if (nl == 1) then
            ! one lane: plain loops (a lane loop of one trip costs more than the work)
            ! (the sums and bounds in locals: in the start's components
            ! each element's update waited on a store and a load)
            low = huge(1.0_wp)
            total = 0.0_wp
            counted = 0.0_wp
            lo = -huge(1.0_wp)
            hi = huge(1.0_wp)
            gg = g(1)
            do i = 1, n
               ci = h(i) - z(i) + u_free(1, i)
               c(1, i) = ci
               low = min(low, ci)
               total = total + merge(ci - gg, 0.0_wp, ci < gg)
               counted = counted + merge(1.0_wp, 0.0_wp, ci < gg)
               lo = max(lo, merge(ci, -huge(1.0_wp), ci < gg))
               hi = min(hi, merge(huge(1.0_wp), ci, ci < gg))
            end do
            below(1) = lo
            above(1) = hi
            cmin(1) = low
            sums(1) = total
            counts(1) = counted
            return
         end if
         cmin = huge(1.0_wp)
         sums = 0.0_wp
         counts = 0.0_wp
         below = -huge(1.0_wp)
         above = huge(1.0_wp)
         do i = 1, n
            !GCC$ ivdep
            do j = 1, nl
               c(j, i) = h(i) - z(i) + u_free(j, i)
               cmin(j) = min(cmin(j), c(j, i))
               sums(j) = sums(j) + merge(c(j, i) - g(j), 0.0_wp, c(j, i) < g(j))
               counts(j) = counts(j) + merge(1.0_wp, 0.0_wp, c(j, i) < g(j))
               below(j) = max(below(j), merge(c(j, i), -huge(1.0_wp), c(j, i) < g(j)))
               above(j) = min(above(j), merge(huge(1.0_wp), c(j, i), c(j, i) < g(j)))
            end do
         end do
      end associate
   end subroutine lane_gaps_from

   !> lane_gaps for the Kelvin-Voigt pad, with its free compression (kv_free:
   !> u_free = b u, b the lane's relaxation over a step) in the same pass:
   !> the same operations as the two, in one loop.
   pure subroutine lane_free_gaps(nl, n, relax, state, z, h, u_free, cmin, d)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: relax(nl), state(nl, n), z(:), h(n)
      real(wp), intent(out) :: u_free(nl, n), cmin(nl), d(nl, n)
      integer :: i, j
      ! c_i (lane_gaps' c) into d, then shifted by its least value in place
      cmin = huge(1.0_wp)
      do i = 1, n
         !GCC$ ivdep
         do j = 1, nl
            u_free(j, i) = relax(j) * state(j, i)
            d(j, i) = h(i) - z(i) + u_free(j, i)
            cmin(j) = min(cmin(j), d(j, i))
         end do
      end do
      do i = 1, n
         !GCC$ ivdep
         do j = 1, nl
            d(j, i) = d(j, i) - cmin(j)
         end do
      end do
   end subroutine lane_free_gaps

   !> For the Kelvin-Voigt pad (the energy scheme; a friction film's facets
   !> are taken after it), the step after the balance in one pass: lane_contacts' pushes
   !> and sums, lane_work_linear's work and mean force (push_prev then the
   !> step's), and kv_update's state u = u_free + push; each value by the
   !> same operations as theirs, in the same order (a copy of their bodies:
   !> change them together, or the fused and general paths part by
   !> rounding). The step's starting compression u_prev is the state
   !> itself (both are u after every step; the first step's work, whatever
   !> they hold, is discarded), and lane_contacts' sum of the pushes
   !> weighted by the facet tangents is not taken: the energy scheme, the
   !> only one fused, does not use it.
   pure subroutine lane_step_kv(nl, n, x, d, dref, u_free, clamped, adhesion, weights, &
         & ddelta, push_prev, state, sum_f, contacts, clamps, u_max, sum_fa, w, total)
      integer, intent(in) :: nl, n
      !> d - dref: the clearances shifted by their least value (dref that
      !> value where d is unshifted, lane_free_gaps_from's, else 0).
      real(wp), intent(in) :: x(nl), d(nl, n), dref(nl), u_free(nl, n), clamped(:), &
         & adhesion(:), weights(nl, 3), ddelta(nl)
      !> In: the previous step's pushes and compressions; out: this step's
      !> (push_prev then holds the pushes max(0, x - d) of this step).
      real(wp), intent(inout) :: push_prev(nl, n), state(nl, n)
      real(wp), intent(out) :: sum_f(nl), contacts(nl), clamps(nl), &
         & sum_fa(nl), w(nl), total(nl)
      real(wp), intent(inout) :: u_max(nl)
      real(wp) :: p, in_contact, u, f, u_prev, s
      real(wp) :: a_f, a_c, a_fa, a_u, a_w, a_t, a_k, xd, w1, w2, w3, dd
      integer :: i, j
      if (nl == 1) then
         ! one lane (a single speed): the same operations in the same order,
         ! its sums in registers (through the arrays of nl, each element's
         ! six additions waited on a store and a load), and lane_clamps' count
         ! in the same pass (its sum over the clamped elements in their
         ! order; the others add an exact 0)
         a_k = 0.0_wp
         a_f = 0.0_wp
         a_c = 0.0_wp
         a_fa = 0.0_wp
         a_w = 0.0_wp
         a_t = 0.0_wp
         a_u = u_max(1)
         xd = x(1)
         w1 = weights(1, 1)
         w2 = weights(1, 2)
         w3 = weights(1, 3)
         dd = ddelta(1)
         do i = 1, n
            p = max(0.0_wp, xd - (d(1, i) - dref(1)))
            in_contact = merge(1.0_wp, 0.0_wp, p > 0.0_wp)
            a_f = a_f + p
            a_c = a_c + in_contact
            a_fa = a_fa + p * adhesion(i)
            a_u = max(a_u, u_free(1, i) + p)
            u = u_free(1, i) + p
            u_prev = state(1, i)
            s = push_prev(1, i) + p
            f = merge(1.0_wp, 0.0_wp, s > 0.0_wp) * &
               & (w1 * u_prev + w2 * u - w3 * max(0.0_wp, (u_prev - u_free(1, i)) - s))
            a_w = a_w + f * ((u - u_prev) - dd)
            a_t = a_t + f
            a_k = a_k + in_contact * clamped(i)
            push_prev(1, i) = p
            state(1, i) = u
         end do
         clamps(1) = a_k
         sum_f(1) = a_f
         contacts(1) = a_c
         sum_fa(1) = a_fa
         u_max(1) = a_u
         w(1) = a_w
         total(1) = a_t
         return
      end if
      sum_f = 0.0_wp
      contacts = 0.0_wp
      sum_fa = 0.0_wp
      w = 0.0_wp
      total = 0.0_wp
      do i = 1, n
         !GCC$ ivdep
         do j = 1, nl
            p = max(0.0_wp, x(j) - (d(j, i) - dref(j)))
            in_contact = merge(1.0_wp, 0.0_wp, p > 0.0_wp)
            sum_f(j) = sum_f(j) + p
            contacts(j) = contacts(j) + in_contact
            sum_fa(j) = sum_fa(j) + p * adhesion(i)
            u_max(j) = max(u_max(j), u_free(j, i) + p)
            u = u_free(j, i) + p
            u_prev = state(j, i)
            s = push_prev(j, i) + p
            f = merge(1.0_wp, 0.0_wp, s > 0.0_wp) * &
               & (weights(j, 1) * u_prev + weights(j, 2) * u - &
               & weights(j, 3) * max(0.0_wp, (u_prev - u_free(j, i)) - s))
            w(j) = w(j) + f * ((u - u_prev) - ddelta(j))
            total(j) = total(j) + f
            push_prev(j, i) = p
            state(j, i) = u
         end do
      end do
      call lane_clamps(nl, n, push_prev, clamped, clamps)
   end subroutine lane_step_kv

   !> The next value of a sequence from its last two, linearly; the last
   !> alone where there is none before it (-huge): the balances' warm starts.
   elemental real(wp) function extrapolated(last, before)
      real(wp), intent(in) :: last, before
      extrapolated = last
      if (before > -huge(1.0_wp)) extrapolated = 2.0_wp * last - before
   end function extrapolated

   !> Per lane, the contacts on clamped facets: a pass over the few elements
   !> on one (clamped(i) /= 0), not a sum over every element and lane.
   pure subroutine lane_clamps(nl, n, push, clamped, clamps)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: push(nl, n), clamped(:)
      real(wp), intent(out) :: clamps(nl)
      integer :: i, j
      clamps = 0.0_wp
      do i = 1, n
         if (clamped(i) == 0.0_wp) cycle
         do j = 1, nl
            clamps(j) = clamps(j) + merge(1.0_wp, 0.0_wp, push(j, i) > 0.0_wp) * clamped(i)
         end do
      end do
   end subroutine lane_clamps

   !> Per lane at penetration x: each element's push max(0, x - d) (its
   !> compression beyond u_free), their sum, the contacts, the sum weighted
   !> by the facet tangents (Eq. 10), the contacts on clamped facets and the
   !> largest compression max(g_i, u_free_i). Counts in reals (exact): one
   !> type in the vector loop.
   pure subroutine lane_contacts(nl, n, x, d, dref, u_free, tan_t, clamped, adhesion, push, &
      & sum_f, contacts, sum_ft, clamps, u_max, sum_fa)
      integer, intent(in) :: nl, n
      !> d - dref: the clearances shifted by their least value (lane_step_kv's).
      real(wp), intent(in) :: x(nl), d(nl, n), dref(nl), u_free(nl, n), tan_t(:), clamped(:), &
         & adhesion(:)
      real(wp), intent(out) :: push(nl, n), sum_f(nl), contacts(nl), sum_ft(nl), clamps(nl)
      real(wp), intent(inout) :: u_max(nl)
      !> sum of push x (tan(theta) - tan(alpha)): the local friction's part
      real(wp), intent(out) :: sum_fa(nl)
      real(wp) :: p, in_contact, sf, sft, nc, ncl, um, sfa
      integer :: i, j
      if (nl == 1) then
         ! one lane: plain loops, the same operations in the same order
         sf = 0.0_wp
         sft = 0.0_wp
         sfa = 0.0_wp
         nc = 0.0_wp
         ncl = 0.0_wp
         um = u_max(1)
         do i = 1, n
            p = max(0.0_wp, x(1) - (d(1, i) - dref(1)))
            push(1, i) = p
            in_contact = merge(1.0_wp, 0.0_wp, p > 0.0_wp)
            sf = sf + p
            nc = nc + in_contact
            sft = sft + p * tan_t(i)
            sfa = sfa + p * adhesion(i)
            ncl = ncl + in_contact * clamped(i)
            um = max(um, u_free(1, i) + p)
         end do
         sum_f(1) = sf
         contacts(1) = nc
         sum_ft(1) = sft
         sum_fa(1) = sfa
         clamps(1) = ncl
         u_max(1) = um
         return
      end if
      sum_f = 0.0_wp
      contacts = 0.0_wp
      sum_ft = 0.0_wp
      sum_fa = 0.0_wp
      do i = 1, n
         do j = 1, nl
            p = max(0.0_wp, x(j) - (d(j, i) - dref(j)))
            push(j, i) = p
            in_contact = merge(1.0_wp, 0.0_wp, p > 0.0_wp)
            sum_f(j) = sum_f(j) + p
            contacts(j) = contacts(j) + in_contact
            sum_ft(j) = sum_ft(j) + p * tan_t(i)
            sum_fa(j) = sum_fa(j) + p * adhesion(i)
            u_max(j) = max(u_max(j), u_free(j, i) + p)
         end do
      end do
      call lane_clamps(nl, n, push, clamped, clamps)
   end subroutine lane_contacts

   !> Per lane: the work of one step on the elements, in units of kel (the
   !> element force per unit push), less the work of the pad's own descent:
   !> sum_i (push_i' + push_i) / 2 x ((u_i - u_i') - (delta - delta')), primes
   !> the previous step (trapezoidal in time: exact for an elastic element,
   !> whose work is then the change of its stored energy K u^2 / 2; for an
   !> element in contact at both steps (u - u') - (delta - delta') is the
   !> rise of the road under it). This is the facets' work: the rubber's
   !> stored energy change plus its dissipation, whatever the rubber model,
   !> and its sum over a closed profile is the rubber's dissipation
   !> (docs/model.md, "Energy").
   !> The step's compressions and pushes then replace the previous ones (one
   !> pass for both).
   pure subroutine lane_work(nl, n, u_free, push, u_prev, push_prev, ddelta, w)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: u_free(nl, n), push(nl, n)
      real(wp), intent(inout) :: u_prev(nl, n), push_prev(nl, n)
      real(wp), intent(in) :: ddelta(nl)
      real(wp), intent(out) :: w(nl)
      integer :: i, j
      real(wp) :: u, acc, dd
      if (nl == 1) then
         ! one lane: a plain loop (a lane loop of one trip costs more)
         acc = 0.0_wp
         dd = ddelta(1)
         do i = 1, n
            u = u_free(1, i) + push(1, i)
            acc = acc + (push_prev(1, i) + push(1, i)) * ((u - u_prev(1, i)) - dd)
            u_prev(1, i) = u
            push_prev(1, i) = push(1, i)
         end do
         w(1) = 0.5_wp * acc
         return
      end if
      w = 0.0_wp
      do i = 1, n
         do j = 1, nl
            u = u_free(j, i) + push(j, i)
            w(j) = w(j) + (push_prev(j, i) + push(j, i)) * ((u - u_prev(j, i)) - ddelta(j))
            u_prev(j, i) = u
            push_prev(j, i) = push(j, i)
         end do
      end do
      w = 0.5_wp * w
   end subroutine lane_work

   !> lane_work with each element's mean push over the step given (the
   !> rubber's mean_push): sum_i mean_i x ((u_i - u_i') - (delta - delta')),
   !> and each lane's sum of the means (total). An element off the road at
   !> both ends of the step (no push at either) touches no facet: it does
   !> no work, whatever its path's mean (it relaxes on its own, and what it
   !> stored is dissipated inside it).
   pure subroutine lane_work_mean(nl, n, u_free, push, mean, slope, u_prev, push_prev, ddelta, &
         & w, total)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: u_free(nl, n), push(nl, n), mean(nl, n)
      !> The mean's slope against the push (rubber_step_type%push_slope).
      real(wp), intent(in) :: slope(nl)
      real(wp), intent(inout) :: u_prev(nl, n), push_prev(nl, n)
      real(wp), intent(in) :: ddelta(nl)
      real(wp), intent(out) :: w(nl), total(nl)
      integer :: i, j
      real(wp) :: u, f, s, change, ramp
      w = 0.0_wp
      total = 0.0_wp
      do i = 1, n
         do j = 1, nl
            u = u_free(j, i) + push(j, i)
            s = push_prev(j, i) + push(j, i)
            ! the contact ramp (lane_work_linear's): the free path's mean
            ! (where >= 0) times max(0, 1 - s / its change)
            change = u_prev(j, i) - u_free(j, i)
            ramp = max(0.0_wp, mean(j, i) - slope(j) * push(j, i)) * &
               & (max(0.0_wp, change - s) / max(change, tiny(1.0_wp)))
            f = merge(1.0_wp, 0.0_wp, s > 0.0_wp) * (mean(j, i) - ramp)
            w(j) = w(j) + f * ((u - u_prev(j, i)) - ddelta(j))
            total(j) = total(j) + f
            u_prev(j, i) = u
            push_prev(j, i) = push(j, i)
         end do
      end do
   end subroutine lane_work_mean

   !> lane_work_mean with each element's mean push c0 u' + c1 u formed here
   !> from the lane's weights (the rubber's mean_weights; u' = u_prev, the
   !> step's start), in the same pass, less the contact ramp
   !> c2 max(0, (u' - u_free) - s), s = push' + push: the free path's own
   !> mean c2 (u' - u_free) where the element barely touches, falling to 0
   !> as its pushes reach the free path's change. The force then goes to 0
   !> with the pushes (continuous where a contact starts or ends), and
   !> where the ramp is not 0 the step's u - u' is negative, so it only adds
   !> to the dissipation (docs/model.md, "The step's force where a contact
   !> starts or ends").
   pure subroutine lane_work_linear(nl, n, u_free, push, weights, u_prev, push_prev, ddelta, &
         & w, total)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: u_free(nl, n), push(nl, n), weights(nl, 3)
      real(wp), intent(inout) :: u_prev(nl, n), push_prev(nl, n)
      real(wp), intent(in) :: ddelta(nl)
      real(wp), intent(out) :: w(nl), total(nl)
      integer :: i, j
      real(wp) :: u, f, s
      w = 0.0_wp
      total = 0.0_wp
      do i = 1, n
         do j = 1, nl
            u = u_free(j, i) + push(j, i)
            s = push_prev(j, i) + push(j, i)
            ! (a 0/1 factor, not a branch: the loop stays a vector loop)
            f = merge(1.0_wp, 0.0_wp, s > 0.0_wp) * &
               & (weights(j, 1) * u_prev(j, i) + weights(j, 2) * u - &
               & weights(j, 3) * max(0.0_wp, (u_prev(j, i) - u_free(j, i)) - s))
            w(j) = w(j) + f * ((u - u_prev(j, i)) - ddelta(j))
            total(j) = total(j) + f
            u_prev(j, i) = u
            push_prev(j, i) = push(j, i)
         end do
      end do
   end subroutine lane_work_linear

   !> The step's compressions and pushes, for the next step's lane_work.
   pure subroutine lane_remember(nl, n, u_free, push, u_prev, push_prev)
      integer, intent(in) :: nl, n
      real(wp), intent(in) :: u_free(nl, n), push(nl, n)
      real(wp), intent(out) :: u_prev(nl, n), push_prev(nl, n)
      integer :: i, j
      do i = 1, n
         do j = 1, nl
            u_prev(j, i) = u_free(j, i) + push(j, i)
            push_prev(j, i) = push(j, i)
         end do
      end do
   end subroutine lane_remember

   !> Whether the scene's &numerics time_scheme is `name`.
   pure logical function scheme_is(m, name)
      type(model_type), intent(in) :: m
      character(len=*), intent(in) :: name
      scheme_is = .false.
      if (allocated(m%time_scheme)) scheme_is = m%time_scheme == name
   end function scheme_is

   !> Whether the scene runs the exact Kelvin-Voigt integrator where it
   !> applies: it asks for it ('exact'), or leaves the choice to the code
   !> ('auto') on a scene it can serve: the Kelvin-Voigt rubber
   !> on a dry road or under the paper's film (wet_model = 'kane2017'),
   !> every position, the energy scheme (elsewhere backward Euler, as
   !> 'extrapolated').
   pure logical function exact_scheme(m)
      type(model_type), intent(in) :: m
      logical :: film_served
      exact_scheme = .false.
      if (.not. allocated(m%time_scheme)) return
      select case (m%time_scheme)
      case ("exact")
         exact_scheme = .true.
      case ("auto")
         film_served = m%depth <= 0.0_wp
         if (allocated(m%wet_model)) film_served = film_served .or. m%wet_model == "kane2017"
         exact_scheme = film_served .and. m%position_stride == 1
         if (allocated(m%rubber_model)) exact_scheme = exact_scheme .and. &
            & m%rubber_model == "kelvin_voigt"
         if (allocated(m%friction_scheme)) exact_scheme = exact_scheme .and. &
            & m%friction_scheme /= "paper"
      end select
   end function exact_scheme

   !> One speed of a Kelvin-Voigt pad on a road without a film, integrated
   !> exactly in time (pavefric_kv_exact); the summary and series as slide's.
   subroutine slide_exact(geo, m, rubber, v, out, mu_inst, hydro_load, penetration, &
         & contact, film_thickness, local_friction, bearing, depth)
      type(geometry_type), intent(in) :: geo
      type(model_type), intent(in) :: m
      type(kelvin_voigt_rubber), intent(in) :: rubber
      real(wp), intent(in) :: v
      type(speed_summary_type), intent(inout) :: out
      real(wp), intent(out), optional :: mu_inst(:,:), hydro_load(:,:), penetration(:,:)
      integer, intent(out), optional :: contact(:,:)
      real(wp), intent(out), optional :: film_thickness(:,:), local_friction(:,:)
      !> The pseudo-bearing's prefactor (Eq. 15) and the water depth, under a
      !> film (both given)
      real(wp), intent(in), optional :: bearing, depth
      type(kv_exact_type) :: r
      type(rubber_step_type) :: decay
      real(wp) :: k, tau, dt, k_land
      integer :: spin
      logical :: short
      k = m%width * geo%dx_el * rubber%stiffness
      tau = rubber%viscosity / rubber%stiffness
      dt = geo%advance / v
      ! the landing: backward Euler over one element length of travel, as
      ! slide's (kv_prepare's K + C V / advance at advance = dx_el)
      k_land = m%width * geo%dx_el * (rubber%stiffness + rubber%viscosity * v / geo%dx_el)
      ! a closed profile spins up until the relaxed start no longer shows
      ! (the memory decays by exp(-dt / tau) a step)
      spin = geo%n_spin
      short = .false.
      if (geo%closed) then
         allocate(decay%mode_decay(1, 1), decay%mode_weight(1, 1))
         decay%mode_decay = exp(-dt / tau)
         decay%mode_weight = 1.0_wp
         call lap_spinup(decay, 1, geo, m%load / k, spin, short)
      end if
      if (present(mu_inst)) then
         call kv_exact_lane(geo%z, geo%h, geo%adhesion, geo%clamped_at, geo%n_el, geo%spacing, &
            & geo%npf, geo%closed, geo%n_avg, spin, k, tau, dt, geo%advance, m%load, k_land, r, &
            & mu_inst(:, 1), penetration(:, 1), contact(:, 1), bearing, depth, hydro_load(:, 1))
         if (present(film_thickness)) then
            film_thickness(:, 1) = 0.0_wp
            local_friction(:, 1) = merge(m%mu_loc, 0.0_wp, contact(:, 1) > 0)
         end if
      else
         call kv_exact_lane(geo%z, geo%h, geo%adhesion, geo%clamped_at, geo%n_el, geo%spacing, &
            & geo%npf, geo%closed, geo%n_avg, spin, k, tau, dt, geo%advance, m%load, k_land, r, &
            & bearing=bearing, depth=depth)
      end if
      if (r%status == 2) then
         out%failed = 1
         return
      end if
      if (r%status == 1 .or. r%status == 3) then
         out%failed = stat_internal
         out%exact_bad_position = r%bad_position
         return
      end if
      if (present(bearing) .and. geo%closed .and. r%mu_hysteresis < -1.0e-9_wp) then
         ! under the film, round a closed profile: a rubber that dissipates
         ! less than nothing is a linearised film that settled on a state
         ! the road does not repeat (a heavy pad the film carries nearly
         ! alone, where its load has two balances: docs/numerics.md); the
         ! speed is declined, as above
         out%failed = stat_internal
         return
      end if
      out%mu_hysteresis = r%mu_hysteresis
      out%mu_adhesion = r%mu_adhesion
      out%mu = r%mu_hysteresis + r%mu_adhesion
      out%hydroplaning_fraction = real(r%n_nocontact, wp) / real(max(geo%n_avg, 1), wp)
      out%contact_fraction = r%contact_share_sum / real(max(geo%n_avg, 1), wp)
      out%wet_fraction = real(r%n_wet, wp) / real(max(geo%n_avg, 1), wp)
      out%max_balance_residual = r%max_balance_residual
      out%mean_hydro_load = r%hydro_sum / real(max(geo%n_avg, 1), wp)
      out%max_compression = r%max_compression
      out%n_clamped = r%n_clamped
      out%bearing_evaluations = r%film_evaluations
      out%memory_updates = int(geo%n_el, i8) * int(geo%n_avg + spin, i8)
      out%spinup = spin
      out%spin_short = short
      out%viscous_memory_ran = .true.
      out%bearing_ran = present(bearing)
      out%friction_film_ran = .false.
      out%mean_local_friction = m%mu_loc
      out%exact_ran = .true.
   end subroutine slide_exact

   !> The error of a refined profile that does not fit in memory.
   pure subroutine no_memory(n, fine, error)
      integer, intent(in) :: n, fine
      type(error_type), allocatable, intent(out) :: error
      call fatal_error(error, "not enough memory for a profile of " // to_str(n) // &
         & " points refined " // to_str(fine) // " times (&numerics elements_per_sample x " // &
         & "substeps); give smaller values, or a shorter profile", stat_memory)
   end subroutine no_memory

end module pavefric_simulate
