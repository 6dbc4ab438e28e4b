/*
 * plotcsv.c - plot columns of a CSV file as an SVG chart (through svgplot).
 *
 *     plotcsv -x seconds -y relmse_gi -g stage,knob -m value \
 *             -f scene=cornell_diffuse_area_gi --loglog --pareto \
 *             -o docs/trade/area_gi.svg docs/trade/trade.csv
 *
 * The CSV is read generically (RFC 4180: a header line naming the columns,
 * fields separated by commas, optionally in double quotes with "" for a
 * quote; LF or CRLF line ends; blank lines ignored); columns are chosen by
 * name.  See usage() for every option.  Exit status: 0 written, 1 bad input
 * (unreadable file, malformed CSV line, missing column, a value that is
 * not a number) or unwritable output, 2 bad usage.
 */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "svgplot.h"

#define MAX_FILTERS 16
#define MAX_KEY_COLUMNS 8

static void
usage(FILE *f)
{
    fputs(
        "usage: plotcsv -x COLUMN -y COLUMN -o OUT.svg [options] INPUT.csv\n"
        "\n"
        "Plots column Y against column X of a CSV file whose first line names the\n"
        "columns (INPUT '-' reads standard input).  Points of a series are joined\n"
        "in order of increasing X.\n"
        "\n"
        "  -x, --x COLUMN          the X values (numbers)\n"
        "  -y, --y COLUMN          the Y values (numbers)\n"
        "  -o, --output FILE       the SVG file to write (atomically)\n"
        "  -g, --group C1,C2,...   one series per distinct combination of these\n"
        "                          columns (default: one series), labelled by the values\n"
        "  -m, --mean-by C1,...    rows of a series that agree in these columns are\n"
        "                          averaged into one point (mean X, mean Y): e.g.\n"
        "                          '-m value' averages over the seeds of each knob value\n"
        "  -f, --filter COL=V1|V2  keep only rows whose COL is one of the values\n"
        "                          (repeatable; all filters must hold)\n"
        "  --logx, --logy, --loglog  log10 axes (points <= 0 are left out)\n"
        "  --pareto                highlight the Pareto front of all points\n"
        "                          (minimising both X and Y): a thick line and rings\n"
        "  --refline SLOPE         a dashed reference line of this slope in axis\n"
        "                          space (log-log: y ~ x^SLOPE), through the first\n"
        "                          point of the first series unless --refline-at\n"
        "  --refline-at X,Y        the point the reference line passes through\n"
        "  --refline-label TEXT    its legend entry (default 'slope SLOPE')\n"
        "  --title TEXT, --xlabel TEXT, --ylabel TEXT  (defaults: from the columns)\n"
        "  --size W,H              picture size in pixels (default 720,480)\n"
        "  -h, --help              this text\n"
        "\n"
        "Rows whose X or Y is empty, nan or inf are skipped (counted in a note on\n"
        "stderr); any other value that is not a number is an error.\n"
        "\n"
        "Example (relMSE against time, one line per stage and knob, seeds averaged):\n"
        "  plotcsv -x seconds -y relmse_gi -g stage,knob -m value \\\n"
        "          -f scene=cornell_diffuse_area_gi --loglog --pareto \\\n"
        "          -o docs/trade/area_gi.svg docs/trade/trade.csv\n"
        "\n"
        "Exit status: 0 written, 1 bad input or output, 2 bad usage.\n",
        f);
}

/* ---- options -------------------------------------------------------------- */

struct options {
    const char *x_col, *y_col, *output, *input;
    const char *group, *mean_by; /* comma-separated column names, or NULL */
    const char *filters[MAX_FILTERS];
    int n_filters;
    bool log_x, log_y, pareto;
    const char *title, *x_label, *y_label;
    bool refline, refline_at;
    double ref_slope, ref_x, ref_y;
    const char *ref_label;
    int width, height;
};

/* A finite number, the whole of s. */
static bool
parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    return end != s && *end == '\0' && errno == 0 && isfinite(*out);
}

/* "A,B" as two numbers. */
static bool
parse_pair(const char *s, double *a, double *b)
{
    char buf[128];
    const char *comma = strchr(s, ',');
    size_t n = comma ? (size_t)(comma - s) : 0;
    if (!comma || n >= sizeof buf) {
        return false;
    }
    memcpy(buf, s, n);
    buf[n] = '\0';
    return parse_double(buf, a) && parse_double(comma + 1, b);
}

/* Options that take a value: the field of opts each one sets. */
static const char **
string_option(struct options *o, const char *name)
{
    const struct {
        const char *short_name, *long_name;
        const char **slot;
    } table[] = {
        {"-x", "--x", &o->x_col},
        {"-y", "--y", &o->y_col},
        {"-o", "--output", &o->output},
        {"-g", "--group", &o->group},
        {"-m", "--mean-by", &o->mean_by},
        {NULL, "--title", &o->title},
        {NULL, "--xlabel", &o->x_label},
        {NULL, "--ylabel", &o->y_label},
        {NULL, "--refline-label", &o->ref_label},
    };

    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
        bool match = strcmp(name, table[i].long_name) == 0
                     || (table[i].short_name && strcmp(name, table[i].short_name) == 0);
        if (match) {
            return table[i].slot;
        }
    }
    return NULL;
}

/* Options without a value; false if name is not one. */
static bool
flag_option(struct options *o, const char *name)
{
    if (strcmp(name, "--logx") == 0 || strcmp(name, "--loglog") == 0) {
        o->log_x = true;
    }
    if (strcmp(name, "--logy") == 0 || strcmp(name, "--loglog") == 0) {
        o->log_y = true;
    }
    if (strcmp(name, "--pareto") == 0) {
        o->pareto = true;
    }
    return strcmp(name, "--logx") == 0 || strcmp(name, "--logy") == 0
           || strcmp(name, "--loglog") == 0 || strcmp(name, "--pareto") == 0;
}

/* Options with a value that needs converting; false (message printed) if
 * the value is bad, true otherwise; *known says whether name is one. */
static bool
valued_option(struct options *o, const char *name, const char *value, bool *known)
{
    *known = true;
    double a, b;
    if (strcmp(name, "-f") == 0 || strcmp(name, "--filter") == 0) {
        if (o->n_filters == MAX_FILTERS || !strchr(value, '=')) {
            fprintf(
                stderr,
                "plotcsv: error: --filter wants COLUMN=VALUE (at most %d)\n",
                MAX_FILTERS);
            return false;
        }
        o->filters[o->n_filters++] = value;
    } else if (strcmp(name, "--refline") == 0) {
        o->refline = parse_double(value, &o->ref_slope);
        if (!o->refline) {
            fprintf(stderr, "plotcsv: error: --refline wants a number, got '%s'\n", value);
        }
        return o->refline;
    } else if (strcmp(name, "--refline-at") == 0) {
        o->refline_at = parse_pair(value, &o->ref_x, &o->ref_y);
        if (!o->refline_at) {
            fprintf(stderr, "plotcsv: error: --refline-at wants X,Y, got '%s'\n", value);
        }
        return o->refline_at;
    } else if (strcmp(name, "--size") == 0) {
        bool ok = parse_pair(value, &a, &b) && a >= 200 && a <= 10000 && b >= 150 && b <= 10000;
        if (!ok) {
            fprintf(
                stderr,
                "plotcsv: error: --size wants W,H in [200,10000]x[150,10000], got '%s'\n",
                value);
        }
        o->width = (int)a;
        o->height = (int)b;
        return ok;
    } else {
        *known = false;
    }
    return true;
}

/* An option with its value; false (message printed) if either is bad. */
static bool
value_option(struct options *o, const char *name, const char *value)
{
    const char **slot = string_option(o, name);
    if (slot) {
        *slot = value;
        return true;
    }
    bool known;
    bool ok = valued_option(o, name, value, &known);
    if (!known) {
        fprintf(stderr, "plotcsv: error: unknown option '%s'\n", name);
    }
    return ok && known;
}

/* 0 parsed, 1 --help, 2 bad usage (message printed). */
static int
parse_options(int argc, char **argv, struct options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
            return 1;
        }
        if (flag_option(o, s)) {
            continue;
        }
        if (s[0] != '-' || strcmp(s, "-") == 0) {
            if (o->input) {
                fprintf(stderr, "plotcsv: error: more than one input file ('%s')\n", s);
                return 2;
            }
            o->input = s;
        } else if (i + 1 >= argc) {
            fprintf(stderr, "plotcsv: error: option '%s' needs a value\n", s);
            return 2;
        } else if (!value_option(o, s, argv[++i])) {
            return 2;
        }
    }
    if (!o->x_col || !o->y_col || !o->output || !o->input) {
        fprintf(stderr, "plotcsv: error: -x, -y, -o and an input file are required\n");
        return 2;
    }
    return 0;
}

/* ---- CSV ----------------------------------------------------------------- */

struct cell {
    const char *text; /* unescaped, NUL-terminated inside csv.text */
    int col; /* 1-based column (byte) where the field starts */
};

struct csv {
    const char *path;
    char *text; /* the file; fields are NUL-terminated in place */
    struct cell *cell; /* cell[row * n_cols + column]; row 0 is the header */
    int *line; /* line[row]: where the row starts */
    size_t n_cells, cell_cap;
    size_t n_rows, row_cap, n_cols;
};

static void
csv_free(struct csv *c)
{
    free(c->text);
    free(c->cell);
    free(c->line);
}

/* Make room for `need` elements of size `size` in *array (capacity *cap). */
static bool
grow(void **array, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap) {
        return true;
    }
    size_t n = *cap ? 2 * *cap : 64;
    n = n < need ? need : n;
    void *p = realloc(*array, n * size);
    if (!p) {
        return false;
    }
    *array = p;
    *cap = n;
    return true;
}

/* Read a whole file (or stdin for "-") into a NUL-terminated buffer. */
static char *
read_all(const char *path, struct diag *err)
{
    FILE *f = strcmp(path, "-") == 0 ? stdin : fopen(path, "rb");
    if (!f) {
        diag_set(err, path, 0, 0, "cannot open: %s", strerror(errno));
        return NULL;
    }
    size_t len = 0, cap = 0;
    char *buf = NULL;
    bool ok = true;
    for (;;) {
        if (!(ok = grow((void **)&buf, &cap, len + 65537, 1))) {
            diag_set(err, path, 0, 0, "out of memory");
            break;
        }
        size_t got = fread(buf + len, 1, 65536, f);
        len += got;
        if (got < 65536) {
            ok = !ferror(f);
            if (!ok) {
                diag_set(err, path, 0, 0, "cannot read: %s", strerror(errno));
            }
            break;
        }
    }
    if (f != stdin) {
        fclose(f);
    }
    if (ok && memchr(buf, '\0', len)) {
        diag_set(err, path, 0, 0, "not a text file (contains a NUL byte)");
        ok = false;
    }
    if (!ok) {
        free(buf);
        return NULL;
    }
    buf[len] = '\0';
    return buf;
}

/* Where the parser is: r reads, w writes the unescaped field (w <= r). */
struct parser {
    char *r, *w;
    int line;
    const char *line_start;
};

/* The rest of a quoted field (the opening quote, at column col, already
 * read). */
static bool
copy_quoted(const struct csv *c, struct parser *p, int col, struct diag *err)
{
    int line = p->line;
    for (;;) {
        char ch = *p->r;
        if (ch == '\0') {
            diag_set(err, c->path, line, col, "unterminated quoted field");
            return false;
        }
        if (ch == '"' && p->r[1] != '"') {
            p->r++;
            return true;
        }
        p->r += ch == '"' ? 2 : 1; /* "" is one quote */
        *p->w++ = ch;
        if (ch == '\n') {
            p->line++;
            p->line_start = p->r;
        }
    }
}

static bool
copy_plain(const struct csv *c, struct parser *p, struct diag *err)
{
    while (*p->r && *p->r != ',' && *p->r != '\n' && !(p->r[0] == '\r' && p->r[1] == '\n')) {
        if (*p->r == '"') {
            int col = (int)(p->r - p->line_start) + 1;
            diag_set(err, c->path, p->line, col, "'\"' inside an unquoted field");
            return false;
        }
        *p->w++ = *p->r++;
    }
    return true;
}

/* One field; *last tells whether it ended its row (newline or end). */
static bool
parse_field(struct csv *c, struct parser *p, bool *last, struct diag *err)
{
    char *start = p->w;
    int col = (int)(p->r - p->line_start) + 1;
    bool quoted = *p->r == '"';
    p->r += quoted;
    if (!(quoted ? copy_quoted(c, p, col, err) : copy_plain(c, p, err))) {
        return false;
    }
    char d = *p->r;
    bool crlf = d == '\r' && p->r[1] == '\n';
    if (d != ',' && d != '\n' && d != '\0' && !crlf) {
        int at = (int)(p->r - p->line_start) + 1;
        diag_set(
            err,
            c->path,
            p->line,
            at,
            "expected ',' or the end of the line after a quoted field");
        return false;
    }
    p->r += d == '\0' ? 0 : crlf ? 2 : 1;
    *last = d != ',';
    if (d == '\n' || crlf) {
        p->line++;
        p->line_start = p->r;
    }
    *p->w++ = '\0'; /* the delimiter has been read: w may overwrite it */
    if (!grow((void **)&c->cell, &c->cell_cap, c->n_cells + 1, sizeof *c->cell)) {
        diag_set(err, c->path, 0, 0, "out of memory");
        return false;
    }
    c->cell[c->n_cells++] = (struct cell){start, col};
    return true;
}

/* Close the row that started at field `first` on line `line`. */
static bool
end_row(struct csv *c, size_t first, int line, struct diag *err)
{
    size_t n = c->n_cells - first;
    if (c->n_rows == 0) {
        c->n_cols = n;
    } else if (n != c->n_cols) {
        diag_set(
            err,
            c->path,
            line,
            1,
            "expected %zu fields as in the header, got %zu",
            c->n_cols,
            n);
        return false;
    }
    if (!grow((void **)&c->line, &c->row_cap, c->n_rows + 1, sizeof *c->line)) {
        diag_set(err, c->path, 0, 0, "out of memory");
        return false;
    }
    c->line[c->n_rows++] = line;
    return true;
}

static bool
csv_read(const char *path, struct csv *c, struct diag *err)
{
    *c = (struct csv){.path = path};
    if (!(c->text = read_all(path, err))) {
        return false;
    }
    struct parser p = {c->text, c->text, 1, c->text};
    while (*p.r) {
        if (*p.r == '\n' || (p.r[0] == '\r' && p.r[1] == '\n')) {
            p.r += *p.r == '\n' ? 1 : 2; /* a blank line */
            p.w = p.r;
            p.line++;
            p.line_start = p.r;
            continue;
        }
        int line = p.line;
        size_t first = c->n_cells;
        bool last = false;
        while (!last) {
            if (!parse_field(c, &p, &last, err)) {
                return false;
            }
        }
        if (!end_row(c, first, line, err)) {
            return false;
        }
    }
    if (c->n_rows == 0) {
        diag_set(err, path, 0, 0, "empty file: no header line");
        return false;
    }
    return true;
}

static const char *
csv_get(const struct csv *c, size_t row, size_t column)
{
    return c->cell[row * c->n_cols + column].text;
}

/* ---- columns ---------------------------------------------------------------- */

/* The column named by the len bytes at name; false (err) if none. */
static bool
find_column(const struct csv *c, const char *name, size_t len, size_t *out, struct diag *err)
{
    for (size_t i = 0; i < c->n_cols; i++) {
        const char *h = csv_get(c, 0, i);
        if (strlen(h) == len && strncmp(h, name, len) == 0) {
            *out = i;
            return true;
        }
    }
    char list[300] = "";
    for (size_t i = 0; i < c->n_cols && strlen(list) + 2 < sizeof list; i++) {
        size_t used = strlen(list);
        snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", csv_get(c, 0, i));
    }
    diag_set(err, c->path, c->line[0], 1, "no column '%.*s' (columns: %s)", (int)len, name, list);
    return false;
}

struct column_list {
    size_t idx[MAX_KEY_COLUMNS];
    size_t n;
};

/* "a,b,c" (NULL: empty) into column indices. */
static bool
find_columns(const struct csv *c, const char *names, struct column_list *out, struct diag *err)
{
    out->n = 0;
    for (const char *s = names; s && *s;) {
        size_t len = strcspn(s, ",");
        if (out->n == MAX_KEY_COLUMNS) {
            diag_set(err, NULL, 0, 0, "at most %d columns in a list", MAX_KEY_COLUMNS);
            return false;
        }
        if (!find_column(c, s, len, &out->idx[out->n++], err)) {
            return false;
        }
        s += len + (s[len] == ',');
    }
    return true;
}

/* Do rows a and b agree in every listed column? */
static bool
same_keys(const struct csv *c, size_t a, size_t b, const struct column_list *cols)
{
    for (size_t i = 0; i < cols->n; i++) {
        if (strcmp(csv_get(c, a, cols->idx[i]), csv_get(c, b, cols->idx[i])) != 0) {
            return false;
        }
    }
    return true;
}

struct filter {
    size_t column;
    const char *values; /* '|'-separated alternatives */
};

static bool
filter_matches(const struct csv *c, size_t row, const struct filter *f)
{
    const char *v = csv_get(c, row, f->column);
    size_t len = strlen(v);
    for (const char *s = f->values;;) {
        size_t n = strcspn(s, "|");
        if (n == len && strncmp(s, v, n) == 0) {
            return true;
        }
        if (s[n] == '\0') {
            return false;
        }
        s += n + 1;
    }
}

/* ---- series ---------------------------------------------------------------- */

struct point {
    size_t row; /* the first row averaged into it */
    double sum_x, sum_y;
    int count;
};

struct series {
    size_t row; /* the first row of the series: its group values */
    struct point *pt;
    size_t n, cap;
    double *x, *y; /* the points' means, sorted by x */
    unsigned char *flag;
    char label[256];
};

struct plot_data {
    const struct csv *csv;
    size_t x_col, y_col;
    struct column_list group, mean_by;
    struct filter filter[MAX_FILTERS];
    int n_filters;
    struct series *s;
    size_t n, cap;
    size_t skipped; /* rows with an empty or non-finite x or y */
};

static void
plot_data_free(struct plot_data *d)
{
    for (size_t i = 0; i < d->n; i++) {
        free(d->s[i].pt);
        free(d->s[i].x);
        free(d->s[i].y);
        free(d->s[i].flag);
    }
    free(d->s);
}

/* The number in a field: *present false when it is empty, nan or inf;
 * false (err) when it is not a number. */
static bool
field_number(
    const struct csv *c,
    size_t row,
    size_t column,
    double *out,
    bool *present,
    struct diag *err)
{
    const char *s = csv_get(c, row, column);
    char *end;
    *out = strtod(s, &end);
    while (*end == ' ' || *end == '\t') {
        end++;
    }
    if (s[strspn(s, " \t")] == '\0') {
        *present = false;
        return true;
    }
    if (end == s || *end != '\0') {
        int col = c->cell[row * c->n_cols + column].col;
        diag_set(
            err,
            c->path,
            c->line[row],
            col,
            "column '%s': expected a number, got '%s'",
            csv_get(c, 0, column),
            s);
        return false;
    }
    *present = isfinite(*out);
    return true;
}

/* The series of row (by its group values), created if new; NULL if out of memory. */
static struct series *
series_for(struct plot_data *d, size_t row)
{
    for (size_t i = 0; i < d->n; i++) {
        if (same_keys(d->csv, d->s[i].row, row, &d->group)) {
            return &d->s[i];
        }
    }
    if (!grow((void **)&d->s, &d->cap, d->n + 1, sizeof *d->s)) {
        return NULL;
    }
    struct series *s = &d->s[d->n++];
    *s = (struct series){.row = row};
    return s;
}

/* The point of row within s (by its mean-by values), created if new. */
static struct point *
point_for(const struct plot_data *d, struct series *s, size_t row)
{
    if (d->mean_by.n > 0) {
        for (size_t i = 0; i < s->n; i++) {
            if (same_keys(d->csv, s->pt[i].row, row, &d->mean_by)) {
                return &s->pt[i];
            }
        }
    }
    if (!grow((void **)&s->pt, &s->cap, s->n + 1, sizeof *s->pt)) {
        return NULL;
    }
    struct point *p = &s->pt[s->n++];
    *p = (struct point){.row = row};
    return p;
}

static bool
add_row(struct plot_data *d, size_t row, struct diag *err)
{
    for (int i = 0; i < d->n_filters; i++) {
        if (!filter_matches(d->csv, row, &d->filter[i])) {
            return true;
        }
    }
    double x, y;
    bool has_x, has_y;
    if (!field_number(d->csv, row, d->x_col, &x, &has_x, err)
        || !field_number(d->csv, row, d->y_col, &y, &has_y, err)) {
        return false;
    }
    if (!has_x || !has_y) {
        d->skipped++;
        return true;
    }
    struct series *s = series_for(d, row);
    struct point *p = s ? point_for(d, s, row) : NULL;
    if (!p) {
        diag_set(err, NULL, 0, 0, "out of memory");
        return false;
    }
    p->sum_x += x;
    p->sum_y += y;
    p->count++;
    return true;
}

static int
compare_points(const void *a, const void *b)
{
    const struct point *p = a;
    const struct point *q = b;
    double px = p->sum_x / p->count;
    double qx = q->sum_x / q->count;
    return px < qx ? -1 : px > qx ? 1 : 0;
}

/* Means, sorted by x, and the legend label. */
static bool
finish_series(const struct plot_data *d, const char *y_name, struct series *s)
{
    qsort(s->pt, s->n, sizeof *s->pt, compare_points);
    s->x = malloc(s->n * sizeof *s->x);
    s->y = malloc(s->n * sizeof *s->y);
    s->flag = calloc(s->n, 1);
    if (!s->x || !s->y || !s->flag) {
        return false;
    }
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] = s->pt[i].sum_x / s->pt[i].count;
        s->y[i] = s->pt[i].sum_y / s->pt[i].count;
    }
    snprintf(s->label, sizeof s->label, "%s", d->group.n ? "" : y_name);
    for (size_t i = 0; i < d->group.n; i++) {
        const char *v = csv_get(d->csv, s->row, d->group.idx[i]);
        size_t used = strlen(s->label);
        snprintf(
            s->label + used,
            sizeof s->label - used,
            "%s%s",
            i ? " / " : "",
            v[0] ? v : "(empty)");
    }
    return true;
}

/* Resolve the columns and filters the options name. */
static bool
resolve(const struct options *o, const struct csv *c, struct plot_data *d, struct diag *err)
{
    *d = (struct plot_data){.csv = c};
    if (!find_column(c, o->x_col, strlen(o->x_col), &d->x_col, err)
        || !find_column(c, o->y_col, strlen(o->y_col), &d->y_col, err)
        || !find_columns(c, o->group, &d->group, err)
        || !find_columns(c, o->mean_by, &d->mean_by, err)) {
        return false;
    }
    for (int i = 0; i < o->n_filters; i++) {
        const char *eq = strchr(o->filters[i], '=');
        if (!find_column(
                c,
                o->filters[i],
                (size_t)(eq - o->filters[i]),
                &d->filter[i].column,
                err)) {
            return false;
        }
        d->filter[i].values = eq + 1;
    }
    d->n_filters = o->n_filters;
    return true;
}

static bool
collect(const struct options *o, struct plot_data *d, struct diag *err)
{
    for (size_t row = 1; row < d->csv->n_rows; row++) {
        if (!add_row(d, row, err)) {
            return false;
        }
    }
    for (size_t i = 0; i < d->n; i++) {
        if (!finish_series(d, o->y_col, &d->s[i])) {
            diag_set(err, NULL, 0, 0, "out of memory");
            return false;
        }
    }
    return true;
}

/* ---- the plot --------------------------------------------------------------- */

/* The Pareto front of all the points of all the series. */
struct front {
    double *x, *y;
    size_t n;
};

/* Compute the front and flag its points in their series.  false: out of
 * memory. */
static bool
pareto(struct plot_data *d, struct front *front)
{
    size_t total = 0;
    for (size_t i = 0; i < d->n; i++) {
        total += d->s[i].n;
    }
    double *cost = malloc((total + 1) * sizeof *cost);
    double *error = malloc((total + 1) * sizeof *error);
    size_t *idx = malloc((total + 1) * sizeof *idx);
    front->x = malloc((total + 1) * sizeof *front->x);
    front->y = malloc((total + 1) * sizeof *front->y);
    bool ok = cost && error && idx && front->x && front->y;
    for (size_t i = 0, k = 0; ok && i < d->n; i++) {
        for (size_t j = 0; j < d->s[i].n; j++, k++) {
            cost[k] = d->s[i].x[j];
            error[k] = d->s[i].y[j];
        }
    }
    front->n = ok ? svgplot_pareto_front(cost, error, total, idx) : 0;
    for (size_t f = 0; f < front->n; f++) {
        front->x[f] = cost[idx[f]];
        front->y[f] = error[idx[f]];
        size_t k = idx[f], i = 0; /* back to (series, point) */
        while (k >= d->s[i].n) {
            k -= d->s[i++].n;
        }
        d->s[i].flag[k] = 1;
    }
    free(cost);
    free(error);
    free(idx);
    return ok;
}

/* Points that a log axis cannot show. */
static size_t
count_hidden(const struct plot_data *d, const struct options *o)
{
    size_t n = 0;
    for (size_t i = 0; i < d->n; i++) {
        for (size_t j = 0; j < d->s[i].n; j++) {
            n += (o->log_x && d->s[i].x[j] <= 0) || (o->log_y && d->s[i].y[j] <= 0);
        }
    }
    return n;
}

/* Fill the svgplot series (room for d->n + 1), the front last; returns
 * how many. */
static size_t
build_series(
    const struct options *o,
    const struct plot_data *d,
    const struct front *front,
    struct svgplot_series *ss)
{
    for (size_t i = 0; i < d->n; i++) {
        const struct series *s = &d->s[i];
        ss[i] = (struct svgplot_series){
            .label = s->label,
            .x = s->x,
            .y = s->y,
            .n = s->n,
            .flag = o->pareto ? s->flag : NULL,
        };
    }
    if (!o->pareto) {
        return d->n;
    }
    ss[d->n] = (struct svgplot_series){
        .label = "Pareto front",
        .x = front->x,
        .y = front->y,
        .n = front->n,
        .colour = SVGPLOT_BLACK,
        .marker = SVGPLOT_MARKER_NONE,
        .highlight = true,
    };
    return d->n + 1;
}

/* The reference line: through --refline-at, else the first point of the
 * first series; label written to buf unless given. */
static struct svgplot_refline
build_refline(const struct options *o, const struct plot_data *d, char *buf, size_t size)
{
    struct svgplot_refline ref = {.slope = o->ref_slope, .x0 = o->ref_x, .y0 = o->ref_y};
    if (!o->refline_at && d->n > 0 && d->s[0].n > 0) {
        ref.x0 = d->s[0].x[0];
        ref.y0 = d->s[0].y[0];
    }
    snprintf(buf, size, "slope %g", o->ref_slope);
    ref.label = o->ref_label ? o->ref_label : buf;
    return ref;
}

static bool
write_plot(const struct options *o, struct plot_data *d, struct diag *err)
{
    struct svgplot_series *ss = calloc(d->n + 1, sizeof *ss);
    struct front front = {0};
    bool ok = ss && (!o->pareto || pareto(d, &front));
    if (!ok) {
        diag_set(err, NULL, 0, 0, "out of memory");
    } else {
        char title[512], slope_label[64];
        snprintf(title, sizeof title, "%s vs %s", o->y_col, o->x_col);
        struct svgplot_refline ref = build_refline(o, d, slope_label, sizeof slope_label);
        struct svgplot plot = {
            .title = o->title ? o->title : title,
            .x_label = o->x_label ? o->x_label : o->x_col,
            .y_label = o->y_label ? o->y_label : o->y_col,
            .x_scale = o->log_x ? SVGPLOT_LOG10 : SVGPLOT_LINEAR,
            .y_scale = o->log_y ? SVGPLOT_LOG10 : SVGPLOT_LINEAR,
            .width = o->width,
            .height = o->height,
            .series = ss,
            .n_series = build_series(o, d, &front, ss),
            .reflines = &ref,
            .n_reflines = o->refline ? 1 : 0,
        };
        ok = svgplot_write(&plot, o->output, err);
    }
    free(ss);
    free(front.x);
    free(front.y);
    return ok;
}

static void
print_notes(const struct options *o, const struct plot_data *d)
{
    if (d->skipped) {
        fprintf(
            stderr,
            "plotcsv: note: skipped %zu row%s with an empty or non-finite %s or %s\n",
            d->skipped,
            d->skipped == 1 ? "" : "s",
            o->x_col,
            o->y_col);
    }
    size_t hidden = count_hidden(d, o);
    if (hidden) {
        fprintf(stderr, "plotcsv: note: %zu points <= 0 cannot be shown on a log axis\n", hidden);
    }
    if (d->n == 0) {
        fprintf(stderr, "plotcsv: warning: no rows to plot (check the filters)\n");
    }
}

int
main(int argc, char **argv)
{
    struct options o = {0};
    int status = parse_options(argc, argv, &o);
    if (status != 0) {
        if (status == 1) {
            usage(stdout);
        } else {
            fputs(
                "usage: plotcsv -x COLUMN -y COLUMN -o OUT.svg [options] INPUT.csv (see --help)\n",
                stderr);
        }
        return status == 1 ? 0 : 2;
    }
    struct csv c;
    struct plot_data d = {0};
    struct diag err = {0};
    bool ok = csv_read(o.input, &c, &err) && resolve(&o, &c, &d, &err) && collect(&o, &d, &err);
    if (ok) {
        print_notes(&o, &d);
        ok = write_plot(&o, &d, &err);
    }
    if (!ok) {
        diag_print(stderr, &err, "error");
    }
    plot_data_free(&d);
    csv_free(&c);
    return ok ? 0 : 1;
}
