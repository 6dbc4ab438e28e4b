/* testlib.c - see testlib.h. */
#define _DEFAULT_SOURCE /* wait4: one child's resource usage */
#include "testlib.h"

#include "vec3.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#ifndef PROJECT_ROOT
#define PROJECT_ROOT "."
#endif

const char *
test_root(void)
{
    const char *root = getenv("ROOT");
    return root && root[0] ? root : PROJECT_ROOT;
}

/* Remove path and, for a directory, everything below it (no symbolic link
 * is followed: unlink removes the link itself). */
static void
remove_tree(const char *path)
{
    DIR *d = opendir(path);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
                continue;
            }
            char child[2048];
            snprintf(child, sizeof child, "%s/%s", path, e->d_name);
            struct stat st;
            if (lstat(child, &st) == 0 && S_ISDIR(st.st_mode)) {
                remove_tree(child);
            } else {
                unlink(child);
            }
        }
        closedir(d);
    }
    remove(path);
}

static char tmpdir_path[1024];

/* The private directory goes when the program ends normally (tests that
 * fail end normally too).  A crash or a signal skips this: the runner
 * (harness/run-tests.sh) gives each program a TMPDIR of its own and removes
 * that whatever happened. */
static void
remove_tmpdir(void)
{
    if (tmpdir_path[0]) {
        remove_tree(tmpdir_path);
    }
}

const char *
test_tmpdir(void)
{
    if (!tmpdir_path[0]) {
        /* The runner's private directory when it names one (a path kept
         * short: Unix socket paths, e.g. Chromium's, end at 108 bytes). */
        const char *given = getenv("TEST_TMPDIR");
        const char *base = getenv("TMPDIR");
        if (given && given[0]) {
            snprintf(tmpdir_path, sizeof tmpdir_path, "%s", given);
            if (mkdir(tmpdir_path, 0700) != 0 && errno != EEXIST) {
                perror(tmpdir_path);
                exit(2);
            }
        } else {
            snprintf(
                tmpdir_path,
                sizeof tmpdir_path,
                "%s/stagelight-test-XXXXXX",
                base && base[0] ? base : "/tmp");
            if (!mkdtemp(tmpdir_path)) {
                perror("mkdtemp");
                exit(2);
            }
        }
        atexit(remove_tmpdir);
    }
    return tmpdir_path;
}

/* Paths handed out stay valid until the program ends: each distinct path
 * is stored once in this table (tests are short programs). */
#define MAX_PATHS 1024
static char *interned[MAX_PATHS];
static int n_interned;

static void
free_interned(void)
{
    for (int i = 0; i < n_interned; i++) {
        free(interned[i]);
    }
}

static const char *
intern_path(const char *dir, const char *name)
{
    char buf[2048];
    snprintf(buf, sizeof buf, "%s/%s", dir, name);
    for (int i = 0; i < n_interned; i++) {
        if (strcmp(interned[i], buf) == 0) {
            return interned[i];
        }
    }
    if (n_interned == 0) {
        atexit(free_interned);
    }
    char *copy = malloc(strlen(buf) + 1);
    if (!copy || n_interned == MAX_PATHS) {
        fprintf(stderr, "testlib: too many paths\n");
        exit(2);
    }
    strcpy(copy, buf);
    interned[n_interned++] = copy;
    return copy;
}

const char *
test_tmp_path(const char *name)
{
    return intern_path(test_tmpdir(), name);
}

const char *
test_root_path(const char *relative)
{
    return intern_path(test_root(), relative);
}

bool
test_write_bytes(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    bool ok = fwrite(data, 1, len, f) == len;
    return fclose(f) == 0 && ok;
}

bool
test_write_file(const char *path, const char *text)
{
    return test_write_bytes(path, text, strlen(text));
}

void
test_put_le32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) {
        p[i] = (unsigned char)(v >> (8 * i));
    }
}

uint32_t
test_get_le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

bool
test_file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

const char *const test_contract_keys[] = {
    "width",
    "height",
    "spp",
    "threads",
    "seed",
    "seconds_total",
    "seconds_load",
    "seconds_build",
    "seconds_render",
    "rays_camera",
    "rays_shadow",
    "rays_secondary",
    "prim_tests",
    "node_visits",
    "nan_pixels",
    "peak_rss_bytes",
    NULL,
};

bool
test_same_file(const char *a, const char *b)
{
    size_t na = 0;
    size_t nb = 0;
    char *da = test_read_file(a, &na);
    char *db = test_read_file(b, &nb);
    bool same = da && db && na == nb && memcmp(da, db, na) == 0;
    free(da);
    free(db);
    return same;
}

char *
test_read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return NULL;
    }
    size_t cap = 4096;
    size_t n = 0;
    char *buf = malloc(cap + 1);
    while (buf) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap) {
            break;
        }
        cap *= 2;
        char *grown = realloc(buf, cap + 1);
        if (!grown) {
            free(buf);
            buf = NULL;
        }
        buf = grown;
    }
    fclose(f);
    if (buf) {
        buf[n] = '\0';
        if (len) {
            *len = n;
        }
    }
    return buf;
}

/* The exit status of a wait status: 128 + signal when killed. */
static int
exit_code(int status)
{
    if (WIFEXITED(status)) {
        return WEXITSTATUS(status);
    }
    return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

/* What a program wrote to capture, into output (truncated to cap); the file
 * is removed. */
static void
read_capture(const char *capture, char *output, size_t cap)
{
    if (output && cap > 0) {
        size_t len = 0;
        char *text = test_read_file(capture, &len);
        output[0] = '\0';
        if (text) {
            snprintf(output, cap, "%s", text);
            free(text);
        }
    }
    remove(capture);
}

/* The one process runner of the tests (test_spawn, test_wait): every test
 * that runs a program goes through here. */
int
test_run_signalled(
    const char *const argv[],
    double delay,
    int signo,
    bool *was_running,
    char *output,
    size_t cap)
{
    const char *capture = test_tmp_path("run-output.txt");
    if (was_running) {
        *was_running = false;
    }
    int pid = test_spawn(argv, capture);
    int status = -1;
    bool running = pid > 0;
    if (running && signo > 0) {
        struct timespec wait = {(time_t)delay, (long)((delay - (double)(time_t)delay) * 1e9)};
        while (nanosleep(&wait, &wait) != 0 && errno == EINTR) {
        }
        int raw = 0;
        running = waitpid((pid_t)pid, &raw, WNOHANG) == 0;
        if (running) {
            kill((pid_t)pid, signo);
        } else {
            status = exit_code(raw);
        }
        if (was_running) {
            *was_running = running;
        }
    }
    if (running) {
        status = test_wait(pid);
    }
    read_capture(capture, output, cap);
    return status;
}

int
test_run_peak(const char *const argv[], char *output, size_t cap, long *peak_kib)
{
    const char *capture = test_tmp_path("run-output.txt");
    int status = test_wait_peak(test_spawn(argv, capture), peak_kib);
    read_capture(capture, output, cap);
    return status;
}

int
test_run(const char *const argv[], char *output, size_t cap)
{
    return test_run_signalled(argv, 0, 0, NULL, output, cap);
}

int
test_count_files(const char *dir, const char *prefix)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d)) {
        n += strncmp(e->d_name, prefix, strlen(prefix)) == 0;
    }
    if (d) {
        closedir(d);
    }
    return n;
}

int
test_spawn(const char *const argv[], const char *capture)
{
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        int in = open("/dev/null", O_RDONLY);
        int out = open(capture, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (in < 0 || out < 0) {
            _exit(127);
        }
        dup2(in, 0);
        dup2(out, 1);
        dup2(out, 2);
        /* The signals tests send get their default disposition, whatever
         * the shell that started this test ignores (background jobs ignore
         * SIGINT). */
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        if (strchr(argv[0], '/')) {
            execv(argv[0], (char *const *)argv);
        } else {
            execvp(argv[0], (char *const *)argv);
        }
        _exit(127);
    }
    return pid < 0 ? -1 : (int)pid;
}

int
test_wait(int pid)
{
    return test_wait_peak(pid, NULL);
}

int
test_wait_peak(int pid, long *peak_kib)
{
    int status = 0;
    struct rusage usage = {.ru_maxrss = 0};
    if (peak_kib) {
        *peak_kib = -1;
    }
    if (pid < 0) {
        return -1;
    }
    while (wait4((pid_t)pid, &status, 0, &usage) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    if (peak_kib) {
#ifdef __APPLE__
        *peak_kib = usage.ru_maxrss / 1024; /* macOS: bytes */
#else
        *peak_kib = usage.ru_maxrss; /* Linux and the BSDs: KiB */
#endif
    }
    return exit_code(status);
}

const char *
test_tool_binary(const char *name)
{
    const char *buildroot = getenv("BUILDROOT");
    char relative[256];
    snprintf(relative, sizeof relative, "tools/%s", name);
    if (buildroot && buildroot[0]) {
        return intern_path(buildroot, relative); /* BUILDROOT ends in '/': a harmless "//" */
    }
    snprintf(relative, sizeof relative, "build/tools/%s", name);
    return test_root_path(relative);
}

int
test_run_tool(const char *name, const char *const args[], char *output, size_t cap)
{
    const char *argv[64];
    int n = 0;
    argv[n++] = test_tool_binary(name);
    for (int i = 0; args[i] && n < 63; i++) {
        argv[n++] = args[i];
    }
    argv[n] = NULL;
    return test_run(argv, output, cap);
}

bool
test_tool_cases(
    const char *name,
    const char *const *const cases[],
    const char *const said[],
    size_t n,
    int status)
{
    static char out[16384];
    bool all = true;
    for (size_t i = 0; i < n; i++) {
        int got = test_run_tool(name, cases[i], out, sizeof out);
        if (got != status || !strstr(out, said[i])) {
            printf(
                "%s, case %zu: exit %d (expected %d and '%s'):\n%s\n",
                name,
                i,
                got,
                status,
                said[i],
                out);
            all = false;
        }
    }
    return all;
}

/* Whether the program at path is the render of stage `stage` in the given
 * precision: its --version line reads "render (STAGE) ..., P precision".
 * A binary of another stage or precision ends the test program (exit 3,
 * no result line), which the runner reports as a failure by name. */
static void
require_stage_binary(const char *variable, const char *path, const char *precision)
{
    const char *stage = getenv("STAGE");
    char output[512];
    const char *argv[] = {path, "--version", NULL};
    int status = test_run(argv, output, sizeof output);
    char expect_stage[256];
    char expect_precision[64];
    snprintf(expect_stage, sizeof expect_stage, "render (%s) ", stage ? stage : "");
    snprintf(expect_precision, sizeof expect_precision, " %s precision", precision);
    if (!stage || !stage[0]) {
        printf(
            "testlib: %s is given but STAGE is not: cannot check that %s is the stage's render\n",
            variable,
            path);
    } else if (
        status == 0 && strncmp(output, expect_stage, strlen(expect_stage)) == 0
        && strstr(output, expect_precision) != NULL) {
        return;
    } else {
        printf(
            "testlib: %s=%s is not the %s-precision render of stage %s (exit %d, --version: %s)\n",
            variable,
            path,
            precision,
            stage,
            status,
            output);
    }
    fflush(stdout);
    exit(3);
}

const char *
test_render_binary(void)
{
    static bool checked;
    const char *render = getenv("RENDER");
    if (!render || !render[0]) {
        return NULL;
    }
    if (!checked) {
        checked = true;
        require_stage_binary("RENDER", render, sizeof(real) == sizeof(float) ? "float" : "double");
    }
    return render;
}

const char *
test_render_float_binary(void)
{
    static bool checked;
    const char *render = getenv("RENDER_FLOAT");
    if (!render || !render[0] || !test_file_exists(render)) {
        return NULL;
    }
    if (!checked) {
        checked = true;
        require_stage_binary("RENDER_FLOAT", render, "float");
    }
    return render;
}

int
test_render(const char *scene, const char *const args[], char *output, size_t cap)
{
    return test_render_peak(scene, args, output, cap, NULL);
}

int
test_render_peak(
    const char *scene,
    const char *const args[],
    char *output,
    size_t cap,
    long *peak_kib)
{
    const char *argv[64];
    int n = 0;
    argv[n++] = test_render_binary();
    if (!argv[0]) {
        snprintf(output ? output : (char[1]){0}, output ? cap : 1, "RENDER is not set");
        return -1;
    }
    argv[n++] = "-q";
    for (int i = 0; args && args[i] && n < 62; i++) {
        argv[n++] = args[i];
    }
    argv[n++] = scene;
    argv[n] = NULL;
    return test_run_peak(argv, output, cap, peak_kib);
}

bool
test_render_image(const char *scene, const char *const args[], struct image *out)
{
    static int counter;
    char name[64];
    snprintf(name, sizeof name, "render-%d.pfm", counter++);
    char path[1024];
    snprintf(path, sizeof path, "%s", test_tmp_path(name));
    const char *argv[64];
    int n = 0;
    argv[n++] = "-o";
    argv[n++] = path;
    for (int i = 0; args && args[i] && n < 62; i++) {
        argv[n++] = args[i];
    }
    argv[n] = NULL;
    char output[8192];
    int status = test_render(scene, argv, output, sizeof output);
    if (status != 0) {
        printf("render %s failed with status %d:\n%s\n", scene, status, output);
        return false;
    }
    struct diag err;
    if (!image_read_pfm(path, out, &err)) {
        diag_print(stdout, &err, "error");
        return false;
    }
    remove(path);
    return true;
}

bool
test_json_number(const char *path, const char *key, double *out)
{
    char *text = test_read_file(path, NULL);
    if (!text) {
        return false;
    }
    char pattern[256];
    snprintf(pattern, sizeof pattern, "\"%s\"", key);
    char *at = strstr(text, pattern);
    bool ok = false;
    if (at) {
        at += strlen(pattern);
        while (*at == ' ' || *at == ':') {
            at++;
        }
        char *end;
        *out = strtod(at, &end);
        ok = end != at;
    }
    free(text);
    return ok;
}

double
test_srgb8_linear(int k)
{
    /* In float, as the project's transfer function is (image.h). */
    float v = (float)k / 255.0f;
    return v <= 0.04045f ? v / 12.92f : (float)pow((v + 0.055) / 1.055, 2.4);
}

bool
test_write_texture(const char *name, int lit)
{
    struct image img = {0};
    struct diag err = {0};
    if (!image_alloc(&img, 4, 2, &err)) {
        return false;
    }
    static const int codes[3] = {204, 102, 51};
    for (int t = 0; t < 8; t++) {
        for (int c = 0; c < 3; c++) {
            img.rgb[3 * t + c] = t < lit ? (float)test_srgb8_linear(codes[c]) : 0;
        }
    }
    bool ok = image_write(&img, test_tmp_path(name), &err);
    image_free(&img);
    return ok;
}

bool
test_pixels_tile(const void *ctx, const struct tile *tile, struct stats *st)
{
    const struct test_pixels *pixels = ctx;
    for (int py = tile->y0; py < tile->y1; py++) {
        for (int px = tile->x0; px < tile->x1; px++) {
            if (driver_stop_requested()) {
                return false;
            }
            struct rng rng = tile_pixel_rng(tile, px, py);
            tile_put(tile, px, py, pixels->pixel(px, py, &rng, st));
        }
    }
    return true;
}
