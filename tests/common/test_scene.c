/*
 * test_scene.c - the scene loader: every scene of scenes/ loads, the Cornell
 * scenes say exactly what SCENES.md says, every scene of tests/scenes/bad/
 * fails with the message its first line expects, and no input, however
 * mangled, crashes the loader.
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gltf.h"
#include "rng.h"
#include "scene.h"
#include "testlib.h"

/* The message a failed load prints, formatted by diag_print itself. */
static void
format_diag(const struct diag *d, char *out, size_t cap)
{
    out[0] = '\0';
    FILE *f = fmemopen(out, cap, "w");
    if (f) {
        diag_print(f, d, "error");
        fclose(f);
    }
}

static bool
load_text(const char *text, const char *name, struct scene *s, struct diag *err)
{
    return scene_load_string(text, strlen(text), name, s, err);
}

/* Load text that must fail; the printed diagnostic goes into out. */
static bool
load_fails(const char *text, char *out, size_t cap)
{
    struct scene s;
    struct diag err = {.line = 0};
    if (load_text(text, "t.scene", &s, &err)) {
        scene_free(&s);
        snprintf(out, cap, "(loaded)");
        return false;
    }
    format_diag(&err, out, cap);
    return true;
}

/* The diagnostic of text, without the trailing newline, e.g.
 * "t.scene:3:5: error: ...". */
#define CHECK_ERROR(text, expected) \
    do { \
        char got_[1024]; \
        CHECK(load_fails(text, got_, sizeof got_)); \
        got_[strcspn(got_, "\n")] = '\0'; \
        CHECK_MSG(strcmp(got_, expected) == 0, "got \"%s\", expected \"%s\"", got_, expected); \
    } while (0)

#define HEADER "camera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40\nimage width 8 height 8\n"
#define WHITE "material white diffuse albedo 0.5 0.5 0.5\n"

static bool
has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s);
    size_t m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* The *.scene files of a directory (relative to the project root), sorted;
 * returns the count, names into names[] (malloc'd; free them). */
static int
list_scenes(const char *dir, char **names, int max)
{
    DIR *d = opendir(test_root_path(dir));
    int n = 0;
    if (!d) {
        return 0;
    }
    for (struct dirent *e; (e = readdir(d)) != NULL && n < max;) {
        if (has_suffix(e->d_name, ".scene")) {
            size_t len = strlen(dir) + strlen(e->d_name) + 2;
            names[n] = malloc(len);
            snprintf(names[n++], len, "%s/%s", dir, e->d_name);
        }
    }
    closedir(d);
    for (int i = 1; i < n; i++) {  // insertion sort: a handful of names
        for (int j = i; j > 0 && strcmp(names[j - 1], names[j]) > 0; j--) {
            char *t = names[j];
            names[j] = names[j - 1];
            names[j - 1] = t;
        }
    }
    return n;
}

static void
free_names(char **names, int n)
{
    for (int i = 0; i < n; i++) {
        free(names[i]);
    }
}

#define MAX_SCENES 512

TEST(every_scene_loads)
{
    char *names[MAX_SCENES];
    int n = list_scenes("scenes", names, MAX_SCENES);
    CHECK(n >= 3);
    for (int i = 0; i < n; i++) {
        struct scene s;
        struct diag err = {.line = 0};
        bool ok = scene_load(test_root_path(names[i]), &s, &err);
        /* Without glTF no glTF scene or mesh loads, and the generated
         * meshes (make models, which reads glTF) are not there to open. */
        bool needs_gltf = strstr(err.msg, "no glTF support") || strstr(err.msg, "cannot load mesh");
        if (!ok && !gltf_available() && needs_gltf) {
            printf("note: %s uses a mesh and this build has no glTF: not loaded\n", names[i]);
            continue;
        }
        char msg[1024];
        format_diag(&err, msg, sizeof msg);
        CHECK_MSG(ok, "%s", msg);
        if (ok) {
            CHECK(s.width >= 1 && s.height >= 1);
            scene_free(&s);
        }
    }
    free_names(names, n);
}

static bool
vec_eq(vec3 a, double x, double y, double z)
{
    double tol = 1e-6;
    return fabs(a.x - x) <= tol && fabs(a.y - y) <= tol && fabs(a.z - z) <= tol;
}

static int
material_named(const struct scene *s, const char *name)
{
    for (int i = 0; i < s->n_materials; i++) {
        if (strcmp(s->materials[i].name, name) == 0) {
            return i;
        }
    }
    return -1;
}

/* The quad with this corner and edges, in either edge order (walls are
 * two-sided, so the order is not part of SCENES.md); -1 if none. */
static int
find_quad(const struct scene *s, const double c[3], const double e1[3], const double e2[3])
{
    for (int i = 0; i < s->n_quads; i++) {
        const struct quad *q = &s->quads[i];
        bool corner = vec_eq(q->corner, c[0], c[1], c[2]);
        bool same = vec_eq(q->edge1, e1[0], e1[1], e1[2]) && vec_eq(q->edge2, e2[0], e2[1], e2[2]);
        bool swap = vec_eq(q->edge1, e2[0], e2[1], e2[2]) && vec_eq(q->edge2, e1[0], e1[1], e1[2]);
        if (corner && (same || swap)) {
            return i;
        }
    }
    return -1;
}

/* The box of SCENES.md: camera, image, albedos and the five walls. */
static void
check_box(const struct scene *s)
{
    CHECK(s->width == 256 && s->height == 256);
    CHECK(vec_eq(s->camera.origin, 0, 1, 3.9));
    CHECK(vec_eq(s->camera.target, 0, 1, 0));
    CHECK(vec_eq(s->camera.up, 0, 1, 0));
    CHECK_NEAR(s->camera.vfov_deg, 40, 0);
    CHECK(vec3_is_zero(s->background) && vec3_is_zero(s->ambient));
    int white = material_named(s, "white");
    int red = material_named(s, "red");
    int green = material_named(s, "green");
    CHECK(white >= 0 && red >= 0 && green >= 0);
    if (white < 0 || red < 0 || green < 0) {
        return;
    }
    CHECK(s->materials[white].kind == MAT_DIFFUSE);
    CHECK(vec_eq(s->materials[white].albedo, 0.73, 0.73, 0.73));
    CHECK(vec_eq(s->materials[red].albedo, 0.65, 0.05, 0.05));
    CHECK(vec_eq(s->materials[green].albedo, 0.12, 0.45, 0.15));

    static const struct {
        double corner[3], e1[3], e2[3];
        const char *material;
    } walls[] = {
        {{-1, 0, -1}, {2, 0, 0}, {0, 0, 2}, "white"},  // floor
        {{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, "white"},  // ceiling
        {{-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, "white"},  // back
        {{-1, 0, -1}, {0, 2, 0}, {0, 0, 2}, "red"},  // left
        {{1, 0, -1}, {0, 2, 0}, {0, 0, 2}, "green"},  // right
    };

    CHECK(s->n_quads == 5);
    for (int i = 0; i < 5; i++) {
        int q = find_quad(s, walls[i].corner, walls[i].e1, walls[i].e2);
        CHECK_MSG(q >= 0, "wall %d", i);
        CHECK(q < 0 || s->quads[q].material == material_named(s, walls[i].material));
    }
}

static void
check_spheres(const struct scene *s, const char *a, const char *b)
{
    CHECK(s->n_spheres == 2);
    if (s->n_spheres != 2) {
        return;
    }
    CHECK(vec_eq(s->spheres[0].center, -0.45, 0.40, -0.30));
    CHECK_NEAR(s->spheres[0].radius, 0.40, 1e-7);
    CHECK(s->spheres[0].material == material_named(s, a));
    CHECK(vec_eq(s->spheres[1].center, 0.45, 0.30, 0.30));
    CHECK_NEAR(s->spheres[1].radius, 0.30, 1e-7);
    CHECK(s->spheres[1].material == material_named(s, b));
}

static void
check_area_light(const struct scene *s)
{
    CHECK(s->n_area_lights == 1 && s->n_point_lights == 0);
    if (s->n_area_lights != 1) {
        return;
    }
    const struct area_light *l = &s->area_lights[0];
    vec3 n = area_light_normal(l);
    CHECK(vec_eq(n, 0, -1, 0));
    CHECK_NEAR(area_light_area(l), 0.25, 1e-7);
    CHECK(vec_eq(area_light_center(l), 0, 1.98, 0));
    CHECK(vec_eq(l->radiance, 12, 10, 8));
    // The rectangle spans x and z in [-0.25, 0.25].
    vec3 far = vec3_add(l->corner, vec3_add(l->edge1, l->edge2));
    CHECK(vec_eq(vec3_min(l->corner, far), -0.25, 1.98, -0.25));
    CHECK(vec_eq(vec3_max(l->corner, far), 0.25, 1.98, 0.25));
}

/* The line of text at a feature's location starts with the keyword. */
static void
check_feature_at(const struct scene *s, enum feature f, const char *keyword)
{
    CHECK_MSG(s->features & FEATURE_BIT(f), "feature %d", (int)f);
    size_t len = 0;
    char *text = test_read_file(s->path, &len);
    CHECK(text != NULL);
    if (!text) {
        return;
    }
    const char *line = text;
    for (int i = 1; i < s->feature_loc[f].line && line; i++) {
        line = strchr(line, '\n');
        line = line ? line + 1 : NULL;
    }
    CHECK(line && s->feature_loc[f].col >= 1);
    if (line) {
        const char *at = line + s->feature_loc[f].col - 1;
        CHECK_MSG(strncmp(at, keyword, strlen(keyword)) == 0, "feature %d at %.20s", (int)f, at);
    }
    free(text);
}

TEST(cornell_diffuse_point)
{
    struct scene s;
    struct diag err = {.line = 0};
    CHECK(scene_load(test_root_path("scenes/cornell_diffuse_point.scene"), &s, &err));
    check_box(&s);
    check_spheres(&s, "white", "white");
    CHECK(s.n_point_lights == 1 && s.n_area_lights == 0);
    if (s.n_point_lights == 1) {
        CHECK(vec_eq(s.point_lights[0].position, 0, 1.9, 0));
        CHECK(vec_eq(s.point_lights[0].intensity, 3.0, 2.5, 2.0));
    }
    CHECK(s.features == FEATURE_BIT(FEAT_POINT_LIGHT));
    check_feature_at(&s, FEAT_POINT_LIGHT, "point_light");
    scene_free(&s);
}

TEST(cornell_diffuse_area)
{
    struct scene s;
    struct diag err = {.line = 0};
    CHECK(scene_load(test_root_path("scenes/cornell_diffuse_area.scene"), &s, &err));
    check_box(&s);
    check_spheres(&s, "white", "white");
    check_area_light(&s);
    CHECK(s.features == FEATURE_BIT(FEAT_AREA_LIGHT));
    check_feature_at(&s, FEAT_AREA_LIGHT, "area_light");
    scene_free(&s);
}

TEST(cornell_specular_area)
{
    struct scene s;
    struct diag err = {.line = 0};
    CHECK(scene_load(test_root_path("scenes/cornell_specular_area.scene"), &s, &err));
    check_box(&s);
    int mirror = -1;
    int glass = -1;
    for (int i = 0; i < s.n_materials; i++) {
        mirror = s.materials[i].kind == MAT_MIRROR ? i : mirror;
        glass = s.materials[i].kind == MAT_GLASS ? i : glass;
    }
    CHECK(mirror >= 0 && glass >= 0);
    if (mirror >= 0 && glass >= 0) {
        check_spheres(&s, s.materials[mirror].name, s.materials[glass].name);
        CHECK(vec_eq(s.materials[mirror].reflectance, 0.95, 0.95, 0.95));
        CHECK_NEAR(s.materials[glass].ior, 1.5, 0);
    }
    check_area_light(&s);
    unsigned want =
        FEATURE_BIT(FEAT_AREA_LIGHT) | FEATURE_BIT(FEAT_MIRROR) | FEATURE_BIT(FEAT_GLASS);
    CHECK(s.features == want);
    check_feature_at(&s, FEAT_MIRROR, "sphere");
    check_feature_at(&s, FEAT_GLASS, "sphere");
    check_feature_at(&s, FEAT_AREA_LIGHT, "area_light");
    scene_free(&s);
}

/* One bad scene: it fails, with exactly the message of its expect line. */
static void
check_bad_scene(const char *relative)
{
    const char *path = test_root_path(relative);
    char *text = test_read_file(path, NULL);
    CHECK_MSG(text != NULL, "%s", path);
    if (!text) {
        return;
    }
    int line = 0;
    int col = 0;
    int start = 0;
    bool has_expect = sscanf(text, "# expect: %d:%d: %n", &line, &col, &start) == 2 && start > 0;
    CHECK_MSG(has_expect, "%s: no '# expect: LINE:COL: MESSAGE' first line", relative);
    if (has_expect) {
        char expected[1024];
        const char *msg = text + start;
        int msg_len = (int)strcspn(msg, "\r\n");
        snprintf(
            expected,
            sizeof expected,
            "%s:%d:%d: error: %.*s\n",
            path,
            line,
            col,
            msg_len,
            msg);
        struct scene s;
        struct diag err = {.line = 0};
        bool loaded = scene_load(path, &s, &err);
        CHECK_MSG(!loaded, "%s loaded", relative);
        char got[1024];
        format_diag(&err, got, sizeof got);
        CHECK_MSG(strcmp(got, expected) == 0, "\n  got      %s  expected %s", got, expected);
        CHECK(!loaded && s.materials == NULL && s.quads == NULL && s.n_spheres == 0);
        if (loaded) {
            scene_free(&s);
        }
    }
    free(text);
}

TEST(bad_scenes)
{
    char *names[MAX_SCENES];
    int n = list_scenes("tests/scenes/bad", names, MAX_SCENES);
    CHECK_MSG(n >= 20, "only %d bad scenes", n);
    for (int i = 0; i < n; i++) {
        check_bad_scene(names[i]);
    }
    free_names(names, n);
}

TEST(empty_file)
{
    CHECK_ERROR("", "t.scene:1:1: error: missing 'camera' statement");
    CHECK_ERROR("\n\n# only a comment\n", "t.scene:4:1: error: missing 'camera' statement");
    struct scene s;
    struct diag err = {.line = 0};
    CHECK(!scene_load_string(NULL, 0, "x.scene", &s, &err));
    CHECK(err.line == 1 && err.col == 1);
    // The same from a file on disk.
    const char *path = test_tmp_path("empty.scene");
    CHECK(test_write_file(path, ""));
    CHECK(!scene_load(path, &s, &err));
    CHECK(strcmp(err.file, path) == 0 && err.line == 1 && err.col == 1);
    CHECK(strcmp(err.msg, "missing 'camera' statement") == 0);
}

TEST(missing_statement_location)
{
    // Without a final newline the end of the file is on the last line...
    CHECK_ERROR(
        "camera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40\n# end",
        "t.scene:2:6: error: missing 'image' statement");
    // ...with one, at the start of the line after it.
    CHECK_ERROR("image width 1 height 1\r\n", "t.scene:2:1: error: missing 'camera' statement");
}

/* Binary garbage made at run time: a NUL, control bytes, DEL, broken UTF-8. */
TEST(garbage_bytes)
{
    static const struct {
        const char *text;
        size_t len;
        const char *expected;
    } cases[] = {
        {HEADER "sphere\0 center", 7, "t.scene:3:7: error: unexpected byte 0x00"},
        {HEADER "\x02", 1, "t.scene:3:1: error: unexpected byte 0x02"},
        {HEADER "# \x7f", 3, "t.scene:3:3: error: unexpected byte 0x7f"},
        {HEADER "ab\rcd\n", 6, "t.scene:3:3: error: unexpected byte 0x0d"},
        {HEADER "# \xff", 3, "t.scene:3:3: error: unexpected byte 0xff"},
        {HEADER "# \xc0\x80", 4, "t.scene:3:3: error: unexpected byte 0xc0"},  // overlong
        {HEADER "# \xed\xa0\x80", 5, "t.scene:3:3: error: unexpected byte 0xed"},  // surrogate
        {HEADER "# \xe2\x82", 4, "t.scene:3:3: error: unexpected byte 0xe2"},  // cut short
        {HEADER "# \xf4\x90\x80\x80", 6, "t.scene:3:3: error: unexpected byte 0xf4"},  // > U+10FFFF
    };

    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct scene s;
        struct diag err = {.line = 0};
        size_t len = strlen(HEADER) + cases[i].len;  // the text after HEADER may hold a NUL
        CHECK(!scene_load_string(cases[i].text, len, "t.scene", &s, &err));
        char got[1024];
        format_diag(&err, got, sizeof got);
        got[strcspn(got, "\n")] = '\0';
        CHECK_MSG(strcmp(got, cases[i].expected) == 0, "case %zu: got \"%s\"", i, got);
    }
}

TEST(comments_tabs_crlf_utf8)
{
    const char *text = "# a comment line\r\n"
                       "\tcamera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40 # tail\r\n"
                       "image width 8\theight 8#glued comment\r\n"
                       "   \t \r\n"
                       "material caf\xc3\xa9_ok diffuse albedo 1 1 1 # caf\xc3\xa9\r\n"
                       "material white diffuse albedo 0.5 0.5 0.5\r\n"
                       "sphere center 0 0 0 radius 1 material white";  // no final newline
    struct scene s;
    struct diag err = {.line = 0};
    // A UTF-8 material name is not a valid name: the error column counts it.
    CHECK(!load_text(text, "t.scene", &s, &err));
    CHECK(err.line == 5 && err.col == 10);
    const char *good = "# a comment line\r\n"
                       "\tcamera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40 # tail \xe2\x9c\x93\r\n"
                       "image width 8\theight 8#glued comment\r\n"
                       "   \t \r\n"
                       "material white diffuse albedo 0.5 0.5 0.5\r\n"
                       "sphere center 0 0 0 radius 1 material white";  // no final newline
    CHECK(load_text(good, "t.scene", &s, &err));
    CHECK(s.width == 8 && s.height == 8 && s.n_spheres == 1 && s.n_materials == 1);
    scene_free(&s);
    // Columns: a tab moves to the next multiple of 8, plus 1.
    CHECK_ERROR("\tsphear", "t.scene:1:9: error: unknown keyword 'sphear'");
    CHECK_ERROR(
        "ambient color 1\t2 3 4",
        "t.scene:1:21: error: too many numbers after 'color', expected 3");
    CHECK_ERROR("1234567\tx", "t.scene:1:1: error: unknown keyword '1234567'");
    CHECK_ERROR(
        HEADER "camera\t\tx",
        "t.scene:3:1: error: duplicate 'camera' statement (first on line 1)");
    CHECK_ERROR(
        HEADER WHITE "sphere center 0 0 0\t\tradius x",
        "t.scene:4:40: error: expected a number after 'radius', got 'x'");
    CHECK_ERROR(
        HEADER WHITE "sphere center 0 0 0 radius\r\n",
        "t.scene:4:27: error: expected a number after 'radius', got end of line");
    // A UTF-8 character counts one column.
    CHECK_ERROR(
        "# \xc3\xa9\n\xc3\xa9t\xc3\xa9 x",
        "t.scene:2:1: error: unknown keyword '\xc3\xa9t\xc3\xa9'");
    CHECK_ERROR(
        "mesh file \"\xc3\xa9\" material nope",
        "t.scene:1:24: error: unknown material 'nope' (none is defined before it)");
}

TEST(free_zero_and_twice)
{
    struct scene s = {.width = 0};
    scene_free(&s);
    struct diag err = {.line = 0};
    CHECK(load_text(HEADER WHITE "sphere center 0 0 0 radius 1 material white\n", "t", &s, &err));
    scene_free(&s);
    CHECK(s.spheres == NULL && s.n_spheres == 0);
    scene_free(&s);
}

TEST(defaults_and_features)
{
    struct scene s;
    struct diag err = {.line = 0};
    CHECK(load_text(HEADER WHITE "sphere center 0 0 0 radius 1 material white\n", "t", &s, &err));
    CHECK(vec3_is_zero(s.background) && vec3_is_zero(s.ambient));
    CHECK(s.features == 0 && s.n_point_lights == 0 && s.n_area_lights == 0);
    CHECK(strcmp(s.path, "t") == 0);
    scene_free(&s);
    const char *text = HEADER "background color 0 0 0\n"  // 3
                              "ambient color 0.1 0 0\n"  // 4
                              "material m mirror reflectance 1 1 1\n"  // 5
                              "material g glass ior 0.75\n"  // 6
                              "material b blend albedo 0.5 0.5 0.5 reflectance 0.5 0 0.2\n"  // 7
                              "material c checker albedo 1 1 1 albedo2 0 0 0 size 0.5\n"  // 8
                              "material unused mirror reflectance 0 0 0\n"  // 9
                              "  quad corner 0 0 0 edge1 1 0 0 edge2 1 0 0 material m\n"  // 10
                              "triangle v0 0 0 0 v1 1 0 0 v2 0 1 0 material g\n"  // 11
                              "sphere center 0 0 0 radius 1 material c\n"  // 12
                              "sphere center 0 0 0 radius 1 material b\n"  // 13
                              "sphere center 0 0 0 radius 1 material m\n"  // 14
                              "point_light position 0 1 0 intensity 0 0 0\n"  // 15
                              "\tarea_light corner 0 0 0 edge1 0 0 1 edge2 1 0 0 radiance 1 1 1\n";
    CHECK(load_text(text, "t", &s, &err));
    unsigned want = FEATURE_BIT(FEAT_AMBIENT) | FEATURE_BIT(FEAT_MIRROR) | FEATURE_BIT(FEAT_GLASS)
                    | FEATURE_BIT(FEAT_CHECKER) | FEATURE_BIT(FEAT_BLEND)
                    | FEATURE_BIT(FEAT_POINT_LIGHT) | FEATURE_BIT(FEAT_AREA_LIGHT);
    CHECK(s.features == want);

    static const struct {
        enum feature f;
        int line, col;
    } at[] = {
        {FEAT_AMBIENT, 4, 1},
        {FEAT_MIRROR, 10, 3},
        {FEAT_GLASS, 11, 1},
        {FEAT_CHECKER, 12, 1},
        {FEAT_BLEND, 13, 1},
        {FEAT_POINT_LIGHT, 15, 1},
        {FEAT_AREA_LIGHT, 16, 9},
    };

    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        struct src_loc loc = s.feature_loc[at[i].f];
        CHECK_MSG(
            loc.line == at[i].line && loc.col == at[i].col,
            "feature %d at %d:%d",
            (int)at[i].f,
            loc.line,
            loc.col);
    }
    CHECK(vec_eq(s.ambient, 0.1, 0, 0));
    // Material values land in their fields.
    CHECK(s.n_materials == 5);
    CHECK(s.materials[1].kind == MAT_GLASS && fabs(s.materials[1].ior - 0.75) < 1e-7);
    CHECK(s.materials[2].kind == MAT_BLEND && vec_eq(s.materials[2].reflectance, 0.5, 0, 0.2));
    CHECK(vec_eq(s.materials[2].albedo, 0.5, 0.5, 0.5));
    CHECK(s.materials[3].kind == MAT_CHECKER && vec_eq(s.materials[3].albedo2, 0, 0, 0));
    CHECK_NEAR(s.materials[3].checker_size, 0.5, 0);
    CHECK(s.materials[0].loc.line == 5 && s.materials[0].loc.col == 1);
    // The zero-area quad is kept; the triangle has three vertices of its own.
    CHECK(s.n_quads == 1 && s.n_triangles == 1 && s.n_vertices == 3);
    CHECK(s.triangles[0].v[0] == 0 && s.triangles[0].v[1] == 1 && s.triangles[0].v[2] == 2);
    CHECK(!s.triangles[0].smooth && vec3_is_zero(s.normals[1]));
    CHECK(vec_eq(s.positions[2], 0, 1, 0));
    // The area light's edges make its normal point to +y here.
    CHECK(vec_eq(area_light_normal(&s.area_lights[0]), 0, 1, 0));
    CHECK(s.area_lights[0].loc.line == 16 && s.area_lights[0].loc.col == 9);
    scene_free(&s);
    CHECK(load_text(HEADER "background color 0 0.5 0\n", "t", &s, &err));
    CHECK(s.features == FEATURE_BIT(FEAT_ENVIRONMENT) && s.feature_loc[FEAT_ENVIRONMENT].line == 3);
    scene_free(&s);
}

TEST(numbers)
{
    static const char *const good[] = {"1", "+1", ".5", "1.", "1e-3", "1E+2", "0.000001", "007"};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        char text[512];
        snprintf(
            text,
            sizeof text,
            HEADER WHITE "sphere center 0 0 0 radius %s material white\n",
            good[i]);
        struct scene s;
        struct diag err = {.line = 0};
        CHECK_MSG(load_text(text, "t", &s, &err), "radius %s: %s", good[i], err.msg);
        scene_free(&s);
    }

    static const struct {
        const char *number, *message;
    } bad[] = {
        {"1e", "expected a number after 'radius', got '1e'"},
        {"--1", "expected a number after 'radius', got '--1'"},
        {"1.2.3", "expected a number after 'radius', got '1.2.3'"},
        {"0x10", "expected a number after 'radius', got '0x10'"},
        {"1,5", "expected a number after 'radius', got '1,5'"},
        {".", "expected a number after 'radius', got '.'"},
        {"Infinity", "expected a finite number after 'radius', got 'Infinity'"},
        {"-NaN", "expected a finite number after 'radius', got '-NaN'"},
        {"nan(1)", "expected a finite number after 'radius', got 'nan(1)'"},
        {"\"1\"", "expected a number after 'radius', got '\"1\"'"},
        {"-1e999", "number '-1e999' is out of range"},
        {"1e-999", "number '1e-999' is out of range"},
    };

    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[512];
        char expected[512];
        snprintf(
            text,
            sizeof text,
            HEADER WHITE "sphere center 0 0 0 radius %s material white\n",
            bad[i].number);
        snprintf(expected, sizeof expected, "t.scene:4:28: error: %s", bad[i].message);
        CHECK_ERROR(text, expected);
    }
    // The range of the real type, whichever it is.
    if (sizeof(real) == sizeof(float)) {
        CHECK_ERROR(
            HEADER WHITE "sphere center 1e39 0 0 radius 1 material white",
            "t.scene:4:15: error: number '1e39' is out of range");
    } else {
        CHECK_ERROR(
            HEADER WHITE "sphere center 1e39 0 0 radius 0 material white",
            "t.scene:4:31: error: radius must be > 0, got 0");
    }
    // Integers.
    CHECK_ERROR(
        "image width 99999999999999999999999 height 1",
        "t.scene:1:13: error: width must be in [1, 16384] pixels, got 99999999999999999999999");
    CHECK_ERROR(
        "image width 0 height 1",
        "t.scene:1:13: error: width must be in [1, 16384] pixels, got 0");
    CHECK_ERROR(
        "image width 1e3 height 1",
        "t.scene:1:13: error: expected an integer after 'width', got '1e3'");
    CHECK_ERROR(
        "image width - height 1",
        "t.scene:1:13: error: expected an integer after 'width', got '-'");
}

TEST(messages)
{
    // Tokens are quoted, cut when long.
    CHECK_ERROR(
        "abcdefghijabcdefghijabcdefghijabcdefghijabcdefghij",
        "t.scene:1:1: error: unknown keyword 'abcdefghijabcdefghijabcdefghijabcdefghij...'");
    CHECK_ERROR("\"camera\"", "t.scene:1:1: error: unknown keyword '\"camera\"'");
    CHECK_ERROR(
        "camera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40 fov 30",
        "t.scene:1:50: error: duplicate field 'fov' in 'camera'");
    CHECK_ERROR(
        "camera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40 zoom 2",
        "t.scene:1:50: error: unknown field 'zoom' in 'camera' (expected origin, target, up, fov or near)");
    CHECK_ERROR(
        "camera origin 0 1 3 up 0 1 0 fov 40",
        "t.scene:1:1: error: missing field 'target' in 'camera'");
    CHECK_ERROR(
        "ambient color 1 1 1 1",
        "t.scene:1:21: error: too many numbers after 'color', expected 3");
    CHECK_ERROR("ambient\n", "t.scene:1:1: error: missing field 'color' in 'ambient'");
    CHECK_ERROR(
        "background color 0 0 -1",
        "t.scene:1:22: error: color must be >= 0 per component, got -1");
    CHECK_ERROR(
        "material",
        "t.scene:1:9: error: expected a material name after 'material', got end of line");
    CHECK_ERROR(
        "material x",
        "t.scene:1:11: error: expected a material kind (diffuse, mirror, glass, blend or checker) after 'x', got end of line");
    CHECK_ERROR(
        "material x diffuse",
        "t.scene:1:1: error: missing field 'albedo' in diffuse material 'x'");
    CHECK_ERROR(
        "material x mirror reflectance 1 1 1.01",
        "t.scene:1:35: error: reflectance must be in [0, 1] per component, got 1.01");
    CHECK_ERROR(
        "material x checker albedo 1 1 1 albedo2 0 0 0",
        "t.scene:1:1: error: missing field 'size' in checker material 'x'");
    CHECK_ERROR(
        "material _a-2 diffuse albedo 1 1 1 albedo 1 1 1",
        "t.scene:1:36: error: duplicate field 'albedo' in diffuse material '_a-2'");
    char long_name[128];
    snprintf(long_name, sizeof long_name, "material %064d diffuse albedo 1 1 1", 0);
    long_name[9] = 'a';
    CHECK_ERROR(
        long_name,
        "t.scene:1:10: error: material name 'a000000000000000000000000000000000000000...' is longer than 63");
    CHECK_ERROR(
        "sphere center 0 0 0 radius 1 material \"white\"",
        "t.scene:1:39: error: expected a material name after 'material', got '\"white\"'");
    CHECK_ERROR(
        "material m diffuse albedo 1 1 1\nmesh file \"\" material m",
        "t.scene:2:11: error: expected a file name after 'file', got an empty string");
    CHECK_ERROR(
        "mesh file",
        "t.scene:1:10: error: expected a file name after 'file', got end of line");
    CHECK_ERROR(
        "mesh file \"a\"b",
        "t.scene:1:14: error: expected a space after the closing quote");
    // Materials are defined before use; a long list is cut.
    CHECK_ERROR(
        HEADER "sphere center 0 0 0 radius 1 material white\n" WHITE,
        "t.scene:3:39: error: unknown material 'white' (none is defined before it)");
    CHECK_ERROR(
        HEADER "material a diffuse albedo 0 0 0\nmaterial b diffuse albedo 0 0 0\n"
               "material c diffuse albedo 0 0 0\nmaterial d diffuse albedo 0 0 0\n"
               "material e diffuse albedo 0 0 0\nmaterial f diffuse albedo 0 0 0\n"
               "material g diffuse albedo 0 0 0\n"
               "quad corner 0 0 0 edge1 1 0 0 edge2 0 1 0 material h",
        "t.scene:10:52: error: unknown material 'h' (defined materials: a, b, c, d, e, f, ...)");
    // Errors stop at the first one, in reading order.
    CHECK_ERROR(
        "image width 0 height x",
        "t.scene:1:13: error: width must be in [1, 16384] pixels, got 0");
    CHECK_ERROR("sphear\n\x01", "t.scene:1:1: error: unknown keyword 'sphear'");
}

TEST(camera_checks)
{
    CHECK_ERROR(
        "camera origin 0 0 0 target 1 1 1 up 2 2 2 fov 40",
        "t.scene:1:34: error: up must not be parallel to the view direction (target - origin)");
    CHECK_ERROR(
        "camera origin 0 0 0 target 1e30 0 0 up -1e-30 0 0 fov 40",
        "t.scene:1:37: error: up must not be parallel to the view direction (target - origin)");
    CHECK_ERROR(
        "camera origin 0 0 0 target 0 0 -1 up 0 1 0 fov 179.9 fov 1",
        "t.scene:1:54: error: duplicate field 'fov' in 'camera'");
    struct scene s;
    struct diag err = {.line = 0};
    // Nearly straight down is fine as long as up is not parallel.
    CHECK(load_text(
        "camera origin 0 5 0 target 0 0 0 up 0 0 -1 fov 0.001\nimage width 1 height 16384",
        "t",
        &s,
        &err));
    CHECK(s.width == 1 && s.height == 16384);
    scene_free(&s);
}

TEST(area_light_checks)
{
    CHECK_ERROR(
        "area_light corner 0 0 0 edge1 0 0 0 edge2 1 0 0 radiance 1 1 1",
        "t.scene:1:1: error: area_light has zero area (edge1 and edge2 are parallel or zero)");
    CHECK_ERROR(
        "area_light corner 0 0 0 edge1 1 0 0 edge2 0 0 1 radiance 1 1 -1",
        "t.scene:1:62: error: radiance must be >= 0 per component, got -1");
    if (sizeof(real) == sizeof(double)) {
        CHECK_ERROR(
            "area_light corner 0 0 0 edge1 1e200 0 0 edge2 0 0 1e200 radiance 1 1 1",
            "t.scene:1:1: error: area_light is too large (its area is not a finite number)");
    }
}

TEST(too_many_materials)
{
    size_t cap = (size_t)(SCENE_MAX_MATERIALS + 1) * 48 + 256;
    char *text = malloc(cap);
    size_t used = (size_t)snprintf(text, cap, HEADER);
    for (int i = 0; i <= SCENE_MAX_MATERIALS; i++) {
        used += (size_t)snprintf(text + used, cap - used, "material m%d diffuse albedo 1 1 1\n", i);
    }
    char expected[128];
    snprintf(
        expected,
        sizeof expected,
        "t.scene:%d:1: error: too many materials (at most %d)",
        SCENE_MAX_MATERIALS + 3,
        SCENE_MAX_MATERIALS);
    CHECK_ERROR(text, expected);
    free(text);
}

/* 1.2 MiB of spheres (about 31,000 in double, more in float, where a
 * sphere is smaller) against a 1 MiB limit: the error names the first
 * sphere that does not fit, computed from the array sizes (the materials
 * array holds 16 entries, the least it allocates). */
TEST(memory_limit)
{
    uint64_t limit = 1 << 20;
    int n = (int)(limit * 6 / 5 / sizeof(struct sphere));
    size_t cap = (size_t)n * 64 + 256;
    char *text = malloc(cap);
    size_t used = (size_t)snprintf(text, cap, HEADER WHITE);
    for (int i = 0; i < n; i++) {
        used += (size_t)snprintf(
            text + used,
            cap - used,
            "sphere center %d 0 0 radius 0.5 material white\n",
            i);
    }
    const char *path = test_tmp_path("many_spheres.scene");
    CHECK(test_write_file(path, text));
    uint64_t fit = (limit - 16 * sizeof(struct material)) / sizeof(struct sphere);
    struct scene s;
    struct diag err = {.line = 0};
    CHECK(!scene_load_limited(path, limit, &s, &err));
    CHECK_MSG(err.line == (int)(3 + fit + 1), "line %d, expected %d", err.line, (int)(4 + fit));
    CHECK_MSG(strstr(err.msg, "memory limit of 1 MiB") != NULL, "%s", err.msg);
    CHECK_MSG(strstr(err.msg, "--max-memory") != NULL, "%s", err.msg);
    CHECK(s.spheres == NULL && s.n_spheres == 0);
    /* Twice the limit is enough, and the arrays stay within it. */
    CHECK(scene_load_limited(path, 2 * limit, &s, &err));
    CHECK(s.n_spheres == n);
    CHECK(scene_bytes(&s) <= 2 * limit);
    scene_free(&s);
    CHECK(scene_load(path, &s, &err));
    CHECK(s.n_spheres == n);
    scene_free(&s);
    free(text);
}

TEST(file_errors)
{
    struct scene s;
    struct diag err = {.line = 0};
    char got[1024];
    const char *missing = test_tmp_path("no-such.scene");
    CHECK(!scene_load(missing, &s, &err));
    format_diag(&err, got, sizeof got);
    char expected[1024];
    snprintf(
        expected,
        sizeof expected,
        "%s: error: cannot open: No such file or directory\n",
        missing);
    CHECK_MSG(strcmp(got, expected) == 0, "got %s", got);
    CHECK(!scene_load(test_tmpdir(), &s, &err));
    CHECK(err.line == 0 && strstr(err.msg, "cannot read") == err.msg);
}

/* Meshes: the file is found beside the scene, and quoted names work. */
TEST(mesh_paths)
{
    char got[1024];
    CHECK(load_fails(
        HEADER WHITE "mesh file \"my \\\"model\\\".glb\" material white",
        got,
        sizeof got));
    CHECK_MSG(
        strcmp(
            got,
            "t.scene:4:11: error: cannot load mesh 'my \"model\".glb': cannot open: No such file or directory\n")
            == 0,
        "%s",
        got);
    // A file beside the scene (not in the current directory) is opened.
    const char *mesh = test_tmp_path("not-a-model.glb");
    CHECK(test_write_file(mesh, "not glTF"));
    struct scene s;
    struct diag err = {.line = 0};
    const char *text =
        HEADER WHITE "mesh file not-a-model.glb material white scale 2 translate 1 2 3";
    CHECK(!load_text(text, test_tmp_path("x.scene"), &s, &err));
    CHECK_MSG(strstr(err.msg, "cannot load mesh 'not-a-model.glb': ") == err.msg, "%s", err.msg);
    CHECK_MSG(strstr(err.msg, "cannot open") == NULL, "%s", err.msg);
    CHECK(err.line == 4 && err.col == 11);
    if (!gltf_available()) {
        CHECK_MSG(strstr(err.msg, "install libtinygltf-dev and rebuild") != NULL, "%s", err.msg);
    }
    // A glTF file that is the scene itself is no mesh of a scene: its
    // errors name the file (the message's location) and what is wrong.
    const char *gltf = test_tmp_path("not-a-scene.gltf");
    CHECK(test_write_file(gltf, "not glTF"));
    const char *const broken[] = {gltf, test_tmp_path("no-such.gltf")};
    for (int i = 0; i < 2; i++) {
        CHECK(!scene_load(broken[i], &s, &err));
        CHECK_MSG(
            strcmp(err.file, broken[i]) == 0 && !strstr(err.msg, "mesh") && err.msg[0],
            "%s: %s",
            err.file,
            err.msg);
    }
    // Scale takes 1 or 3 numbers.
    CHECK_ERROR(
        HEADER WHITE "mesh file a.glb material white scale 1 2",
        "t.scene:4:41: error: expected 3 numbers after 'scale', got end of line");
    CHECK_ERROR(
        HEADER WHITE "mesh file a.glb material white scale 1 nan 1",
        "t.scene:4:40: error: expected 3 finite numbers after 'scale', got 'nan'");
    CHECK_ERROR(
        HEADER WHITE "mesh file a.glb material white scale x",
        "t.scene:4:38: error: expected 1 or 3 numbers after 'scale', got 'x'");
    CHECK_ERROR(
        HEADER WHITE "mesh file a.glb material white scale 0",
        "t.scene:4:38: error: scale must be non-zero, got 0");
    CHECK_ERROR(
        HEADER WHITE "mesh file a.glb material white scale 1 2 3 4",
        "t.scene:4:44: error: too many numbers after 'scale', expected 1 or 3");
    CHECK_ERROR(
        HEADER WHITE "mesh file a.glb material white rotate 0 1 0",
        "t.scene:4:44: error: expected 4 numbers after 'rotate', got end of line");
}

static void
put_f32(unsigned char *p, float f)
{
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    test_put_le32(p, bits);
}

/* A binary glTF of one triangle with vertex normals, written by hand:
 * 12-byte header, a JSON chunk (padded with spaces), a BIN chunk. */
static bool
write_triangle_glb(const char *path)
{
    static const char json[] =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
        "{\"POSITION\":0,\"NORMAL\":1},\"mode\":4}]}],\"buffers\":[{\"byteLength\":72}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":72}],\"accessors\":["
        "{\"bufferView\":0,\"byteOffset\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,1]},"
        "{\"bufferView\":0,\"byteOffset\":36,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}]}";
    // A triangle in a tilted plane, its normal (0, -1, 1)/sqrt(2) at every vertex.
    static const float data[18] = {
        0,
        0,
        0,
        1,
        0,
        0,
        0,
        1,
        1,
        0,
        -0.70710678f,
        0.70710678f,
        0,
        -0.70710678f,
        0.70710678f,
        0,
        -0.70710678f,
        0.70710678f};
    size_t json_len = (sizeof json - 1 + 3) / 4 * 4;
    size_t total = 12 + 8 + json_len + 8 + sizeof data;
    unsigned char glb[1024];
    memset(glb, ' ', sizeof glb);
    test_put_le32(glb, 0x46546C67);  // "glTF"
    test_put_le32(glb + 4, 2);
    test_put_le32(glb + 8, (uint32_t)total);
    test_put_le32(glb + 12, (uint32_t)json_len);
    test_put_le32(glb + 16, 0x4E4F534A);  // "JSON"
    memcpy(glb + 20, json, sizeof json - 1);
    unsigned char *bin = glb + 20 + json_len;
    test_put_le32(bin, sizeof data);
    test_put_le32(bin + 4, 0x004E4942);  // "BIN"
    for (int i = 0; i < 18; i++) {
        put_f32(bin + 8 + 4 * i, data[i]);
    }
    FILE *f = fopen(path, "wb");
    bool ok = f && fwrite(glb, 1, total, f) == total;
    return f && fclose(f) == 0 && ok;
}

TEST(mesh_transform)
{
    REQUIRE_GLTF();
    CHECK(write_triangle_glb(test_tmp_path("triangle.glb")));
    const char *text = HEADER WHITE "triangle v0 0 0 0 v1 1 0 0 v2 0 1 0 material white\n"
                                    "mesh file triangle.glb material white scale 2 3 4 "
                                    "rotate 0 2 0 90 translate 1 2 3\n";
    struct scene s;
    struct diag err = {.line = 0};
    bool ok = load_text(text, test_tmp_path("mesh.scene"), &s, &err);
    CHECK_MSG(ok, "%s", err.msg);
    if (!ok) {
        return;
    }
    CHECK(s.n_vertices == 6 && s.n_triangles == 2);
    CHECK(s.features == FEATURE_BIT(FEAT_MESH));
    CHECK(s.feature_loc[FEAT_MESH].line == 5 && s.feature_loc[FEAT_MESH].col == 1);
    // Scale (2, 3, 4), then 90 degrees about +y (x -> -z, z -> x), then (1, 2, 3).
    CHECK(vec_eq(s.positions[3], 1, 2, 3));
    CHECK(vec_eq(s.positions[4], 1, 2, 1));
    CHECK(vec_eq(s.positions[5], 5, 5, 3));
    // Normals by the inverse transpose: (0, -1/3, 1/4) -> (0, -0.8, 0.6), rotated.
    for (int i = 3; i < 6; i++) {
        CHECK_MSG(
            vec_eq(s.normals[i], 0.6, -0.8, 0),
            "normal %d = %g %g %g",
            i,
            s.normals[i].x,
            s.normals[i].y,
            s.normals[i].z);
    }
    const struct triangle *t = &s.triangles[1];
    CHECK(t->v[0] == 3 && t->v[1] == 4 && t->v[2] == 5 && t->smooth && t->material == 0);
    CHECK(!s.triangles[0].smooth);
    scene_free(&s);
}

/* Load and check only what must hold either way: no crash (ASan would
 * tell), a located diagnostic on failure, a consistent scene on success.
 * The scene's name puts it in a directory that does not exist, so that its
 * mesh statements fail fast instead of loading a million triangles for each
 * of the thousands of variants (mesh files are relative to the scene). */
static void
load_any(const char *text, size_t len)
{
    struct scene s;
    struct diag err = {.line = 0};
    if (!scene_load_string(text, len, "/nonexistent/fuzz.scene", &s, &err)) {
        CHECK(err.line >= 1 && err.col >= 1 && err.msg[0]);
        CHECK(s.materials == NULL && s.spheres == NULL && s.n_vertices == 0);
        return;
    }
    CHECK(s.width >= 1 && s.width <= SCENE_MAX_IMAGE_DIM && s.height >= 1);
    CHECK(s.camera.vfov_deg > 0 && s.camera.vfov_deg < 180);
    for (int i = 0; i < s.n_spheres; i++) {
        CHECK(s.spheres[i].radius > 0 && s.spheres[i].material < s.n_materials);
    }
    for (int i = 0; i < s.n_area_lights; i++) {
        CHECK(area_light_area(&s.area_lights[i]) > 0);
    }
    scene_free(&s);
}

TEST(fuzz)
{
    static const char *const interesting = " \t\n\r#\"0-.e\x01\x80\xff";
    char *names[MAX_SCENES];
    int n = list_scenes("scenes", names, MAX_SCENES);
    /* A fixed seed: the mutations are the same each run. */
    struct rng state = rng_make(12345, 0);
    for (int i = 0; i < n; i++) {
        size_t len = 0;
        char *text = test_read_file(test_root_path(names[i]), &len);
        CHECK(text != NULL);
        if (!text) {
            continue;
        }
        // Copies of exactly the bytes given, so that ASan sees any read past them.
        for (size_t cut = 0; cut <= len; cut++) {
            char *prefix = malloc(cut + 1);
            memcpy(prefix, text, cut);
            load_any(prefix, cut);
            free(prefix);
        }
        char *copy = malloc(len);
        for (int round = 0; round < 2000 && len > 0; round++) {
            memcpy(copy, text, len);
            int changes = 1 + (int)(rng_next_u32(&state) % 4);
            for (int k = 0; k < changes; k++) {
                size_t at = rng_next_u32(&state) % len;
                uint32_t r = rng_next_u32(&state);
                copy[at] = r & 1 ? interesting[(r >> 1) % strlen(interesting)] : (char)(r >> 8);
            }
            load_any(copy, len);
        }
        free(copy);
        free(text);
    }
    free_names(names, n);
}

/* A leading UTF-8 byte-order mark is accepted, and columns after it are
 * counted as the user sees them; one anywhere else is still an error. */
TEST(a_leading_byte_order_mark_is_accepted)
{
    struct scene s;
    struct diag err;
    const char *scene = "\xEF\xBB\xBF"
                        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
                        "image width 8 height 8\n";
    CHECK_MSG(load_text(scene, "bom.scene", &s, &err), "%s", err.msg);
    scene_free(&s);
    CHECK(!load_text(
        "\xEF\xBB\xBF"
        "frobnicate 1\n",
        "bom.scene",
        &s,
        &err));
    CHECK_MSG(err.line == 1 && err.col == 1, "%d:%d %s", err.line, err.col, err.msg);
    CHECK(!load_text("image width 8 height 8\n\xEF\xBB\xBF", "bom.scene", &s, &err));
    /* Named where it is, not shown (it is invisible): two files joined. */
    CHECK(!load_text(
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n\xEF\xBB\xBFimage width 8 height 8\n",
        "bom.scene",
        &s,
        &err));
    CHECK_MSG(
        err.line == 2 && err.col == 1 && strstr(err.msg, "U+FEFF")
            && !strstr(err.msg, "\xEF\xBB\xBF"),
        "%d:%d %s",
        err.line,
        err.col,
        err.msg);
}

/* The camera's near plane and a sphere light, as written; the sphere light
 * is a feature of its own (stages before 03 light it as a point) and its
 * intensity as a point is L pi r^2. */
TEST(near_plane_and_sphere_light)
{
    static const char text[] = "camera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40 near 1.5\n"
                               "image width 8 height 8\n"
                               "sphere_light center 1 2 3 radius 0.5 radiance 4 2 1\n";
    struct scene s;
    struct diag err = {.line = 0};
    CHECK(load_text(text, "t.scene", &s, &err));
    CHECK(s.camera.near == (real)1.5);
    CHECK(s.n_sphere_lights == 1 && (s.features & FEATURE_BIT(FEAT_SPHERE_LIGHT)));
    if (s.n_sphere_lights == 1) {
        CHECK(vec_eq(s.sphere_lights[0].center, 1, 2, 3) && s.sphere_lights[0].radius == (real)0.5);
        CHECK(vec_eq(s.sphere_lights[0].radiance, 4, 2, 1));
        vec3 i = sphere_light_intensity(&s.sphere_lights[0]);
        /* 4 pi r^2 L to a few roundings of a real. */
        CHECK_NEAR(i.x, 4 * 0.25 * 3.14159265358979, 1e-9 + 16 * REAL_EPSILON);
        CHECK(s.feature_loc[FEAT_SPHERE_LIGHT].line == 3);
        CHECK(vec_eq(light_emitted(&s, 0, true), 4, 2, 1));
        CHECK(vec_eq(light_emitted(&s, 0, false), 0, 0, 0));
    }
    scene_free(&s);
    static const char plain[] = "camera origin 0 1 3 target 0 1 0 up 0 1 0 fov 40\n"
                                "image width 8 height 8\n";
    CHECK(load_text(plain, "t.scene", &s, &err));
    CHECK(s.camera.near == 0 && s.n_sphere_lights == 0);
    scene_free(&s);
}

TEST_MAIN(
    TEST_ENTRY(a_leading_byte_order_mark_is_accepted),
    TEST_ENTRY(every_scene_loads),
    TEST_ENTRY(near_plane_and_sphere_light),
    TEST_ENTRY(cornell_diffuse_point),
    TEST_ENTRY(cornell_diffuse_area),
    TEST_ENTRY(cornell_specular_area),
    TEST_ENTRY(bad_scenes),
    TEST_ENTRY(empty_file),
    TEST_ENTRY(missing_statement_location),
    TEST_ENTRY(garbage_bytes),
    TEST_ENTRY(comments_tabs_crlf_utf8),
    TEST_ENTRY(free_zero_and_twice),
    TEST_ENTRY(defaults_and_features),
    TEST_ENTRY(numbers),
    TEST_ENTRY(messages),
    TEST_ENTRY(camera_checks),
    TEST_ENTRY(area_light_checks),
    TEST_ENTRY(too_many_materials),
    TEST_ENTRY(memory_limit),
    TEST_ENTRY(file_errors),
    TEST_ENTRY(mesh_paths),
    TEST_ENTRY(mesh_transform),
    TEST_ENTRY(fuzz))
