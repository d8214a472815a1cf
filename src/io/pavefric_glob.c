/* File-name pattern expansion for batch scenes: POSIX glob(3), sorted.
 * Writes the matches, newline-separated, into out (at most outlen bytes)
 * and returns the number of bytes needed (so a caller can retry with a
 * larger buffer), or -1 on a read error. No match gives 0. */
#include <glob.h>
#include <string.h>

int pavefric_glob(const char *pattern, char *out, int outlen, int *count)
{
    glob_t g;
    int rc = glob(pattern, 0, NULL, &g);
    *count = 0;
    if (rc == GLOB_NOMATCH) return 0;
    if (rc != 0) return -1;
    size_t need = 0;
    for (size_t i = 0; i < g.gl_pathc; ++i) need += strlen(g.gl_pathv[i]) + 1;
    if ((size_t)outlen >= need) {
        size_t used = 0;
        for (size_t i = 0; i < g.gl_pathc; ++i) {
            size_t n = strlen(g.gl_pathv[i]);
            memcpy(out + used, g.gl_pathv[i], n);
            used += n;
            out[used++] = '\n';
        }
    }
    *count = (int)g.gl_pathc;
    globfree(&g);
    return (int)need;
}
