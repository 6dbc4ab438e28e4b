/* signals.c - stop a render, or clean up and die (see signals.h). */
#include "signals.h"

#include <pthread.h>
#include <signal.h>
#include <stddef.h>

#include "atomic_file.h"
#include "driver.h"

/* Signals that ask the render to stop: the first is a request, the second
 * ends the program. */
static const int stop_signals[] = {SIGINT, SIGTERM, SIGHUP};

/* Signals whose default action ends the program, and that come from
 * outside (a user, a pipe, a limit) rather than from a fault. */
static const int fatal_signals[] = {
    SIGQUIT,
    SIGPIPE,
    SIGALRM,
    SIGUSR1,
    SIGUSR2,
    SIGXCPU,
    SIGXFSZ,
    SIGVTALRM,
    SIGPROF,
    SIGABRT,
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static volatile sig_atomic_t stop_received;

/* Remove the temporary files, then end as the signal's default action
 * does: the parent (a shell, make, a scheduler) sees the true cause. */
static void
die_cleanly(int signo)
{
    atomic_file_remove_temporaries();
    struct sigaction sa = {0};
    sa.sa_handler = SIG_DFL;
    sigemptyset(&sa.sa_mask);
    sigaction(signo, &sa, NULL);
    sigset_t unblock;
    sigemptyset(&unblock);
    sigaddset(&unblock, signo);
    pthread_sigmask(SIG_UNBLOCK, &unblock, NULL);
    raise(signo);
}

static void
on_stop_signal(int signo)
{
    if (stop_received) {
        die_cleanly(signo);
        return;
    }
    stop_received = 1;
    driver_request_stop();
}

static void
on_fatal_signal(int signo)
{
    die_cleanly(signo);
}

/* A signal the parent set to be ignored (nohup, a background job's
 * SIGINT, a daemon's SIGPIPE) stays ignored. */
static void
set_handler(int signo, void (*handler)(int))
{
    struct sigaction old;
    if (sigaction(signo, NULL, &old) == 0 && old.sa_handler == SIG_IGN) {
        return;
    }
    struct sigaction sa = {0};
    sa.sa_handler = handler;
    sigfillset(&sa.sa_mask); /* one handler at a time */
    sigaction(signo, &sa, NULL);
}

void
signals_install(void)
{
    for (size_t i = 0; i < COUNT(stop_signals); i++) {
        set_handler(stop_signals[i], on_stop_signal);
    }
    for (size_t i = 0; i < COUNT(fatal_signals); i++) {
        set_handler(fatal_signals[i], on_fatal_signal);
    }
}

static void
block_all(int how)
{
    sigset_t set;
    sigemptyset(&set);
    for (size_t i = 0; i < COUNT(stop_signals); i++) {
        sigaddset(&set, stop_signals[i]);
    }
    for (size_t i = 0; i < COUNT(fatal_signals); i++) {
        sigaddset(&set, fatal_signals[i]);
    }
    pthread_sigmask(how, &set, NULL);
}

void
signals_hold(void)
{
    block_all(SIG_BLOCK);
}

void
signals_release(void)
{
    block_all(SIG_UNBLOCK);
}
