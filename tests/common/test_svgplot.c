/*
 * test_svgplot.c - the SVG plots of tests/lib/svgplot.c: well-formed XML (by a
 * small checker below), escaped text, nice linear ticks, decade ticks on
 * log axes, reference lines, atomic writing and the Pareto front.
 */
#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "svgplot.h"
#include "testlib.h"

/* ---- a minimal XML well-formedness checker ---------------------------------
 * Enough of XML 1.0 for what svgplot writes: declaration, DOCTYPE without an
 * internal subset, comments, CDATA, elements with quoted attributes (no
 * duplicates), the five entities and character references.  Returns NULL
 * when the document is well formed, else what is wrong (static buffer). */

#define XML_DEPTH 32
#define XML_NAME 64

struct xml_state {
    const char *p;
    char stack[XML_DEPTH][XML_NAME];
    int depth;
    int roots;
    char why[160];
};

static bool
xml_fail(struct xml_state *x, const char *what)
{
    snprintf(x->why, sizeof x->why, "%s at \"%.30s\"", what, x->p);
    return false;
}

static bool
is_name_char(char c)
{
    return isalnum((unsigned char)c) || c == '_' || c == ':' || c == '-' || c == '.';
}

/* Read a name into out; false if there is none. */
static bool
xml_name(struct xml_state *x, char *out)
{
    size_t n = 0;
    if (!(isalpha((unsigned char)*x->p) || *x->p == '_' || *x->p == ':')) {
        return false;
    }
    while (is_name_char(*x->p) && n + 1 < XML_NAME) {
        out[n++] = *x->p++;
    }
    out[n] = '\0';
    return !is_name_char(*x->p);
}

/* An entity or character reference at p ('&'); advances past it. */
static bool
xml_reference(struct xml_state *x)
{
    static const char *const named[] = {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"};
    for (int i = 0; i < 5; i++) {
        if (strncmp(x->p, named[i], strlen(named[i])) == 0) {
            x->p += strlen(named[i]);
            return true;
        }
    }
    const char *q = x->p + 1;
    if (*q++ != '#') {
        return xml_fail(x, "unknown entity");
    }
    bool hex = *q == 'x';
    q += hex;
    const char *digits = q;
    while (hex ? isxdigit((unsigned char)*q) : isdigit((unsigned char)*q)) {
        q++;
    }
    if (q == digits || *q != ';') {
        return xml_fail(x, "bad character reference");
    }
    x->p = q + 1;
    return true;
}

/* Skip past `end`, which must come. */
static bool
xml_skip_past(struct xml_state *x, const char *end)
{
    const char *e = strstr(x->p, end);
    if (!e) {
        return xml_fail(x, "unterminated markup");
    }
    x->p = e + strlen(end);
    return true;
}

/* Attributes up to '>' or "/>"; sets *empty for "/>". */
static bool
xml_attributes(struct xml_state *x, bool *empty)
{
    char seen[32][XML_NAME];
    int n_seen = 0;
    for (;;) {
        bool space = isspace((unsigned char)*x->p);
        while (isspace((unsigned char)*x->p)) {
            x->p++;
        }
        if (*x->p == '>' || (x->p[0] == '/' && x->p[1] == '>')) {
            *empty = *x->p == '/';
            x->p += *empty ? 2 : 1;
            return true;
        }
        char name[XML_NAME];
        if (!space || !xml_name(x, name) || *x->p++ != '=') {
            return xml_fail(x, "bad attribute");
        }
        for (int i = 0; i < n_seen; i++) {
            if (strcmp(seen[i], name) == 0) {
                return xml_fail(x, "duplicate attribute");
            }
        }
        if (n_seen < 32) {
            strcpy(seen[n_seen++], name);
        }
        char quote = *x->p++;
        if (quote != '"' && quote != '\'') {
            return xml_fail(x, "unquoted attribute value");
        }
        while (*x->p != quote) {
            if (*x->p == '\0' || *x->p == '<') {
                return xml_fail(x, "bad attribute value");
            }
            if (*x->p == '&' ? !xml_reference(x) : (x->p++, false)) {
                return false;
            }
        }
        x->p++;
    }
}

static bool
xml_start_tag(struct xml_state *x)
{
    char name[XML_NAME];
    bool empty = false;
    x->p++;
    if (!xml_name(x, name)) {
        return xml_fail(x, "bad element name");
    }
    if (!xml_attributes(x, &empty)) {
        return false;
    }
    if (x->depth == 0) {
        x->roots++;
    }
    if (!empty) {
        if (x->depth == XML_DEPTH) {
            return xml_fail(x, "too deep");
        }
        strcpy(x->stack[x->depth++], name);
    }
    return true;
}

static bool
xml_end_tag(struct xml_state *x)
{
    char name[XML_NAME];
    x->p += 2;
    if (!xml_name(x, name) || *x->p++ != '>') {
        return xml_fail(x, "bad end tag");
    }
    if (x->depth == 0 || strcmp(x->stack[x->depth - 1], name) != 0) {
        return xml_fail(x, "mismatched end tag");
    }
    x->depth--;
    return true;
}

static bool
xml_markup(struct xml_state *x)
{
    if (strncmp(x->p, "<?", 2) == 0) {
        return xml_skip_past(x, "?>");
    }
    if (strncmp(x->p, "<!--", 4) == 0) {
        return xml_skip_past(x, "-->");
    }
    if (strncmp(x->p, "<![CDATA[", 9) == 0) {
        return x->depth > 0 ? xml_skip_past(x, "]]>") : xml_fail(x, "CDATA outside the root");
    }
    if (strncmp(x->p, "<!DOCTYPE", 9) == 0) {
        return x->roots == 0 ? xml_skip_past(x, ">") : xml_fail(x, "late DOCTYPE");
    }
    return x->p[1] == '/' ? xml_end_tag(x) : xml_start_tag(x);
}

static const char *
xml_check(const char *doc, char *why, size_t cap)
{
    struct xml_state x = {.p = doc};
    bool ok = strncmp(doc, "<?xml ", 6) == 0 || xml_fail(&x, "no XML declaration");
    while (ok && *x.p) {
        if (*x.p == '<') {
            ok = xml_markup(&x);
        } else if (*x.p == '&') {
            ok = xml_reference(&x);
        } else if (x.depth == 0 && !isspace((unsigned char)*x.p)) {
            ok = xml_fail(&x, "text outside the root");
        } else {
            x.p++;
        }
    }
    if (ok && (x.depth != 0 || x.roots != 1)) {
        ok = xml_fail(&x, "unbalanced document");
    }
    if (ok) {
        return NULL;
    }
    snprintf(why, cap, "%s", x.why);
    return why;
}

TEST(xml_checker_catches_errors)
{
    char why[200];
    CHECK(
        xml_check("<?xml version=\"1.0\"?><a b=\"1\"><c/>x &amp; y</a>", why, sizeof why) == NULL);
    CHECK(xml_check("<?xml version=\"1.0\"?><a><b></a></b>", why, sizeof why) != NULL);
    CHECK(xml_check("<?xml version=\"1.0\"?><a>x & y</a>", why, sizeof why) != NULL);
    CHECK(xml_check("<?xml version=\"1.0\"?><a b=\"<\"/>", why, sizeof why) != NULL);
    CHECK(xml_check("<?xml version=\"1.0\"?><a b=\"1\" b=\"2\"/>", why, sizeof why) != NULL);
    CHECK(xml_check("<?xml version=\"1.0\"?><a></a><b/>", why, sizeof why) != NULL);
    CHECK(xml_check("<?xml version=\"1.0\"?><a>", why, sizeof why) != NULL);
}

/* ---- plots ---------------------------------------------------------------- */

/* Write plot to name in the temp dir, read it back (free it), and check
 * it is well formed. */
static char *
render_plot(const struct svgplot *plot, const char *name)
{
    const char *path = test_tmp_path(name);
    struct diag err = {0};
    if (!svgplot_write(plot, path, &err)) {
        diag_print(stdout, &err, "error");
        return NULL;
    }
    size_t len;
    char *doc = test_read_file(path, &len);
    if (doc) {
        char why[200];
        const char *problem = xml_check(doc, why, sizeof why);
        CHECK_MSG(problem == NULL, "%s: %s", name, problem);
        CHECK(strlen(doc) == len);
    }
    return doc;
}

static size_t
count(const char *doc, const char *needle)
{
    size_t n = 0;
    for (const char *p = strstr(doc, needle); p; p = strstr(p + 1, needle)) {
        n++;
    }
    return n;
}

TEST(linear_plot_is_well_formed_and_escaped)
{
    static const double x[] = {0, 1, 2, NAN, 4, 5};
    static const double y1[] = {0.1, 0.4, 0.35, 0.2, 0.9, 0.7};
    static const double y2[] = {0.5, 0.5, 0.6, 0.62, 0.64, 0.7};
    struct svgplot_series s[2] = {
        {.label = "a <b> & \"c\" 'd'", .x = x, .y = y1, .n = 6},
        {.label = "caf\xc3\xa9 \xff bad\x01",
         .x = x,
         .y = y2,
         .n = 6,
         .colour = SVGPLOT_PURPLE,
         .no_line = true},
    };
    struct svgplot plot = {
        .title = "Title <&>\"",
        .x_label = "x & y",
        .y_label = "<y>",
        .series = s,
        .n_series = 2,
    };
    char *doc = render_plot(&plot, "linear.svg");
    CHECK(doc != NULL);
    if (!doc) {
        return;
    }
    CHECK(strstr(doc, "a &lt;b&gt; &amp; &quot;c&quot; &apos;d&apos;") != NULL);
    CHECK(strstr(doc, "Title &lt;&amp;&gt;&quot;") != NULL);
    CHECK(strstr(doc, "x &amp; y") && strstr(doc, "&lt;y&gt;"));
    /* Valid UTF-8 kept, an invalid byte replaced, a control character dropped. */
    CHECK(strstr(doc, "caf\xc3\xa9 ? bad<") != NULL);
    CHECK(strstr(doc, "\xff") == NULL && strstr(doc, "\x01") == NULL);
    /* The NaN breaks series 1's line in two; series 2 has none. */
    CHECK(count(doc, "<polyline") == 2);
    CHECK(strstr(doc, svgplot_palette[0]) && strstr(doc, svgplot_palette[3]));
    /* Linear ticks 0..5 step 1 and 0..1 step 0.2, labelled. */
    CHECK(strstr(doc, ">5</text>") && strstr(doc, ">0.8</text>"));
    free(doc);
}

TEST(log_plot_with_reference_line_and_front)
{
    static const double spp[] = {1, 4, 16, 64, 256};
    static const double err_a[] = {0.5, 0.13, 0.031, 0.0079, 0.002};
    static const double secs[] = {0.1, 0.3, 1.2, 5.0, 21};
    static const double err_b[] = {0.2, -1, 0.012, 0.0031, 0.0009};
    static const unsigned char flag[] = {1, 0, 1, 0, 1};
    struct svgplot_series s[3] = {
        {.label = "path", .x = spp, .y = err_a, .n = 5},
        {.label = "nee", .x = secs, .y = err_b, .n = 5, .flag = flag},
        {.label = "Pareto front",
         .x = secs,
         .y = err_b,
         .n = 5,
         .colour = SVGPLOT_BLACK,
         .highlight = true,
         .marker = SVGPLOT_MARKER_NONE},
    };
    struct svgplot_refline ref = {.slope = -1, .x0 = 1, .y0 = 0.5, .label = "1/spp"};
    struct svgplot plot = {
        .title = "relMSE vs spp",
        .x_scale = SVGPLOT_LOG10,
        .y_scale = SVGPLOT_LOG10,
        .series = s,
        .n_series = 3,
        .reflines = &ref,
        .n_reflines = 1,
    };
    char *doc = render_plot(&plot, "loglog.svg");
    CHECK(doc != NULL);
    if (!doc) {
        return;
    }
    /* x from 0.1 to 1000, y from 1e-4 to 1: decade labels, plain from
     * 0.001 to 10000, as powers of ten beyond. */
    CHECK(strstr(doc, ">0.1</text>") && strstr(doc, ">1000</text>"));
    CHECK(strstr(doc, ">10<tspan dy=\"-6\" font-size=\"9\">-4</tspan></text>") != NULL);
    CHECK(strstr(doc, "1/spp") != NULL);
    CHECK(count(doc, "class=\"refline\"") == 2); /* the line and its legend sample */
    CHECK(strstr(doc, "stroke-width=\"3.5\"") != NULL);
    CHECK(count(doc, "fill=\"none\" stroke=\"#D55E00\" stroke-width=\"1.5\"/>") == 3);
    free(doc);
}

TEST(legend_fits_the_picture)
{
    /* 30 series in a 300 px tall picture: the rows that do not fit are
     * counted; a long label is cut with an ellipsis after the 38
     * characters that fit the widest legend, (320 - 50) / 7. */
    static const double x[] = {1, 2};
    static const double y[] = {3, 4};
    struct svgplot_series s[30];
    for (int i = 0; i < 30; i++) {
        s[i] = (struct svgplot_series){.label = "series", .x = x, .y = y, .n = 2};
    }
    s[0].label = "a label far too long for the legend column, which is at most 320 pixels wide";
    struct svgplot plot = {.series = s, .n_series = 30, .height = 300};
    char *doc = render_plot(&plot, "legend.svg");
    CHECK(doc != NULL);
    if (!doc) {
        return;
    }
    CHECK(strstr(doc, "\xe2\x80\xa6 and ") != NULL);
    CHECK(strstr(doc, "a label far too long for the legend co\xe2\x80\xa6") != NULL);
    CHECK(strstr(doc, "320 pixels") == NULL);
    free(doc);
}

TEST(log_ticks_are_decades)
{
    double lo, hi;
    svgplot_axis_range(0.003, 42, SVGPLOT_LOG10, &lo, &hi);
    CHECK(lo == 1e-3 && hi == 1e2);
    struct svgplot_tick t[64];
    size_t n = svgplot_ticks(lo, hi, SVGPLOT_LOG10, t, 64);
    CHECK(n == 6 + 5 * 8);
    int majors = 0;
    for (size_t i = 0; i < n && i < 64; i++) {
        if (t[i].major) {
            double e = log10(t[i].value);
            CHECK_NEAR(e, round(e), 1e-12);
            char buf[16];
            snprintf(buf, sizeof buf, "1e%d", (int)round(e));
            CHECK(t[i].value == strtod(buf, NULL));
            majors++;
        }
        CHECK(i == 0 || t[i].value > t[i - 1].value);
    }
    CHECK(majors == 6);
    CHECK(t[1].value == 2e-3 && !t[1].major);

    /* Exact decades stay; one value spans one decade. */
    svgplot_axis_range(1e-2, 1e3, SVGPLOT_LOG10, &lo, &hi);
    CHECK(lo == 1e-2 && hi == 1e3);
    svgplot_axis_range(5, 5, SVGPLOT_LOG10, &lo, &hi);
    CHECK(lo == 1 && hi == 10);

    /* 24 decades: a labelled decade every 3, no minor ticks. */
    n = svgplot_ticks(1e-12, 1e12, SVGPLOT_LOG10, t, 64);
    CHECK(n == 9);
    for (size_t i = 0; i < n && i < 64; i++) {
        int e = -12 + 3 * (int)i;
        char buf[16];
        snprintf(buf, sizeof buf, "1e%d", e);
        CHECK_MSG(t[i].major && t[i].value == strtod(buf, NULL), "tick %zu = %g", i, t[i].value);
    }
}

TEST(linear_ticks_are_nice)
{
    double lo, hi;
    /* Widened to whole steps of the widened range: 0..1 by 0.2, not
     * 0.1..0.9 (whose span would ask for steps of 0.2 off its ends). */
    svgplot_axis_range(0.13, 0.87, SVGPLOT_LINEAR, &lo, &hi);
    CHECK(lo == 0);
    CHECK_NEAR(hi, 1, 1e-15);
    struct svgplot_tick t[32];
    size_t n = svgplot_ticks(lo, hi, SVGPLOT_LINEAR, t, 32);
    CHECK(n == 6);
    for (size_t i = 0; i < n && i < 32; i++) {
        CHECK_NEAR(t[i].value, 0.2 * (double)i, 1e-12);
        CHECK(t[i].major);
    }
    svgplot_axis_range(0.13, 0.43, SVGPLOT_LINEAR, &lo, &hi);
    n = svgplot_ticks(lo, hi, SVGPLOT_LINEAR, t, 32);
    CHECK(n >= 2 && n <= 32);
    CHECK_NEAR(t[0].value, lo, 1e-12);
    CHECK_NEAR(t[n - 1].value, hi, 1e-12);
    svgplot_axis_range(-37, 420, SVGPLOT_LINEAR, &lo, &hi);
    CHECK(lo == -100 && hi == 500);
    n = svgplot_ticks(lo, hi, SVGPLOT_LINEAR, t, 32);
    CHECK(n == 7 && t[1].value == 0);
    svgplot_axis_range(0, 0, SVGPLOT_LINEAR, &lo, &hi);
    CHECK(lo < 0 && hi > 0);
    CHECK(svgplot_ticks(1, 1, SVGPLOT_LINEAR, t, 32) == 0);
    CHECK(svgplot_ticks(-1, 1, SVGPLOT_LOG10, t, 32) == 0);
}

TEST(write_is_atomic)
{
    struct svgplot plot = {.title = "empty"};
    char *doc = render_plot(&plot, "empty.svg");
    CHECK(doc != NULL);
    free(doc);
    /* No temporary file is left beside the target. */
    DIR *d = opendir(test_tmpdir());
    CHECK(d != NULL);
    for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d)) {
        CHECK_MSG(strstr(e->d_name, ".tmp") == NULL, "left over: %s", e->d_name);
    }
    if (d) {
        closedir(d);
    }
    struct diag err = {0};
    CHECK(!svgplot_write(&plot, test_tmp_path("no/such/dir.svg"), &err));
    CHECK(strstr(err.file, "no/such/dir.svg") != NULL);
}

TEST(pareto_front_of_a_known_set)
{
    /* (cost, error): the front is 0 (1, 9), 3 (2, 5), 5 (4, 2), 6 (8, 1);
     * 1 is dominated by 3, 2 by 5, 4 by 3, 7 duplicates 3, 8 is NaN. */
    static const double cost[] = {1, 3, 5, 2, 2.5, 4, 8, 2, NAN};
    static const double error[] = {9, 6, 3, 5, 5, 2, 1, 5, 0.1};
    size_t idx[9];
    size_t n = svgplot_pareto_front(cost, error, 9, idx);
    CHECK(n == 4);
    static const size_t want[] = {0, 3, 5, 6};
    for (size_t i = 0; i < 4 && i < n; i++) {
        CHECK_MSG(idx[i] == want[i], "front[%zu] = %zu", i, idx[i]);
    }
    /* Equal cost: only the lower error survives. */
    static const double c2[] = {1, 1};
    static const double e2[] = {3, 2};
    CHECK(svgplot_pareto_front(c2, e2, 2, idx) == 1 && idx[0] == 1);
    CHECK(svgplot_pareto_front(c2, e2, 0, idx) == 0);
}

TEST_MAIN(
    TEST_ENTRY(xml_checker_catches_errors),
    TEST_ENTRY(linear_plot_is_well_formed_and_escaped),
    TEST_ENTRY(log_plot_with_reference_line_and_front),
    TEST_ENTRY(legend_fits_the_picture),
    TEST_ENTRY(log_ticks_are_decades),
    TEST_ENTRY(linear_ticks_are_nice),
    TEST_ENTRY(write_is_atomic),
    TEST_ENTRY(pareto_front_of_a_known_set))
