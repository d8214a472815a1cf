!> Running a scene file end to end: namelist, profile, model, NetCDF output.
!> Shared by the program and the Python layer, so both give the same numbers.
module pavefric_run
   use pavefric_kinds, only: wp, i8, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_io
   use pavefric_format, only: to_str
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_profile, only: raw_profile_type, read_raw_profile, unit_factor
   use pavefric_preprocess, only: preprocess, clean_profile_type, preprocess_report_type
   use pavefric_simulate, only: sim_result_type, simulate, make_components, estimate_cost, &
      & element_grid, add_spinup_cost, add_refinement_cost, &
      & cost_estimate_type, check_memory, tolerance_guess, check_profile_scale
   use pavefric_rubber, only: rubber_model
   use pavefric_film, only: film_model
   use pavefric_outputs, only: output_metadata_type
   use pavefric_netcdf, only: write_results, temporary_name, check_replaceable
   use pavefric_fsys, only: make_directory, dir_name, remove_file, output_guard_type, &
      & check_output_path, release_temporary, setting
   use pavefric_texture, only: texture_metrics
   use pavefric_ifi, only: ifi_from_sweep
   use pavefric_heights, only: max_profile_height
   use pavefric_model, only: parameter_table, parameters_namelist_text
   use pavefric_error, only: add_warning, add_warnings
   implicit none
   private

   public :: run_scene, run_profile, load_scene_profile, ctm_dx, preprocess_summary, timestamp
   public :: scene_estimate, estimate_text, announce_interface, checked_estimate
   public :: rms_plausible_low, rms_plausible_high, mu_plausible_high
   public :: texture_warning, result_warnings, check_writable

   !> Spacing of a Circular Track Meter profile (m), the default dx.
   real(wp), parameter :: ctm_dx = 0.87e-3_wp
   !> Plausible RMS height of a road texture profile (m): below, the heights
   !> are most likely in another unit than declared; above, not a texture.
   real(wp), parameter :: rms_plausible_low = 1.0e-5_wp, rms_plausible_high = 0.02_wp
   !> The paper's wet model's regimes (bearing_regime_warning): a depth
   !> under this share of the texture depth that carries load, or over this
   !> multiple of it.
   real(wp), parameter :: thin_film_share = 0.01_wp, deep_water_ratio = 2.0_wp
   !> The paper's bearing at or below slow_kmh carrying more than
   !> slow_film_share of the load is warned of (bearing_regime_warning).
   real(wp), parameter :: slow_kmh = 1.0_wp, slow_film_share = 0.1_wp
   !> kane2017 under a heavy pad: the film's share of the load and the share
   !> of elements touching above which the seated pad's load is the film's
   !> (bearing_regime_warning).
   real(wp), parameter :: seated_film_share = 0.9_wp, seated_contact = 0.5_wp
   !> A run estimated to take this long (s) or more is announced before it starts.
   real(wp), parameter :: announce_seconds = 1.0_wp
   !> Largest plausible friction coefficient (DFT and skid testers read up to ~1.3).
   real(wp), parameter :: mu_plausible_high = 2.0_wp

   abstract interface
      !> Told one line before a long step starts (the program prints it).
      subroutine announce_interface(text)
         character(len=*), intent(in) :: text
      end subroutine announce_interface
   end interface

contains

   !> The cost of running `scene` on its preprocessed profile, before it runs
   !> (the same numbers the run records in its output).
   function scene_estimate(scene, clean) result(c)
      type(scene_type), intent(in) :: scene
      type(clean_profile_type), intent(in) :: clean
      type(cost_estimate_type) :: c
      class(rubber_model), allocatable :: rubber
      class(film_model), allocatable :: film
      logical :: friction_film
      integer :: npe, phases
      real(wp) :: dxe
      call make_components(scene%model, rubber, film)
      friction_film = .false.
      if (allocated(film)) friction_film = film%changes_friction()
      call element_grid(scene%model, size(clean%z), clean%dx, scene%closed, npe, dxe, phases)
      c = estimate_cost(scene%model, npe, dxe, scene%closed, &
         & size(scene%speeds_kmh), scene%series, friction_film, rubber%state_size())
      call add_spinup_cost(scene%model, npe, dxe, scene%closed, scene%speeds_kmh, c)
      ! every phase of the pad's grid is a run of that size
      c%element_steps = c%element_steps * phases
      c%total_element_steps = c%total_element_steps * phases
      c%seconds = c%seconds * real(phases, wp)
      ! where a probe finds the pad standing on few elements: the passes
      ! that refine it (the same numbers simulate records)
      call add_refinement_cost(scene%model, clean%z, clean%dx, scene%closed, &
         & scene%speeds_kmh, c)
      ! with a tolerance, its refinement's passes (a guess)
      call tolerance_guess(scene%model, c)
   end function scene_estimate

   !> scene_estimate, refused (error) when the run would not fit in the
   !> memory the process may use, and in words (estimate_text): what the
   !> program announces and Python's simulate() and run() warn with.
   subroutine checked_estimate(scene, clean, cost, line, error)
      type(scene_type), intent(in) :: scene
      type(clean_profile_type), intent(in) :: clean
      type(cost_estimate_type), intent(out) :: cost
      character(len=:), allocatable, intent(out) :: line
      type(error_type), allocatable, intent(out) :: error
      ! (a profile far shorter than the pad would be estimated on a grid
      ! of one point, as a pad of more elements than memory holds)
      call check_profile_scale(scene%model, size(clean%z), clean%dx, error)
      if (allocated(error)) return
      cost = scene_estimate(scene, clean)
      call check_memory(cost, scene%model, scene%series, error)
      if (allocated(error)) return
      call estimate_text(cost, scene%model%tolerance, line)
   end subroutine checked_estimate

   !> The estimate in words, for the progress line.
   subroutine estimate_text(c, tolerance, text)
      type(cost_estimate_type), intent(in) :: c
      real(wp), intent(in) :: tolerance
      character(len=:), allocatable, intent(out) :: text
      character(len=32) :: mib, sec
      character(len=:), allocatable :: listed
      write(mib, '(i0)') max(1_i8, nint(c%bytes / 2.0_wp**20, i8))
      if (c%seconds < 0.01_wp) then
         sec = "under 0.01"
      else
         write(sec, '(f0.2)') c%seconds
         if (sec(1:1) == ".") sec = "0" // sec
      end if
      text = "estimate: " // to_str(c%total_element_steps) // " element-steps, about " // &
         & trim(mib) // " MiB, " // trim(sec) // " s on one thread"
      if (c%refine_seconds >= 0.01_wp .and. allocated(c%refine_speeds)) then
         write(sec, '(f0.2)') c%refine_seconds
         if (sec(1:1) == ".") sec = "0" // sec
         call speeds_list(c%refine_speeds, listed)
         text = text // ", " // trim(sec) // " s of it refining the pad at " // &
            & listed // " km/h, where a probe found it on fewer " // &
            & "than 4 elements in contact (&numerics min_contacts, error_estimate)"
      end if
      if (tolerance > 0.0_wp) then
         text = text // " for the first pass (&numerics tolerance: each refinement doubles it)"
         if (c%tolerance_substeps > 0) then
            write(sec, '(f0.1)') c%tolerance_seconds
            if (sec(1:1) == ".") sec = "0" // sec
            write(mib, '(i0)') max(1_i8, nint(min(c%tolerance_bytes / 2.0_wp**20, 9.0e18_wp), i8))
            text = text // "; tolerance = " // to_str(tolerance) // " may need substeps " // &
               & to_str(c%tolerance_substeps) // ", about " // trim(sec) // " s in all and " // &
               & "about " // trim(mib) // " MiB at the last pass (a guess from how the " // &
               & "default scenes converge)"
         end if
      end if
   end subroutine estimate_text

   !> Speeds as "20, 50 and 80" (a subroutine: no deferred-length function
   !> results in the library, docs/api.md).
   !> More than 8 speeds: the first 6, "...", the last and how many in all
   !> (the estimate's line must fit Python's 1024 characters).
   pure subroutine speeds_list(v, text)
      real(wp), intent(in) :: v(:)
      character(len=:), allocatable, intent(out) :: text
      integer, parameter :: most = 8
      integer :: k
      text = ""
      if (size(v) > most) then
         do k = 1, most - 2
            text = text // to_str(v(k)) // ", "
         end do
         text = text // "... and " // to_str(v(size(v))) // " (" // to_str(size(v)) // &
            & " speeds)"
         return
      end if
      do k = 1, size(v)
         if (k > 1 .and. k == size(v)) then
            text = text // " and "
         else if (k > 1) then
            text = text // ", "
         end if
         text = text // to_str(v(k))
      end do
   end subroutine speeds_list

   !> Read the scene's profile (any supported format), preprocess it as the
   !> scene says, and settle its spacing.
   subroutine load_scene_profile(scene, clean, error, raw_out, raw_in)
      type(scene_type), intent(in) :: scene
      type(clean_profile_type), intent(out) :: clean
      type(error_type), allocatable, intent(out) :: error
      !> The profile as the file delivered it (Python's read_profile shows it).
      type(raw_profile_type), intent(out), optional :: raw_out
      !> The profile already read (a batch reads a NetCDF survey's profiles
      !> from its open catalogue): only the rest of the path is taken.
      type(raw_profile_type), intent(in), optional :: raw_in
      type(raw_profile_type) :: raw
      real(wp) :: dx, file_dx
      integer :: n
      if (present(raw_in)) then
         raw = raw_in
      else
         call read_raw_profile(scene%profile_file, scene%format, unit_factor(scene%height_unit), &
            & scene%x_column, scene%z_column, raw, error, profile_name=scene%profile_name)
         if (allocated(error)) return
      end if
      ! A height no road has, for a run (read_profile, raw_out, shows what
      ! the file holds): named by its line where the file has lines (the
      ! run's own check, after preprocessing, can name an index only)
      if (.not. present(raw_out)) then
         call check_raw_range(raw, scene%profile_file, error)
         if (allocated(error)) return
      end if
      ! The spacing: &surface dx, else the file's stated spacing (NetCDF dx),
      ! else a CTM's; distances in the file then set it (preprocessing).
      dx = ctm_dx
      if (raw%dx > 0.0_wp) dx = raw%dx
      if (scene%dx > 0.0_wp) dx = scene%dx
      file_dx = 0.0_wp
      if (raw%has_x) then
         n = size(raw%x)
         if (n >= 2) file_dx = (raw%x(n) - raw%x(1)) / real(n - 1, wp)
      else if (raw%dx > 0.0_wp) then
         file_dx = raw%dx
      end if
      if (file_dx > 0.0_wp .and. scene%dx > 0.0_wp .and. &
            & scene%preprocess%resample_dx <= 0.0_wp .and. &
            & abs(scene%dx - file_dx) > 0.01_wp * file_dx) then
         call fatal_error(error, "&surface dx = " // to_str(scene%dx) // &
            & ": disagrees (by more than 1 %) with the spacing " // to_str(file_dx) // &
            & " m of the distances in '" // scene%profile_file // "'; remove dx to take " // &
            & "the file's spacing, or correct it")
         return
      end if
      call preprocess(raw, dx, scene%preprocess, clean, error)
      if (present(raw_out)) call move_alloc_raw(raw, raw_out)
   contains
      subroutine check_raw_range(r, path, err)
         type(raw_profile_type), intent(in) :: r
         character(len=*), intent(in) :: path
         type(error_type), allocatable, intent(out) :: err
         integer :: k
         character(len=:), allocatable :: where
         if (.not. allocated(r%z)) return
         do k = 1, size(r%z)
            if (allocated(r%valid)) then
               if (.not. r%valid(k)) cycle
            end if
            if (.not. (abs(r%z(k)) > max_profile_height)) cycle
            where = "&surface profile_file = '" // path // "': height " // to_str(k)
            if (allocated(r%line)) then
               if (size(r%line) == size(r%z)) where = path // ":" // to_str(r%line(k)) // &
                  & ": height"
            end if
            call fatal_error(err, where // " " // to_str(r%z(k)) // " m: beyond +-" // &
               & to_str(max_profile_height) // " m, not a texture; are the heights in the " // &
               & "unit declared (&surface height_unit, or the file's header)?")
            return
         end do
      end subroutine check_raw_range

      subroutine move_alloc_raw(a, b)
         type(raw_profile_type), intent(inout) :: a
         type(raw_profile_type), intent(out) :: b
         b = a
      end subroutine move_alloc_raw
   end subroutine load_scene_profile

   !> One line saying what preprocessing did.
   pure function preprocess_summary(r) result(text)
      type(preprocess_report_type), intent(in) :: r
      character(len=preprocess_summary_len(r)) :: text
      character(len=:), allocatable :: deferred_text
      call preprocess_summary_text(r, deferred_text)
      text = deferred_text
   end function preprocess_summary

   !> The length of preprocess_summary's text.
   pure integer function preprocess_summary_len(r)
      type(preprocess_report_type), intent(in) :: r
      character(len=:), allocatable :: deferred_text
      call preprocess_summary_text(r, deferred_text)
      preprocess_summary_len = len(deferred_text)
   end function preprocess_summary_len

   !> The text of preprocess_summary, into a deferred-length argument.
   pure subroutine preprocess_summary_text(r, text)
      type(preprocess_report_type), intent(in) :: r
      character(len=:), allocatable, intent(out) :: text
      text = "format " // r%format // "; " // to_str(r%points_read) // " points read; " // &
         & to_str(r%trimmed_start) // " trimmed at the start and " // to_str(r%trimmed_end) // &
         & " at the end (reference plates); " // to_str(r%dropouts) // &
         & " dropouts interpolated; " // to_str(r%spikes) // " spike points replaced; "
      if (r%resampled) then
         text = text // "resampled from " // to_str(r%dx_in) // " m to " // to_str(r%dx_out) // &
            & " m; "
      else
         text = text // "spacing " // to_str(r%dx_out) // " m kept; "
      end if
      if (r%filtered) then
         text = text // "low-pass filtered; "
      else
         text = text // "not filtered; "
      end if
      text = text // to_str(r%points_out) // " points used"
   end subroutine preprocess_summary_text

   !> Run the scene in `path`; write its NetCDF output to `output_override`
   !> when that is not empty, else to the namelist's &output file, else to
   !> outputs/<scene name>.nc. `command` goes into the history attribute.
   subroutine run_scene(path, output_override, command, out_path, res, error, warnings, announce, &
         & refine_seconds)
      character(len=*), intent(in) :: path, output_override, command
      character(len=:), allocatable, intent(out) :: out_path
      type(sim_result_type), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      !> The warnings recorded in the output, one a line.
      character(len=:), allocatable, intent(out), optional :: warnings
      !> Told the cost estimate before the model runs, when it is long
      !> (announce_seconds or more; the output records it always).
      procedure(announce_interface), optional :: announce
      !> The up-front estimate's seconds for the passes that refine the pad,
      !> when the caller made it (>= 0; Python's run() does): recorded as
      !> they are instead of probing the profile again.
      real(wp), intent(in), optional :: refine_seconds
      logical :: created, ok
      character(len=:), allocatable :: said
      ! (the warnings through a local: passed on as an optional deferred-length
      ! dummy they came back empty with gfortran 12)
      call run_scene_in(path, output_override, command, out_path, res, error, created, &
         & said, announce, refine_seconds)
      if (present(warnings) .and. allocated(said)) warnings = said
      ! a run that failed leaves nothing behind, not even the default
      ! directory it made for its output (an attack of 2026-12-07: bad input
      ! left an empty outputs/); remove() takes an empty directory only
      if (allocated(error) .and. created) ok = remove_file("outputs")
   end subroutine run_scene

   !> run_scene's work; `created`: whether it made the default directory
   !> 'outputs' (which was not there).
   subroutine run_scene_in(path, output_override, command, out_path, res, error, created, &
         & warnings, announce, refine_seconds)
      character(len=*), intent(in) :: path, output_override, command
      character(len=:), allocatable, intent(out) :: out_path
      type(sim_result_type), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      logical, intent(out) :: created
      character(len=:), allocatable, intent(out), optional :: warnings
      procedure(announce_interface), optional :: announce
      real(wp), intent(in), optional :: refine_seconds
      logical :: existed
      character(len=:), allocatable :: line
      real(wp) :: refine
      type(cost_estimate_type) :: cost
      type(scene_type) :: scene
      type(output_metadata_type) :: meta
      type(clean_profile_type) :: clean
      type(output_guard_type) :: guard
      character(len=:), allocatable :: out_what

      created = .false.
      call read_scene(path, scene, error)
      if (allocated(error)) return
      out_what = "&output file"
      if (len_trim(output_override) > 0) then
         out_path = trim(output_override)
         out_what = "-o"
      else if (len(scene%output_file) > 0) then
         out_path = scene%output_file
      else
         inquire(file="outputs/.", exist=existed)
         if (.not. make_directory("outputs")) then
            call fatal_error(error, "&output file: the default directory 'outputs' cannot " // &
               & "be created here; set &output file or use -o")
            return
         end if
         created = .not. existed
         out_path = "outputs/" // scene%name // ".nc"
      end if
      ! Refuse an output that is an input or not a regular file, and find an
      ! unwritable one, before spending time on the model.
      call check_output_path(out_path, out_what, guard, error)
      if (allocated(error)) return
      call guard%check_input(path, "the scene file", error)
      if (allocated(error)) return
      call guard%check_input(scene%profile_file, "the profile (&surface profile_file)", error)
      if (allocated(error)) return
      call check_replaceable(out_path, out_what, error)
      if (allocated(error)) return
      call check_writable(out_path, out_what, error)
      if (allocated(error)) return

      call load_scene_profile(scene, clean, error)
      if (allocated(error)) return
      refine = -1.0_wp
      if (present(refine_seconds)) refine = refine_seconds
      if (present(announce)) then
         ! a refusal is the one line, not after the estimate
         call checked_estimate(scene, clean, cost, line, error)
         if (allocated(error)) return
         if (max(cost%seconds, cost%tolerance_seconds) >= announce_seconds) call announce(line)
         refine = cost%refine_seconds
      end if
      call run_profile(scene, clean, res, meta, error, refine)
      if (allocated(error)) return
      meta%title = "pavefric friction-speed curve of scene " // scene%name
      meta%history = timestamp() // " pavefric " // pavefric_version // ": " // command
      meta%preprocess = clean%report
      meta%preprocessing = preprocess_summary(clean%report)
      meta%scene_file = path
      if (present(warnings)) warnings = meta%warnings
      call write_results(out_path, res, meta, error)
   end subroutine run_scene_in

   !> The one path from a scene and a profile to results: the model, the
   !> texture metrics and every warning, shared by the program, Python and
   !> the C API. `clean` holds heights (m), spacing and, for instrument
   !> files, their quality flags.
   subroutine run_profile(scene, clean, res, meta, error, refine_seconds)
      type(scene_type), intent(in) :: scene
      type(clean_profile_type), intent(in) :: clean
      type(sim_result_type), intent(out) :: res
      type(output_metadata_type), intent(out) :: meta
      type(error_type), allocatable, intent(out) :: error
      !> simulate's: the up-front estimate's refinement seconds (< 0 or
      !> absent: simulate probes the profile itself).
      real(wp), intent(in), optional :: refine_seconds
      type(error_type), allocatable :: texture_error

      call simulate(scene%model, clean%z, clean%dx, scene%closed, scene%speeds_kmh, &
         & scene%series, res, error, refine_seconds)
      if (allocated(error)) then
         ! the core's words for the profile ("the profile has 8 points, ..."):
         ! which file (a batch names its profile itself)
         if (index(error%message, "the profile ") == 1 .and. len(scene%profile_file) > 0) &
            & error%message = "&surface profile_file = '" // scene%profile_file // "': " // &
            & error%message
         return
      end if
      meta%title = "pavefric friction-speed curve"
      meta%history = ""
      meta%input_namelist = scene%text
      meta%profile_file = scene%profile_file
      meta%dx = clean%dx
      meta%profile_points = size(clean%z)
      meta%closed = scene%closed
      meta%has_parameters = .true.
      meta%parameters = scene%parameters
      if (scene%is_batch) then
         call parameters_namelist_text(parameter_table(), scene%parameters, meta%parameters_text)
      else
         call parameters_namelist_text(parameter_table(), scene%parameters, meta%parameters_text, &
            & groups="surface preprocess pad rubber water operation numerics output")
      end if
      meta%warnings = scene%warnings
      if (len(res%warnings) > 0) call add_warnings(meta%warnings, res%warnings)
      ! Texture metrics: reported when the profile holds a whole valid segment.
      if (allocated(clean%dropout_fraction)) then
         call texture_metrics(clean%z, clean%dx, scene%closed, 0.1_wp, .true., meta%texture, &
            & texture_error, dropout_fraction=clean%dropout_fraction, spike=clean%spike)
      else
         call texture_metrics(clean%z, clean%dx, scene%closed, 0.1_wp, .true., meta%texture, &
            & texture_error)
      end if
      meta%has_texture = .not. allocated(texture_error)
      if (allocated(texture_error)) meta%texture_note = texture_error%message
      ! What a road can be: the texture, and the results.
      call texture_warning(clean%z, meta%warnings)
      call result_warnings(scene, res, meta%has_texture, meta%texture%mpd, "", meta%warnings)
      ! (the IFI indexes wet friction, measured with water on the road: a
      ! dry run's friction taken for a DFT's would mislead, so no F60 there)
      if (meta%has_texture .and. scene%model%depth > 0.0_wp) then
         meta%ifi = ifi_from_sweep(res%speed_kmh, res%mu, meta%texture%mpd)
      else
         meta%ifi = ifi_from_sweep(res%speed_kmh, res%mu, 0.0_wp)
      end if
   end subroutine run_profile

   !> The warnings about a run's results that every interface records (a
   !> scene's `warnings`, a batch's `warning_message` per profile): an element
   !> compressed beyond the rubber, a friction no road gives, the wet model
   !> outside its regime. `where` follows the speed in the text (a batch's
   !> water depth); `mpd` is used when `has_texture`.
   subroutine result_warnings(scene, res, has_texture, mpd, where, warnings)
      type(scene_type), intent(in) :: scene
      type(sim_result_type), intent(in) :: res
      logical, intent(in) :: has_texture
      real(wp), intent(in) :: mpd
      character(len=*), intent(in) :: where
      character(len=:), allocatable, intent(inout) :: warnings
      integer :: j
      do j = 1, size(res%mu)
         if (res%max_compression(j) > res%thickness) call add_warning(warnings, &
            & "an element is compressed by " // to_str(res%max_compression(j)) // " m at " // &
            & to_str(res%speed_kmh(j)) // " km/h" // where // ", beyond the rubber thickness " // &
            & "(&pad thickness = " // to_str(res%thickness) // " m); the linear model has no " // &
            & "floor there")
         if (res%mu(j) > mu_plausible_high) call add_warning(warnings, "mu = " // &
            & to_str(res%mu(j)) // " at " // to_str(res%speed_kmh(j)) // " km/h" // where // &
            & ": above what any road gives (" // to_str(mu_plausible_high) // "); check " // &
            & "&surface mu_loc and the profile's units")
      end do
      call bearing_regime_warning(scene, res, has_texture, mpd, warnings)
   end subroutine result_warnings

   !> The paper's wet model (wet_model = 'kane2017') outside the regime where
   !> its answer means what it says (docs/model.md, "Where Eq. 15 misleads"):
   !> a film far thinner than the texture that still carries load (friction
   !> then jumps as depth -> 0 instead of returning to the dry value), and
   !> water deeper than twice the texture (Eq. 15's wedge load falls as the
   !> inlet film grows, so friction rises back toward dry with more water).
   subroutine bearing_regime_warning(scene, res, has_texture, mpd, warnings)
      type(scene_type), intent(in) :: scene
      type(sim_result_type), intent(in) :: res
      logical, intent(in) :: has_texture
      real(wp), intent(in) :: mpd
      character(len=:), allocatable, intent(inout) :: warnings
      real(wp) :: depth, texture
      integer :: j
      depth = scene%model%depth
      if (.not. depth > 0.0_wp .or. scene%model%wet_model /= "kane2017") return
      if (.not. any(res%wet_fraction > 0.0_wp)) return
      ! the bearing at a walking pace or slower: Eq. 15's load falls with
      ! V^beta but grows without bound as the film closes, so where the pad
      ! can close its gaps the film keeps the load as V -> 0 and friction does
      ! not return to dry (a 20 um RMS texture: 0.055 at 1e-6, 1e-3 and 1
      ! km/h, 0.50 at 0; attack20). The first such speed of the list is named.
      if (allocated(res%film_load_share)) then
         do j = 1, size(res%speed_kmh)
            if (.not. (res%speed_kmh(j) > 0.0_wp .and. res%speed_kmh(j) <= slow_kmh)) cycle
            if (.not. res%film_load_share(j) > slow_film_share) cycle
            call add_warning(warnings, "&operation speeds_kmh(" // to_str(j) // ") = " // &
               & to_str(res%speed_kmh(j)) // " km h-1: the film of wet_model = 'kane2017' " // &
               & "carries " // to_str(nint(100.0_wp * res%film_load_share(j))) // " % of " // &
               & "the load at this creeping speed (Eq. 15's load grows without bound as the " // &
               & "film closes under the pad), so friction does not return to the dry value " // &
               & "as the speed goes to 0 (docs/model.md); wet_model = 'squeeze' does")
            exit
         end do
      end if
      ! a seated pad whose load the film carries: Eq. 15's mean gap under a
      ! heavy pad closes as the pad sinks, and its load grows without bound,
      ! so the film takes the load from elements that touch the road and mu
      ! falls as 1 / load, the same at every speed (attack21: 1,000 N, 95 %
      ! of the load on the film with 97 % of the elements touching, mu 0.033
      ! at 20-80 km/h; 4,000 N, a car tyre's, 0.008). The first such speed.
      if (allocated(res%film_load_share) .and. allocated(res%contact_fraction)) then
         do j = 1, size(res%speed_kmh)
            if (.not. res%speed_kmh(j) > slow_kmh) cycle
            if (.not. (res%film_load_share(j) > seated_film_share .and. &
               & res%contact_fraction(j) > seated_contact)) cycle
            call add_warning(warnings, "&pad load = " // to_str(scene%model%load) // &
               & " N: at " // to_str(res%speed_kmh(j)) // " km/h the film of wet_model = " // &
               & "'kane2017' carries " // to_str(nint(100.0_wp * res%film_load_share(j))) // &
               & " % of the load while " // &
               & to_str(nint(100.0_wp * res%contact_fraction(j))) // " % of the pad's " // &
               & "elements touch the road (Eq. 15's load grows without bound as the mean gap " // &
               & "under a heavy pad closes), so mu falls as 1 / load instead of following the " // &
               & "texture and the speed (docs/model.md); wet_model = 'squeeze' does not")
            exit
         end do
      end if
      if (has_texture) then
         texture = mpd
      else
         texture = 0.0_wp
      end if
      if (.not. texture > 0.0_wp) return
      if (depth < thin_film_share * texture) then
         call add_warning(warnings, "&water depth = " // to_str(depth) // " m, under " // &
            & to_str(thin_film_share) // " of the texture depth (MPD " // to_str(texture) // &
            & " m), still carried load with wet_model = 'kane2017' (the film closes under " // &
            & "the pad, Eq. 15): the paper's model jumps as the depth goes to 0 instead of " // &
            & "returning to the dry friction (docs/model.md); wet_model = 'squeeze' does not")
      else if (depth > deep_water_ratio * texture) then
         call add_warning(warnings, "&water depth = " // to_str(depth) // " m is more " // &
            & "than " // to_str(deep_water_ratio) // " x the texture depth (MPD " // &
            & to_str(texture) // " m): with wet_model = 'kane2017' the bearing's load (Eq. 15)" // &
            & " falls as the water deepens, so friction rises back toward dry (docs/model.md);" // &
            & " wet_model = 'squeeze' does not")
      end if
   end subroutine bearing_regime_warning

   !> A warning when the profile's RMS height is outside what a road texture
   !> can be (most often heights in another unit than &surface height_unit says).
   pure subroutine texture_warning(z, warnings)
      real(wp), intent(in) :: z(:)
      character(len=:), allocatable, intent(inout) :: warnings
      real(wp) :: mean, scale, rms
      if (size(z) < 2) return
      scale = maxval(abs(z))
      if (scale > 0.0_wp) then
         mean = sum(z / scale) / real(size(z), wp)
         rms = scale * sqrt(sum((z / scale - mean)**2) / real(size(z), wp))
      else
         rms = 0.0_wp
      end if
      if (rms < rms_plausible_low .or. rms > rms_plausible_high) call add_warning(warnings, &
         & "the profile's RMS height is " // to_str(rms) // " m, outside what a road " // &
         & "texture can be [" // to_str(rms_plausible_low) // ", " // &
         & to_str(rms_plausible_high) // "] m: are the heights in the unit declared " // &
         & "(&surface height_unit, or the file's header)?")
   end subroutine texture_warning

   !> Error unless a file can be created beside `path`.
   subroutine check_writable(path, what, error)
      character(len=*), intent(in) :: path
      !> where the path came from: "&output file" or "-o"
      character(len=*), intent(in) :: what
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      character(len=512) :: msg
      character(len=:), allocatable :: reason
      integer :: unit, ios, k
      logical :: ok
      call temporary_name(path, tmp)
      open(newunit=unit, file=tmp, status="replace", action="write", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call release_temporary(tmp)
         ! the runtime's "Cannot open file '<temporary>': <reason>": the reason
         ! alone (the temporary's name is not the user's)
         k = index(msg, "': ", back=.true.)
         if (k > 0) then
            reason = trim(msg(k+3:))
         else
            reason = trim(msg)
         end if
         call fatal_error(error, setting(what, path) // ": cannot write in directory '" // &
            & dir_name(path) // "' (" // reason // "); create the directory " // &
            & "or give another path", stat_io)
         return
      end if
      close(unit, status="delete")
      ok = remove_file(tmp)
      call release_temporary(tmp)
   end subroutine check_writable

   !> Local time as ISO 8601 (a fixed length, not a deferred-length result:
   !> gfortran keeps the length of those in a static variable).
   function timestamp() result(text)
      character(len=25) :: text
      character(len=8) :: d
      character(len=10) :: t
      character(len=5) :: zone
      call date_and_time(d, t, zone)
      text = d(1:4) // "-" // d(5:6) // "-" // d(7:8) // "T" // t(1:2) // ":" // t(3:4) // ":" // &
         & t(5:6) // zone(1:3) // ":" // zone(4:5)
   end function timestamp

end module pavefric_run
