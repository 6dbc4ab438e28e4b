/*
 * compare_report.c - compare's report page: one self-contained HTML file.
 *
 * The render, the reference and the error map are embedded as PNG data
 * URIs (RFC 2397; base64 of RFC 4648 section 4), so the page can be mailed
 * or attached to a grade without its images going missing; nothing is
 * fetched (no external script, style sheet or font: system fonts only).
 * A slider (and a flip button) shows the render over the reference; it is
 * a few lines of inline script, and the page still reads without it.  The
 * layout is one column on a phone and side by side on a wider screen
 * (flex-wrap, a viewport meta tag).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomic_file.h"
#include "compare_report.h"

static void
put_escaped(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&':
            fputs("&amp;", f);
            break;
        case '<':
            fputs("&lt;", f);
            break;
        case '>':
            fputs("&gt;", f);
            break;
        case '"':
            fputs("&quot;", f);
            break;
        default:
            fputc(*s, f);
        }
    }
}

static const char style[] =
    "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:0 auto;padding:12px;"
    "max-width:1200px;color:#111;background:#fff;line-height:1.4}\n"
    "h1{font-size:1.3em;margin:.2em 0 .6em;overflow-wrap:anywhere}\n"
    ".verdict{padding:10px 14px;border-radius:6px;font-size:1.1em;margin:0 0 12px}\n"
    ".agree{background:#c8ecc8;border:3px solid #1b7a1b}\n"
    ".biased{background:#f8c8c0;border:3px solid #b0201a}\n"
    ".untested{background:#e4e4e4;border:3px solid #666}\n"
    ".row{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}\n"
    "figure{margin:0;flex:1 1 300px;min-width:0}\n"
    "figcaption{font-weight:600;margin:4px 0}\n"
    "img{display:block;width:100%;height:auto;image-rendering:pixelated}\n"
    "figure.slider{max-width:720px}\n"
    ".stack{position:relative}\n"
    ".stack img.over{position:absolute;top:0;left:0;clip-path:inset(0 50% 0 0)}\n"
    "input[type=range]{width:100%}\n"
    "button{font-size:1em;padding:4px 10px;margin:4px 0}\n"
    "table{border-collapse:collapse;margin:8px 0;max-width:100%}\n"
    "td,th{padding:3px 10px 3px 0;text-align:left;vertical-align:top;border-bottom:1px solid #ddd;"
    "overflow-wrap:anywhere}\n"
    "ul{padding-left:1.2em}\n"
    "p.note{color:#444;font-size:.92em}\n";

/* The slider moves the render's clipping edge; the button swaps which
 * image is shown whole. */
static const char script[] =
    "var s=document.getElementById('slide'),o=document.getElementById('over');\n"
    "function clip(){o.style.clipPath='inset(0 '+(100-s.value)+'% 0 0)';}\n"
    "s.addEventListener('input',clip);\n"
    "document.getElementById('flip').addEventListener('click',function(){"
    "s.value=s.value>50?0:100;clip();});\n";

static void
put_image(
    FILE *f,
    const unsigned char *png,
    size_t n,
    const char *cls,
    const char *id,
    const char *alt)
{
    fprintf(
        f,
        "<img%s%s%s%s%s%s decoding=\"sync\" alt=\"%s\" src=\"data:image/png;base64,",
        cls ? " class=\"" : "",
        cls ? cls : "",
        cls ? "\"" : "",
        id ? " id=\"" : "",
        id ? id : "",
        id ? "\"" : "",
        alt);
    image_write_base64(f, png, n);
    fputs("\">", f);
}

/* A note paragraph after the verdict's (which the caller closes): lead,
 * then text as a sentence; nothing when text is empty. */
static void
put_note(FILE *f, const char *id, const char *lead, const char *text)
{
    if (text[0]) {
        fprintf(f, "</p>\n<p class=\"note\" id=\"%s\">%s", id, lead);
        put_escaped(f, text);
        fputs(".", f);
    }
}

/* The block test takes each block's mean as normal.  A few bright paths
 * (caustics, fireflies) that most renders miss make a block's mean skewed,
 * darker than the reference more often than the level says; a block's
 * variance is therefore at least its neighbourhood's (metrics.c), which
 * brings the rate back to the level (docs/calibration/README.md), but a
 * scene nobody calibrated can still surprise.  More samples tell the two
 * apart: a bias keeps its size, and its standard errors grow. */
const char compare_bias_hint[] =
    "to tell a bias from rare bright paths (caustics, fireflies) that these samples missed, render "
    "again with 4 times the spp: a bias keeps its size and its standard errors double; a chance "
    "darkening fades";

bool
compare_bias_hint_applies(const struct comparison *c)
{
    for (int i = 0; i < c->n_failing; i++) {
        const struct metrics_block *b = metrics_block_test(&c->blocks, c->failing[i]);
        int ch = compare_block_channel(b);
        if (b->mean[ch] < b->ref_mean[ch]) {
            return true;
        }
    }
    return false;
}

/* Measured by make calibrate-compare (docs/calibration/README.md) with the
 * statistics of metrics.c and regions.c as they are: update with them. */
static const char measured_alarms[] =
    "no false alarm in 200 pairs on any reference scene at 64x64; at 256x256, 1 in 400 on the "
    "area-lit box and none in 200 on the others";

void
compare_format_alarms(char *buf, size_t cap, const struct comparison *c)
{
    int tests =
        3 * (c->blocks.n_blocks + c->blocks.n_windows) + (c->regions ? c->regions->n_tests : 0);
    if (c->noise == NOISE_NONE) {
        snprintf(buf, cap, "%s", "");
        return;
    }
    snprintf(
        buf,
        cap,
        "a correct render is called biased here with probability at most %g (--alpha, shared by "
        "all %d tests); make calibrate-compare measured, for two renders of 64 spp: %s "
        "(docs/calibration/README.md). A \"biased\" you doubt: render again with 4 times the spp, "
        "or add renders with other --seed values; a bias keeps its size, a false alarm does not "
        "come back",
        c->alpha,
        tests,
        measured_alarms);
}

void
compare_format_power(char *buf, size_t cap, const struct comparison *c)
{
    const struct metrics_power *p = &c->power;
    snprintf(buf, cap, "%s", "");
    if (c->noise == NOISE_NONE || p->n == 0) {
        return;
    }
    bool windows = c->blocks.n_windows > 0;
    int side = windows ? 2 * c->block_size : c->block_size;
    char half[64], most[64], target[64], times[64];
    metrics_format_plain(half, sizeof half, 100 * p->bias_half);
    metrics_format_plain(most, sizeof most, 100 * p->bias_most);
    metrics_format_plain(target, sizeof target, 100 * COMPARE_TARGET_BIAS);
    metrics_format_plain(times, sizeof times, p->samples_most);
    const char *unit = windows ? "window" : "block";
    char more[256];
    if (p->samples_most <= 1) {
        snprintf(more, sizeof more, "%s%% is found so in 9 %ss of 10 already", target, unit);
    } else if (isinf(p->samples_most)) {
        snprintf(
            more,
            sizeof more,
            "%s%% in 9 %ss of 10 is hidden by the reference's own noise",
            target,
            unit);
    } else {
        snprintf(
            more,
            sizeof more,
            "to find %s%% so in 9 %ss of 10: about %s times these renders' samples (--spp, or "
            "more renders with other --seed values)",
            target,
            unit,
            times);
    }
    snprintf(
        buf,
        cap,
        "a bias that brightens or darkens a %dx%d %s by %s%% is found 9 times in 10 in half the "
        "%ss, and one of %s%% in 9 %ss of 10; %s",
        side,
        side,
        unit,
        half,
        unit,
        most,
        unit,
        more);
}

void
compare_format_means(char *buf, size_t cap, const struct metrics *m, const char *separator)
{
    snprintf(
        buf,
        cap,
        "render %.5g %.5g %.5g%sreference %.5g %.5g %.5g",
        m->mean[0],
        m->mean[1],
        m->mean[2],
        separator,
        m->ref_mean[0],
        m->ref_mean[1],
        m->ref_mean[2]);
}

static void
put_numbers(FILE *f, const struct comparison *c)
{
    const struct metrics *m = &c->m;
    fputs("<h2>Numbers</h2>\n<table>\n", f);
    fprintf(
        f,
        "<tr><th>relMSE</th><td>%.4g</td></tr>\n<tr><th>RMSE</th><td>%.4g</td></tr>\n",
        m->relmse,
        m->rmse);
    char means[160];
    compare_format_means(means, sizeof means, m, "<br>");
    fprintf(f, "<tr><th>mean R G B</th><td>%s</td></tr>\n", means);
    fprintf(
        f,
        "<tr><th>size</th><td>%d &times; %d pixels</td></tr>\n",
        c->render.width,
        c->render.height);
    if (c->mask) {
        fprintf(
            f,
            "<tr><th>compared</th><td>%zu pixels: the reference's smooth ones (grey in the map: not "
            "compared)</td></tr>\n",
            c->n_masked);
    }
    if (c->noise != NOISE_NONE) {
        fprintf(
            f,
            "<tr><th>test</th><td>%d blocks of %d&times;%d pixels and %d windows of "
            "%d&times;%d (2&times;2 blocks, overlapping), 3 channels each, every test at "
            "level %.2g (family level %g, Sidak-corrected); noise from %s</td></tr>\n",
            c->blocks.n_blocks,
            c->block_size,
            c->block_size,
            c->blocks.n_windows,
            2 * c->block_size,
            2 * c->block_size,
            c->level,
            c->alpha,
            c->noise == NOISE_RENDERS ? "the spread of the renders" : "the variance image");
    }
    fputs("<tr><th>render</th><td>", f);
    for (int j = 0; j < c->k; j++) {
        put_escaped(f, c->render_paths[j]);
        fputs(j + 1 < c->k ? "<br>" : "", f);
    }
    fputs("</td></tr>\n<tr><th>reference</th><td>", f);
    put_escaped(f, c->reference_path);
    fputs("</td></tr>\n</table>\n", f);
}

static void
put_failing(FILE *f, const struct comparison *c)
{
    if (c->n_failing == 0) {
        return;
    }
    fprintf(f, "<h2>Failing blocks and windows (%d)</h2>\n<ul>\n", c->n_failing);
    for (int i = 0; i < c->n_failing && i < 100; i++) {
        char line[256];
        compare_describe_block(line, sizeof line, metrics_block_test(&c->blocks, c->failing[i]));
        fputs("<li>", f);
        put_escaped(f, line);
        fputs("</li>\n", f);
    }
    if (c->n_failing > 100) {
        fprintf(f, "<li>... and %d more</li>\n", c->n_failing - 100);
    }
    fputs("</ul>\n", f);
    if (compare_bias_hint_applies(c)) {
        fputs("<p class=\"note\">", f);
        put_escaped(f, compare_bias_hint);
        fputs(".</p>\n", f);
    }
}

/* --regions: a row per region of the reference scene's feature pass. */
static void
put_regions(FILE *f, const struct comparison *c)
{
    const struct region_report *rep = c->regions;
    if (!rep) {
        return;
    }
    fputs(
        "<h2>By region</h2>\n<p class=\"note\">Each pixel's region is what the reference scene shows "
        "there (its feature pass: render --aov feature).  Replay a pixel of a biased region with "
        "render --pixel X,Y --trace - and the options of the render.</p>\n<table>\n",
        f);
    for (int i = 0; i < rep->n_regions; i++) {
        const struct region_result *r = &rep->regions[i];
        char name[32], line[512];
        regions_describe(line, sizeof line, r, rep);
        fprintf(
            f,
            "<tr><th>%s</th><td>%zu pixels: ",
            regions_label_name(r->label, name, sizeof name),
            r->n_pixels);
        put_escaped(f, line);
        if (r->biased && r->pixel_x >= 0) {
            fprintf(f, "; replay pixel %d,%d", r->pixel_x, r->pixel_y);
        }
        fputs("</td></tr>\n", f);
    }
    fputs("</table>\n", f);
}

static const char how_to_read[] =
    "<h2>How to read this page</h2>\n"
    "<p class=\"note\">The error map shows each pixel's signed relative error of luminance: blue where the "
    "render is darker than the reference, red where it is brighter, white where they agree.  Noise "
    "looks like salt and pepper that fades with more samples.  A bias "
    "(a missing cosine, a wrong pdf, light leaking through an offset) is a region of one colour that "
    "stays when the samples grow; the block test finds those and outlines them in black.  "
    "'Consistent' means no block differs by more than its noise explains at the stated level: "
    "with too few samples a small bias can still hide in the noise.</p>\n";

static void
write_page(FILE *f, const struct comparison *c, unsigned char *const png[3], const size_t n[3])
{
    const char *title = c->title ? c->title : c->render_paths[0];
    fputs(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>compare: ",
        f);
    put_escaped(f, title);
    fprintf(f, "</title>\n<style>\n%s</style>\n</head>\n<body>\n<h1>", style);
    put_escaped(f, title);
    const char *cls = c->noise == NOISE_NONE && c->status == COMPARE_AGREE && !(c->max_relmse > 0)
                          ? "untested"
                      : c->status == COMPARE_AGREE ? "agree"
                                                   : "biased";
    fprintf(f, "</h1>\n<p class=\"verdict %s\" id=\"verdict\">", cls);
    put_escaped(f, c->verdict);
    char alarms[1024], power[512];
    compare_format_alarms(alarms, sizeof alarms, c);
    put_note(f, "alarms", "", alarms);
    compare_format_power(power, sizeof power, c);
    put_note(f, "power", "What it can find: ", power);
    fputs("</p>\n<div class=\"row\">\n<figure><figcaption>Render</figcaption>", f);
    put_image(f, png[0], n[0], NULL, NULL, "render");
    fputs("</figure>\n<figure><figcaption>Reference</figcaption>", f);
    put_image(f, png[1], n[1], NULL, NULL, "reference");
    fputs("</figure>\n<figure><figcaption>Error map</figcaption>", f);
    put_image(f, png[2], n[2], NULL, NULL, "error map");
    fputs(
        "</figure>\n</div>\n<h2>Render over reference</h2>\n"
        "<p class=\"note\">Left of the edge: the render; right: the reference.  Drag the slider, or "
        "flip between them.</p>\n<div class=\"row\"><figure class=\"slider\"><div class=\"stack\">",
        f);
    put_image(f, png[1], n[1], NULL, NULL, "reference");
    put_image(f, png[0], n[0], "over", "over", "render");
    fputs(
        "</div>\n<input type=\"range\" id=\"slide\" min=\"0\" max=\"100\" value=\"50\" "
        "aria-label=\"render or reference\">\n<button id=\"flip\" type=\"button\">flip</button>"
        "</figure></div>\n",
        f);
    put_numbers(f, c);
    put_regions(f, c);
    put_failing(f, c);
    fputs(how_to_read, f);
    fprintf(f, "<script>\n%s</script>\n</body>\n</html>\n", script);
}

bool
compare_write_html(
    const struct comparison *c,
    const struct image *map,
    const char *path,
    struct diag *err)
{
    const struct image *images[3] = {&c->render, &c->reference, map};
    unsigned char *png[3] = {NULL, NULL, NULL};
    size_t n[3] = {0, 0, 0};
    bool ok = true;
    for (int i = 0; i < 3 && ok; i++) {
        png[i] = image_png_bytes(images[i], &n[i], err);
        ok = png[i] != NULL;
    }
    struct atomic_file af;
    if (ok && atomic_file_open(&af, path, err)) {
        write_page(af.f, c, png, n);
        ok = atomic_file_commit(&af, err);
    } else {
        ok = false;
    }
    for (int i = 0; i < 3; i++) {
        free(png[i]);
    }
    return ok;
}
