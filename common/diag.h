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

struct diag {
    char file[512]; /* empty when the problem has no file */
    int line, col; /* 1-based; 0 when unknown */
    char msg[512];
};

/* Fill d (which may be NULL: then nothing happens).  file may be NULL. */
void diag_set(struct diag *d, const char *file, int line, int col, const char *fmt, ...)
    DIAG_PRINTF(5, 6);

/* Print "file:line:col: severity: msg" (parts that are unknown left out). */
void diag_print(FILE *f, const struct diag *d, const char *severity);

#endif /* DIAG_H */
