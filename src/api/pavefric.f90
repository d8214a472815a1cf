!> pavefric: hysteretic rubber friction on a wet pavement texture profile
!> (Kane et al. 2017). The public Fortran API, re-exported from the modules:
!> `use pavefric` is all a user needs (docs/api.md).
!>
!> The program's path: read_scene -> load_scene_profile -> run_profile ->
!> write_results. A session (session_type) bundles a scene, its profile and
!> its results, as the C API's handle does: load_session, session_set_*,
!> session_run, session_get_result, session_write.
module pavefric
   use pavefric_kinds, only: wp, pavefric_version, kmh_to_ms
   use pavefric_error, only: error_type, fatal_error, stat_input, stat_internal, stat_memory, &
      & stat_io
   use pavefric_model, only: model_type, validate_model, param_spec_type, param_set_type, &
      & param_value_type, parameter_table, default_parameters, apply_namelist, find_parameter, &
      & model_from_parameters, parameters_namelist, format_value
   use pavefric_profile, only: profile_type, read_profile_text
   use pavefric_preprocess, only: clean_profile_type, preprocess_type
   use pavefric_simulate, only: sim_result_type, simulate, effects_text
   use pavefric_scene, only: scene_type, read_scene, scene_from_text, scene_from_parameters, &
      & scene_from_typed
   use pavefric_run, only: run_scene, run_profile, load_scene_profile, ctm_dx
   use pavefric_outputs, only: output_var_type, output_table, output_present, output_values, &
      & n_outputs, output_metadata_type, dim_speed, dim_position_speed
   use pavefric_netcdf, only: write_results
   use pavefric_texture, only: texture_type, texture_metrics, mean_profile_depth
   use pavefric_session, only: session_type, load_session, session_from_text, &
      & session_set_parameter, session_set_value, session_get_parameter, session_set_profile, &
      & session_run, session_result_size, session_get_result, session_write, session_warnings, &
      & n_scene_results, scene_results
   implicit none
   private

   ! kinds, constants, errors
   public :: wp, pavefric_version, kmh_to_ms, ctm_dx
   public :: error_type, fatal_error, stat_input, stat_internal, stat_memory, stat_io
   ! parameters: the one table
   public :: model_type, validate_model, param_spec_type, param_set_type, param_value_type
   public :: parameter_table, default_parameters, apply_namelist, find_parameter
   public :: model_from_parameters, parameters_namelist, format_value
   ! scenes, profiles, runs
   public :: scene_type, read_scene, scene_from_text, scene_from_parameters, scene_from_typed
   public :: profile_type, read_profile_text, clean_profile_type, preprocess_type
   public :: load_scene_profile, run_profile, run_scene
   public :: sim_result_type, simulate, effects_text
   ! results and output
   public :: output_var_type, output_table, output_present, output_values, n_outputs
   public :: output_metadata_type, dim_speed, dim_position_speed, write_results
   public :: texture_type, texture_metrics, mean_profile_depth
   ! sessions (what a C API handle holds)
   public :: session_type, load_session, session_from_text, session_set_parameter
   public :: session_set_value, session_get_parameter, session_set_profile, session_run
   public :: session_result_size, n_scene_results, scene_results
   public :: session_get_result, session_write, session_warnings
end module pavefric
