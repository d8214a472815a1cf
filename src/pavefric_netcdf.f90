!> NetCDF-4 output of a scene's results, with CF-1.10 metadata, and the
!> checked writer type every NetCDF output goes through. Every
!> netCDF call goes through `check`, which adds context to nf90_strerror.
!> The file is built in memory, written under a temporary name when it is
!> complete and renamed on success, so a failed run leaves no half-written
!> output and HDF5 never sees a failing disk (src/pavefric_ncmem.c); the
!> temporary name is on the list a fatal signal cleans up (pavefric_fsys).
module pavefric_netcdf
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   use netcdf
   use pavefric_kinds, only: wp, i8, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_io, stat_memory
   use pavefric_simulate, only: sim_result_type, effects_text
   use pavefric_texture, only: texture_type
   use pavefric_preprocess, only: preprocess_report_type
   use pavefric_fsys, only: rename_file, remove_file, process_id, register_temporary, &
      & release_temporary, test_pause
   use pavefric_format, only: to_str
   implicit none
   private

   public :: write_results, output_metadata_type, temporary_name, commit_temporary
   public :: nc_writer_type

   !> Text that describes where the results came from.
   type :: output_metadata_type
      character(len=:), allocatable :: title, history, input_namelist, profile_file
      real(wp) :: dx = 0.0_wp
      integer :: profile_points = 0
      logical :: closed = .true.
      !> Texture metrics of the profile, when they could be computed.
      logical :: has_texture = .false.
      type(texture_type) :: texture
      character(len=:), allocatable :: texture_note
      !> What preprocessing did to the profile.
      type(preprocess_report_type) :: preprocess
      character(len=:), allocatable :: preprocessing
   end type output_metadata_type

   !> A NetCDF file being written and the first error met: every call goes
   !> through `check`, which adds context to nf90_strerror; after an error the
   !> remaining calls do nothing.
   type :: nc_writer_type
      integer :: ncid = -1
      character(len=:), allocatable :: path
      type(error_type), allocatable :: error
   contains
      procedure :: create => writer_create
      procedure :: check => writer_check
      procedure :: def => writer_def
      procedure, private :: gatt_text, gatt_int
      generic :: gatt => gatt_text, gatt_int
      procedure :: close => writer_close
   end type nc_writer_type

   interface
      function c_nc_create_mem(path, ncid) bind(C, name="pavefric_nc_create_mem") result(status)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: ncid
         integer(c_int) :: status
      end function c_nc_create_mem
      subroutine c_nc_close_to_file(ncid, path, nc_status, errno) &
            & bind(C, name="pavefric_nc_close_to_file")
         import :: c_int, c_char
         integer(c_int), value :: ncid
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), intent(out) :: nc_status, errno
      end subroutine c_nc_close_to_file
      function c_strerror(errno, out, outlen) bind(C, name="pavefric_strerror") result(n)
         import :: c_int, c_char
         integer(c_int), value :: errno, outlen
         character(kind=c_char), intent(out) :: out(*)
         integer(c_int) :: n
      end function c_strerror
   end interface

contains

   !> Start the NetCDF-4 file that `close` will write to `path`. The file is
   !> built in memory and written by pavefric at `close`, so that HDF5 never
   !> meets a failing disk (see src/pavefric_ncmem.c): a full disk is then an
   !> ordinary write error, and the process stays sound.
   subroutine writer_create(w, path)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: path
      integer(c_int) :: status, ncid
      w%path = path
      status = c_nc_create_mem(path // c_null_char, ncid)
      if (status /= nf90_noerr) then
         w%ncid = -1
         call fatal_error(w%error, "&output file: cannot create '" // path // "' (" // &
            & trim(nf90_strerror(int(status))) // ")", stat_of(int(status)))
         return
      end if
      w%ncid = int(ncid)
   end subroutine writer_create

   subroutine writer_check(w, status, what)
      class(nc_writer_type), intent(inout) :: w
      integer, intent(in) :: status
      character(len=*), intent(in) :: what
      if (allocated(w%error)) return
      if (status /= nf90_noerr) call fatal_error(w%error, "&output file: writing " // what // &
         & " to '" // w%path // "' failed (" // trim(nf90_strerror(status)) // ")", &
         & stat_of(status))
   end subroutine writer_check

   !> The status kind of a failed netCDF call: out of memory, or a file that
   !> could not be written (disk full, permissions, file-size limit).
   pure function stat_of(status) result(stat)
      integer, intent(in) :: status
      integer :: stat
      stat = stat_io
      if (status == nf90_enomem) stat = stat_memory
   end function stat_of

   !> Define a variable with its units (none if empty) and long name.
   subroutine writer_def(w, name, xtype, dims, units, long_name, varid)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: name, units, long_name
      integer, intent(in) :: xtype, dims(:)
      integer, intent(out) :: varid
      varid = -1
      if (allocated(w%error)) return
      call w%check(nf90_def_var(w%ncid, name, xtype, dims, varid), "variable " // name)
      if (len(units) > 0) call w%check(nf90_put_att(w%ncid, varid, "units", units), &
         & name // " units")
      call w%check(nf90_put_att(w%ncid, varid, "long_name", long_name), name // " long_name")
   end subroutine writer_def

   subroutine gatt_text(w, name, text)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: name, text
      call w%check(nf90_put_att(w%ncid, nf90_global, name, text), "attribute " // name)
   end subroutine gatt_text

   subroutine gatt_int(w, name, value)
      class(nc_writer_type), intent(inout) :: w
      character(len=*), intent(in) :: name
      integer, intent(in) :: value
      call w%check(nf90_put_att(w%ncid, nf90_global, name, value), "attribute " // name)
   end subroutine gatt_int

   !> Write the file to its path and close it; `error` receives the first
   !> error met, if any. After an error the file is abandoned (nf90_abort)
   !> and nothing is written; the caller removes what a failed write left.
   subroutine writer_close(w, error)
      class(nc_writer_type), intent(inout) :: w
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: status, errno, n
      character(len=256) :: text
      if (w%ncid >= 0) then
         if (allocated(w%error)) then
            status = nf90_abort(w%ncid)
         else
            call c_nc_close_to_file(int(w%ncid, c_int), w%path // c_null_char, status, errno)
            if (status /= nf90_noerr) then
               call fatal_error(w%error, "&output file: closing '" // w%path // "' failed (" // &
                  & trim(nf90_strerror(int(status))) // ")", stat_of(int(status)))
            else if (errno /= 0) then
               text = ""
               n = c_strerror(errno, text, len(text, c_int))
               call fatal_error(w%error, "&output file: writing '" // w%path // "' failed (" // &
                  & text(1:n) // ")", stat_io)
            end if
         end if
         w%ncid = -1
      end if
      if (allocated(w%error)) call move_alloc(w%error, error)
   end subroutine writer_close

   !> The temporary name a final path is first written under. The name goes
   !> on the list of temporary files a fatal signal removes (in the
   !> program); `commit_temporary` takes it off.
   function temporary_name(path) result(tmp)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: tmp
      tmp = path // ".tmp" // to_str(process_id())
      call register_temporary(tmp)
   end function temporary_name

   !> Write `res` to `path` (NetCDF-4), via a temporary file and a rename.
   subroutine write_results(path, res, meta, error)
      character(len=*), intent(in) :: path
      type(sim_result_type), intent(in) :: res
      type(output_metadata_type), intent(in) :: meta
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      tmp = temporary_name(path)
      call write_file(tmp, res, meta, error)
      call commit_temporary(tmp, path, error)
   end subroutine write_results

   !> Rename a finished temporary file onto `path`; remove it when writing
   !> failed (`error` allocated on entry) or the rename fails. An existing
   !> `path` is replaced only by a complete file. The temporary name leaves
   !> the list a fatal signal cleans up.
   subroutine commit_temporary(tmp, path, error)
      character(len=*), intent(in) :: tmp, path
      type(error_type), allocatable, intent(inout) :: error
      logical :: ok
      if (.not. allocated(error)) then
         call test_pause("commit")
         if (.not. rename_file(tmp, path)) call fatal_error(error, "&output file = '" // path // &
            & "': cannot rename the finished temporary file onto it", stat_io)
      end if
      if (allocated(error)) ok = remove_file(tmp)
      call release_temporary(tmp)
   end subroutine commit_temporary

   subroutine write_file(path, res, meta, error)
      character(len=*), intent(in) :: path
      type(sim_result_type), intent(in) :: res
      type(output_metadata_type), intent(in) :: meta
      type(error_type), allocatable, intent(out) :: error
      type(nc_writer_type) :: w
      integer :: d_speed, d_pos
      integer :: v_speed, v_kmh, v_mu, v_ncl, v_hyd, v_wet, v_res, v_mwh, v_comp, v_nbe
      integer :: v_mem, v_vis, v_bea, v_pos, v_mui, v_hl, v_pen, v_ce, v_mpd, v_rh, v_rs
      logical :: series

      series = allocated(res%mu_inst)
      call w%create(path)
      if (allocated(w%error)) goto 99

      call w%check(nf90_def_dim(w%ncid, "speed", size(res%speed), d_speed), "dimension speed")
      if (allocated(w%error)) goto 99
      call w%def("speed", nf90_double, [d_speed], "m s-1", "sliding speed of the pad", v_speed)
      if (allocated(w%error)) goto 99
      call w%check(nf90_put_att(w%ncid, v_speed, "axis", "X"), "speed axis")
      call w%def("speed_kmh", nf90_double, [d_speed], "km h-1", "sliding speed of the pad", &
         & v_kmh)
      call w%def("mu", nf90_double, [d_speed], "1", &
         & "friction coefficient averaged over the profile (Kane et al. 2017, Eq. 12)", v_mu)
      call w%def("n_clamped", nf90_int64, [d_speed], "1", &
         & "contacts on facets clamped at theta_max, summed over averaged positions", v_ncl)
      call w%def("hydroplaning_fraction", nf90_double, [d_speed], "1", &
         & "share of averaged positions where no element touched the profile", v_hyd)
      call w%def("wet_fraction", nf90_double, [d_speed], "1", &
         & "share of averaged positions where the hydrodynamic bearing carried load", v_wet)
      call w%def("max_balance_residual", nf90_double, [d_speed], "1", &
         & "largest |sum F + Wh - W| / W over averaged positions", v_res)
      call w%def("mean_hydro_load", nf90_double, [d_speed], "N", &
         & "load carried by the hydrodynamic bearing, averaged over positions", v_mwh)
      call w%def("max_compression", nf90_double, [d_speed], "m", &
         & "largest compression of a rubber element (compare with the pad thickness)", v_comp)
      call w%def("bearing_evaluations", nf90_int64, [d_speed], "1", &
         & "evaluations of the bearing load formula (0: the bearing did not run)", v_nbe)
      call w%def("memory_updates", nf90_int64, [d_speed], "1", &
         & "element-steps that updated viscous memory (0: no viscous memory kept)", v_mem)
      call w%def("viscous_memory_ran", nf90_byte, [d_speed], "", &
         & "whether the rubber elements carried viscous memory", v_vis)
      call w%def("bearing_ran", nf90_byte, [d_speed], "", &
         & "whether the hydrodynamic bearing took part in the load balance", v_bea)
      if (meta%has_texture) then
         call w%def("mpd", nf90_double, [integer ::], "m", &
            & "mean profile depth (ISO 13473-1 / ASTM E1845, 100 mm segments, slope " // &
            & "suppression)", v_mpd)
         call w%check(nf90_put_att(w%ncid, v_mpd, "n_segments", meta%texture%n_segments), "mpd")
         call w%check(nf90_put_att(w%ncid, v_mpd, "n_valid_segments", meta%texture%n_valid), "mpd")
         call w%def("rms_height", nf90_double, [integer ::], "m", &
            & "RMS profile height about the mean", v_rh)
         call w%def("rms_slope", nf90_double, [integer ::], "1", &
            & "RMS slope between neighbouring samples at the profile spacing", v_rs)
      end if
      if (allocated(w%error)) goto 99
      call flags(v_vis)
      call flags(v_bea)
      if (series) then
         call w%check(nf90_def_dim(w%ncid, "position", res%n_positions, d_pos), "dimension position")
         call w%def("position", nf90_double, [d_pos], "m", &
            & "distance slid from the first averaged position", v_pos)
         call w%def("mu_inst", nf90_double, [d_pos, d_speed], "1", &
            & "instantaneous friction coefficient (Kane et al. 2017, Eq. 11)", v_mui)
         call w%def("hydro_load", nf90_double, [d_pos, d_speed], "N", &
            & "load carried by the hydrodynamic bearing (Eq. 15)", v_hl)
         call w%def("penetration", nf90_double, [d_pos, d_speed], "m", &
            & "global penetration delta of the pad (Eq. 4)", v_pen)
         call w%def("contact_elements", nf90_int, [d_pos, d_speed], "1", &
            & "pad elements in contact with the profile", v_ce)
      end if
      if (allocated(w%error)) goto 99

      call w%gatt("Conventions", "CF-1.10")
      call w%gatt("title", meta%title)
      call w%gatt("source", "pavefric " // pavefric_version)
      call w%gatt("pavefric_version", pavefric_version)
      call w%gatt("references", "Kane, Do, Cerezo, Rado & Khelifi (2017), Contribution to " // &
         & "pavement friction modelling: an introduction of the wetting effect, " // &
         & "Int. J. Pavement Eng., doi:10.1080/10298436.2017.1369776")
      call w%gatt("history", meta%history)
      call w%gatt("effects", effects_text(res))
      call w%gatt("profile_file", meta%profile_file)
      call w%gatt("input_namelist", meta%input_namelist)
      if (allocated(meta%texture_note)) call w%gatt("texture_note", meta%texture_note)
      if (allocated(meta%preprocessing)) then
         call w%gatt("preprocessing", meta%preprocessing)
         call w%gatt("preprocess_format", meta%preprocess%format)
         call w%gatt("preprocess_points_read", meta%preprocess%points_read)
         call w%gatt("preprocess_trimmed_start", meta%preprocess%trimmed_start)
         call w%gatt("preprocess_trimmed_end", meta%preprocess%trimmed_end)
         call w%gatt("preprocess_dropouts", meta%preprocess%dropouts)
         call w%gatt("preprocess_spikes", meta%preprocess%spikes)
         call w%gatt("preprocess_points_out", meta%preprocess%points_out)
         call w%gatt("preprocess_resampled", merge(1, 0, meta%preprocess%resampled))
         call w%gatt("preprocess_filtered", merge(1, 0, meta%preprocess%filtered))
         call w%check(nf90_put_att(w%ncid, nf90_global, "preprocess_dx_in", meta%preprocess%dx_in), &
            & "att")
      end if
      call w%check(nf90_put_att(w%ncid, nf90_global, "profile_points", meta%profile_points), "att")
      call w%check(nf90_put_att(w%ncid, nf90_global, "profile_dx", meta%dx), "att")
      call w%check(nf90_put_att(w%ncid, nf90_global, "profile_closed", merge(1, 0, meta%closed)), &
         & "att")
      call w%check(nf90_put_att(w%ncid, nf90_global, "pad_elements", res%n_elements), "att")
      call w%check(nf90_put_att(w%ncid, nf90_global, "averaged_positions", res%n_positions), "att")
      call w%check(nf90_put_att(w%ncid, nf90_global, "spinup_positions", res%n_spinup), "att")
      if (allocated(w%error)) goto 99
      call w%check(nf90_enddef(w%ncid), "end of definitions")
      if (allocated(w%error)) goto 99

      call w%check(nf90_put_var(w%ncid, v_speed, res%speed), "speed")
      call w%check(nf90_put_var(w%ncid, v_kmh, res%speed_kmh), "speed_kmh")
      call w%check(nf90_put_var(w%ncid, v_mu, res%mu), "mu")
      call w%check(nf90_put_var(w%ncid, v_ncl, res%n_clamped), "n_clamped")
      call w%check(nf90_put_var(w%ncid, v_hyd, res%hydroplaning_fraction), "hydroplaning_fraction")
      call w%check(nf90_put_var(w%ncid, v_wet, res%wet_fraction), "wet_fraction")
      call w%check(nf90_put_var(w%ncid, v_res, res%max_balance_residual), "max_balance_residual")
      call w%check(nf90_put_var(w%ncid, v_mwh, res%mean_hydro_load), "mean_hydro_load")
      call w%check(nf90_put_var(w%ncid, v_comp, res%max_compression), "max_compression")
      call w%check(nf90_put_var(w%ncid, v_nbe, res%bearing_evaluations), "bearing_evaluations")
      call w%check(nf90_put_var(w%ncid, v_mem, res%memory_updates), "memory_updates")
      call w%check(nf90_put_var(w%ncid, v_vis, merge(1, 0, res%viscous_memory_ran)), "flags")
      call w%check(nf90_put_var(w%ncid, v_bea, merge(1, 0, res%bearing_ran)), "flags")
      if (meta%has_texture) then
         call w%check(nf90_put_var(w%ncid, v_mpd, meta%texture%mpd), "mpd")
         call w%check(nf90_put_var(w%ncid, v_rh, meta%texture%rms_height), "rms_height")
         call w%check(nf90_put_var(w%ncid, v_rs, meta%texture%rms_slope), "rms_slope")
      end if
      if (series) then
         call w%check(nf90_put_var(w%ncid, v_pos, res%position), "position")
         call w%check(nf90_put_var(w%ncid, v_mui, res%mu_inst), "mu_inst")
         call w%check(nf90_put_var(w%ncid, v_hl, res%hydro_load), "hydro_load")
         call w%check(nf90_put_var(w%ncid, v_pen, res%penetration), "penetration")
         call w%check(nf90_put_var(w%ncid, v_ce, res%contact_elements), "contact_elements")
      end if
99    continue
      call w%close(error)

   contains

      subroutine flags(varid)
         integer, intent(in) :: varid
         call w%check(nf90_put_att(w%ncid, varid, "flag_values", [0_1, 1_1]), "flag_values")
         call w%check(nf90_put_att(w%ncid, varid, "flag_meanings", "no yes"), "flag_meanings")
      end subroutine flags

   end subroutine write_file

end module pavefric_netcdf
