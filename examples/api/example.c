/* pavefric from C: friction per speed of a scene, optionally at another
 * water depth, and its NetCDF output (docs/api.md).
 *
 *   cc example.c $(pkg-config --cflags --libs pavefric) -o example
 *   ./example scene.nml [depth_m [output.nc]]
 */
#include <stdio.h>
#include <stdlib.h>

#include "pavefric.h"

/* Print the error of the last call and say whether there was one. */
static int failed(pavefric_error error, const char *what)
{
    char message[2048];
    if (!pavefric_check_error(error))
        return 0;
    pavefric_get_error(error, message, (int)sizeof message);
    fprintf(stderr, "%s: %s\n", what, message);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s scene.nml [depth_m [output.nc]]\n", argv[0]);
        return 2;
    }
    pavefric_error error = pavefric_new_error();
    if (error == NULL)
        return 1;
    int status = 1;
    double *speeds = NULL, *mu = NULL;

    pavefric_scene scene = pavefric_load_scene(error, argv[1]);
    if (failed(error, "load"))
        goto done;
    if (argc > 2) {
        /* the value as written in a namelist, checked as the program checks it */
        pavefric_set_parameter(error, scene, "water", "depth", argv[2]);
        if (failed(error, "set_parameter"))
            goto done;
    }
    int ns = pavefric_get_speed_count(scene);
    speeds = malloc(ns * sizeof *speeds);
    mu = malloc(ns * sizeof *mu);
    if (speeds == NULL || mu == NULL)
        goto done;
    pavefric_get_speeds(error, scene, speeds, ns);
    pavefric_run(error, scene, mu); /* reads the scene's profile file */
    if (failed(error, "run"))
        goto done;
    for (int j = 0; j < ns; j++)
        printf("%g km/h: mu = %.17g\n", speeds[j], mu[j]);

    char warnings[4096];
    if (pavefric_get_warnings(error, scene, warnings, (int)sizeof warnings) > 0)
        fprintf(stderr, "warnings:\n%s\n", warnings);
    if (argc > 3) {
        pavefric_write_output(error, scene, argv[3]);
        if (failed(error, "write"))
            goto done;
    }
    status = 0;
done:
    free(speeds);
    free(mu);
    pavefric_delete_scene(&scene);
    pavefric_delete_error(&error);
    return status;
}
