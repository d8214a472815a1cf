!> The simulation driver: the pad slides over the profile, position after
!> position, at each speed (paper Fig. 4). It works through the rubber and
!> film components (pavefric_rubber, pavefric_film) and never branches on
!> which ones it has. Speeds are independent, so they run in parallel under
!> OpenMP with results identical to a serial run.
module pavefric_simulate
   use, intrinsic :: iso_c_binding, only: c_long_long
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use pavefric_kinds, only: wp, i8, kmh_to_ms
   use pavefric_error, only: error_type, fatal_error, add_warning, stat_memory, stat_internal
   use pavefric_format, only: to_str
   use pavefric_model, only: model_type, validate_model, shape_code, shape_rounded
   use pavefric_profile, only: refine_profile, check_heights
   use pavefric_rubber, only: rubber_model, rubber_step_type, kelvin_voigt_rubber
   use pavefric_film, only: film_model, film_step_type, pseudo_bearing_film
   use pavefric_squeeze, only: squeeze_film
   use pavefric_facet, only: facet_friction, facet_tangent
   use pavefric_balance, only: dry_root, wet_root, wet_state_type, gap_field
   implicit none
   private

   public :: sim_result_type, simulate, pad_elements, averaged_positions, effects_text
   public :: make_components

   !> Largest height a profile may have (m): far beyond any texture, small
   !> enough that no difference of heights can overflow.
   real(wp), parameter :: max_height = 1.0e6_wp

   interface
      function c_physical_memory() bind(C, name="pavefric_physical_memory") result(bytes)
         import :: c_long_long
         integer(c_long_long) :: bytes
      end function c_physical_memory
   end interface

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
      !> Speeds (m s-1) and (km h-1).
      real(wp), allocatable :: speed(:), speed_kmh(:)
      !> Mean friction coefficient over the profile (Eq. 12).
      real(wp), allocatable :: mu(:)
      !> Share of averaged positions where no element touched.
      real(wp), allocatable :: hydroplaning_fraction(:)
      !> Share of averaged positions where the film carried load.
      real(wp), allocatable :: wet_fraction(:)
      !> Largest |sum F + Wh - W| / W over the averaged positions.
      real(wp), allocatable :: max_balance_residual(:)
      !> Mean load carried by the film (N).
      real(wp), allocatable :: mean_hydro_load(:)
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
      !> Whether a load-carrying film took part in the balance at this speed.
      logical, allocatable :: bearing_ran(:)
      !> Whether a friction-changing film ran at this speed.
      logical, allocatable :: friction_film_ran(:)
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
      !> The effects that ran, comma-separated (the output's `effects`).
      character(len=:), allocatable :: effects
      !> Warnings about suspicious results, one a line ('' = none).
      character(len=:), allocatable :: warnings
   end type sim_result_type

   !> One speed's averaged results (see sim_result_type for their meaning).
   type :: speed_summary_type
      real(wp) :: mu = 0, hydroplaning_fraction = 0, wet_fraction = 0
      real(wp) :: max_balance_residual = 0, mean_hydro_load = 0, max_compression = 0
      real(wp) :: mean_local_friction = 0, mean_film_thickness = 0
      integer(i8) :: n_clamped = 0, bearing_evaluations = 0, memory_updates = 0
      logical :: viscous_memory_ran = .false., bearing_ran = .false.
      logical :: friction_film_ran = .false.
      !> stat_memory when the speed's work arrays could not be allocated.
      integer :: failed = 0
   end type speed_summary_type

   !> Everything about the profile and pad that does not depend on speed.
   type :: geometry_type
      real(wp), allocatable :: z(:), tan_theta(:), h(:)
      !> Facet slopes tan(alpha), for films that change the local friction.
      real(wp), allocatable :: slope(:)
      logical, allocatable :: clamped(:)
      integer :: n_el = 0, spacing = 1, stride = 1, n_avg = 0, n_spin = 0, npf = 0
      logical :: closed = .true.
      !> Element width (m) and pad advance per step (m).
      real(wp) :: dx_el = 0.0_wp, advance = 0.0_wp
   end type geometry_type

contains

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

   !> The rubber and film components a model calls for: a film only with
   !> water (depth > 0), so a dry scene simulates no film at all.
   subroutine make_components(m, rubber, film)
      type(model_type), intent(in) :: m
      class(rubber_model), allocatable, intent(out) :: rubber
      class(film_model), allocatable, intent(out) :: film
      allocate(rubber, source=kelvin_voigt_rubber(stiffness=m%stiffness, viscosity=m%viscosity))
      if (.not. m%depth > 0.0_wp) return
      select case (m%wet_model)
      case ("squeeze")
         allocate(film, source=squeeze_film(depth=m%depth, eta=m%water_viscosity, &
            & sigma=m%microtexture_rms, width=m%width))
      case default
         allocate(film, source=pseudo_bearing_film(depth=m%depth, eta=m%water_viscosity, &
            & alpha=m%alpha, beta=m%beta, width=m%width, length=m%length))
      end select
   end subroutine make_components

   !> Run the friction model on heights `z` (m) at spacing `dx` (m) for each
   !> speed in `speeds_kmh`.
   subroutine simulate(m, z, dx, closed, speeds_kmh, want_series, res, error)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed, want_series
      type(sim_result_type), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      type(geometry_type) :: geo
      type(speed_summary_type) :: summary
      class(rubber_model), allocatable :: rubber
      class(film_model), allocatable :: film
      integer :: j, ns, stat
      logical :: friction_film

      res%warnings = ""
      res%effects = ""
      call validate_model(m, error)
      if (allocated(error)) return
      call check_inputs(m, z, dx, closed, speeds_kmh, error)
      if (allocated(error)) return
      call make_components(m, rubber, film)
      friction_film = .false.
      if (allocated(film)) friction_film = film%changes_friction()
      call check_memory(m, size(z), dx, closed, size(speeds_kmh), want_series, friction_film, &
         & error)
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
      allocate(res%mu(ns), res%hydroplaning_fraction(ns), res%wet_fraction(ns), &
         & res%max_balance_residual(ns), res%mean_hydro_load(ns), res%max_compression(ns), &
         & res%n_clamped(ns), res%bearing_evaluations(ns), res%memory_updates(ns), &
         & res%viscous_memory_ran(ns), res%bearing_ran(ns), res%friction_film_ran(ns), &
         & res%mean_local_friction(ns), res%mean_film_thickness(ns), stat=stat)
      if (stat == 0 .and. want_series) then
         allocate(res%mu_inst(geo%n_avg, ns), res%hydro_load(geo%n_avg, ns), &
            & res%penetration(geo%n_avg, ns), res%contact_elements(geo%n_avg, ns), &
            & res%position(geo%n_avg), stat=stat)
         if (stat == 0 .and. friction_film) allocate(res%film_thickness(geo%n_avg, ns), &
            & res%local_friction(geo%n_avg, ns), stat=stat)
         if (stat == 0) res%position = [(real(j, wp) * geo%advance, j = 0, geo%n_avg - 1)]
      end if
      if (stat /= 0) then
         call fatal_error(error, "not enough memory for the results of " // to_str(ns) // &
            & " speeds and " // to_str(geo%n_avg) // " positions", stat_memory)
         return
      end if

      ! Each speed is computed serially by one thread: the thread count cannot
      ! change a bit of the result.
      !$omp parallel do schedule(dynamic, 1) default(shared) private(j, summary)
      do j = 1, ns
         if (want_series) then
            if (friction_film) then
               call slide(geo, m, rubber, film, res%speed(j), summary, res%mu_inst(:, j), &
                  & res%hydro_load(:, j), res%penetration(:, j), res%contact_elements(:, j), &
                  & res%film_thickness(:, j), res%local_friction(:, j))
            else
               call slide(geo, m, rubber, film, res%speed(j), summary, res%mu_inst(:, j), &
                  & res%hydro_load(:, j), res%penetration(:, j), res%contact_elements(:, j))
            end if
         else
            call slide(geo, m, rubber, film, res%speed(j), summary)
         end if
         res%mu(j) = summary%mu
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
         res%memory_updates(j) = merge(-1_i8, res%memory_updates(j), summary%failed /= 0)
      end do
      !$omp end parallel do
      if (any(res%memory_updates < 0)) then
         call fatal_error(error, "not enough memory for the work arrays of a speed", stat_memory)
         return
      end if

      res%effects = "elastic_contact,facet_friction"
      if (any(res%viscous_memory_ran)) res%effects = res%effects // "," // rubber%memory_effect()
      if (allocated(film)) then
         if (any(res%bearing_ran) .or. any(res%friction_film_ran)) &
            & res%effects = res%effects // "," // film%effect()
      end if
      call check_results(res, error)
   end subroutine simulate

   !> Checks that need the profile and speeds as well as the parameters.
   subroutine check_inputs(m, z, dx, closed, speeds_kmh, error)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx, speeds_kmh(:)
      logical, intent(in) :: closed
      type(error_type), allocatable, intent(out) :: error
      integer :: j, n_el
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
            & " m: beyond +-" // to_str(max_height) // " m, not a texture (are the heights " // &
            & "in the unit declared?)")
         return
      end if
      n_el = pad_elements(m, dx)
      if (n_el < 1) then
         call fatal_error(error, "&pad length = " // to_str(m%length) // &
            & ": shorter than half a pad element (dx / elements_per_sample = " // &
            & to_str(dx / real(m%elements_per_sample, wp)) // " m)")
         return
      end if
      if (averaged_positions(m, size(z), dx, closed) < 1) then
         if (n_el >= huge(1) .or. real(size(z), wp) * real(m%elements_per_sample, wp) * &
               & real(m%substeps, wp) > 2.0e9_wp) then
            call fatal_error(error, "&numerics elements_per_sample = " // &
               & to_str(m%elements_per_sample) // " and substeps = " // to_str(m%substeps) // &
               & ": the refined profile of " // to_str(size(z)) // " points would have more " // &
               & "than 2e9 samples, or the pad more than 2e9 elements", stat_memory)
         else
            call fatal_error(error, "&surface profile_file: the profile has " // &
               & to_str(size(z)) // " points, fewer than the pad's " // to_str(n_el) // &
               & " elements (&pad length = " // to_str(m%length) // " m at dx = " // &
               & to_str(dx) // " m)")
         end if
         return
      end if
   end subroutine check_inputs

   !> Estimate the memory a run needs and refuse it, before allocating, when
   !> it exceeds what the machine has (a clear error instead of the process
   !> being killed).
   subroutine check_memory(m, np, dx, closed, ns, want_series, friction_film, error)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np, ns
      real(wp), intent(in) :: dx
      logical, intent(in) :: closed, want_series, friction_film
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: fine, n_ext, n_el, bytes, n_avg, limit
      fine = real(m%elements_per_sample, wp) * real(m%substeps, wp)
      n_el = real(pad_elements(m, dx), wp)
      n_ext = real(np, wp) * fine + n_el * real(m%substeps, wp)
      ! geometry: z, tan_theta, clamped (+ slopes), and the refinement's copies
      bytes = n_ext * (8.0_wp + 8.0_wp + 4.0_wp) * 2.0_wp
      if (friction_film) bytes = bytes + n_ext * 16.0_wp * real(min(ns, 64), wp)
      ! per speed (one per thread at most, counted for all): element arrays
      bytes = bytes + n_el * 8.0_wp * 10.0_wp * real(ns, wp)
      n_avg = real(averaged_positions(m, np, dx, closed), wp)
      if (want_series) bytes = bytes + n_avg * real(ns, wp) * 8.0_wp * 6.0_wp
      limit = real(c_physical_memory(), wp)
      if (limit <= 0.0_wp) limit = 16.0_wp * 2.0_wp**30
      if (bytes > 0.8_wp * limit) then
         call fatal_error(error, "the run needs about " // to_str(nint(bytes / 2.0_wp**20, i8)) // &
            & " MiB, more than this machine's memory (" // to_str(nint(limit / 2.0_wp**20, i8)) // &
            & " MiB): reduce &numerics elements_per_sample or substeps, the number of " // &
            & "speeds, or set &output series = .false.", stat_memory)
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
      real(wp), allocatable :: zf(:), tf(:), t_fine(:), sf(:)
      logical, allocatable :: cf(:), c_fine(:)
      real(wp) :: dxf, xc, r
      integer :: fine, n_ext, k, i, stat

      fine = m%elements_per_sample * m%substeps
      dxf = dx / real(fine, wp)
      if (fine > 1) then
         call refine_profile(z, closed, fine, zf)
      else
         zf = z
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
      allocate(tf(size(z)), cf(size(z)), sf(size(z)), stat=stat)
      if (stat /= 0) then
         call fatal_error(error, "not enough memory for the facets of " // to_str(size(z)) // &
            & " points", stat_memory)
         return
      end if
      call facet_friction(z, dx, closed, m%mu_loc, m%theta_max_deg, tf, cf, slopes=sf)
      if (fine > 1) then
         call refine_profile(tf, closed, fine, t_fine)
         call move_alloc(t_fine, tf)
         if (with_slopes) then
            call refine_profile(sf, closed, fine, t_fine)
            call move_alloc(t_fine, sf)
         end if
         allocate(c_fine(geo%npf))
         do k = 1, geo%npf
            c_fine(k) = cf(min(size(z), (k - 1 + fine / 2) / fine + 1))
            if (closed .and. (k - 1 + fine / 2) / fine + 1 > size(z)) c_fine(k) = cf(1)
         end do
         call move_alloc(c_fine, cf)
      end if
      if (closed) then
         n_ext = geo%npf + (geo%n_el - 1) * geo%spacing
         allocate(geo%z(n_ext), geo%tan_theta(n_ext), geo%clamped(n_ext), stat=stat)
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
            geo%clamped(k) = cf(i)
            if (with_slopes) geo%slope(k) = sf(i)
         end do
      else
         call move_alloc(zf, geo%z)
         call move_alloc(tf, geo%tan_theta)
         call move_alloc(cf, geo%clamped)
         if (with_slopes) call move_alloc(sf, geo%slope)
      end if

      ! Undeformed pad bottom h_i above the reference plane.
      allocate(geo%h(geo%n_el))
      geo%h = 0.0_wp
      if (shape_code(m%shape) == shape_rounded) then
         r = m%radius
         do i = 1, geo%n_el
            xc = (real(i, wp) - 0.5_wp - 0.5_wp * real(geo%n_el, wp)) * geo%dx_el
            if (r < 1.0e150_wp) then
               geo%h(i) = r - sqrt(r**2 - xc**2)
            else
               ! R**2 would overflow: the same sagitta without the square,
               ! x**2 / (R + sqrt(R - x) sqrt(R + x)) (a flat pad as R grows).
               geo%h(i) = xc**2 / (r + sqrt(r - xc) * sqrt(r + xc))
            end if
         end do
      end if
   end subroutine build_geometry

   !> One speed: spin-up, then the averaged positions (Eqs. 2-12).
   subroutine slide(geo, m, rubber, film, speed, out, mu_inst, hydro_load, penetration, contact, &
         & film_thickness, local_friction)
      type(geometry_type), intent(in) :: geo
      type(model_type), intent(in) :: m
      class(rubber_model), intent(in) :: rubber
      class(film_model), allocatable, intent(in) :: film
      real(wp), intent(in) :: speed
      type(speed_summary_type), intent(out) :: out
      real(wp), intent(out), optional :: mu_inst(:), hydro_load(:), penetration(:)
      integer, intent(out), optional :: contact(:)
      real(wp), intent(out), optional :: film_thickness(:), local_friction(:)

      type(rubber_step_type) :: rstep
      type(film_step_type) :: fstep
      type(wet_state_type) :: wet
      real(wp), allocatable :: c(:), d(:), state(:,:), u_free(:), work(:), push(:), gap(:)
      real(wp), allocatable :: fstate(:,:), pressure(:), share(:), tan_el(:)
      integer, allocatable :: samples(:)
      real(wp) :: kel, s_load, cmin, x, x_dry, x_guess, delta_prev, wh, sum_f, sum_ft, u_new
      real(wp) :: mu_sum, resid_max, wh_sum, u_max, mu_j, resid, tan_max, mu_eff, film_sum
      real(wp) :: local_sum, force_sum, film_mean_sum
      integer(i8) :: n_clamped, n_eval
      integer :: t, k1, k, i, n, n_contact, n_nocontact, n_wet, n_clamp_j, stat, q, lead, lead_prev
      logical :: load_film, friction_film, series, clamped

      n = geo%n_el
      series = present(mu_inst)
      call rubber%prepare(speed, geo%advance, rstep)
      kel = m%width * geo%dx_el * rstep%k_eff       ! Eq. 2: F = l dx p, p = K_eff (g - u_free)
      s_load = m%load / kel
      ! Simulate only the effects the scene calls for: a film needs water and
      ! motion (Sect. 3); the rubber's memory needs viscosity and motion.
      load_film = .false.
      friction_film = .false.
      if (allocated(film)) then
         call film%prepare(speed, geo%advance, fstep)
         load_film = fstep%active .and. film%carries_load()
         friction_film = fstep%active .and. film%changes_friction()
      end if

      allocate(c(n), d(n), work(n), push(n), u_free(n), gap(n), stat=stat)
      if (stat == 0 .and. rstep%memory) allocate(state(rubber%state_size(), n), stat=stat)
      if (stat == 0 .and. friction_film) allocate(fstate(film%state_size(), geo%npf), &
         & pressure(n), share(n), tan_el(n), samples(n * geo%spacing), stat=stat)
      if (stat /= 0) then
         out%failed = 1
         return
      end if
      u_free = 0.0_wp
      if (rstep%memory) state = 0.0_wp
      tan_max = tan(m%theta_max_deg * acos(-1.0_wp) / 180.0_wp)
      if (friction_film) call film%reset(fstep, fstate)

      delta_prev = -huge(1.0_wp)
      mu_sum = 0.0_wp
      wh_sum = 0.0_wp
      resid_max = 0.0_wp
      u_max = 0.0_wp
      local_sum = 0.0_wp
      force_sum = 0.0_wp
      film_mean_sum = 0.0_wp
      n_clamped = 0
      n_eval = 0
      n_nocontact = 0
      n_wet = 0
      lead_prev = -huge(1)
      do t = -geo%n_spin, geo%n_avg - 1
         if (geo%closed) then
            k1 = modulo(t * geo%stride + 1, geo%npf) + 1
         else
            k1 = t * geo%stride + 1
         end if
         ! c_i = h_i - z_k + u_free_i: the penetration at which element i
         ! starts to push (Eqs. 4, 8).
         if (rstep%memory) call rubber%free_compression(rstep, state, u_free)
         cmin = huge(1.0_wp)
         if (rstep%memory) then
            do i = 1, n
               c(i) = geo%h(i) - geo%z(k1 + (i-1) * geo%spacing) + u_free(i)
               cmin = min(cmin, c(i))
            end do
         else
            do i = 1, n
               c(i) = geo%h(i) - geo%z(k1 + (i-1) * geo%spacing)
               cmin = min(cmin, c(i))
            end do
         end if
         d = c - cmin
         ! warm start from the previous position's penetration
         x_guess = delta_prev - cmin
         call dry_root(d, s_load, x_guess, x_dry, work)
         x = x_dry
         wh = 0.0_wp
         if (load_film) then
            call gap_field(d, x_dry, gap)
            if (film%engages(fstep, gap)) then
               call wet_root(d, kel, m%load, film, fstep, x_dry, m%wet_tolerance, x, wet, gap)
               wh = wet%hydro_load
               n_eval = n_eval + wet%evaluations
            end if
         end if

         sum_f = 0.0_wp
         n_contact = 0
         do i = 1, n
            push(i) = max(0.0_wp, x - d(i))
            sum_f = sum_f + push(i)
            n_contact = n_contact + merge(1, 0, push(i) > 0.0_wp)
         end do

         n_clamp_j = 0
         sum_ft = 0.0_wp
         if (friction_film) then
            ! the film on the road samples entering under the leading edge
            ! (counted without wrapping round a closed profile)
            lead = t * geo%stride + n * geo%spacing + merge(1, 0, geo%closed)
            if (lead_prev == -huge(1)) lead_prev = lead
            do k = lead_prev + 1, lead
               call film%enter(fstep, fstate, physical(k))
            end do
            lead_prev = lead
            do i = 1, n
               pressure(i) = rstep%k_eff * push(i)
               do q = 1, geo%spacing
                  samples((i-1) * geo%spacing + q) = physical(k1 + (i-1) * geo%spacing + q - 1)
               end do
            end do
            call film%friction(fstep, fstate, samples, geo%spacing, pressure, geo%dx_el, share)
            film_sum = 0.0_wp
            do i = 1, n
               k = k1 + (i-1) * geo%spacing
               if (share(i) >= 1.0_wp) then
                  tan_el(i) = geo%tan_theta(k)
                  clamped = geo%clamped(k)
                  mu_eff = m%mu_loc
               else
                  mu_eff = m%mu_loc * share(i)
                  call facet_tangent(geo%slope(k), mu_eff, tan_max, tan_el(i), clamped)
               end if
               sum_ft = sum_ft + push(i) * tan_el(i)
               n_clamp_j = n_clamp_j + merge(1, 0, push(i) > 0.0_wp .and. clamped)
               local_sum = local_sum + merge(push(i) * mu_eff, 0.0_wp, t >= 0)
               film_sum = film_sum + film%thickness(fstate(:, samples((i-1) * geo%spacing + 1)))
            end do
            if (t >= 0) then
               force_sum = force_sum + sum_f
               film_mean_sum = film_mean_sum + film_sum / real(n, wp)
            end if
         else
            do i = 1, n
               k = k1 + (i-1) * geo%spacing
               sum_ft = sum_ft + push(i) * geo%tan_theta(k)        ! Eq. 10
               n_clamp_j = n_clamp_j + merge(1, 0, push(i) > 0.0_wp .and. geo%clamped(k))
            end do
         end if
         do i = 1, n
            u_new = u_free(i) + push(i)                          ! max(g_i, u_free_i)
            u_max = max(u_max, u_new)
         end do
         if (rstep%memory) call rubber%update(rstep, state, u_free, push)
         delta_prev = cmin + x
         if (t < 0) cycle                                    ! spin-up

         sum_f = kel * sum_f
         mu_j = kel * sum_ft / m%load                        ! Eq. 11: divided by W
         resid = abs(sum_f + wh - m%load) / m%load
         mu_sum = mu_sum + mu_j
         wh_sum = wh_sum + wh
         resid_max = max(resid_max, resid)
         n_clamped = n_clamped + n_clamp_j
         if (n_contact == 0) n_nocontact = n_nocontact + 1
         if (wh > 0.0_wp) n_wet = n_wet + 1
         if (series) then
            mu_inst(t+1) = mu_j
            hydro_load(t+1) = wh
            penetration(t+1) = cmin + x
            contact(t+1) = n_contact
            if (present(film_thickness)) then
               film_thickness(t+1) = film_sum / real(n, wp)
               local_friction(t+1) = 0.0_wp
               if (sum_f > 0.0_wp) local_friction(t+1) = kel * local_partial() / sum_f
            end if
         end if
      end do

      out%mu = mu_sum / real(geo%n_avg, wp)                  ! Eq. 12
      out%hydroplaning_fraction = real(n_nocontact, wp) / real(geo%n_avg, wp)
      out%wet_fraction = real(n_wet, wp) / real(geo%n_avg, wp)
      out%max_balance_residual = resid_max
      out%mean_hydro_load = wh_sum / real(geo%n_avg, wp)
      out%max_compression = u_max
      out%n_clamped = n_clamped
      out%bearing_evaluations = n_eval
      if (rstep%memory) out%memory_updates = int(n, i8) * int(geo%n_avg + geo%n_spin, i8)
      out%viscous_memory_ran = rstep%memory
      out%bearing_ran = load_film
      out%friction_film_ran = friction_film
      if (friction_film .and. force_sum > 0.0_wp) out%mean_local_friction = local_sum / force_sum
      if (friction_film) out%mean_film_thickness = film_mean_sum / real(geo%n_avg, wp)
   contains
      !> The road sample an extended index stands for.
      pure integer function physical(kk)
         integer, intent(in) :: kk
         if (geo%closed) then
            physical = modulo(kk - 1, geo%npf) + 1
         else
            physical = min(kk, geo%npf)
         end if
      end function physical

      !> sum_i push_i mu_eff_i at the current position.
      pure real(wp) function local_partial()
         integer :: ii
         local_partial = 0.0_wp
         do ii = 1, n
            local_partial = local_partial + push(ii) * merge(m%mu_loc, m%mu_loc * share(ii), &
               & share(ii) >= 1.0_wp)
         end do
      end function local_partial
   end subroutine slide

   !> The effects that ran, comma-separated: what the output's `effects`
   !> attribute says.
   pure function effects_text(res) result(text)
      type(sim_result_type), intent(in) :: res
      character(len=:), allocatable :: text
      text = res%effects
   end function effects_text

end module pavefric_simulate
