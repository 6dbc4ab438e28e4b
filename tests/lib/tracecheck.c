/*
 * tracecheck.c - running and reading pixel traces (tracecheck.h).
 */
#include "tracecheck.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stagecheck.h"
#include "testlib.h"

#define OUTPUT_CAP 16384

const char *
tracecheck_pixel(const char *scene, int x, int y, const char *const args[])
{
    static int counter;
    char name[64];
    snprintf(name, sizeof name, "trace-%d.json", counter++);
    const char *path = test_tmp_path(name);
    char pixel[64];
    snprintf(pixel, sizeof pixel, "%d,%d", x, y);
    const char *argv[64];
    int n = 0;
    for (int i = 0; args && args[i] && n < 58; i++) {
        argv[n++] = args[i];
    }
    argv[n++] = "--pixel";
    argv[n++] = pixel;
    argv[n++] = "--trace";
    argv[n++] = path;
    argv[n] = NULL;
    static char output[OUTPUT_CAP];
    int status = test_render(scene, argv, output, sizeof output);
    if (status != 0 || !test_file_exists(path)) {
        printf("render --pixel %s %s: exit %d\n%s\n", pixel, scene, status, output);
        return NULL;
    }
    return path;
}

const char *
tracecheck_ball_scene(const char *name, const char *light)
{
    return stagecheck_scene(
        name,
        "camera origin 0 4 4 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 21 height 21\n"
        "material white diffuse albedo 0.8 0.8 0.8\n"
        "sphere center 0 1 0 radius 0.3 material white\n"
        "%s\n"
        "quad corner -4 0 -4 edge1 0 0 8 edge2 8 0 0 material white\n",
        light);
}

const char *
tracecheck_one_vertex(const char *scene, int x, int y, const char *option, const char *value)
{
    const char *args[12] = {"-s", "1"};
    int n = 2;
    const char *stage = getenv("STAGE");
    if (stage && strcmp(stage, "06") >= 0) {
        args[n++] = "--aa";
        args[n++] = "grid";
    }
    if (stage && strcmp(stage, "07") >= 0) {
        args[n++] = "--max-depth";
        args[n++] = "2";
    }
    if (option) {
        args[n++] = option;
        args[n++] = value;
    }
    args[n] = NULL;
    return scene ? tracecheck_pixel(scene, x, y, args) : NULL;
}

bool
tracecheck_value(const char *path, float value[3])
{
    size_t len;
    char *text = test_read_file(path, &len);
    const char *p = text ? strstr(text, "\"value\": [") : NULL;
    bool ok = p != NULL;
    if (p) {
        p += strlen("\"value\": [");
    }
    for (int i = 0; ok && i < 3; i++) {
        char *end;
        double v = strtod(p, &end);
        ok = end != p;
        value[i] = (float)v;
        p = end + strspn(end, ", ");
    }
    free(text);
    return ok;
}

int
tracecheck_count(const char *path, const char *text)
{
    size_t len;
    char *file = test_read_file(path, &len);
    int n = 0;
    for (const char *p = file; p && (p = strstr(p, text)) != NULL; p += strlen(text)) {
        n++;
    }
    free(file);
    return n;
}

int
tracecheck_numbers(const char *path, const char *key, double *out, int max)
{
    size_t len;
    char *file = test_read_file(path, &len);
    int n = 0;
    for (const char *p = file; p && (p = strstr(p, key)) != NULL; p += strlen(key)) {
        if (n < max) {
            out[n] = strtod(p + strlen(key), NULL);
        }
        n++;
    }
    free(file);
    return n;
}

/* Run a python3 program on path: 1 when it exits 0, 0 (its output in why)
 * when it exits otherwise, -1 when there is no python3. */
static int
run_python(const char *program, const char *path, char *why, size_t cap)
{
    const char *const argv[] = {"python3", "-c", program, path, NULL};
    int status = test_run(argv, why, cap);
    if (status == -1 || status == 127) {
        return -1;
    }
    return status == 0;
}

int
tracecheck_json_valid(const char *path, char *why, size_t cap)
{
    static const char program[] =
        "import json, struct, sys\n"
        "d = json.load(open(sys.argv[1]))\n"
        "def num(x): return isinstance(x, (int, float)) and not isinstance(x, bool)\n"
        "assert isinstance(d, dict), 'not an object'\n"
        "p = d['pixel']\n"
        "assert len(p) == 2 and all(isinstance(c, int) for c in p), 'pixel'\n"
        "v = d['value']\n"
        "assert len(v) == 3 and all(num(c) for c in v), 'value'\n"
        "assert isinstance(d['samples'], list) and d['samples'], 'samples'\n"
        "for s in d['samples']:\n"
        "    assert isinstance(s['events'], list), 'events'\n"
        "    for e in s['events']:\n"
        "        assert isinstance(e['type'], str) and isinstance(e['level'], int), e\n"
        "passes = d['passes']\n"
        "assert passes and all(len(q['estimate']) == 3 for q in passes), 'passes'\n"
        "f32 = lambda x: struct.unpack('f', struct.pack('f', x))[0]\n"
        "if not d['truncated'] and all(num(c) for q in passes for c in q['estimate']):\n"
        "    for c in range(3):\n"
        "        s = 0.0\n"
        "        for q in passes: s += q['estimate'][c]\n"
        "        mean = f32(s * (1.0 / len(passes)))\n"
        "        assert abs(mean - v[c]) <= 1e-5 * max(1.0, abs(v[c])), ('mean', c, mean, v[c])\n";
    return run_python(program, path, why, cap);
}

int
tracecheck_svg_valid(const char *path, char *why, size_t cap)
{
    static const char program[] =
        "import sys, xml.etree.ElementTree as ET\n"
        "root = ET.parse(sys.argv[1]).getroot()\n"
        "assert root.tag == '{http://www.w3.org/2000/svg}svg', root.tag\n"
        "images = root.findall('{http://www.w3.org/2000/svg}image')\n"
        "href = '{http://www.w3.org/1999/xlink}href'\n"
        "assert images and images[0].get(href, '').startswith('data:image/png;base64,'), 'no image'\n"
        "assert root.findall('.//{http://www.w3.org/2000/svg}line'), 'no segment'\n";
    return run_python(program, path, why, cap);
}
