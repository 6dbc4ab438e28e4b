/*
 * expect.h - the extremes battery's expectation table and results log,
 * header-only (like check.h), for the programs of the battery:
 * tests/stage/01_extremes_render.c, 04-06_extremes_glass.c and
 * 07_extremes_paths.c (black-box renders, tests/extremes/render.h),
 * 01_extremes_geometry.c and 04_extremes_optics.c (white-box).
 *
 * tests/extremes/expect.tsv says, for every case, stage and precision,
 * whether the case is expected to pass, to fail (xfail, with the band its
 * figure is documented to lie in) or is not run (skip).  A program computes
 * each case's outcome (passed or not, one figure, a note) and hands it to
 * expect_judge(), which
 *   - CHECKs it against the table: an unexpected failure fails, and so does
 *     an unexpected pass (the table must be flipped when a fix lands) and an
 *     expected failure whose figure left its documented band (it fails
 *     differently than documented: something else changed);
 *   - appends one line to the results log, from which
 *     tests/extremes/report.sh writes the table of docs/extremes.md.
 *
 * The log is TEST_LOG_DIR/extremes-STAGE_NAME-TAG.tsv (TEST_LOG_DIR is set
 * by tests/Makefile; the temporary directory otherwise), rewritten by each
 * run of a program.
 */
#ifndef EXTREMES_EXPECT_H
#define EXTREMES_EXPECT_H

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "testlib.h"

enum expect_kind {
    EXPECT_PASS,
    EXPECT_XFAIL,
    EXPECT_SKIP,
    EXPECT_MISSING, /* no row matches: an undocumented case fails */
};

struct expectation {
    enum expect_kind kind;
    double lo, hi; /* XFAIL: the documented band of the figure (may be +-inf) */
    char reason[512];
};

/* What a case measured. */
struct outcome {
    bool passed;
    double figure; /* the case's one number (its meaning is in expect.tsv) */
    char note[512]; /* other measured numbers, for the log */
};

/* The stage number NN of "NN_name". */
static inline int
expect_stage(void)
{
    return atoi(STAGE_NAME);
}

/* Whether `stages` ("*", "NN" or "NN-MM") contains stage n. */
static inline bool
expect_stage_matches(const char *stages, int n)
{
    if (strcmp(stages, "*") == 0) {
        return true;
    }
    int from = 0;
    int to = 0;
    int fields = sscanf(stages, "%d-%d", &from, &to);
    if (fields == 1) {
        to = from;
    }
    return fields >= 1 && from <= n && n <= to;
}

/* "-" is an open end of a band. */
static inline double
expect_bound(const char *text, double open)
{
    return strcmp(text, "-") == 0 ? open : strtod(text, NULL);
}

/* Split a tab-separated line in place into at most max fields. */
static inline int
expect_split(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        fields[n++] = p;
        char *tab = strchr(p, '\t');
        if (!tab) {
            break;
        }
        *tab = '\0';
        p = tab + 1;
    }
    p = fields[n - 1];
    p[strcspn(p, "\r\n")] = '\0';
    return n;
}

/* Fill *out from the row of expect.tsv for this case, the running stage and
 * `precision` ("double" or "float").  Exactly one row must match; none or
 * several give EXPECT_MISSING with the reason saying which. */
static inline void
expect_lookup(const char *case_name, const char *precision, struct expectation *out)
{
    *out = (struct expectation){.kind = EXPECT_MISSING, .lo = -INFINITY, .hi = INFINITY};
    snprintf(out->reason, sizeof out->reason, "no row for it in tests/extremes/expect.tsv");
    FILE *f = fopen(test_root_path("tests/extremes/expect.tsv"), "r");
    if (!f) {
        snprintf(out->reason, sizeof out->reason, "cannot open tests/extremes/expect.tsv");
        return;
    }
    char line[2048];
    int matches = 0;
    while (fgets(line, sizeof line, f)) {
        char *fields[7];
        if (line[0] == '#' || line[0] == '\n' || expect_split(line, fields, 7) < 7) {
            continue;
        }
        bool precision_ok = strcmp(fields[2], "*") == 0 || strcmp(fields[2], precision) == 0;
        if (strcmp(fields[0], case_name) != 0 || !precision_ok
            || !expect_stage_matches(fields[1], expect_stage())) {
            continue;
        }
        if (++matches > 1) {
            out->kind = EXPECT_MISSING;
            snprintf(out->reason, sizeof out->reason, "several rows of expect.tsv match it");
            break;
        }
        out->kind = strcmp(fields[3], "pass") == 0    ? EXPECT_PASS
                    : strcmp(fields[3], "xfail") == 0 ? EXPECT_XFAIL
                    : strcmp(fields[3], "skip") == 0  ? EXPECT_SKIP
                                                      : EXPECT_MISSING;
        out->lo = expect_bound(fields[4], -INFINITY);
        out->hi = expect_bound(fields[5], INFINITY);
        snprintf(out->reason, sizeof out->reason, "%s", fields[6]);
    }
    fclose(f);
}

/* Append a line to this program's results log (TAG names the program). */
static inline void
expect_log(const char *tag, const char *line)
{
    static bool started;
    const char *dir = getenv("TEST_LOG_DIR");
    char path[1024];
    snprintf(
        path,
        sizeof path,
        "%s/extremes-%s-%s.tsv",
        dir && dir[0] ? dir : test_tmpdir(),
        STAGE_NAME,
        tag);
    FILE *f = fopen(path, started ? "a" : "w");
    if (f) {
        fputs(line, f);
        fclose(f);
    }
    started = true;
}

static const char *const expect_kind_names[] = {"pass", "xfail", "skip", "missing"};

/* Judge an outcome against the table (see the top of this file) and log it.
 * A skipped case is logged and not judged. */
static inline void
expect_judge(const char *tag, const char *case_name, const char *precision, const struct outcome *o)
{
    struct expectation e;
    expect_lookup(case_name, precision, &e);
    bool in_band = e.lo <= o->figure && o->figure <= e.hi;
    const char *verdict = "ok";
    if (e.kind == EXPECT_MISSING) {
        verdict = "undocumented";
    } else if (e.kind == EXPECT_PASS && !o->passed) {
        verdict = "unexpected-fail";
    } else if (e.kind == EXPECT_XFAIL && o->passed) {
        verdict = "unexpected-pass";
    } else if (e.kind == EXPECT_XFAIL && !in_band) {
        verdict = "fails-differently";
    }
    bool ok = strcmp(verdict, "ok") == 0;
    printf(
        "%-28s %-6s expect %-5s got %-4s figure %-11.4g %s%s\n",
        case_name,
        precision,
        expect_kind_names[e.kind],
        o->passed ? "pass" : "fail",
        o->figure,
        ok ? "" : "<- ",
        ok ? "" : verdict);
    if (o->note[0]) {
        printf("    %s\n", o->note);
    }
    CHECK_MSG(
        ok,
        "%s (%s): %s; expect.tsv: %s [%g, %g] %s",
        case_name,
        precision,
        verdict,
        expect_kind_names[e.kind],
        e.lo,
        e.hi,
        e.reason);
    char line[1536];
    snprintf(
        line,
        sizeof line,
        "%s\t%s\t%s\t%s\t%s\t%.4g\t%s\t%s\n",
        case_name,
        STAGE_NAME,
        precision,
        expect_kind_names[e.kind],
        o->passed ? "pass" : "fail",
        o->figure,
        verdict,
        o->note);
    expect_log(tag, line);
}

/* Log a case the table skips (or that cannot run here), with why. */
static inline void
expect_log_skip(const char *tag, const char *case_name, const char *precision, const char *why)
{
    printf("%-28s %-6s skipped: %s\n", case_name, precision, why);
    char line[1024];
    snprintf(
        line,
        sizeof line,
        "%s\t%s\t%s\tskip\tskip\tnan\tok\t%s\n",
        case_name,
        STAGE_NAME,
        precision,
        why);
    expect_log(tag, line);
}

#endif /* EXTREMES_EXPECT_H */
