/* What the process may still use, for memory estimates made before large
 * allocations: the smallest of the machine's physical memory, what is left
 * under the process's address-space and data limits (ulimit -v / -d, less
 * the address space already mapped) and under its control group's limit
 * (cgroup v2 memory.max less memory.current, v1 memory.limit_in_bytes:
 * what SLURM and containers set). Bytes; 0 when none is known. */
#include <stdio.h>
#include <sys/resource.h>
#include <unistd.h>

static long long cgroup_limit(const char *path)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 0;
    char buf[64] = {0};
    long long v = 0;
    if (fgets(buf, sizeof buf, f) != NULL && buf[0] >= '0' && buf[0] <= '9')
        sscanf(buf, "%lld", &v);       /* "max" (no limit) leaves 0 */
    fclose(f);
    return v;
}

static long long smaller(long long a, long long b)
{
    if (a <= 0)
        return b;
    if (b <= 0)
        return a;
    return a < b ? a : b;
}

/* pages of address space the process has mapped (/proc/self/statm) */
static long long mapped_bytes(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    long long pages = 0;
    if (f == NULL)
        return 0;
    if (fscanf(f, "%lld", &pages) != 1)
        pages = 0;
    fclose(f);
    return pages * (long long)sysconf(_SC_PAGESIZE);
}

long long pavefric_physical_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES);
    long size = sysconf(_SC_PAGESIZE);
    long long limit = (pages > 0 && size > 0) ? (long long)pages * (long long)size : 0;
    struct rlimit r;
    long long mapped = mapped_bytes();
    if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
        limit = smaller(limit, (long long)r.rlim_cur - mapped > 1 ? (long long)r.rlim_cur - mapped : 1);
    if (getrlimit(RLIMIT_DATA, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
        limit = smaller(limit, (long long)r.rlim_cur - mapped > 1 ? (long long)r.rlim_cur - mapped : 1);
    long long v2 = cgroup_limit("/sys/fs/cgroup/memory.max");
    if (v2 > 0) {
        long long used = cgroup_limit("/sys/fs/cgroup/memory.current");
        limit = smaller(limit, v2 - used > 1 ? v2 - used : 1);
    }
    long long v1 = cgroup_limit("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    if (v1 > 0 && v1 < (1LL << 60))    /* v1 writes a huge number for "no limit" */
        limit = smaller(limit, v1);
    return limit;
}
