/* SPDX-License-Identifier: MIT */
/* What the nceig program sets up before any library runs: its stop signals, and malloc
   under an address-space limit. This file is linked into the program only, never into the
   tests: only main.f90 uses its module (program_start.f90).

   Stop signals. SIGTERM, SIGINT, SIGHUP and SIGXCPU are the user's (or the batch system's)
   decision to stop: they end the run by that signal, whatever it is doing. A handler cannot
   promise that: METIS installs its own for SIGTERM around each of its calls (GKlib's
   gk_sigtrap, a longjmp back into METIS, which then returns METIS_ERROR), so a SIGTERM
   during an ordering became "METIS failed" (exit 5). So the four signals are blocked in
   every thread, from before the first library constructor runs (OpenBLAS starts its
   threads there, and a thread inherits the mask of the thread that starts it), and one
   thread of ours waits for them with sigwaitinfo. It hands each to the main thread through
   SIGRTMIN, whose handler ends the run as filesystem_c.c's cleanup does (the staging folder
   removed, or a commit under way finished first).

   malloc under ulimit -v. glibc gives each thread that allocates an arena of its own,
   reserving 64 MiB of address space; under RLIMIT_AS whether OpenBLAS's threads got one
   depended on the order in which threads ran, and so did the limit the address-space check
   (memory_budget.f90) asked for. With a limit, one arena serves every thread. */
/* _GNU_SOURCE: SYS_tgkill through syscall(2). */
#define _GNU_SOURCE
#include <errno.h>
#include <malloc.h>
#include <pthread.h>
#include <signal.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

void nceig_signal_on_main(int signal_number);   /* filesystem_c.c */
void nceig_signal_set_name(const char *name);   /* filesystem_c.c */

enum { N_STOP = 4 };
static const int stop_signals[N_STOP] = {SIGTERM, SIGINT, SIGHUP, SIGXCPU};
static volatile sig_atomic_t received;   /* the signal the waiting thread took */

static void stop_set(sigset_t *set)
{
    int i;
    sigemptyset(set);
    for (i = 0; i < N_STOP; i++) sigaddset(set, stop_signals[i]);
}

/* Run by the dynamic loader before any shared library's constructor (.preinit_array). */
static void before_libraries(int argc, char **argv, char **envp)
{
    sigset_t set;
    struct rlimit limit;
    (void)argc;
    (void)argv;
    (void)envp;
    stop_set(&set);
    (void)pthread_sigmask(SIG_BLOCK, &set, NULL);
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        (void)mallopt(M_ARENA_MAX, 1);
}

__attribute__((section(".preinit_array"), used)) static void (*const preinit)(int, char **,
                                                                              char **) =
    before_libraries;

/* The handover signal, on the main thread: end the run by the signal taken. */
static void on_handover(int signal_number)
{
    (void)signal_number;
    nceig_signal_on_main(received);
}

static void *wait_for_signals(void *argument)
{
    sigset_t set = *(sigset_t *)argument;
    for (;;) {
        int signal_number = sigwaitinfo(&set, NULL);
        if (signal_number < 0) continue;   /* EINTR */
        received = signal_number;
        (void)syscall(SYS_tgkill, (long)getpid(), (long)getpid(), (long)SIGRTMIN);
    }
    return NULL;
}

/* Start the thread that takes the four signals. A signal the process ignores at the start
   (SIGINT and SIGHUP of a shell's background job) stays ignored: Linux keeps a blocked
   signal pending even when its action is to ignore it, so it is left out of the wait.
   `name` (the input file) is named by the line the end prints. Where the thread cannot
   start (ulimit -u), the signals are unblocked in the calling thread instead: they then
   reach it through filesystem_c.c's handler, as in a program without this thread. */
void nceig_signal_thread_start(const char *name)
{
    static sigset_t waited;
    struct sigaction action;
    pthread_attr_t attributes;
    pthread_t thread;
    sigset_t set;
    int i, status;

    nceig_signal_set_name(name);
    sigemptyset(&waited);
    for (i = 0; i < N_STOP; i++) {
        struct sigaction current;
        if (sigaction(stop_signals[i], NULL, &current) == 0 && current.sa_handler == SIG_IGN)
            continue;
        sigaddset(&waited, stop_signals[i]);
    }
    memset(&action, 0, sizeof action);
    action.sa_handler = on_handover;
    sigfillset(&action.sa_mask);
    status = sigaction(SIGRTMIN, &action, NULL) == 0 ? 0 : errno;
    if (status == 0) status = pthread_attr_init(&attributes);
    if (status == 0) {
        (void)pthread_attr_setdetachstate(&attributes, PTHREAD_CREATE_DETACHED);
        /* Its stack counts under ulimit -v too: 1 MiB holds the libraries' thread-local
           storage (64 KiB is too small for it: EINVAL) and a sigwaitinfo loop. */
        (void)pthread_attr_setstacksize(&attributes, 1048576);
        status = pthread_create(&thread, &attributes, wait_for_signals, &waited);
        (void)pthread_attr_destroy(&attributes);
    }
    if (status != 0) {
        stop_set(&set);
        (void)pthread_sigmask(SIG_UNBLOCK, &set, NULL);
    }
}
