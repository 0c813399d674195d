/* SPDX-License-Identifier: MIT */
/* errno is a macro (thread-local storage), and struct stat differs between systems: neither
   can be reached portably from Fortran's bind(C), so these two live here. */
#include <errno.h>
#include <sys/stat.h>

int nceig_errno(void) { return errno; }

int nceig_is_directory(const char *path)
{
    struct stat info;
    return stat(path, &info) == 0 && S_ISDIR(info.st_mode);
}
