!> pavefric: hysteretic rubber friction on a wet pavement texture profile
!> (Kane et al. 2017). The public API, re-exported from the modules.
module pavefric
   use pavefric_kinds, only: wp, pavefric_version
   use pavefric_error, only: error_type
   use pavefric_model, only: model_type, validate_model
   use pavefric_profile, only: profile_type, read_profile_text
   use pavefric_simulate, only: sim_result_type, simulate, effects_text
   use pavefric_scene, only: scene_type, read_scene
   use pavefric_run, only: run_scene
   use pavefric_texture, only: texture_type, texture_metrics, mean_profile_depth
   implicit none
   public
end module pavefric
