/* pavefric: tyre-rubber/pavement friction from a texture profile, dry and wet
 * (Kane et al. 2017). The C API of libpavefric; docs/api.md explains it.
 *
 * Build:  cc my.c $(pkg-config --cflags --libs pavefric)
 *         (after pip install: PKG_CONFIG_PATH=$(pavefric-config --pkgconfigdir))
 *
 * Conventions
 * - Handles (pavefric_error, pavefric_scene) are opaque heap objects owned by
 *   the caller: create them with pavefric_new_error, pavefric_load_scene or
 *   pavefric_new_scene and free them with pavefric_delete_error /
 *   pavefric_delete_scene, which set the caller's pointer to NULL (deleting
 *   NULL does nothing).
 * - Every call that takes an error handle first clears it, then sets it on
 *   failure with a message naming the input (the namelist group, variable
 *   and value, or the file and line), as the pavefric program reports it.
 *   Check it after each call: pavefric_check_error(error) is 1 when set.
 *   Nothing stops the process.
 * - A NULL error handle makes a call do nothing (it returns NULL, 0 or -1).
 *   A NULL scene, string or array, or a too small array, sets the error.
 * - Text comes out NUL-terminated into (buffer, buffer_size), truncated to
 *   buffer_size - 1 bytes; the functions returning int give the whole
 *   length (without the NUL), so a caller can retry with more room.
 * - Units are SI (heights and spacing in m), speeds in km/h as in the
 *   namelists; arrays are plain C arrays of double.
 * - No global state: different scene handles may be used from different
 *   threads at once (each with its own error handle); one handle must not
 *   be used by two threads at the same time.
 */
#ifndef PAVEFRIC_H
#define PAVEFRIC_H

#ifdef __cplusplus
extern "C" {
#endif

/** Error handle: the last call's error (opaque). */
typedef struct pavefric_error_type *pavefric_error;
/** Scene handle: a scene's parameters, its profile, its last results (opaque). */
typedef struct pavefric_scene_type *pavefric_scene;

/** Error kinds (pavefric_get_error_status). */
#define PAVEFRIC_OK 0
#define PAVEFRIC_INPUT_ERROR 1    /* bad input: a namelist value, a profile, a scene */
#define PAVEFRIC_INTERNAL_ERROR 2 /* an inconsistency inside pavefric (please report) */
#define PAVEFRIC_MEMORY_ERROR 3   /* not enough memory for the work asked for */
#define PAVEFRIC_IO_ERROR 4       /* a file could not be written or read back */

/** Library version as 10000 * major + 100 * minor + patch. */
int pavefric_get_version(void);

/* --- errors ------------------------------------------------------------ */

/** A new error handle (no error set); NULL when memory is exhausted. */
pavefric_error pavefric_new_error(void);
/** 1 if the last call set an error, 0 if not, 2 for a NULL handle. */
int pavefric_check_error(pavefric_error error);
/** The error's kind: PAVEFRIC_OK (none) ... PAVEFRIC_IO_ERROR; -1 for NULL. */
int pavefric_get_error_status(pavefric_error error);
/** The message ("" when none) into buffer[buffer_size], NUL-terminated and
 *  truncated; nothing is written for a NULL buffer or buffer_size < 1. */
void pavefric_get_error(pavefric_error error, char *buffer, int buffer_size);
/** Length of the message in bytes, without the NUL (0 when none). */
int pavefric_get_error_length(pavefric_error error);
/** Free the handle and set *error to NULL. */
void pavefric_delete_error(pavefric_error *error);

/* --- scenes ------------------------------------------------------------ */

/** Read and check the scene namelist at namelist_path as the program does.
 *  Its profile file is read (and preprocessed) at the first pavefric_run,
 *  unless pavefric_set_profile gives the heights first. NULL on failure. */
pavefric_scene pavefric_load_scene(pavefric_error error, const char *namelist_path);
/** A scene from namelist text (the groups of a scene file; no file is
 *  read): &operation speeds_kmh and &surface dx are required, the heights
 *  come from pavefric_set_profile. NULL on failure. */
pavefric_scene pavefric_new_scene(pavefric_error error, const char *namelist_text);
/** Free the handle and set *scene to NULL. */
void pavefric_delete_scene(pavefric_scene *scene);

/** Number of speeds (&operation speeds_kmh); 0 for a NULL handle. */
int pavefric_get_speed_count(pavefric_scene scene);
/** The speeds (km/h), in the scene's order, into speeds_kmh[size]. */
void pavefric_get_speeds(pavefric_error error, pavefric_scene scene, double *speeds_kmh,
                         int size);

/** Set &group name = value, the value written as in a namelist ("1e-3",
 *  ".true.", "'rounded'", "20, 40, 60"), read by the program's namelist
 *  reader with its checks and messages. On error the scene is unchanged. */
void pavefric_set_parameter(pavefric_error error, pavefric_scene scene, const char *group,
                            const char *name, const char *value);
/** Typed setters: &group name = value from a C value, checked against the
 *  variable's declaration (range, choices, list length) as the namelist
 *  reader checks it, with its messages, and no namelist text in between.
 *  _double sets a real variable (or a list to one value), _int a whole
 *  number (or a real), _bool a logical (value 0 or 1), _text a text
 *  variable (without quotes), _doubles a list of n values (n = 0 unsets
 *  it). A value of another type than the variable's is an error naming
 *  both. On error the scene is unchanged. */
void pavefric_set_parameter_double(pavefric_error error, pavefric_scene scene,
                                   const char *group, const char *name, double value);
void pavefric_set_parameter_int(pavefric_error error, pavefric_scene scene,
                                const char *group, const char *name, int value);
void pavefric_set_parameter_bool(pavefric_error error, pavefric_scene scene,
                                 const char *group, const char *name, int value);
void pavefric_set_parameter_text(pavefric_error error, pavefric_scene scene,
                                 const char *group, const char *name, const char *value);
void pavefric_set_parameter_doubles(pavefric_error error, pavefric_scene scene,
                                    const char *group, const char *name, int n,
                                    const double *values);
/** The value of &group name the scene uses, as namelist text, into
 *  buffer[buffer_size]; returns its whole length (0: an optional variable
 *  not set, or an error). */
int pavefric_get_parameter(pavefric_error error, pavefric_scene scene, const char *group,
                           const char *name, char *buffer, int buffer_size);

/** Give the profile: n heights (m) at spacing dx_m (m), closed = 1 for a
 *  closed CTM circle, 0 for an open profile. dx_m and closed become the
 *  scene's &surface dx and closed. The heights are copied. */
void pavefric_set_profile(pavefric_error error, pavefric_scene scene, int n,
                          const double *heights_m, double dx_m, int closed);

/** Run the model. mu[pavefric_get_speed_count(scene)] receives the
 *  scene-averaged friction per speed, in the scene's speed order (mu may be
 *  NULL). Other results: pavefric_get_result. */
void pavefric_run(pavefric_error error, pavefric_scene scene, double *mu);

/* --- results of the last run ------------------------------------------- */

/** Number of result names: speed_kmh, speed (m/s), position (m, series
 *  only), then every variable of the output file's table (docs/outputs.md),
 *  then the file's scalars mpd, rms_height, rms_slope, ifi_f60, ifi_sp and
 *  speed_constant (one value each, where the run has it). */
int pavefric_get_result_count(void);
/** Result name number index (0-based) into buffer[buffer_size]; returns its
 *  length (0 when index is out of range). */
int pavefric_get_result_name(int index, char *buffer, int buffer_size);
/** Number of values of result name after the last run: the speed count for
 *  per-speed variables, positions x speeds for series (&output series), 1
 *  for a scalar;
 *  0 when the run has no such variable or before a run; -1 (error set)
 *  for an unknown name. */
int pavefric_get_result_size(pavefric_error error, pavefric_scene scene, const char *name);
/** Values of result name into values[size]: per speed in the scene's speed
 *  order; series as [speed][position] (position varying fastest);
 *  integers and flags as exact doubles. The same bits as the program's
 *  NetCDF file and pavefric.simulate in Python. */
void pavefric_get_result(pavefric_error error, pavefric_scene scene, const char *name,
                         double *values, int size);
/** The warnings about the scene and, after a run, its results (one a line,
 *  as the program prints and records them) into buffer[buffer_size];
 *  returns their whole length (0: none). */
int pavefric_get_warnings(pavefric_error error, pavefric_scene scene, char *buffer,
                          int buffer_size);
/** Write the last run's results to the NetCDF file path: the program's
 *  output file (a temporary file, renamed when complete). */
void pavefric_write_output(pavefric_error error, pavefric_scene scene, const char *path);

#ifdef __cplusplus
}
#endif

#endif /* PAVEFRIC_H */
