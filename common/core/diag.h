/*
 * diag.h - diagnostics: where something went wrong and what.
 *
 * Library code never prints and never exits: it fills a struct diag and
 * returns false (or NULL).  main() (through run.c, its shared plumbing)
 * prints the diagnostic in GNU's format,
 *     FILE:LINE:COL: error: MESSAGE
 * which editors, grep and CI annotations understand, and picks the exit
 * status.  A diagnostic without a line (an I/O error) prints as FILE: error:.
 */
#ifndef DIAG_H
#define DIAG_H

#include <stdio.h>

#ifdef __GNUC__
#define DIAG_PRINTF(fmt_index, first_arg) __attribute__((format(printf, fmt_index, first_arg)))
#else
#define DIAG_PRINTF(fmt_index, first_arg)
#endif

/* What failed: the input (the usual case), or the system's memory, which
 * main() reports with an exit status of its own (CONTRACT.md: 4). */
enum diag_kind {
    DIAG_INVALID = 0, /* the input is wrong, or asks for more than a limit allows */
    DIAG_NO_MEMORY, /* an allocation within the limits was refused by the system */
};

struct diag {
    char file[512]; /* empty when the problem has no file */
    int line, col; /* 1-based; 0 when unknown */
    char msg[512];
    enum diag_kind kind;
};

/* Fill d (which may be NULL: then nothing happens).  file may be NULL.
 * The kind is DIAG_INVALID. */
void diag_set(struct diag *d, const char *file, int line, int col, const char *fmt, ...)
    DIAG_PRINTF(5, 6);

/* Say that what d reports is an allocation the system refused (d may be
 * NULL). */
void diag_mark_no_memory(struct diag *d);

/* Print "file:line:col: severity: msg" (parts that are unknown left out). */
void diag_print(FILE *f, const struct diag *d, const char *severity);

#endif /* DIAG_H */
