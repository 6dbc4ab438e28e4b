/*
 * signals.h - what a signal does to a run of `render`.
 *
 * SIGINT (Ctrl-C), SIGTERM (kill, timeout, a batch scheduler at its time
 * limit) and SIGHUP (a closed terminal) ask the render to stop after the
 * passes completed so far: stage 07 writes those, the other stages write
 * nothing (CONTRACT.md: exit 130).  A second one of them, and any other
 * signal that would end the program, removes the temporary files of
 * outputs being written (atomic_file.h) and then ends the program as that
 * signal does.  Only SIGKILL, which cannot be caught, leaves one behind.
 *
 * Faults (SIGSEGV, SIGBUS, SIGFPE, SIGILL) are bugs, left to the default
 * action and to the sanitizers, whose reports must not be hidden.
 */
#ifndef SIGNALS_H
#define SIGNALS_H

/* Install the handlers (a signal ignored by the parent stays ignored). */
void signals_install(void);

/* Hold back the signals above while the outputs are renamed into place,
 * so that a run ends with all of its outputs or none; signals_release()
 * delivers what arrived meanwhile. */
void signals_hold(void);
void signals_release(void);

#endif /* SIGNALS_H */
