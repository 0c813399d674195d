/* SPDX-License-Identifier: MIT */
/* The address-space limit of the process (ulimit -v): struct rlimit and RLIM_INFINITY are
   not reachable portably from Fortran's bind(C). Under a limit too small for OpenBLAS's
   buffers, OpenBLAS retries its failed mmap for ever inside CHOLMOD, so the run checks
   first. */
#include <sys/resource.h>

/* The soft RLIMIT_AS in bytes, or -1 when there is none (or it cannot be read). */
long long nceig_address_space_limit(void)
{
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
        return -1;
    return (long long)limit.rlim_cur;
}
