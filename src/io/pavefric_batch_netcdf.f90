!> NetCDF-4 output of a batch run (profile x water_depth x speed_kmh), through the
!> checked writer of pavefric_netcdf: temp file and rename, first error kept.
module pavefric_batch_netcdf
   use netcdf
   use pavefric_kinds, only: wp, i8, pavefric_version, kmh_to_ms
   use pavefric_error, only: error_type, fatal_error, stat_io, stat_memory
   use pavefric_batch_types, only: batch_type, block_type, status_computed, status_failed, &
      & printable_utf8
   use pavefric_netcdf, only: nc_writer_type, temporary_name, commit_temporary, check_replaceable, &
      & put_parameter_attributes
   use pavefric_model, only: parameter_table, parameters_namelist_text
   use pavefric_outputs, only: output_short_name
   implicit none
   private

   public :: write_batch_results

contains

   !> Write a batch's results (profile x water_depth x speed_kmh) to `path`, via a
   !> temporary file and a rename. `history` goes into the history attribute;
   !> `film_effect` names the scene's film in `effects` where one ran.
   subroutine write_batch_results(path, batch, blocks, history, film_effect, error)
      character(len=*), intent(in) :: path, history, film_effect
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      ! checked before the run too (check_batch_outputs); again in case a
      ! file appeared there while the batch ran
      call check_replaceable(path, "&output file", error)
      if (allocated(error)) return
      call temporary_name(path, tmp)
      call write_batch_file(tmp, batch, blocks, history, film_effect, error)
      call commit_temporary(tmp, path, error)
   end subroutine write_batch_results

   !> The file: dimensions profile x water_depth x speed_kmh, each with a
   !> numeric coordinate variable (`profile` numbers the profiles 1, 2, ...
   !> in the order of the batch, so xarray plots any variable as it opens
   !> the file); `profile_name` (a CF label), `speed` (m/s) and `chainage`
   !> (when the list gives it) are auxiliary coordinates. No `depth`
   !> dimension: CF reads a dimension of that name as the vertical axis,
   !> which a water film's thickness is not. Integer variables carry a
   !> _FillValue only when a profile failed (only then can a value be
   !> missing), so that readers keep them integers otherwise.
   subroutine write_batch_file(path, batch, blocks, history, film_effect, error)
      character(len=*), intent(in) :: path, history, film_effect
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      type(nc_writer_type) :: w
      integer :: stat, d_p, d_d, d_s, d_name, d_msg, d_warn, np, nd, ns, lname, lmsg, lwarn, i, k
      integer :: v_warn, v_nwarn
      integer :: v_muh, v_mua, v_mue, v_eps, v_used
      integer :: v_num, v_name, v_depth, v_speed, v_kmh, v_mu, v_wet, v_hyd, v_res, v_ncl, v_mpd, v_rh
      integer :: v_rs, v_status, v_err, v_chain, v_pre(10)
      real(wp), allocatable :: a(:,:,:), t(:)
      integer, allocatable :: counts(:)
      logical, allocatable :: ok(:)
      character(len=:), allocatable :: names(:), msgs(:), warns(:)
      logical :: failed, any_failed
      character(len=:), allocatable :: effects, profile_coords, result_coords, parameters_text
      integer(i8), allocatable :: c(:,:,:)
      real(wp), parameter :: fill = nf90_fill_double
      integer, parameter :: ifill = nf90_fill_int
      integer(1), parameter :: bfill = nf90_fill_byte
      integer(i8), parameter :: i8fill = -9223372036854775806_i8   ! NC_FILL_INT64

      call prepare_texts()
      if (allocated(w%error)) then
         call move_alloc(w%error, error)
         return
      end if
      call w%create(path)
      if (allocated(w%error)) goto 99
      call define_coordinates()
      call define_results()
      call define_profile_record()
      if (allocated(w%error)) goto 99
      call define_fills_and_coordinates()
      call global_attributes()
      if (allocated(w%error)) goto 99
      call w%check(nf90_enddef(w%ncid), "end of definitions")
      if (allocated(w%error)) goto 99
      call put_coordinates()
      call put_results()
      if (allocated(w%error)) goto 99
      call put_profile_record()
99    continue
      call w%close(error)
   contains
      !> The profiles' names, failure messages and warnings as NUL-padded
      !> character arrays, which profiles ran, the effects, the coordinates.
      subroutine prepare_texts()
         np = size(blocks)
         nd = batch%n_depths
         ns = batch%n_speeds
         lname = 1
         lmsg = 1
         lwarn = 1
         ! a block's message: why it failed, or the warnings of a computed profile
         do i = 1, np
            lname = max(lname, len(batch%names(i)%s))
            if (.not. allocated(blocks(i)%message)) cycle
            if (blocks(i)%status == status_failed) then
               lmsg = max(lmsg, len(blocks(i)%message))
            else
               lwarn = max(lwarn, len(blocks(i)%message))
            end if
         end do
         allocate(character(len=lname) :: names(np), stat=stat)
         if (stat == 0) allocate(character(len=lmsg) :: msgs(np), stat=stat)
         if (stat == 0) allocate(character(len=lwarn) :: warns(np), stat=stat)
         if (stat /= 0) then                                    ! (files) stat_memory
            call fatal_error(w%error, "&output file: not enough memory to write '" // path // "'", &
               & stat_memory)
            return
         end if
         do i = 1, np
            ! NUL-padded, as netCDF readers expect of character arrays
            names(i) = repeat(achar(0), lname)
            names(i)(1:len(batch%names(i)%s)) = printable_utf8(batch%names(i)%s)
            msgs(i) = repeat(achar(0), lmsg)
            warns(i) = repeat(achar(0), lwarn)
            if (.not. allocated(blocks(i)%message)) cycle
            failed = blocks(i)%status == status_failed
            if (failed) msgs(i)(1:len(blocks(i)%message)) = printable_utf8(blocks(i)%message)
            ! the warnings' line breaks are kept (printable_utf8 would blank them)
            if (.not. failed) warns(i)(1:len(blocks(i)%message)) = blocks(i)%message
         end do
         ! profiles read (their preprocessing record is known), and computed
         ok = [(blocks(i)%status == status_computed, i = 1, np)]
         effects = "elastic_contact,facet_friction"
         if (any([(blocks(i)%viscous, i = 1, np)])) effects = effects // ",viscous_memory"
         if (any([(blocks(i)%bearing, i = 1, np)]) .and. len(film_effect) > 0) &
            & effects = effects // "," // film_effect
         any_failed = .not. all(ok)
         profile_coords = "profile_name"
         if (batch%has_chainage) profile_coords = "profile_name chainage"
         result_coords = "speed " // profile_coords

      end subroutine prepare_texts

      !> The dimensions and the coordinate variables.
      subroutine define_coordinates()
         call w%check(nf90_def_dim(w%ncid, "profile", np, d_p), "dimension profile")
         call w%check(nf90_def_dim(w%ncid, "water_depth", nd, d_d), "dimension water_depth")
         call w%check(nf90_def_dim(w%ncid, "speed_kmh", ns, d_s), "dimension speed_kmh")
         call w%check(nf90_def_dim(w%ncid, "name_strlen", lname, d_name), "dimension name_strlen")
         call w%check(nf90_def_dim(w%ncid, "message_strlen", lmsg, d_msg), "dimension message_strlen")
         call w%check(nf90_def_dim(w%ncid, "warning_strlen", lwarn, d_warn), "dimension warning_strlen")
         call w%def("profile", nf90_int, [d_p], "1", "profile number: the profile's place " // &
            & "in the batch (1 = first; the order of the list, or of the sorted file names)", &
            & v_num)
         call w%def("profile_name", nf90_char, [d_name, d_p], "", "profile name: the file name " // &
            & "without directory and extension (the path below the profiles' common " // &
            & "directory when two files share a name)", v_name)
         call w%check(nf90_put_att(w%ncid, v_name, "_Encoding", "utf-8"), "encoding")
         call w%def("water_depth", nf90_double, [d_d], "m", "depth of the water film on " // &
            & "the road surface (the bearing's inlet film; 0: dry)", v_depth)
         call w%def("speed_kmh", nf90_double, [d_s], "km h-1", "sliding speed of the pad", v_kmh)
         call w%def("speed", nf90_double, [d_s], "m s-1", "sliding speed of the pad", v_speed)
         if (batch%has_chainage) then
            call w%def("chainage", nf90_double, [d_p], "m", "distance along the road of the " // &
               & "profile (chainage, from the profile list)", v_chain)
         end if
      end subroutine define_coordinates

      !> The per-speed, per-depth, per-profile results.
      subroutine define_results()
         call def_as_scene("mu", nf90_double, [d_s, d_d, d_p], "1", &
            & "friction coefficient averaged over the profile (Kane et al. 2017, Eq. 12)", v_mu)
         call def_as_scene("mu_hysteresis", nf90_double, [d_s, d_d, d_p], "1", &
            & "the rubber's part of mu: its dissipation per unit load and distance slid", v_muh)
         call def_as_scene("mu_adhesion", nf90_double, [d_s, d_d, d_p], "1", &
            & "the local friction's part of mu: mu_loc's work on the facets per unit load " // &
            & "and distance slid (mu = mu_hysteresis + mu_adhesion)", v_mua)
         call def_as_scene("mu_error_estimate", nf90_double, [d_s, d_d, d_p], "1", &
            & "estimated error of mu from the time step and the pad's elements (&numerics " // &
            & "error_estimate, as in a single scene, docs/outputs.md; or the tolerance's " // &
            & "estimate); " // &
            & "missing where none was made", v_mue)
         call def_as_scene("estimate_elements_per_sample", nf90_int64, [d_s, d_d, d_p], "1", &
            & "elements_per_sample of the finest pass mu_error_estimate was made from (as in " // &
            & "a single scene, docs/outputs.md): the scene's where it halved the time step " // &
            & "only, more where the pad's elements were halved (it stood on fewer than 4 " // &
            & "elements in contact, or the exact integrator ran); missing where no estimate " // &
            & "was made", v_eps)
         call def_as_scene("elements_per_sample_used", nf90_int64, [d_s, d_d, d_p], "1", &
            & "elements_per_sample of the run the results come from (as in a single scene, " // &
            & "docs/outputs.md): the scene's, or more where &numerics min_contacts halved " // &
            & "the pad's elements until it stood on that many in contact; missing where the " // &
            & "profile failed", v_used)
         call def_as_scene("wet_fraction", nf90_double, [d_s, d_d, d_p], "1", &
            & "share of averaged positions where the hydrodynamic bearing carried load", v_wet)
         call def_as_scene("hydroplaning_fraction", nf90_double, [d_s, d_d, d_p], "1", &
            & "share of averaged positions where no element touched the profile", v_hyd)
         call def_as_scene("max_balance_residual", nf90_double, [d_s, d_d, d_p], "1", &
            & "largest |sum F + Wh - W| / W over averaged positions", v_res)
         call def_as_scene("n_clamped", nf90_int64, [d_s, d_d, d_p], "1", &
            & "contacts on facets clamped at theta_max, summed over averaged positions", v_ncl)
      end subroutine define_results

      !> A variable a scene's file has too, under the same long_name (the
      !> scene's few words, output_short_name); the batch's description
      !> whole in comment.
      subroutine def_as_scene(name, xtype, dims, units, description, varid)
         character(len=*), intent(in) :: name, units, description
         integer, intent(in) :: xtype, dims(:)
         integer, intent(out) :: varid
         character(len=:), allocatable :: label
         call output_short_name(name, label)
         call w%def(name, xtype, dims, units, description, varid, label)
      end subroutine def_as_scene

      !> Per profile: texture, status, messages, warnings and the
      !> preprocessing record (as a scene file's preprocess_* attributes).
      subroutine define_profile_record()
         call def_as_scene("mpd", nf90_double, [d_p], "m", "mean profile depth (ISO " // &
            & "13473-1 / ASTM E1845, 100 mm segments, slope suppression)", v_mpd)
         call def_as_scene("rms_height", nf90_double, [d_p], "m", &
            & "RMS profile height about the mean", v_rh)
         call def_as_scene("rms_slope", nf90_double, [d_p], "1", &
            & "RMS slope between neighbouring samples at the profile spacing", v_rs)
         call w%def("status", nf90_byte, [d_p], "", "whether the profile was computed", v_status)
         call w%check(nf90_put_att(w%ncid, v_status, "flag_values", [1_1, 2_1]), "flags")
         call w%check(nf90_put_att(w%ncid, v_status, "flag_meanings", "computed failed"), "flags")
         call w%def("error_message", nf90_char, [d_msg, d_p], "", "why a profile failed", v_err)
         call w%check(nf90_put_att(w%ncid, v_err, "_Encoding", "utf-8"), "encoding")
         call w%def("n_warnings", nf90_int, [d_p], "1", "warnings about the profile and its " // &
            & "results (distinct; those a scene of this profile alone records in its " // &
            & "'warnings')", v_nwarn)
         call w%def("warning_message", nf90_char, [d_warn, d_p], "", "the profile's warnings, " // &
            & "one a line (the first 5; empty: none)", v_warn)
         call w%check(nf90_put_att(w%ncid, v_warn, "_Encoding", "utf-8"), "encoding")
         ! many profiles with the same warnings: compress their text
         call w%check(nf90_def_var_deflate(w%ncid, v_warn, 0, 1, 1), "warning_message")
         ! the preprocessing record of each profile (as a scene file's preprocess_* attributes)
         call w%def("preprocess_points_read", nf90_int, [d_p], "1", "points read from the " // &
            & "profile file", v_pre(1))
         call w%def("preprocess_trimmed_start", nf90_int, [d_p], "1", "points trimmed at the " // &
            & "start (reference plate)", v_pre(2))
         call w%def("preprocess_trimmed_end", nf90_int, [d_p], "1", "points trimmed at the " // &
            & "end (reference plate)", v_pre(3))
         call w%def("preprocess_dropouts", nf90_int, [d_p], "1", "dropouts interpolated", v_pre(4))
         call w%def("preprocess_spikes", nf90_int, [d_p], "1", "spike points replaced", v_pre(5))
         call w%def("preprocess_points_out", nf90_int, [d_p], "1", "points of the profile " // &
            & "the model ran on", v_pre(6))
         call w%def("preprocess_resampled", nf90_byte, [d_p], "", "whether the profile was " // &
            & "resampled", v_pre(7))
         call w%def("preprocess_filtered", nf90_byte, [d_p], "", "whether the profile was " // &
            & "low-pass filtered", v_pre(8))
         call w%def("preprocess_dx_in", nf90_double, [d_p], "m", "spacing of the profile as " // &
            & "read", v_pre(9))
         call w%def("profile_dx", nf90_double, [d_p], "m", "spacing of the profile the model ran on", &
            & v_pre(10))
         do k = 7, 8
            call w%check(nf90_put_att(w%ncid, v_pre(k), "flag_values", [0_1, 1_1]), "flags")
            call w%check(nf90_put_att(w%ncid, v_pre(k), "flag_meanings", "no yes"), "flags")
         end do
      end subroutine define_profile_record

      !> Fill values (missing where a profile failed) and coordinates attributes.
      subroutine define_fills_and_coordinates()
         do k = 1, 10
            select case (k)
            case (1:6)
               if (any_failed) call w%check(nf90_def_var_fill(w%ncid, v_pre(k), 0, ifill), &
                  & "fill value")
            case (7:8)
               if (any_failed) call w%check(nf90_def_var_fill(w%ncid, v_pre(k), 0, bfill), &
                  & "fill value")
            case default
               call w%check(nf90_def_var_fill(w%ncid, v_pre(k), 0, fill), "fill value")
            end select
            call w%check(nf90_put_att(w%ncid, v_pre(k), "coordinates", profile_coords), &
               & "coordinates")
         end do
         if (any_failed) call w%check(nf90_def_var_fill(w%ncid, v_ncl, 0, i8fill), &
            & "fill value")
         if (any_failed) call w%check(nf90_def_var_fill(w%ncid, v_used, 0, i8fill), &
            & "fill value")
         ! missing wherever no estimate was made, not only where a profile failed
         call w%check(nf90_def_var_fill(w%ncid, v_eps, 0, i8fill), "fill value")
         do k = 1, 10
            call fillatt([v_mu, v_muh, v_mua, v_mue, v_wet, v_hyd, v_res, v_mpd, v_rh, v_rs], k)
         end do
         do k = 1, 10
            call coordatt([v_mu, v_muh, v_mua, v_mue, v_eps, v_used, v_wet, v_hyd, v_res, &
               & v_ncl], k, result_coords)
         end do
         do k = 1, 5
            call coordatt([v_mpd, v_rh, v_rs, v_status, v_err], k, profile_coords)
         end do
         do k = 1, 2
            call coordatt([v_nwarn, v_warn], k, profile_coords)
         end do
      end subroutine define_fills_and_coordinates

      !> The file's global attributes.
      subroutine global_attributes()
         call w%gatt("Conventions", "CF-1.10")
         call w%gatt("title", "pavefric batch " // batch%scene%name)
         call w%gatt("source", "pavefric " // pavefric_version)
         call w%gatt("pavefric_version", pavefric_version)
         call w%gatt("references", "Kane, Do, Cerezo, Rado & Khelifi (2017), Contribution to " // &
            & "pavement friction modelling: an introduction of the wetting effect, " // &
            & "Int. J. Pavement Eng., doi:10.1080/10298436.2017.1369776")
         call w%gatt("history", history)
         call w%gatt("effects", effects)
         call w%gatt("warnings", batch%scene%warnings)
         call w%gatt("input_namelist", batch%scene%text)
         call parameters_namelist_text(parameter_table(), batch%scene%parameters, parameters_text)
         call put_parameter_attributes(w, batch%scene%parameters, parameters_text)
         call w%gatt("profiles_computed", count(ok))
         call w%gatt("profiles_failed", count([(blocks(i)%status == status_failed, i = 1, np)]))
         call w%gatt("profiles_with_warnings", count([(blocks(i)%n_warnings > 0, i = 1, np)]))
      end subroutine global_attributes

      subroutine put_coordinates()
         call w%check(nf90_put_var(w%ncid, v_num, [(i, i = 1, np)]), "profile")
         call w%check(nf90_put_var(w%ncid, v_name, names), "profile_name")
         call w%check(nf90_put_var(w%ncid, v_depth, batch%depths), "water_depth")
         call w%check(nf90_put_var(w%ncid, v_kmh, batch%speeds), "speed_kmh")
         call w%check(nf90_put_var(w%ncid, v_speed, batch%speeds * kmh_to_ms), "speed")
         if (batch%has_chainage) call w%check(nf90_put_var(w%ncid, v_chain, batch%chainage), &
            & "chainage")
      end subroutine put_coordinates

      !> The results, missing (fill) where a profile failed.
      subroutine put_results()
         allocate(a(ns, nd, np), c(ns, nd, np), t(np), counts(np), stat=stat)
         if (stat /= 0) call fatal_error(w%error, "&output file: not enough memory to write '" // &
            & path // "'", stat_memory)
         if (allocated(w%error)) return
         do i = 1, np
            a(:, :, i) = merge(blocks(i)%mu, fill, ok(i))
         end do
         call w%check(nf90_put_var(w%ncid, v_mu, a), "mu")
         do i = 1, np
            a(:, :, i) = merge(blocks(i)%mu_hysteresis, fill, ok(i))
         end do
         call w%check(nf90_put_var(w%ncid, v_muh, a), "mu_hysteresis")
         do i = 1, np
            a(:, :, i) = merge(blocks(i)%mu_adhesion, fill, ok(i))
         end do
         call w%check(nf90_put_var(w%ncid, v_mua, a), "mu_adhesion")
         do i = 1, np
            a(:, :, i) = merge(blocks(i)%mu_error, fill, ok(i) .and. blocks(i)%mu_error >= 0.0_wp)
         end do
         call w%check(nf90_put_var(w%ncid, v_mue, a), "mu_error_estimate")
         do i = 1, np
            c(:, :, i) = merge(nint(blocks(i)%estimate_eps, i8), i8fill, &
               & ok(i) .and. blocks(i)%estimate_eps >= 1.0_wp)
         end do
         call w%check(nf90_put_var(w%ncid, v_eps, c), "estimate_elements_per_sample")
         do i = 1, np
            c(:, :, i) = merge(nint(blocks(i)%eps_used, i8), i8fill, ok(i))
         end do
         call w%check(nf90_put_var(w%ncid, v_used, c), "elements_per_sample_used")
         do i = 1, np
            a(:, :, i) = merge(blocks(i)%wet, fill, ok(i))
         end do
         call w%check(nf90_put_var(w%ncid, v_wet, a), "wet_fraction")
         do i = 1, np
            a(:, :, i) = merge(blocks(i)%hydroplaning, fill, ok(i))
         end do
         call w%check(nf90_put_var(w%ncid, v_hyd, a), "hydroplaning_fraction")
         do i = 1, np
            a(:, :, i) = merge(blocks(i)%residual, fill, ok(i))
            c(:, :, i) = merge(nint(blocks(i)%n_clamped, i8), i8fill, ok(i))
         end do
         call w%check(nf90_put_var(w%ncid, v_res, a), "max_balance_residual")
         call w%check(nf90_put_var(w%ncid, v_ncl, c), "n_clamped")
      end subroutine put_results

      !> Texture, status, messages, warnings and the preprocessing record.
      subroutine put_profile_record()
         t = [(merge(blocks(i)%mpd, fill, blocks(i)%has_texture), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_mpd, t), "mpd")
         t = [(merge(blocks(i)%rms_height, fill, blocks(i)%has_texture), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_rh, t), "rms_height")
         t = [(merge(blocks(i)%rms_slope, fill, blocks(i)%has_texture), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_rs, t), "rms_slope")
         call w%check(nf90_put_var(w%ncid, v_status, [(blocks(i)%status, i = 1, np)]), "status")
         call w%check(nf90_put_var(w%ncid, v_err, msgs), "error_message")
         call w%check(nf90_put_var(w%ncid, v_warn, warns), "warning_message")
         counts = [(blocks(i)%n_warnings, i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_nwarn, counts), "n_warnings")
         ! the preprocessing record of the profiles that were read and run
         counts = [(merge(blocks(i)%points_read, ifill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(1), counts), "preprocess_points_read")
         counts = [(merge(blocks(i)%trimmed_start, ifill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(2), counts), "preprocess_trimmed_start")
         counts = [(merge(blocks(i)%trimmed_end, ifill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(3), counts), "preprocess_trimmed_end")
         counts = [(merge(blocks(i)%dropouts, ifill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(4), counts), "preprocess_dropouts")
         counts = [(merge(blocks(i)%spikes, ifill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(5), counts), "preprocess_spikes")
         counts = [(merge(blocks(i)%points_used, ifill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(6), counts), "preprocess_points_out")
         counts = [(merge(merge(1, 0, blocks(i)%resampled), int(bfill), ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(7), counts), "preprocess_resampled")
         counts = [(merge(merge(1, 0, blocks(i)%filtered), int(bfill), ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(8), counts), "preprocess_filtered")
         t = [(merge(blocks(i)%dx_in, fill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(9), t), "preprocess_dx_in")
         t = [(merge(blocks(i)%dx, fill, ok(i)), i = 1, np)]
         call w%check(nf90_put_var(w%ncid, v_pre(10), t), "profile_dx")
      end subroutine put_profile_record

      subroutine fillatt(ids, k)
         integer, intent(in) :: ids(:), k
         call w%check(nf90_def_var_fill(w%ncid, ids(k), 0, fill), "fill value")
      end subroutine fillatt
      subroutine coordatt(ids, k, text)
         integer, intent(in) :: ids(:), k
         character(len=*), intent(in) :: text
         call w%check(nf90_put_att(w%ncid, ids(k), "coordinates", text), "coordinates")
      end subroutine coordatt
   end subroutine write_batch_file

end module pavefric_batch_netcdf
