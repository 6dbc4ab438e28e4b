/* diag.c - fill and print diagnostics (see diag.h). */
#include "diag.h"

#include <stdarg.h>
#include <string.h>

void
diag_set(struct diag *d, const char *file, int line, int col, const char *fmt, ...)
{
    if (!d) {
        return;
    }
    snprintf(d->file, sizeof d->file, "%s", file ? file : "");
    d->line = line;
    d->col = col;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->msg, sizeof d->msg, fmt, ap);
    va_end(ap);
    d->kind = DIAG_INVALID;
}

void
diag_mark_no_memory(struct diag *d)
{
    if (d) {
        d->kind = DIAG_NO_MEMORY;
    }
}

void
diag_print(FILE *f, const struct diag *d, const char *severity)
{
    if (d->file[0] && d->line > 0) {
        fprintf(f, "%s:%d:%d: %s: %s\n", d->file, d->line, d->col, severity, d->msg);
    } else if (d->file[0]) {
        fprintf(f, "%s: %s: %s\n", d->file, severity, d->msg);
    } else {
        fprintf(f, "%s: %s\n", severity, d->msg);
    }
}
