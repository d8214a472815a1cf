!> NetCDF-4 output of a batch run (profile x depth x speed), through the
!> checked writer of pavefric_netcdf: temp file and rename, first error kept.
module pavefric_batch_netcdf
   use netcdf
   use pavefric_kinds, only: wp, i8, pavefric_version
   use pavefric_error, only: error_type, fatal_error, stat_memory
   use pavefric_batch_types, only: batch_type, block_type
   use pavefric_netcdf, only: nc_writer_type, temporary_name, commit_temporary
   implicit none
   private

   public :: write_batch_results

contains

   !> Write a batch's results (profile x depth x speed) to `path`, via a
   !> temporary file and a rename. `history` goes into the history attribute.
   subroutine write_batch_results(path, batch, blocks, history, error)
      character(len=*), intent(in) :: path, history
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      tmp = temporary_name(path)
      call write_batch_file(tmp, batch, blocks, history, error)
      call commit_temporary(tmp, path, error)
   end subroutine write_batch_results

   subroutine write_batch_file(path, batch, blocks, history, error)
      character(len=*), intent(in) :: path, history
      type(batch_type), intent(in) :: batch
      type(block_type), intent(in) :: blocks(:)
      type(error_type), allocatable, intent(out) :: error
      type(nc_writer_type) :: w
      integer :: stat, d_p, d_d, d_s, d_name, d_msg, np, nd, ns, lname, lmsg, i
      integer :: v_name, v_depth, v_speed, v_kmh, v_mu, v_wet, v_hyd, v_res, v_ncl, v_mpd, v_rh
      integer :: v_rs, v_status, v_err, ids(10)
      real(wp), allocatable :: a(:,:,:), t(:)
      character(len=:), allocatable :: names(:), msgs(:)
      character(len=:), allocatable :: effects
      integer(i8), allocatable :: c(:,:,:)
      real(wp), parameter :: fill = nf90_fill_double

      np = size(blocks)
      nd = batch%n_depths
      ns = batch%n_speeds
      lname = 1
      lmsg = 1
      do i = 1, np
         lname = max(lname, len(batch%names(i)%s))
         if (allocated(blocks(i)%message)) lmsg = max(lmsg, len(blocks(i)%message))
      end do
      allocate(character(len=lname) :: names(np), stat=stat)
      if (stat == 0) allocate(character(len=lmsg) :: msgs(np), stat=stat)
      if (stat /= 0) then                                    ! (files) stat_memory
         call fatal_error(error, "&output file: not enough memory to write '" // path // "'", &
            & stat_memory)
         return
      end if
      do i = 1, np
         names(i) = batch%names(i)%s
         msgs(i) = ""
         if (allocated(blocks(i)%message)) msgs(i) = blocks(i)%message
      end do
      effects = "elastic_contact,facet_friction"
      if (any([(blocks(i)%viscous, i = 1, np)])) effects = effects // ",viscous_memory"
      if (any([(blocks(i)%bearing, i = 1, np)])) effects = effects // ",hydrodynamic_bearing"

      call w%create(path)
      if (allocated(w%error)) goto 99
      call w%check(nf90_def_dim(w%ncid, "profile", np, d_p), "dimension profile")
      call w%check(nf90_def_dim(w%ncid, "depth", nd, d_d), "dimension depth")
      call w%check(nf90_def_dim(w%ncid, "speed", ns, d_s), "dimension speed")
      call w%check(nf90_def_dim(w%ncid, "name_strlen", lname, d_name), "dimension name_strlen")
      call w%check(nf90_def_dim(w%ncid, "message_strlen", lmsg, d_msg), "dimension message_strlen")
      call w%def("profile_name", nf90_char, [d_name, d_p], "", "profile file name, without " // &
         & "directory and extension", v_name)
      call w%check(nf90_put_att(w%ncid, v_name, "_Encoding", "utf-8"), "encoding")
      call w%def("depth", nf90_double, [d_d], "m", "water depth (inlet film of the bearing)", v_depth)
      call w%def("speed", nf90_double, [d_s], "m s-1", "sliding speed of the pad", v_speed)
      call w%def("speed_kmh", nf90_double, [d_s], "km h-1", "sliding speed of the pad", v_kmh)
      call w%def("mu", nf90_double, [d_s, d_d, d_p], "1", &
         & "friction coefficient averaged over the profile (Kane et al. 2017, Eq. 12)", v_mu)
      call w%def("wet_fraction", nf90_double, [d_s, d_d, d_p], "1", &
         & "share of averaged positions where the hydrodynamic bearing carried load", v_wet)
      call w%def("hydroplaning_fraction", nf90_double, [d_s, d_d, d_p], "1", &
         & "share of averaged positions where no element touched the profile", v_hyd)
      call w%def("max_balance_residual", nf90_double, [d_s, d_d, d_p], "1", &
         & "largest |sum F + Wh - W| / W over averaged positions", v_res)
      call w%def("n_clamped", nf90_int64, [d_s, d_d, d_p], "1", &
         & "contacts on facets clamped at theta_max, summed over averaged positions", v_ncl)
      call w%def("mpd", nf90_double, [d_p], "m", "mean profile depth (ISO 13473-1 / " // &
         & "ASTM E1845, 100 mm segments, slope suppression)", v_mpd)
      call w%def("rms_height", nf90_double, [d_p], "m", "RMS profile height about the mean", v_rh)
      call w%def("rms_slope", nf90_double, [d_p], "1", "RMS slope at the profile spacing", v_rs)
      call w%def("status", nf90_byte, [d_p], "", "whether the profile was computed", v_status)
      call w%check(nf90_put_att(w%ncid, v_status, "flag_values", [1_1, 2_1]), "flags")
      call w%check(nf90_put_att(w%ncid, v_status, "flag_meanings", "computed failed"), "flags")
      call w%def("error_message", nf90_char, [d_msg, d_p], "", "why a profile failed", v_err)
      call w%check(nf90_put_att(w%ncid, v_err, "_Encoding", "utf-8"), "encoding")
      do i = 1, 7
         call fillatt([v_mu, v_wet, v_hyd, v_res, v_mpd, v_rh, v_rs], i)
      end do
      ! the profile names label every per-profile variable (CF auxiliary coordinate)
      ids = [v_mu, v_wet, v_hyd, v_res, v_ncl, v_mpd, v_rh, v_rs, v_status, v_err]
      do i = 1, size(ids)
         call w%check(nf90_put_att(w%ncid, ids(i), "coordinates", "profile_name"), "coordinates")
      end do
      call w%gatt("Conventions", "CF-1.10")
      call w%gatt("title", "pavefric batch " // batch%scene%name)
      call w%gatt("source", "pavefric " // pavefric_version)
      call w%gatt("pavefric_version", pavefric_version)
      call w%gatt("history", history)
      call w%gatt("effects", effects)
      call w%gatt("input_namelist", batch%scene%text)
      call w%check(nf90_put_att(w%ncid, nf90_global, "profiles_failed", count([(blocks(i)%status &
         & == 2, i = 1, np)])), "att")
      if (allocated(w%error)) goto 99
      call w%check(nf90_enddef(w%ncid), "end of definitions")
      if (allocated(w%error)) goto 99

      call w%check(nf90_put_var(w%ncid, v_name, names), "profile_name")
      call w%check(nf90_put_var(w%ncid, v_depth, batch%depths), "depth")
      call w%check(nf90_put_var(w%ncid, v_speed, batch%speeds / 3.6_wp), "speed")
      call w%check(nf90_put_var(w%ncid, v_kmh, batch%speeds), "speed_kmh")
      allocate(a(ns, nd, np), c(ns, nd, np), t(np), stat=stat)
      if (stat /= 0) call fatal_error(w%error, "&output file: not enough memory to write '" // &
         & path // "'", stat_memory)                       ! (files) stat_memory
      if (allocated(w%error)) goto 99
      do i = 1, np
         a(:, :, i) = merge(blocks(i)%mu, fill, blocks(i)%status == 1)
      end do
      call w%check(nf90_put_var(w%ncid, v_mu, a), "mu")
      do i = 1, np
         a(:, :, i) = merge(blocks(i)%wet, fill, blocks(i)%status == 1)
      end do
      call w%check(nf90_put_var(w%ncid, v_wet, a), "wet_fraction")
      do i = 1, np
         a(:, :, i) = merge(blocks(i)%hydroplaning, fill, blocks(i)%status == 1)
      end do
      call w%check(nf90_put_var(w%ncid, v_hyd, a), "hydroplaning_fraction")
      do i = 1, np
         a(:, :, i) = merge(blocks(i)%residual, fill, blocks(i)%status == 1)
         c(:, :, i) = nint(blocks(i)%n_clamped, i8)
      end do
      call w%check(nf90_put_var(w%ncid, v_res, a), "max_balance_residual")
      call w%check(nf90_put_var(w%ncid, v_ncl, c), "n_clamped")
      t = [(merge(blocks(i)%mpd, fill, blocks(i)%has_texture), i = 1, np)]
      call w%check(nf90_put_var(w%ncid, v_mpd, t), "mpd")
      t = [(merge(blocks(i)%rms_height, fill, blocks(i)%has_texture), i = 1, np)]
      call w%check(nf90_put_var(w%ncid, v_rh, t), "rms_height")
      t = [(merge(blocks(i)%rms_slope, fill, blocks(i)%has_texture), i = 1, np)]
      call w%check(nf90_put_var(w%ncid, v_rs, t), "rms_slope")
      call w%check(nf90_put_var(w%ncid, v_status, [(blocks(i)%status, i = 1, np)]), "status")
      call w%check(nf90_put_var(w%ncid, v_err, msgs), "error_message")
99    continue
      call w%close(error)
   contains
      subroutine fillatt(ids, k)
         integer, intent(in) :: ids(:), k
         call w%check(nf90_def_var_fill(w%ncid, ids(k), 0, fill), "fill value")
      end subroutine fillatt
   end subroutine write_batch_file

end module pavefric_batch_netcdf
