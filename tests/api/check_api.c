/* Test driver of the C API (tests/test_api.py builds it outside the source
 * tree against the installed library through pkg-config).
 *
 *   check_api dump SCENE OUTPUT.nc [HEIGHTS.bin DX CLOSED]
 *       run the scene (its profile file, or the heights given: raw doubles,
 *       m) and print every result as "name n value..." with exact hex
 *       floats (%a); write OUTPUT.nc unless it is "-". SCENE "text:..." is
 *       namelist text (pavefric_new_scene) instead of a file.
 *   check_api bad SCENE
 *       bad input through every entry point; print each error as
 *       "case NAME: check=C status=S length=L message=..." and go on;
 *       end with a good run ("continued: ...").
 *   check_api repeat SCENE OUTPUT.nc DEPTH...
 *       set &water depth to each DEPTH in turn on one handle, running after
 *       each; write the last run to OUTPUT.nc and print its mu (%a).
 *   check_api threads SCENE DEPTH...
 *       one scene handle per depth, run at once in as many threads, then
 *       one after the other; print "depth D: same|different" (handles are
 *       independent: no global state).
 *   check_api typed SCENE
 *       the same changes to SCENE made twice on two handles, once as
 *       namelist text (pavefric_set_parameter) and once through the typed
 *       setters (_double, _int, _bool, _text, _doubles); print each run's mu
 *       ("text mu ..." and "typed mu ...", %a) and get_parameter's text of
 *       each changed variable; then bad typed values, each reported as in
 *       `bad`, with the scene's mu after them ("after mu ...": unchanged).
 *   check_api stress THREADS JOBS [SCENE [DIR]]
 *       JOBS small scenes from namelist text (each its own speeds, heights,
 *       parameters), with set_parameter, get_parameter, two runs, a result
 *       and the warnings each; every fifth job also loads SCENE, runs it at
 *       30 km/h and writes DIR/stress_K.nc. Run on THREADS threads at once,
 *       then serially; print "stress: T threads, N jobs, M same as serial"
 *       and exit 1 unless every job's numbers and texts are the same bits.
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pavefric.h"

static void report(const char *name, pavefric_error error)
{
    char message[4096];
    pavefric_get_error(error, message, (int)sizeof message);
    printf("case %s: check=%d status=%d length=%d message=%s\n", name,
           pavefric_check_error(error), pavefric_get_error_status(error),
           pavefric_get_error_length(error), message);
}

static double *read_heights(const char *path, int *n)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    fseek(f, 0, SEEK_END);
    long bytes = ftell(f);
    fseek(f, 0, SEEK_SET);
    *n = (int)(bytes / (long)sizeof(double));
    double *z = malloc((size_t)bytes);
    if (z != NULL && fread(z, sizeof(double), (size_t)*n, f) != (size_t)*n) {
        free(z);
        z = NULL;
    }
    fclose(f);
    return z;
}

static int dump(int argc, char **argv)
{
    pavefric_error error = pavefric_new_error();
    pavefric_scene scene = strncmp(argv[2], "text:", 5) == 0
                               ? pavefric_new_scene(error, argv[2] + 5)
                               : pavefric_load_scene(error, argv[2]);
    if (pavefric_check_error(error)) {
        report("load", error);
        return 1;
    }
    if (argc > 6) {
        int n = 0;
        double *z = read_heights(argv[4], &n);
        if (z == NULL)
            return 1;
        pavefric_set_profile(error, scene, n, z, strtod(argv[5], NULL), atoi(argv[6]));
        free(z);
        if (pavefric_check_error(error)) {
            report("set_profile", error);
            return 1;
        }
    }
    int ns = pavefric_get_speed_count(scene);
    double *mu = malloc(ns * sizeof *mu);
    pavefric_run(error, scene, mu);
    if (pavefric_check_error(error)) {
        report("run", error);
        return 1;
    }
    printf("mu_from_run %d", ns);
    for (int j = 0; j < ns; j++)
        printf(" %a", mu[j]);
    printf("\n");
    free(mu);
    char name[256];
    for (int k = 0; k < pavefric_get_result_count(); k++) {
        pavefric_get_result_name(k, name, (int)sizeof name);
        int n = pavefric_get_result_size(error, scene, name);
        if (n <= 0)
            continue;
        double *values = malloc(n * sizeof *values);
        pavefric_get_result(error, scene, name, values, n);
        if (pavefric_check_error(error)) {
            report(name, error);
            return 1;
        }
        printf("%s %d", name, n);
        for (int i = 0; i < n; i++)
            printf(" %a", values[i]);
        printf("\n");
        free(values);
    }
    if (strcmp(argv[3], "-") != 0) {
        pavefric_write_output(error, scene, argv[3]);
        if (pavefric_check_error(error)) {
            report("write", error);
            return 1;
        }
    }
    pavefric_delete_scene(&scene);
    pavefric_delete_error(&error);
    return scene == NULL && error == NULL ? 0 : 1;
}

static int bad(char **argv)
{
    pavefric_error error = pavefric_new_error();
    char text[64];

    /* a missing scene file: NULL, and the message names the path */
    pavefric_scene missing = pavefric_load_scene(error, "no/such/dir/missing.nml");
    report("missing_scene", error);
    printf("missing_scene_handle_null: %d\n", missing == NULL);

    /* a NULL scene handle and a NULL path */
    pavefric_run(error, NULL, NULL);
    report("null_scene", error);
    pavefric_load_scene(error, NULL);
    report("null_path", error);
    printf("null_error_handle: check=%d load=%d\n", pavefric_check_error(NULL),
           pavefric_load_scene(NULL, argv[2]) == NULL);

    pavefric_scene scene = pavefric_load_scene(error, argv[2]);
    report("good_load", error);

    /* a NaN height */
    double z[5] = {0.0, 1e-4, NAN, -1e-4, 0.0};
    pavefric_set_profile(error, scene, 5, z, 0.87e-3, 1);
    report("nan_height", error);
    /* an infinite spacing, an empty profile, a bad closed flag */
    z[2] = 0.0;
    pavefric_set_profile(error, scene, 5, z, INFINITY, 1);
    report("infinite_dx", error);
    pavefric_set_profile(error, scene, 0, z, 0.87e-3, 1);
    report("no_heights", error);
    pavefric_set_profile(error, scene, 5, z, 0.87e-3, 7);
    report("bad_closed", error);

    /* parameters: out of range, unknown, two at once, not a number */
    pavefric_set_parameter(error, scene, "water", "depth", "-1e-3");
    report("negative_depth", error);
    pavefric_set_parameter(error, scene, "water", "deep", "1e-3");
    report("unknown_variable", error);
    pavefric_set_parameter(error, scene, "sea", "depth", "1e-3");
    report("unknown_group", error);
    pavefric_set_parameter(error, scene, "water", "depth", "1e-3, viscosity = 2e-3");
    report("two_assignments", error);
    pavefric_set_parameter(error, scene, "rubber", "stiffness", "1.4e8x");
    report("not_a_number", error);
    pavefric_set_parameter(error, scene, "pad", "radius", "0.001");
    pavefric_set_parameter(error, scene, "pad", "shape", "'rounded'");
    report("radius_too_small", error);
    pavefric_get_parameter(error, scene, "water", "depth", text, (int)sizeof text);
    printf("depth_unchanged: %s\n", text);

    /* results before a run, an unknown result, a too small array */
    double values[2];
    pavefric_get_result(error, scene, "mu", values, 2);
    report("result_before_run", error);
    printf("unknown_result_size: %d\n", pavefric_get_result_size(error, scene, "friction"));
    report("unknown_result", error);
    /* a name with a blank at its end is not the name (attack22: "mpd "
       was read as "mpd", Fortran's comparison ignoring trailing blanks) */
    printf("blank_result_size: %d\n", pavefric_get_result_size(error, scene, "mpd "));
    report("blank_result", error);
    pavefric_set_parameter(error, scene, "water", "depth ", "1e-3");
    report("blank_parameter", error);
    pavefric_write_output(error, scene, "never.nc");
    report("write_before_run", error);

    /* a too small buffer: truncated, NUL-terminated, length tells the room */
    pavefric_set_parameter(error, scene, "water", "depth", "-1e-3");
    char small[8];
    memset(small, 'x', sizeof small);
    pavefric_get_error(error, small, (int)sizeof small);
    printf("small_buffer: '%s' nul=%d length=%d\n", small, small[7] == '\0',
           pavefric_get_error_length(error));
    pavefric_get_error(error, NULL, 100);
    pavefric_get_error(error, small, 0);

    /* and the process goes on: a good run */
    int ns = pavefric_get_speed_count(scene);
    double *mu = malloc(ns * sizeof *mu);
    pavefric_run(error, scene, mu);
    report("good_run", error);
    double *small_array = malloc(sizeof(double));
    pavefric_get_result(error, scene, "mu", small_array, 1);
    report("small_array", error);
    pavefric_write_output(error, scene, "no/such/dir/out.nc");
    report("unwritable_output", error);
    printf("continued: speeds=%d mu0=%a\n", ns, mu[0]);
    free(mu);
    free(small_array);
    pavefric_delete_scene(&scene);
    pavefric_delete_scene(&scene); /* deleting NULL does nothing */
    pavefric_delete_scene(NULL);
    pavefric_delete_error(&error);
    pavefric_delete_error(NULL);
    printf("version: %d\n", pavefric_get_version());
    return 0;
}

struct job {
    const char *scene, *depth;
    double mu[64];
    int ns, failed;
};

static void *run_job(void *arg)
{
    struct job *job = arg;
    pavefric_error error = pavefric_new_error();
    pavefric_scene scene = pavefric_load_scene(error, job->scene);
    if (!pavefric_check_error(error))
        pavefric_set_parameter(error, scene, "water", "depth", job->depth);
    job->ns = pavefric_get_speed_count(scene);
    if (job->ns > 64)
        job->ns = 64;
    if (!pavefric_check_error(error))
        pavefric_run(error, scene, job->mu);
    job->failed = pavefric_check_error(error);
    pavefric_delete_scene(&scene);
    pavefric_delete_error(&error);
    return NULL;
}

static int threads(int argc, char **argv)
{
    int n = argc - 3;
    struct job *parallel = calloc(n, sizeof *parallel), *serial = calloc(n, sizeof *serial);
    pthread_t *ids = calloc(n, sizeof *ids);
    for (int k = 0; k < n; k++) {
        parallel[k].scene = serial[k].scene = argv[2];
        parallel[k].depth = serial[k].depth = argv[3 + k];
        if (pthread_create(&ids[k], NULL, run_job, &parallel[k]) != 0)
            return 1;
    }
    for (int k = 0; k < n; k++)
        pthread_join(ids[k], NULL);
    for (int k = 0; k < n; k++) {
        run_job(&serial[k]);
        int same = !parallel[k].failed && !serial[k].failed && parallel[k].ns == serial[k].ns &&
                   memcmp(parallel[k].mu, serial[k].mu, serial[k].ns * sizeof(double)) == 0;
        printf("depth %s: %s mu0=%a\n", argv[3 + k], same ? "same" : "different",
               serial[k].mu[0]);
    }
    free(parallel);
    free(serial);
    free(ids);
    return 0;
}

static int repeat(int argc, char **argv)
{
    pavefric_error error = pavefric_new_error();
    pavefric_scene scene = pavefric_load_scene(error, argv[2]);
    int ns = pavefric_get_speed_count(scene);
    double *mu = malloc((ns > 0 ? ns : 1) * sizeof *mu);
    for (int k = 4; k < argc && !pavefric_check_error(error); k++) {
        pavefric_set_parameter(error, scene, "water", "depth", argv[k]);
        if (!pavefric_check_error(error))
            pavefric_run(error, scene, mu);
    }
    if (!pavefric_check_error(error))
        pavefric_write_output(error, scene, argv[3]);
    if (pavefric_check_error(error)) {
        report("repeat", error);
        return 1;
    }
    printf("mu %d", ns);
    for (int j = 0; j < ns; j++)
        printf(" %a", mu[j]);
    printf("\n");
    free(mu);
    pavefric_delete_scene(&scene);
    pavefric_delete_error(&error);
    return 0;
}

/* stress: many small scenes at once. Job k: a scene from namelist text
 * (speeds and mu_loc of its own), synthetic heights of its own (a sum of
 * sines, no file), then set_parameter / get_parameter / run twice, results
 * and warnings read back; every job's record is compared with the serial
 * run's, bit for bit. Jobs with `files` also load the scene file and write
 * a NetCDF file (the files lock). */
#define STRESS_SPEEDS 3
#define STRESS_POINTS 250

struct stress_job {
    int k;
    const char *scene_file, *dir;
    double mu[2][STRESS_SPEEDS], compression[STRESS_SPEEDS], mu_file[64];
    char depth[64], warnings[4096];
    int ns_file, failed;
    char message[512];
};

static void stress_job(struct stress_job *job)
{
    int k = job->k;
    pavefric_error error = pavefric_new_error();
    char text[512];
    snprintf(text, sizeof text,
             "&surface dx = 1e-3, mu_loc = %.2f / &water depth = %.1fe-3 / "
             "&operation speeds_kmh = %d, %d, %d / &numerics tolerance = 1e-3 /",
             0.45 + 0.01 * (k % 20), 0.1 * (k % 7), 10 + k % 5, 40 + k % 9, 70 + k % 11);
    pavefric_scene scene = pavefric_new_scene(error, text);
    double z[STRESS_POINTS];
    for (int i = 0; i < STRESS_POINTS; i++)
        z[i] = 1e-4 * (3.0 * sin(0.05 * i * (1 + k % 3)) + sin(0.31 * i + k) +
                       0.5 * sin(1.7 * i + 0.3 * k));
    if (!pavefric_check_error(error))
        pavefric_set_profile(error, scene, STRESS_POINTS, z, 0.5e-3, 0);
    if (!pavefric_check_error(error))
        pavefric_run(error, scene, job->mu[0]);
    char value[32];
    snprintf(value, sizeof value, "%de-4", 2 + k % 9);
    if (!pavefric_check_error(error))
        pavefric_set_parameter(error, scene, "water", "depth", value);
    if (!pavefric_check_error(error))
        pavefric_get_parameter(error, scene, "water", "depth", job->depth, (int)sizeof job->depth);
    if (!pavefric_check_error(error))
        pavefric_run(error, scene, job->mu[1]);
    if (!pavefric_check_error(error))
        pavefric_get_result(error, scene, "max_compression", job->compression, STRESS_SPEEDS);
    if (!pavefric_check_error(error))
        pavefric_get_warnings(error, scene, job->warnings, (int)sizeof job->warnings);
    if (!pavefric_check_error(error) && job->scene_file != NULL) {
        pavefric_scene file_scene = pavefric_load_scene(error, job->scene_file);
        job->ns_file = pavefric_get_speed_count(file_scene);
        if (job->ns_file > 64)
            job->ns_file = 64;
        if (!pavefric_check_error(error))
            pavefric_set_parameter(error, file_scene, "operation", "speeds_kmh", "30");
        job->ns_file = pavefric_get_speed_count(file_scene);
        if (!pavefric_check_error(error))
            pavefric_run(error, file_scene, job->mu_file);
        char path[4096];
        snprintf(path, sizeof path, "%s/stress_%d.nc", job->dir, k);
        if (!pavefric_check_error(error))
            pavefric_write_output(error, file_scene, path);
        pavefric_delete_scene(&file_scene);
    }
    job->failed = pavefric_check_error(error);
    if (job->failed)
        pavefric_get_error(error, job->message, (int)sizeof job->message);
    pavefric_delete_scene(&scene);
    pavefric_delete_error(&error);
}

struct stress_worker {
    struct stress_job *jobs;
    int first, step, n;
};

static void *stress_worker(void *arg)
{
    struct stress_worker *w = arg;
    for (int k = w->first; k < w->n; k += w->step)
        stress_job(&w->jobs[k]);
    return NULL;
}

static int stress(int argc, char **argv)
{
    int nthreads = atoi(argv[2]), n = atoi(argv[3]);
    const char *scene_file = argc > 4 ? argv[4] : NULL;
    const char *dir = argc > 5 ? argv[5] : ".";
    struct stress_job *serial = calloc(n, sizeof *serial), *parallel = calloc(n, sizeof *parallel);
    struct stress_worker *workers = calloc(nthreads, sizeof *workers);
    pthread_t *ids = calloc(nthreads, sizeof *ids);
    for (int k = 0; k < n; k++) {
        serial[k].k = parallel[k].k = k;
        serial[k].dir = parallel[k].dir = dir;
        /* one job in five also reads the scene file and writes NetCDF */
        if (k % 5 == 0)
            serial[k].scene_file = parallel[k].scene_file = scene_file;
    }
    for (int t = 0; t < nthreads; t++) {
        workers[t] = (struct stress_worker){parallel, t, nthreads, n};
        if (pthread_create(&ids[t], NULL, stress_worker, &workers[t]) != 0)
            return 1;
    }
    for (int t = 0; t < nthreads; t++)
        pthread_join(ids[t], NULL);
    struct stress_worker one = {serial, 0, 1, n};
    stress_worker(&one);
    int same = 0;
    for (int k = 0; k < n; k++) {
        struct stress_job *a = &parallel[k], *b = &serial[k];
        if (a->failed || b->failed) {
            printf("job %d: failed: %s | %s\n", k, a->message, b->message);
            continue;
        }
        int ok = memcmp(a->mu, b->mu, sizeof a->mu) == 0 && memcmp(a->compression, b->compression, sizeof a->compression) == 0 &&
                 strcmp(a->depth, b->depth) == 0 && strcmp(a->warnings, b->warnings) == 0 &&
                 a->ns_file == b->ns_file &&
                 memcmp(a->mu_file, b->mu_file, sizeof a->mu_file) == 0;
        if (ok)
            same++;
        else
            printf("job %d: different (depth '%s' / '%s', mu %a / %a)\n", k, a->depth, b->depth,
                   a->mu[1][0], b->mu[1][0]);
    }
    printf("stress: %d threads, %d jobs, %d same as serial; job 0 mu %a %a depth '%s'\n",
           nthreads, n, same, serial[0].mu[0][0], serial[0].mu[1][0], serial[0].depth);
    free(serial);
    free(parallel);
    free(workers);
    free(ids);
    return same == n ? 0 : 1;
}

/* typed: the typed setters against the namelist-text setter. */
static void print_mu(const char *label, pavefric_error error, pavefric_scene scene)
{
    int ns = pavefric_get_speed_count(scene);
    double mu[64];
    pavefric_run(error, scene, mu);
    if (pavefric_check_error(error)) {
        report(label, error);
        return;
    }
    printf("%s mu %d", label, ns);
    for (int j = 0; j < ns && j < 64; j++)
        printf(" %a", mu[j]);
    printf("\n");
}

static int typed(char **argv)
{
    static const char *changed[][2] = {{"water", "depth"}, {"pad", "load"},
                                       {"numerics", "substeps"}, {"numerics", "error_estimate"},
                                       {"water", "wet_model"}, {"operation", "speeds_kmh"},
                                       {"surface", "mu_loc"}};
    pavefric_error error = pavefric_new_error();
    pavefric_scene by_text = pavefric_load_scene(error, argv[2]);
    pavefric_scene by_type = pavefric_load_scene(error, argv[2]);
    if (pavefric_check_error(error)) {
        report("load", error);
        return 1;
    }
    pavefric_set_parameter(error, by_text, "water", "depth", "2e-4");
    pavefric_set_parameter(error, by_text, "pad", "load", "40");
    pavefric_set_parameter(error, by_text, "numerics", "substeps", "2");
    pavefric_set_parameter(error, by_text, "numerics", "error_estimate", ".false.");
    pavefric_set_parameter(error, by_text, "water", "wet_model", "'squeeze'");
    pavefric_set_parameter(error, by_text, "operation", "speeds_kmh", "10, 35.5, 70");
    pavefric_set_parameter(error, by_text, "surface", "mu_loc", "0.45");
    if (pavefric_check_error(error)) {
        report("text", error);
        return 1;
    }
    const double speeds[3] = {10.0, 35.5, 70.0};
    pavefric_set_parameter_double(error, by_type, "water", "depth", 2e-4);
    pavefric_set_parameter_int(error, by_type, "pad", "load", 40); /* a whole number for a real */
    pavefric_set_parameter_int(error, by_type, "numerics", "substeps", 2);
    pavefric_set_parameter_bool(error, by_type, "numerics", "error_estimate", 0);
    pavefric_set_parameter_text(error, by_type, "water", "wet_model", "squeeze");
    pavefric_set_parameter_doubles(error, by_type, "operation", "speeds_kmh", 3, speeds);
    pavefric_set_parameter_double(error, by_type, "surface", "mu_loc", 0.45);
    if (pavefric_check_error(error)) {
        report("typed", error);
        return 1;
    }
    print_mu("text", error, by_text);
    print_mu("typed", error, by_type);
    for (size_t k = 0; k < sizeof changed / sizeof changed[0]; k++) {
        char a[256], b[256];
        pavefric_get_parameter(error, by_text, changed[k][0], changed[k][1], a, (int)sizeof a);
        pavefric_get_parameter(error, by_type, changed[k][0], changed[k][1], b, (int)sizeof b);
        printf("get %s %s: text=%s typed=%s\n", changed[k][0], changed[k][1], a, b);
    }
    /* bad typed values: each an error naming the variable; the scene stays */
    const double too_many[2] = {1.0, -5.0};
    pavefric_set_parameter_double(error, by_type, "water", "depth", -1.0);
    report("negative_depth", error);
    pavefric_set_parameter_double(error, by_type, "water", "depth", NAN);
    report("nan_depth", error);
    pavefric_set_parameter_double(error, by_type, "water", "depth", INFINITY);
    report("infinite_depth", error);
    pavefric_set_parameter_int(error, by_type, "numerics", "substeps", 0);
    report("zero_substeps", error);
    pavefric_set_parameter_double(error, by_type, "numerics", "substeps", 2.5);
    report("real_for_integer", error);
    pavefric_set_parameter_text(error, by_type, "water", "wet_model", "reynolds2");
    report("unknown_choice", error);
    pavefric_set_parameter_text(error, by_type, "water", "depth", "1e-3");
    report("text_for_real", error);
    pavefric_set_parameter_bool(error, by_type, "numerics", "error_estimate", 2);
    report("bool_two", error);
    pavefric_set_parameter_doubles(error, by_type, "operation", "speeds_kmh", 2, too_many);
    report("negative_speed", error);
    pavefric_set_parameter_doubles(error, by_type, "operation", "speeds_kmh", -1, too_many);
    report("negative_count", error);
    pavefric_set_parameter_doubles(error, by_type, "operation", "speeds_kmh", 0, too_many);
    report("empty_speeds", error);
    pavefric_scene no_speeds = pavefric_new_scene(error, "&surface dx = 1e-3 /");
    report("text_without_speeds", error);
    pavefric_delete_scene(&no_speeds);
    pavefric_set_parameter_double(error, by_type, "water", "no_such", 1.0);
    report("unknown_variable", error);
    pavefric_set_parameter_double(error, by_type, NULL, "depth", 1.0);
    report("null_group", error);
    pavefric_set_parameter_double(error, by_type, "numerics", "tolerance", 1e-3);
    pavefric_set_parameter_int(error, by_type, "numerics", "substeps", 4096);
    report("across_variables", error);
    pavefric_set_parameter_double(error, by_type, "numerics", "tolerance", 0.0);
    print_mu("after", error, by_type);
    pavefric_delete_scene(&by_text);
    pavefric_delete_scene(&by_type);
    pavefric_delete_error(&error);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 4 && strcmp(argv[1], "stress") == 0)
        return stress(argc, argv);
    if (argc >= 5 && strcmp(argv[1], "repeat") == 0)
        return repeat(argc, argv);
    if (argc >= 4 && strcmp(argv[1], "threads") == 0)
        return threads(argc, argv);
    if (argc >= 4 && strcmp(argv[1], "dump") == 0)
        return dump(argc, argv);
    if (argc >= 3 && strcmp(argv[1], "typed") == 0)
        return typed(argv);
    if (argc >= 3 && strcmp(argv[1], "bad") == 0)
        return bad(argv);
    fprintf(stderr, "usage: check_api dump SCENE OUTPUT.nc [HEIGHTS.bin DX CLOSED] | "
                    "check_api bad SCENE | check_api repeat SCENE OUTPUT.nc DEPTH... | "
                    "check_api threads SCENE DEPTH... | "
                    "check_api stress THREADS JOBS [SCENE [DIR]]\n");
    return 2;
}
