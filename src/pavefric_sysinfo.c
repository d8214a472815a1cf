/* What the machine has, for memory estimates made before large
 * allocations: physical memory in bytes (0 when unknown). */
#include <unistd.h>

long long pavefric_physical_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES);
    long size = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || size <= 0) return 0;
    return (long long)pages * (long long)size;
}
