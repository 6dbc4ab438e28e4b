/*
 * cli_value.c - the values of the command line's options (cli_value.h).
 */
#include "cli_value.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *
skip_digits(const char *p, int *count)
{
    while (*p >= '0' && *p <= '9') {
        p++;
        ++*count;
    }
    return p;
}

/* The one syntax of every number on the command line: an optional sign,
 * decimal digits and, for a real, a fraction and an exponent.  No blanks,
 * no hexadecimal, no "inf" or "nan", which strtoll and strtod alone would
 * also take. */
static bool
is_decimal(const char *text, bool whole)
{
    const char *p = text + (*text == '+' || *text == '-');
    int digits = 0;
    p = skip_digits(p, &digits);
    if (!whole && *p == '.') {
        p = skip_digits(p + 1, &digits);
    }
    if (digits == 0) {
        return false;
    }
    if (!whole && (*p == 'e' || *p == 'E')) {
        p += 1 + (p[1] == '+' || p[1] == '-');
        int exponent_digits = 0;
        p = skip_digits(p, &exponent_digits);
        if (exponent_digits == 0) {
            return false;
        }
    }
    return *p == '\0';
}

/* A whole number in [min, max]; the message gives the range. */
bool
cli_parse_whole(
    const char *name,
    const char *text,
    long long min,
    long long max,
    long long *out,
    struct diag *err)
{
    char *end;
    errno = 0;
    long long v = is_decimal(text, true) ? strtoll(text, &end, 10) : 0;
    if (!is_decimal(text, true) || errno == ERANGE || v < min || v > max) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "--%s expects a whole number in [%lld, %lld], got '%s'",
            name,
            min,
            max,
            text);
        return false;
    }
    *out = v;
    return true;
}

bool
cli_parse_int(
    const char *name,
    const char *text,
    double min,
    double max,
    int *out,
    struct diag *err)
{
    long long v;
    if (!cli_parse_whole(name, text, (long long)min, (long long)max, &v, err)) {
        return false;
    }
    *out = (int)v;
    return true;
}

bool
cli_parse_real(
    const char *name,
    const char *text,
    double min,
    double max,
    real *out,
    struct diag *err)
{
    errno = 0;
    double v = is_decimal(text, false) ? strtod(text, NULL) : NAN;
    if (!is_decimal(text, false) || errno == ERANGE || !isfinite(v) || v < min || v > max) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "--%s expects a number in [%g, %g], got '%s'",
            name,
            min,
            max,
            text);
        return false;
    }
    *out = (real)v;
    return true;
}

bool
cli_parse_pair(const struct option_spec *spec, const char *text, struct diag *err)
{
    int *pair = spec->dest;
    const char *comma = strchr(text, ',');
    char first[64];
    size_t len = comma ? (size_t)(comma - text) : 0;
    if (!comma || len >= sizeof first) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "--%s expects %s (two whole numbers), got '%s'",
            spec->name,
            spec->arg,
            text);
        return false;
    }
    memcpy(first, text, len);
    first[len] = '\0';
    return cli_parse_int(spec->name, first, spec->min, spec->max, &pair[0], err)
           && cli_parse_int(spec->name, comma + 1, spec->min, spec->max, &pair[1], err);
}

bool
cli_parse_choice(const struct option_spec *spec, const char *text, struct diag *err)
{
    const char *word = spec->choices;
    size_t len = strlen(text);
    for (int index = 0; word && *word; index++) {
        const char *bar = strchr(word, '|');
        size_t wlen = bar ? (size_t)(bar - word) : strlen(word);
        if (wlen == len && strncmp(word, text, len) == 0) {
            *(int *)spec->dest = index;
            return true;
        }
        word = bar ? bar + 1 : NULL;
    }
    diag_set(err, NULL, 0, 0, "--%s expects one of %s, got '%s'", spec->name, spec->choices, text);
    return false;
}
