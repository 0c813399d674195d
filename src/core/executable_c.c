/* SPDX-License-Identifier: MIT */
/* The path of the running executable, from /proc/self/exe (Linux): an installed nceig finds
 * its helper scripts relative to itself, wherever the prefix was moved. */
#define _DEFAULT_SOURCE   /* readlink under -std=c11 */
#include <unistd.h>

/* Fills path (NUL-terminated) and returns its length, or 0 when it cannot be read. */
int nceig_executable_path(char *path, int capacity)
{
    ssize_t n;
    if (capacity <= 1)
        return 0;
    n = readlink("/proc/self/exe", path, (size_t)capacity - 1);
    if (n <= 0 || n >= capacity - 1)
        n = 0;
    path[n] = '\0';
    return (int)n;
}
