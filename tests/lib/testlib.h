/*
 * testlib.h - helpers shared by the test programs: temporary files, running
 * a stage's render binary, reading what it wrote.
 */
#ifndef TESTLIB_H
#define TESTLIB_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "driver.h"
#include "gltf.h"
#include "image.h"

/* Ends a test as skipped (check.h's SKIP) when this build reads no glTF:
 * tinygltf is optional, and a test that needs a mesh file cannot run
 * without it. */
#define REQUIRE_GLTF() \
    do { \
        if (!gltf_available()) { \
            SKIP("built without tinygltf (optional: apt-get install libtinygltf-dev): " \
                 "no glTF file can be read"); \
        } \
    } while (0)

/* The project root (environment ROOT, else the compiled-in path). */
const char *test_root(void);

/* A fresh private directory for this test program (created on first use,
 * removed with everything in it when the program exits): $TEST_TMPDIR when
 * the runner gives one, else a new directory in $TMPDIR. */
const char *test_tmpdir(void);

/* tmpdir/name; the string stays valid until the program ends. */
const char *test_tmp_path(const char *name);

/* root/relative; the string stays valid until the program ends. */
const char *test_root_path(const char *relative);

bool test_write_file(const char *path, const char *text);

/* Write len bytes to path (created or truncated); false on any failure. */
bool test_write_bytes(const char *path, const void *data, size_t len);

/* 32-bit unsigned values in little-endian byte order (glTF's). */
void test_put_le32(unsigned char *p, uint32_t v);
uint32_t test_get_le32(const unsigned char *p);
bool test_file_exists(const char *path);

/* How many entries of directory dir have a name starting with prefix
 * (".stagelight-": the renderer's temporary files). */
int test_count_files(const char *dir, const char *prefix);

/* Whether two files hold the same bytes (false if either cannot be read). */
bool test_same_file(const char *a, const char *b);

/* The numeric keys every --stats file holds (CONTRACT.md), NULL-terminated. */
extern const char *const test_contract_keys[];

/* Read a whole file; NULL on failure.  *len gets its length. Free it. */
char *test_read_file(const char *path, size_t *len);

/* Run argv[0] (looked up in PATH when it holds no '/') with arguments argv
 * (NULL-terminated), stdin from /dev/null.
 * Returns the exit status (128 + signal when killed, -1 when it could not
 * run).  Its stdout and stderr together go to `output` (truncated to cap,
 * NUL-terminated) when output is not NULL. */
int test_run(const char *const argv[], char *output, size_t cap);

/* test_run, and the program's peak resident set size in KiB into *peak_kib
 * (test_wait_peak; peak_kib may be NULL). */
int test_run_peak(const char *const argv[], char *output, size_t cap, long *peak_kib);

/* Start argv as test_run does, its stdout and stderr into the file
 * `capture`, without waiting: returns its process id (-1 on failure). */
int test_spawn(const char *const argv[], const char *capture);

/* Wait for a process test_spawn started: its exit status, 128 + signal
 * when killed, -1 on failure. */
int test_wait(int pid);

/* test_wait, and the process's peak resident set size in KiB (its own, from
 * wait4) into *peak_kib (-1 on failure; peak_kib may be NULL). */
int test_wait_peak(int pid, long *peak_kib);

/* test_run, but sends signal signo to the program `delay` seconds after it
 * started if it is still running then (*was_running says whether it was;
 * may be NULL).  The program starts with signo's default disposition. */
int test_run_signalled(
    const char *const argv[],
    double delay,
    int signo,
    bool *was_running,
    char *output,
    size_t cap);

/* Path of a command-line tool of tests/tools/ (compare, merge, ...):
 * $BUILDROOT/tools/NAME (tests/Makefile exports BUILDROOT), else
 * root/build/tools/NAME.  The string stays valid until the program ends. */
const char *test_tool_binary(const char *name);

/* Run the tool `name` (test_tool_binary) with args (NULL-terminated, the
 * program left out), as test_run does. */
int test_run_tool(const char *name, const char *const args[], char *output, size_t cap);

/* Run the tool `name` with each argument list cases[i] (i < n): true when
 * every run exits with `status` and its output holds said[i]; each run
 * that does not is printed. */
bool test_tool_cases(
    const char *name,
    const char *const *const cases[],
    const char *const said[],
    size_t n,
    int status);

/* Path of the stage's render binary (environment RENDER); NULL if unset.
 * The first call checks that it is the render of the stage the runner names
 * (environment STAGE) in this build's precision, and ends the program with
 * exit status 3 and no result line if it is not. */
const char *test_render_binary(void);

/* The same stage built with REAL=float (environment RENDER_FLOAT), checked
 * the same way; NULL if unset or missing. */
const char *test_render_float_binary(void);

/* Run the stage's binary: render -q [args...] scene.  args is
 * NULL-terminated and may be NULL. */
int test_render(const char *scene, const char *const args[], char *output, size_t cap);

/* test_render, and its peak resident set size in KiB (test_run_peak). */
int test_render_peak(
    const char *scene,
    const char *const args[],
    char *output,
    size_t cap,
    long *peak_kib);

/* Render scene to a PFM in the temp dir and read it back; false (with the
 * binary's output printed) when the run or the read fails. */
bool test_render_image(const char *scene, const char *const args[], struct image *out);

/* Value of a numeric key in a flat JSON object file (the --stats file);
 * false when the file or the key is missing. */
bool test_json_number(const char *path, const char *key, double *out);

/* The linear value of the 8-bit sRGB code k (IEC 61966-2-1), written
 * here from the standard, in float as image.h's image_linear_from_srgb is. */
double test_srgb8_linear(int k);

/* A 4 x 2 PNG texture, NAME in the temp dir, whose first `lit` texels have
 * the sRGB codes (204, 102, 51) and the others are black (written from
 * the codes' linear values; the PNG encoder rounds them back). */
bool test_write_texture(const char *name, int lit);

/* A driver job of the tests whose value is made per pixel (driver.h): its
 * ctx is a struct test_pixels, and test_pixels_tile its tile function,
 * which gives each pixel its own random stream (tile_pixel_rng) as the
 * stages' render_tile does. */
struct test_pixels {
    vec3 (*pixel)(int px, int py, struct rng *rng, struct stats *st);
};
bool test_pixels_tile(const void *ctx, const struct tile *tile, struct stats *st);

#endif /* TESTLIB_H */
