!> The simulation driver: the pad slides over the profile, position after
!> position, at each speed (paper Fig. 4). Speeds are independent, so they
!> run in parallel under OpenMP with results identical to a serial run.
module pavefric_simulate
   use pavefric_kinds, only: wp, i8, kmh_to_ms
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str
   use pavefric_model, only: model_type, validate_model, shape_code, shape_rounded
   use pavefric_profile, only: refine_profile, check_heights
   use pavefric_rubber, only: kv_step_type, kv_step
   use pavefric_facet, only: facet_friction
   use pavefric_balance, only: dry_root, wet_root, mean_gap, wet_state_type
   use pavefric_bearing, only: bearing_prefactor
   implicit none
   private

   public :: sim_result_type, simulate, pad_elements, averaged_positions, effects_text

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
      !> Share of averaged positions where the bearing carried load.
      real(wp), allocatable :: wet_fraction(:)
      !> Largest |sum F + Wh - W| / W over the averaged positions.
      real(wp), allocatable :: max_balance_residual(:)
      !> Mean load carried by the bearing (N).
      real(wp), allocatable :: mean_hydro_load(:)
      !> Largest compression of an element (m), to compare with the thickness.
      real(wp), allocatable :: max_compression(:)
      !> Contacts on facets steeper than theta_max, summed over positions.
      integer(i8), allocatable :: n_clamped(:)
      !> Evaluations of the bearing formula (0 when it did not run).
      integer(i8), allocatable :: bearing_evaluations(:)
      !> Element-steps that updated viscous memory (0 for an elastic scene).
      integer(i8), allocatable :: memory_updates(:)
      !> Whether the elements carried viscous memory at this speed.
      logical, allocatable :: viscous_memory_ran(:)
      !> Whether the hydrodynamic bearing was part of the balance at this speed.
      logical, allocatable :: bearing_ran(:)
      !> Distance slid from the first averaged position (m), with series.
      real(wp), allocatable :: position(:)
      !> Per position and speed, with series: instantaneous friction (Eq. 11),
      !> bearing load (N), pad penetration delta (m), elements in contact.
      real(wp), allocatable :: mu_inst(:,:), hydro_load(:,:), penetration(:,:)
      integer, allocatable :: contact_elements(:,:)
   end type sim_result_type

   !> One speed's averaged results (see sim_result_type for their meaning).
   type :: speed_summary_type
      real(wp) :: mu = 0, hydroplaning_fraction = 0, wet_fraction = 0
      real(wp) :: max_balance_residual = 0, mean_hydro_load = 0, max_compression = 0
      integer(i8) :: n_clamped = 0, bearing_evaluations = 0, memory_updates = 0
      logical :: viscous_memory_ran = .false., bearing_ran = .false.
   end type speed_summary_type

   !> Everything about the profile and pad that does not depend on speed.
   type :: geometry_type
      real(wp), allocatable :: z(:), tan_theta(:), h(:)
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
      n = nint(m%length / (dx / real(m%elements_per_sample, wp)))
   end function pad_elements

   !> Averaged positions for a profile of np samples (0 if the pad does not fit).
   pure function averaged_positions(m, np, dx, closed) result(n_avg)
      type(model_type), intent(in) :: m
      integer, intent(in) :: np
      real(wp), intent(in) :: dx
      logical, intent(in) :: closed
      integer :: n_avg, n_el, s, npf, fine
      n_el = pad_elements(m, dx)
      s = m%substeps
      fine = m%elements_per_sample * s
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
      integer :: j, ns

      call validate_model(m, error)
      if (allocated(error)) return
      call check_inputs(m, z, dx, closed, speeds_kmh, error)
      if (allocated(error)) return
      call build_geometry(m, z, dx, closed, geo)

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
         & res%viscous_memory_ran(ns), &
         & res%bearing_ran(ns))
      if (want_series) then
         allocate(res%mu_inst(geo%n_avg, ns), res%hydro_load(geo%n_avg, ns), &
            & res%penetration(geo%n_avg, ns), res%contact_elements(geo%n_avg, ns), &
            & res%position(geo%n_avg))
         res%position = [(real(j, wp) * geo%advance, j = 0, geo%n_avg - 1)]
      end if

      ! Each speed is computed serially by one thread: the thread count cannot
      ! change a bit of the result.
      !$omp parallel do schedule(dynamic, 1) default(shared) private(j, summary)
      do j = 1, ns
         if (want_series) then
            call slide(geo, m, res%speed(j), summary, res%mu_inst(:, j), res%hydro_load(:, j), &
               & res%penetration(:, j), res%contact_elements(:, j))
         else
            call slide(geo, m, res%speed(j), summary)
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
      end do
      !$omp end parallel do
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
         if (.not. (speeds_kmh(j) >= 0.0_wp .and. speeds_kmh(j) <= huge(1.0_wp))) then
            call fatal_error(error, "&operation speeds_kmh(" // to_str(j) // ") = " // &
               & to_str(speeds_kmh(j)) // ": must be finite and >= 0")
            return
         end if
      end do
      call check_heights(z, error)
      if (allocated(error)) return
      n_el = pad_elements(m, dx)
      if (n_el < 1) then
         call fatal_error(error, "&pad length = " // to_str(m%length) // &
            & ": shorter than half a pad element (dx / elements_per_sample = " // &
            & to_str(dx / real(m%elements_per_sample, wp)) // " m)")
         return
      end if
      if (averaged_positions(m, size(z), dx, closed) < 1) then
         call fatal_error(error, "&surface profile_file: the profile has " // to_str(size(z)) // &
            & " points, fewer than the pad's " // to_str(n_el) // " elements (&pad length = " // &
            & to_str(m%length) // " m at dx = " // to_str(dx) // " m)")
         return
      end if
   end subroutine check_inputs

   !> Refine the profile, compute facet friction, lay out the pad, and extend
   !> a closed profile by wrapping so element indices never need a modulo.
   subroutine build_geometry(m, z, dx, closed, geo)
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: z(:), dx
      logical, intent(in) :: closed
      type(geometry_type), intent(out) :: geo
      real(wp), allocatable :: zf(:), tf(:), t_fine(:)
      logical, allocatable :: cf(:), c_fine(:)
      real(wp) :: dxf, xc
      integer :: fine, n_ext, k, i

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
      allocate(tf(size(z)), cf(size(z)))
      call facet_friction(z, dx, closed, m%mu_loc, m%theta_max_deg, tf, cf)
      if (fine > 1) then
         call refine_profile(tf, closed, fine, t_fine)
         call move_alloc(t_fine, tf)
         allocate(c_fine(geo%npf))
         do k = 1, geo%npf
            c_fine(k) = cf(min(size(z), (k - 1 + fine / 2) / fine + 1))
            if (closed .and. (k - 1 + fine / 2) / fine + 1 > size(z)) c_fine(k) = cf(1)
         end do
         call move_alloc(c_fine, cf)
      end if
      if (closed) then
         n_ext = geo%npf + (geo%n_el - 1) * geo%spacing
         allocate(geo%z(n_ext), geo%tan_theta(n_ext), geo%clamped(n_ext))
         do k = 1, n_ext
            i = modulo(k - 1, geo%npf) + 1
            geo%z(k) = zf(i)
            geo%tan_theta(k) = tf(i)
            geo%clamped(k) = cf(i)
         end do
      else
         call move_alloc(zf, geo%z)
         call move_alloc(tf, geo%tan_theta)
         call move_alloc(cf, geo%clamped)
      end if

      ! Undeformed pad bottom h_i above the reference plane.
      allocate(geo%h(geo%n_el))
      geo%h = 0.0_wp
      if (shape_code(m%shape) == shape_rounded) then
         do i = 1, geo%n_el
            xc = (real(i, wp) - 0.5_wp - 0.5_wp * real(geo%n_el, wp)) * geo%dx_el
            geo%h(i) = m%radius - sqrt(m%radius**2 - xc**2)
         end do
      end if
   end subroutine build_geometry

   !> One speed: spin-up, then the averaged positions (Eqs. 2-12).
   subroutine slide(geo, m, speed, out, mu_inst, hydro_load, penetration, contact)
      type(geometry_type), intent(in) :: geo
      type(model_type), intent(in) :: m
      real(wp), intent(in) :: speed
      type(speed_summary_type), intent(out) :: out
      real(wp), intent(out), optional :: mu_inst(:), hydro_load(:), penetration(:)
      integer, intent(out), optional :: contact(:)

      type(kv_step_type) :: kv
      type(wet_state_type) :: wet
      real(wp), allocatable :: c(:), d(:), u(:), u_free(:), work(:)
      real(wp) :: kel, s_load, cmin, x, x_dry, x_guess, delta_prev, wh, h_m, prefactor, push, sum_f, sum_ft, u_new
      real(wp) :: mu_sum, resid_max, wh_sum, u_max, mu_j, resid
      integer(i8) :: n_clamped, n_eval
      integer :: t, k1, k, i, n, n_contact, n_nocontact, n_wet, n_clamp_j
      logical :: bearing_on, series

      n = geo%n_el
      series = present(mu_inst)
      kv = kv_step(m%stiffness, m%viscosity, speed, geo%advance)
      kel = m%width * geo%dx_el * kv%k_eff        ! Eq. 2: F = l dx p, p = K_eff (g - u_free)
      s_load = m%load / kel
      ! Simulate only the effects the scene calls for: the bearing needs water
      ! and motion (Sect. 3); viscous memory needs C > 0 and V > 0.
      bearing_on = m%depth > 0.0_wp .and. speed > 0.0_wp
      prefactor = 0.0_wp
      if (bearing_on) prefactor = bearing_prefactor(m%alpha, m%beta, m%water_viscosity, &
         & speed, m%width, m%length)

      allocate(c(n), d(n), work(n))
      if (kv%memory) then
         allocate(u(n), u_free(n))
         u = 0.0_wp
      end if

      delta_prev = -huge(1.0_wp)
      mu_sum = 0.0_wp
      wh_sum = 0.0_wp
      resid_max = 0.0_wp
      u_max = 0.0_wp
      n_clamped = 0
      n_eval = 0
      n_nocontact = 0
      n_wet = 0
      do t = -geo%n_spin, geo%n_avg - 1
         if (geo%closed) then
            k1 = modulo(t * geo%stride + 1, geo%npf) + 1
         else
            k1 = t * geo%stride + 1
         end if
         ! c_i = h_i - z_k + u_free_i: the penetration at which element i
         ! starts to push (Eqs. 4, 8).
         cmin = huge(1.0_wp)
         if (kv%memory) then
            do i = 1, n
               u_free(i) = kv%relax * u(i)
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
         if (bearing_on) then
            h_m = mean_gap(d, x_dry)
            ! Wet iff the water fills the valleys under the pad (Sect. 3).
            if (h_m < m%depth) then
               call wet_root(d, kel, m%load, prefactor, m%depth, x_dry, m%wet_tolerance, x, wet)
               wh = wet%hydro_load
               n_eval = n_eval + wet%evaluations
            end if
         end if

         sum_f = 0.0_wp
         sum_ft = 0.0_wp
         n_contact = 0
         n_clamp_j = 0
         do i = 1, n
            k = k1 + (i-1) * geo%spacing
            push = max(0.0_wp, x - d(i))
            sum_f = sum_f + push
            sum_ft = sum_ft + push * geo%tan_theta(k)        ! Eq. 10
            n_contact = n_contact + merge(1, 0, push > 0.0_wp)
            n_clamp_j = n_clamp_j + merge(1, 0, push > 0.0_wp .and. geo%clamped(k))
            u_new = push
            if (kv%memory) then                              ! max(g_i, u_free_i)
               u_new = u_free(i) + push
               u(i) = u_new
            end if
            u_max = max(u_max, u_new)
         end do
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
      if (kv%memory) out%memory_updates = int(n, i8) * int(geo%n_avg + geo%n_spin, i8)
      out%viscous_memory_ran = kv%memory
      out%bearing_ran = bearing_on
   end subroutine slide

   !> The effects that ran, comma-separated: what the output's `effects`
   !> attribute says.
   pure function effects_text(res) result(text)
      type(sim_result_type), intent(in) :: res
      character(len=:), allocatable :: text
      text = "elastic_contact,facet_friction"
      if (any(res%viscous_memory_ran)) text = text // ",viscous_memory"
      if (any(res%bearing_ran)) text = text // ",hydrodynamic_bearing"
   end function effects_text

end module pavefric_simulate
