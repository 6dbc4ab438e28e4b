/*
 * cli_value.h - the values of the command line's options: numbers, decimal only (an
 * optional sign, digits, for a real a fraction and an exponent), in a
 * range, with a message that names the option and the range
 * (docs/contract.md: no hexadecimal, no "inf" or "nan", which strtoll and
 * strtod alone would also take); pairs "X,Y" and choices "a|b|c" of a
 * stage's options (struct option_spec, cli.h).
 */
#ifndef CLI_VALUE_H
#define CLI_VALUE_H

#include <stdbool.h>

#include "cli.h"
#include "diag.h"
#include "vec3.h"

/* --name's whole number text in [min, max] into *out; false with err set. */
bool cli_parse_whole(
    const char *name,
    const char *text,
    long long min,
    long long max,
    long long *out,
    struct diag *err);
/* --name's whole number text in [min, max] into *out; false with err set. */
bool cli_parse_int(
    const char *name,
    const char *text,
    double min,
    double max,
    int *out,
    struct diag *err);
/* --name's real number text in [min, max] into *out; false with err set. */
bool cli_parse_real(
    const char *name,
    const char *text,
    double min,
    double max,
    real *out,
    struct diag *err);

/* spec's "X,Y" (two whole numbers in its range) into its int[2]. */
bool cli_parse_pair(const struct option_spec *spec, const char *text, struct diag *err);
/* spec's choice, one of its "a|b|c", into its int: the choice's index. */
bool cli_parse_choice(const struct option_spec *spec, const char *text, struct diag *err);

#endif
