!> A scene: one namelist file holding the surface, pad, rubber, water,
!> operation, numerics and output groups. Reading only; no physics.
!>
!> Every group is optional (defaults apply). An unknown group, an unknown
!> variable or a value that cannot be read is an error naming the group, the
!> variable and the value.
module pavefric_scene
   use pavefric_kinds, only: wp
   use pavefric_error, only: error_type, fatal_error
   use pavefric_format, only: to_str, to_lower
   use pavefric_model, only: model_type
   use pavefric_profile, only: unit_factor
   use pavefric_fsys, only: dir_name, base_name, join_path
   use pavefric_preprocess, only: preprocess_type
   implicit none
   private

   public :: scene_type, read_scene, read_text_file, max_speeds

   !> Largest number of speeds in one scene.
   integer, parameter :: max_speeds = 4096
   integer, parameter :: path_len = 4096

   character(len=*), parameter :: known_groups = &
      & " surface preprocess pad rubber water operation numerics output batch "

   !> A scene read from a namelist file.
   type :: scene_type
      !> Scene name: the namelist file's name without extension.
      character(len=:), allocatable :: name
      !> The namelist file's path and its whole text.
      character(len=:), allocatable :: path, text
      !> Physical and numerical parameters.
      type(model_type) :: model
      !> &surface profile_file, resolved against the namelist's directory.
      character(len=:), allocatable :: profile_file
      !> &surface height_unit: 'mm', 'um' or 'm'.
      character(len=:), allocatable :: height_unit
      !> &surface dx (m); <= 0 when not given (then the file's or 0.87e-3).
      real(wp) :: dx = -1.0_wp
      !> &surface closed: a closed CTM circle (.true.) or an open profile.
      logical :: closed = .true.
      !> &surface format ('auto', 'plain', 'captif', 'csv'), x_column, z_column.
      character(len=:), allocatable :: format, x_column, z_column
      !> &preprocess: making an instrument profile fit for analysis.
      type(preprocess_type) :: preprocess
      !> &operation speeds_kmh.
      real(wp), allocatable :: speeds_kmh(:)
      !> &output file ('' = outputs/<name>.nc) and series.
      character(len=:), allocatable :: output_file
      logical :: series = .false.
      !> Whether the scene is a batch (it has a &batch group).
      logical :: is_batch = .false.
      !> &batch profiles: a file-name pattern or a directory (relative to the
      !> namelist's directory); profile_list: a file naming one profile a line.
      character(len=:), allocatable :: batch_profiles, batch_profile_list
      !> &batch depths (m); empty: &water depth.
      real(wp), allocatable :: batch_depths(:)
      !> &batch restart: resume from the journal of an interrupted run.
      logical :: batch_restart = .true.
      !> &batch progress_every: profiles between progress lines (0: about 20 lines).
      integer :: batch_progress_every = 0
   end type scene_type

   abstract interface
      !> Read one namelist group into `scene`, from `unit` or from `text`.
      subroutine group_reader(scene, ios, msg, unit, text)
         import :: scene_type
         type(scene_type), intent(inout) :: scene
         integer, intent(out) :: ios
         character(len=*), intent(inout) :: msg
         integer, intent(in), optional :: unit
         character(len=*), intent(in), optional :: text
      end subroutine group_reader
   end interface

contains

   !> Read a whole text file into one string (lines joined by newlines).
   subroutine read_text_file(path, text, error)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: text
      type(error_type), allocatable, intent(out) :: error
      integer :: unit, ios, fsize
      character(len=512) :: msg
      open(newunit=unit, file=path, status="old", action="read", access="stream", &
         & form="unformatted", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "cannot open '" // path // "' (" // trim(msg) // ")")
         return
      end if
      inquire(unit=unit, size=fsize)
      allocate(character(len=max(fsize, 0)) :: text)
      if (fsize > 0) read(unit, iostat=ios, iomsg=msg) text
      close(unit)
      if (ios /= 0) call fatal_error(error, "cannot read '" // path // "' (" // trim(msg) // ")")
   end subroutine read_text_file

   !> Read and check a scene file.
   subroutine read_scene(path, scene, error)
      character(len=*), intent(in) :: path
      type(scene_type), intent(out) :: scene
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: groups
      character(len=10), parameter :: group_names(9) = [character(len=10) :: "surface", &
         & "preprocess", "pad", "rubber", "water", "operation", "numerics", "output", "batch"]
      integer :: unit, ios, i
      character(len=512) :: msg

      call read_text_file(path, scene%text, error)
      if (allocated(error)) then
         error%message = "scene file: " // error%message
         return
      end if
      scene%path = path
      scene%name = base_name(path)
      call list_groups(scene%text, path, groups, error)
      if (allocated(error)) return

      open(newunit=unit, file=path, status="old", action="read", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call fatal_error(error, "scene file: cannot open '" // path // "' (" // trim(msg) // ")")
         return
      end if
      scene%profile_file = ""
      scene%height_unit = "mm"
      scene%output_file = ""
      scene%format = "auto"
      scene%x_column = ""
      scene%z_column = ""
      scene%batch_profiles = ""
      scene%batch_profile_list = ""
      do i = 1, size(group_names)
         if (.not. has(groups, trim(group_names(i)))) cycle
         select case (trim(group_names(i)))
         case ("surface")
            call read_group(unit, "surface", "profile_file height_unit dx closed mu_loc " // &
               & "format x_column z_column", nml_surface, scene, error)
         case ("preprocess")
            call read_group(unit, "preprocess", "dropouts trim_plates plate_threshold " // &
               & "plate_min_length plate_buffer spike_slope resample_dx lowpass_wavelength", &
               & nml_preprocess, scene, error)
         case ("pad")
            call read_group(unit, "pad", "length width thickness load shape radius", &
               & nml_pad, scene, error)
         case ("rubber")
            call read_group(unit, "rubber", "stiffness viscosity", nml_rubber, scene, error)
         case ("water")
            call read_group(unit, "water", "depth viscosity alpha beta", nml_water, scene, error)
         case ("operation")
            call read_group(unit, "operation", "speeds_kmh", nml_operation, scene, error)
         case ("numerics")
            call read_group(unit, "numerics", "theta_max_deg substeps elements_per_sample " // &
               & "position_stride wet_tolerance", nml_numerics, scene, error)
         case ("output")
            call read_group(unit, "output", "file series", nml_output, scene, error)
         case ("batch")
            scene%is_batch = .true.
            call read_group(unit, "batch", "profiles profile_list depths restart " // &
               & "progress_every", nml_batch, scene, error)
         end select
         if (allocated(error)) exit
      end do
      close(unit)
      if (allocated(error)) return
      if (unit_factor(scene%height_unit) <= 0.0_wp) then
         call fatal_error(error, "&surface height_unit = '" // scene%height_unit // &
            & "': unknown (expected 'mm', 'um' or 'm')")
         return
      end if
      if (scene%dx /= -1.0_wp .and. .not. (scene%dx > 0.0_wp .and. scene%dx <= huge(1.0_wp))) then
         call fatal_error(error, "&surface dx = " // to_str(scene%dx) // ": must be finite and > 0")
         return
      end if
      if (.not. allocated(scene%speeds_kmh)) then
         call fatal_error(error, "&operation speeds_kmh: not given in '" // path // &
            & "' (a list of sliding speeds in km/h is required)")
         return
      end if
      if (scene%is_batch) then
         if (len(scene%batch_profiles) == 0 .eqv. len(scene%batch_profile_list) == 0) then
            call fatal_error(error, "&batch: give exactly one of profiles (a pattern or " // &
               & "directory) and profile_list (a file) in '" // path // "'")
            return
         end if
         if (allocated(scene%batch_depths)) then
            if (any(.not. (scene%batch_depths >= 0.0_wp .and. scene%batch_depths < huge(1.0_wp)))) then
               call fatal_error(error, "&batch depths: every depth must be finite and >= 0")
               return
            end if
         end if
         if (len(scene%batch_profiles) > 0) scene%batch_profiles = &
            & join_path(dir_name(path), scene%batch_profiles)
         if (len(scene%batch_profile_list) > 0) scene%batch_profile_list = &
            & join_path(dir_name(path), scene%batch_profile_list)
         return
      end if
      if (len(scene%profile_file) == 0) then
         call fatal_error(error, "&surface profile_file: not given in '" // path // "'")
         return
      end if
      scene%profile_file = join_path(dir_name(path), scene%profile_file)
   contains
      pure logical function has(list, name)
         character(len=*), intent(in) :: list, name
         has = index(list, " " // name // " ") > 0
      end function has
   end subroutine read_scene

   !> Names of the groups in `text`, space-separated; an unknown group is an
   !> error (a misspelt group would otherwise be skipped in silence).
   subroutine list_groups(text, path, groups, error)
      character(len=*), intent(in) :: text, path
      character(len=:), allocatable, intent(out) :: groups
      type(error_type), allocatable, intent(out) :: error
      integer :: i, j, lineno
      logical :: in_quote, line_start
      character :: q
      groups = " "
      lineno = 1
      in_quote = .false.
      line_start = .true.
      q = " "
      i = 1
      do while (i <= len(text))
         associate(ch => text(i:i))
            if (ch == achar(10)) then
               lineno = lineno + 1
               line_start = .true.
               in_quote = .false.
            else if (in_quote) then
               if (ch == q) in_quote = .false.
            else if (ch == "'" .or. ch == '"') then
               in_quote = .true.
               q = ch
               line_start = .false.
            else if (ch == "!") then
               do while (i < len(text))
                  if (text(i+1:i+1) == achar(10)) exit
                  i = i + 1
               end do
            else if ((ch == "&" .or. ch == "$") .and. line_start) then
               j = i + 1
               do while (j <= len(text))
                  if (verify(text(j:j), "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_0123456789") /= 0) exit
                  j = j + 1
               end do
               if (j > i + 1) then
                  if (.not. to_lower(text(i+1:j-1)) == "end") then
                     if (index(known_groups, " " // to_lower(text(i+1:j-1)) // " ") == 0) then
                        call fatal_error(error, "&" // text(i+1:j-1) // ": unknown namelist " // &
                           & "group at " // path // ":" // to_str(lineno) // " (known:" // &
                           & known_groups // ")")
                        return
                     end if
                     groups = groups // to_lower(text(i+1:j-1)) // " "
                  end if
               end if
               i = j - 1
               line_start = .false.
            else if (ch /= " " .and. ch /= achar(9) .and. ch /= achar(13)) then
               line_start = .false.
            end if
         end associate
         i = i + 1
      end do
   end subroutine list_groups


   !> Read one group through `reader`; when that fails, find the culprit:
   !> the group's assignments are read one by one from an internal file, so
   !> the message names the group, the variable and the value.
   subroutine read_group(unit, group, names, reader, scene, error)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: group, names
      procedure(group_reader) :: reader
      type(scene_type), intent(inout) :: scene
      type(error_type), allocatable, intent(out) :: error
      type(scene_type) :: trial
      character(len=:), allocatable :: body, assign, name
      character(len=512) :: msg, imsg
      integer :: start, next, ios, eq

      rewind(unit)
      msg = ""
      call reader(scene, ios, msg, unit=unit)
      if (ios == 0) return

      call group_body(unit, group, body)
      start = next_assignment(body, 1)
      do while (start > 0)
         next = next_assignment(body, start + 1)
         if (next > 0) then
            assign = trim(body(start:next-1))
         else
            assign = trim(body(start:))
         end if
         call strip_trailing_comma(assign)
         eq = index(assign, "=")
         name = to_lower(trim(adjustl(assign(1:eq-1))))
         if (index(name, "(") > 0) name = name(1:index(name, "(")-1)
         if (index(" " // names // " ", " " // trim(name) // " ") == 0) then
            call fatal_error(error, "&" // group // " " // trim(name) // " = " // &
               & trim(adjustl(assign(eq+1:))) // ": unknown variable in " // scene%path // &
               & " (known: " // names // ")")
            return
         end if
         imsg = ""
         trial = scene
         call reader(trial, ios, imsg, text="&" // group // " " // assign // " /")
         if (ios /= 0) then
            call fatal_error(error, "&" // group // " " // trim(name) // " = " // &
               & trim(adjustl(assign(eq+1:))) // ": cannot be read as its type in " // &
               & scene%path // " (" // trim(imsg) // ")")
            return
         end if
         start = next
      end do
      call fatal_error(error, "&" // group // ": cannot be read in " // scene%path // " (" // &
         & trim(msg) // ")")
   end subroutine read_group

   subroutine strip_trailing_comma(s)
      character(len=:), allocatable, intent(inout) :: s
      integer :: n
      n = len_trim(s)
      if (n > 0) then
         if (s(n:n) == ",") s = s(1:n-1)
      end if
   end subroutine strip_trailing_comma

   !> The text of group `group` in the file on `unit`, between "&group" and
   !> its terminating "/", comments removed, lines joined with blanks.
   subroutine group_body(unit, group, body)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: group
      character(len=:), allocatable, intent(out) :: body
      character(len=4096) :: line
      integer :: ios, pos, i
      logical :: inside, in_quote
      character :: q
      body = ""
      inside = .false.
      rewind(unit)
      do
         read(unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (.not. inside) then
            pos = index(to_lower(line), "&" // group)
            if (pos == 0 .or. len_trim(line(1:max(pos-1, 0))) > 0) cycle
            inside = .true.
            line = line(pos + len(group) + 1:)
         end if
         in_quote = .false.
         q = " "
         do i = 1, len_trim(line)
            if (in_quote) then
               if (line(i:i) == q) in_quote = .false.
            else if (line(i:i) == "'" .or. line(i:i) == '"') then
               in_quote = .true.
               q = line(i:i)
            else if (line(i:i) == "!") then
               line(i:) = ""
               exit
            else if (line(i:i) == "/") then
               body = body // " " // line(1:i-1)
               return
            end if
         end do
         body = body // " " // trim(line)
      end do
   end subroutine group_body

   !> Start of the next "name =" or "name(i) =" outside quotes, from `from`;
   !> 0 when there is none.
   function next_assignment(body, from) result(pos)
      character(len=*), intent(in) :: body
      integer, intent(in) :: from
      integer :: pos, i, j, k
      logical :: in_quote
      character :: q
      character(len=*), parameter :: ident = &
         & "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_0123456789%"
      pos = 0
      in_quote = .false.
      q = " "
      ! quote state from the start of the body
      do i = 1, from - 1
         if (in_quote) then
            if (body(i:i) == q) in_quote = .false.
         else if (body(i:i) == "'" .or. body(i:i) == '"') then
            in_quote = .true.
            q = body(i:i)
         end if
      end do
      do i = from, len(body)
         if (in_quote) then
            if (body(i:i) == q) in_quote = .false.
            cycle
         end if
         if (body(i:i) == "'" .or. body(i:i) == '"') then
            in_quote = .true.
            q = body(i:i)
            cycle
         end if
         if (verify(body(i:i), ident(1:53)) /= 0) cycle
         if (i > 1) then
            if (verify(body(i-1:i-1), " ," // achar(9)) /= 0) cycle
         end if
         j = i
         do while (j <= len(body))
            if (verify(body(j:j), ident) /= 0) exit
            j = j + 1
         end do
         k = j
         if (k <= len(body)) then
            if (body(k:k) == "(") then
               k = index(body(k:), ")") + k
               if (k == j) cycle
            end if
         end if
         do while (k <= len(body))
            if (body(k:k) /= " ") exit
            k = k + 1
         end do
         if (k <= len(body)) then
            if (body(k:k) == "=") then
               pos = i
               return
            end if
         end if
      end do
   end function next_assignment

   ! --- one namelist per group: read from the file or from a text ----------

   subroutine nml_surface(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      character(len=path_len) :: profile_file
      character(len=16) :: height_unit, format
      character(len=256) :: x_column, z_column
      real(wp) :: dx, mu_loc
      logical :: closed
      namelist /surface/ profile_file, height_unit, dx, closed, mu_loc, format, x_column, z_column
      profile_file = scene%profile_file
      format = scene%format
      x_column = scene%x_column
      z_column = scene%z_column
      height_unit = scene%height_unit
      dx = scene%dx
      closed = scene%closed
      mu_loc = scene%model%mu_loc
      if (present(unit)) read(unit, nml=surface, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=surface, iostat=ios, iomsg=msg)
      scene%profile_file = trim(profile_file)
      scene%height_unit = trim(height_unit)
      scene%dx = dx
      scene%closed = closed
      scene%model%mu_loc = mu_loc
      scene%format = trim(format)
      scene%x_column = trim(x_column)
      scene%z_column = trim(z_column)
   end subroutine nml_surface

   subroutine nml_batch(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      real(wp), parameter :: unset = -huge(1.0_wp)
      character(len=path_len) :: profiles, profile_list
      real(wp) :: depths(max_speeds)
      logical :: restart
      integer :: progress_every, n
      namelist /batch/ profiles, profile_list, depths, restart, progress_every
      profiles = scene%batch_profiles
      profile_list = scene%batch_profile_list
      depths = unset
      restart = scene%batch_restart
      progress_every = scene%batch_progress_every
      if (present(unit)) read(unit, nml=batch, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=batch, iostat=ios, iomsg=msg)
      if (ios /= 0) return
      scene%batch_profiles = trim(profiles)
      scene%batch_profile_list = trim(profile_list)
      scene%batch_restart = restart
      scene%batch_progress_every = progress_every
      n = max_speeds
      do while (n > 0)
         if (depths(n) /= unset) exit
         n = n - 1
      end do
      if (n > 0) scene%batch_depths = depths(1:n)
   end subroutine nml_batch

   subroutine nml_preprocess(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      character(len=16) :: dropouts
      logical :: trim_plates
      real(wp) :: plate_threshold, plate_min_length, plate_buffer, spike_slope, resample_dx
      real(wp) :: lowpass_wavelength
      namelist /preprocess/ dropouts, trim_plates, plate_threshold, plate_min_length, &
         & plate_buffer, spike_slope, resample_dx, lowpass_wavelength
      associate(p => scene%preprocess)
         dropouts = p%dropouts
         trim_plates = p%trim_plates
         plate_threshold = p%plate_threshold
         plate_min_length = p%plate_min_length
         plate_buffer = p%plate_buffer
         spike_slope = p%spike_slope
         resample_dx = p%resample_dx
         lowpass_wavelength = p%lowpass_wavelength
         if (present(unit)) read(unit, nml=preprocess, iostat=ios, iomsg=msg)
         if (present(text)) read(text, nml=preprocess, iostat=ios, iomsg=msg)
         p%dropouts = dropouts
         p%trim_plates = trim_plates
         p%plate_threshold = plate_threshold
         p%plate_min_length = plate_min_length
         p%plate_buffer = plate_buffer
         p%spike_slope = spike_slope
         p%resample_dx = resample_dx
         p%lowpass_wavelength = lowpass_wavelength
      end associate
   end subroutine nml_preprocess

   subroutine nml_pad(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      real(wp) :: length, width, thickness, load, radius
      character(len=16) :: shape
      namelist /pad/ length, width, thickness, load, shape, radius
      length = scene%model%length
      width = scene%model%width
      thickness = scene%model%thickness
      load = scene%model%load
      shape = scene%model%shape
      radius = scene%model%radius
      if (present(unit)) read(unit, nml=pad, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=pad, iostat=ios, iomsg=msg)
      scene%model%length = length
      scene%model%width = width
      scene%model%thickness = thickness
      scene%model%load = load
      scene%model%shape = shape
      scene%model%radius = radius
   end subroutine nml_pad

   subroutine nml_rubber(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      real(wp) :: stiffness, viscosity
      namelist /rubber/ stiffness, viscosity
      stiffness = scene%model%stiffness
      viscosity = scene%model%viscosity
      if (present(unit)) read(unit, nml=rubber, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=rubber, iostat=ios, iomsg=msg)
      scene%model%stiffness = stiffness
      scene%model%viscosity = viscosity
   end subroutine nml_rubber

   subroutine nml_water(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      real(wp) :: depth, viscosity, alpha, beta
      namelist /water/ depth, viscosity, alpha, beta
      depth = scene%model%depth
      viscosity = scene%model%water_viscosity
      alpha = scene%model%alpha
      beta = scene%model%beta
      if (present(unit)) read(unit, nml=water, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=water, iostat=ios, iomsg=msg)
      scene%model%depth = depth
      scene%model%water_viscosity = viscosity
      scene%model%alpha = alpha
      scene%model%beta = beta
   end subroutine nml_water

   subroutine nml_operation(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      real(wp), parameter :: unset = -huge(1.0_wp)
      real(wp) :: speeds_kmh(max_speeds)
      integer :: n
      namelist /operation/ speeds_kmh
      speeds_kmh = unset
      if (present(unit)) read(unit, nml=operation, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=operation, iostat=ios, iomsg=msg)
      if (ios /= 0) return
      n = max_speeds
      do while (n > 0)
         if (speeds_kmh(n) /= unset) exit
         n = n - 1
      end do
      if (n == 0) return
      if (any(speeds_kmh(1:n) == unset)) then
         ios = -99
         msg = "the list of speeds has gaps"
         return
      end if
      scene%speeds_kmh = speeds_kmh(1:n)
   end subroutine nml_operation

   subroutine nml_numerics(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      real(wp) :: theta_max_deg, wet_tolerance
      integer :: substeps, elements_per_sample, position_stride
      namelist /numerics/ theta_max_deg, substeps, elements_per_sample, position_stride, &
         & wet_tolerance
      theta_max_deg = scene%model%theta_max_deg
      substeps = scene%model%substeps
      elements_per_sample = scene%model%elements_per_sample
      position_stride = scene%model%position_stride
      wet_tolerance = scene%model%wet_tolerance
      if (present(unit)) read(unit, nml=numerics, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=numerics, iostat=ios, iomsg=msg)
      scene%model%theta_max_deg = theta_max_deg
      scene%model%substeps = substeps
      scene%model%elements_per_sample = elements_per_sample
      scene%model%position_stride = position_stride
      scene%model%wet_tolerance = wet_tolerance
   end subroutine nml_numerics

   subroutine nml_output(scene, ios, msg, unit, text)
      type(scene_type), intent(inout) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      integer, intent(in), optional :: unit
      character(len=*), intent(in), optional :: text
      character(len=path_len) :: file
      logical :: series
      namelist /output/ file, series
      file = scene%output_file
      series = scene%series
      if (present(unit)) read(unit, nml=output, iostat=ios, iomsg=msg)
      if (present(text)) read(text, nml=output, iostat=ios, iomsg=msg)
      scene%output_file = trim(file)
      scene%series = series
   end subroutine nml_output

end module pavefric_scene
