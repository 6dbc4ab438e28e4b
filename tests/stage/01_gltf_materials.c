/*
 * 01_gltf_materials.c - a glTF mesh with no `material` on its line takes
 * its file's materials (docs/scene-format.md, "Materials from the file"),
 * through the stage's binary; every stage.
 *
 *  - Each mapped kind renders bit for bit as the same scene written by
 *    hand: a generated .glb (an icosphere) whose material is a diffuse
 *    colour, a smooth metal or KHR_materials_transmission with
 *    KHR_materials_ior, against `mesh ... material m` with the
 *    corresponding scene material (same triangles, same numbers).  The
 *    stage's warnings and its --strict verdict are the same too.
 *  - `material NAME` on the line overrides the file: an emissive red file
 *    renders as the grey line's material, with no warning.
 *  - Textures stand as their images' mean colour: a base colour texture
 *    renders as the hand-written albedo of its mean; an emissive texture
 *    glowing on a quarter of its texels leaves the surface reflecting.
 *  - Each kind of dropped feature (textures, roughness and metalness in
 *    between, tints, alpha, other extensions) gives its warning line
 *    naming the file, the material and what is used instead, the image is
 *    written; with --strict the same line is an error, exit 1, no image.
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "meshgen.h"
#include "stagecheck.h"
#include "testlib.h"

#define OUTPUT_CAP 8192

/* The scene around the mesh: a floor, a point light, the camera. */
#define SCENE_HEAD \
    "camera origin 0 1.2 3 target 0 0.4 0 up 0 1 0 fov 40\n" \
    "image width 40 height 32\n" \
    "material floor diffuse albedo 0.5 0.5 0.5\n" \
    "quad corner -3 -0.5 -3 edge1 0 0 6 edge2 6 0 0 material floor\n" \
    "point_light position 1 3 2 intensity 8 8 8\n"

/* An icosphere of radius 0.5 at (0, 0.2, 0), written to NAME.glb in the
 * temporary directory with the given material JSON; returns the path. */
static const char *
write_sphere(const char *name, const char *material)
{
    static const double centre[3] = {0, 0.2, 0};
    struct meshgen_mesh m = meshgen_icosphere(2, 0.5, centre);
    char file[64];
    snprintf(file, sizeof file, "%s.glb", name);
    const char *path = test_tmp_path(file);
    struct meshgen_glb_options opts = {.material = material};
    bool ok = m.n_triangles > 0 && meshgen_write_glb(&m, path, &opts);
    meshgen_free(&m);
    CHECK_MSG(ok, "cannot write %s", path);
    return ok ? path : NULL;
}

/* Render scene to out (a .pfm in the temporary directory); the exit
 * status, with the binary's output in text. */
static int
render_to(const char *scene, const char *out, bool strict, char *text)
{
    const char *const plain[] = {"-o", out, NULL};
    const char *const strict_args[] = {"-o", out, "--strict", NULL};
    return test_render(scene, strict ? strict_args : plain, text, OUTPUT_CAP);
}

struct kind_case {
    const char *name;
    const char *gltf; /* the material in the file; NULL: none */
    const char *scene; /* the same, as a scene material named m */
};

static const struct kind_case kinds[] = {
    {"diffuse",
     "{\"name\":\"clay\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.6,0.3,0.2,1],"
     "\"metallicFactor\":0,\"roughnessFactor\":1}}",
     "material m diffuse albedo 0.6 0.3 0.2"},
    {"mirror",
     "{\"name\":\"chrome\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.8,0.7,1],"
     "\"metallicFactor\":1,\"roughnessFactor\":0}}",
     "material m mirror reflectance 0.9 0.8 0.7"},
    {"glass",
     "{\"name\":\"water\",\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0},"
     "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
     "\"KHR_materials_ior\":{\"ior\":1.33}}}",
     "material m glass ior 1.33"},
    /* No material at all: glTF's default (white, metallic 1, roughness 1),
     * shaded white diffuse without a note, and --strict takes it. */
    {"unmaterialed", NULL, "material m diffuse albedo 1 1 1"},
};

TEST(each_kind_renders_as_the_scene_written_by_hand)
{
    REQUIRE_GLTF();
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        const struct kind_case *k = &kinds[i];
        if (!write_sphere(k->name, k->gltf)) {
            continue;
        }
        char name[64];
        snprintf(name, sizeof name, "%s_file.scene", k->name);
        const char *from_file = stagecheck_scene(name, SCENE_HEAD "mesh file %s.glb\n", k->name);
        snprintf(name, sizeof name, "%s_hand.scene", k->name);
        const char *by_hand = stagecheck_scene(
            name,
            SCENE_HEAD "%s\nmesh file %s.glb material m\n",
            k->scene,
            k->name);
        const char *a = test_tmp_path("file.pfm");
        const char *b = test_tmp_path("hand.pfm");
        static char text_a[OUTPUT_CAP];
        static char text_b[OUTPUT_CAP];
        CHECK(from_file && by_hand);
        if (!from_file || !by_hand) {
            continue;
        }
        CHECK_MSG(render_to(from_file, a, false, text_a) == 0, "%s: %s", k->name, text_a);
        CHECK_MSG(render_to(by_hand, b, false, text_b) == 0, "%s: %s", k->name, text_b);
        CHECK_MSG(test_same_file(a, b), "%s: the file's material renders differently", k->name);
        /* The same verdict under --strict (a stage before 04 refuses both:
         * mirror and glass are features it does not model). */
        int strict_a = render_to(from_file, a, true, text_a);
        int strict_b = render_to(by_hand, b, true, text_b);
        CHECK_MSG(
            strict_a == strict_b,
            "%s: --strict %d vs %d: %s",
            k->name,
            strict_a,
            strict_b,
            text_a);
        CHECK_MSG(!strstr(text_a, "not modelled;") || strict_a != 0, "%s: %s", k->name, text_a);
        if (!k->gltf) {
            CHECK_MSG(strict_a == 0 && !strstr(text_a, "warning"), "%s: %s", k->name, text_a);
        }
        printf("%s: identical images, --strict exit %d\n", k->name, strict_a);
    }
}

TEST(material_on_the_line_overrides_the_file)
{
    REQUIRE_GLTF();
    const char *lamp = "{\"name\":\"lamp\",\"emissiveFactor\":[1,0,0],\"pbrMetallicRoughness\":"
                       "{\"metallicFactor\":0.5,\"roughnessFactor\":0.5}}";
    if (!write_sphere("lamp", lamp) || !write_sphere("plain", NULL)) {
        return;
    }
    const char *over = stagecheck_scene(
        "over.scene",
        SCENE_HEAD "material grey diffuse albedo 0.4 0.4 0.4\nmesh file lamp.glb material grey\n");
    const char *plain = stagecheck_scene(
        "plain.scene",
        SCENE_HEAD "material grey diffuse albedo 0.4 0.4 0.4\nmesh file plain.glb material grey\n");
    static char text[OUTPUT_CAP];
    const char *a = test_tmp_path("over.pfm");
    const char *b = test_tmp_path("plain.pfm");
    CHECK(over && plain);
    if (over && plain) {
        CHECK_MSG(render_to(over, a, true, text) == 0, "%s", text);
        CHECK_MSG(strstr(text, "lamp") == NULL, "a warning about the overridden file: %s", text);
        CHECK_MSG(render_to(plain, b, true, text) == 0, "%s", text);
        CHECK(test_same_file(a, b));
    }
}

struct dropped_case {
    const char *material;
    const char *members; /* what the material refers to (textures), or NULL */
    const char *says;
};

/* A texture of three bytes: no image format, so its mean cannot be had. */
#define TEXTURE \
    "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"data:image/png;base64,AAAA\"}]"

static const struct dropped_case dropped[] = {
    {"{\"name\":\"duck\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
     "\"metallicFactor\":0}}",
     TEXTURE,
     "material 'duck': baseColorTexture not modelled (image 0 is neither PNG nor JPEG); using "
     "baseColorFactor (1, 1, 1)"},
    {"{\"name\":\"bumpy\",\"normalTexture\":{\"index\":0},\"pbrMetallicRoughness\":"
     "{\"metallicFactor\":0}}",
     TEXTURE,
     "material 'bumpy': normalTexture not modelled; using the mesh's normals"},
    {"{\"name\":\"satin\",\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0.5}}",
     NULL,
     "material 'satin': roughnessFactor 0.5 of a non-metal not modelled"},
    {"{\"name\":\"brushed\",\"pbrMetallicRoughness\":{\"metallicFactor\":1,\"roughnessFactor\":0.3}}",
     NULL,
     "material 'brushed': roughnessFactor 0.3 of a metal not modelled"},
    {"{\"name\":\"half\",\"pbrMetallicRoughness\":{\"metallicFactor\":0.5,\"roughnessFactor\":0}}",
     NULL,
     "material 'half': metallicFactor 0.5 not modelled (only 0 and 1); shaded as a mirror"},
    {"{\"name\":\"lit\",\"emissiveFactor\":[1,1,1],\"pbrMetallicRoughness\":"
     "{\"baseColorFactor\":[0.5,0.5,0.5,1]}}",
     NULL,
     "material 'lit': baseColorFactor (0.5, 0.5, 0.5) of an emissive material not modelled"},
    {"{\"name\":\"frosted\",\"pbrMetallicRoughness\":{\"roughnessFactor\":0},\"extensions\":"
     "{\"KHR_materials_transmission\":{\"transmissionFactor\":0.5}}}",
     NULL,
     "material 'frosted': transmissionFactor 0.5 not modelled"},
    {"{\"name\":\"bottle\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.8,0.2,1],"
     "\"roughnessFactor\":0},\"extensions\":{\"KHR_materials_transmission\":"
     "{\"transmissionFactor\":1}}}",
     NULL,
     "material 'bottle': baseColorFactor (0.2, 0.8, 0.2) of a transmissive material not "
     "modelled; clear glass"},
    {"{\"name\":\"ghost\",\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
     "[1,1,1,0.5],\"metallicFactor\":0}}",
     NULL,
     "material 'ghost': alphaMode BLEND (alpha 0.5) not modelled; opaque"},
    {"{\"name\":\"car\",\"pbrMetallicRoughness\":{\"metallicFactor\":0},\"extensions\":"
     "{\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1}}}",
     NULL,
     "material 'car': KHR_materials_clearcoat not modelled; ignored"},
};

/* Writes NAME.glb with a material and the members it needs. */
static const char *
write_dropped(const char *name, const struct dropped_case *c)
{
    static const double centre[3] = {0, 0.2, 0};
    struct meshgen_mesh m = meshgen_icosphere(1, 0.5, centre);
    char file[64];
    snprintf(file, sizeof file, "%s.glb", name);
    const char *path = test_tmp_path(file);
    struct meshgen_glb_options opts = {.material = c->material, .members = c->members};
    bool ok = m.n_triangles > 0 && meshgen_write_glb(&m, path, &opts);
    meshgen_free(&m);
    CHECK_MSG(ok, "cannot write %s", path);
    return ok ? path : NULL;
}

TEST(each_dropped_kind_warns_and_strict_refuses)
{
    REQUIRE_GLTF();
    for (size_t i = 0; i < sizeof dropped / sizeof dropped[0]; i++) {
        const struct dropped_case *c = &dropped[i];
        char name[32];
        snprintf(name, sizeof name, "dropped%zu", i);
        if (!write_dropped(name, c)) {
            continue;
        }
        const char *scene =
            stagecheck_scene("dropped.scene", SCENE_HEAD "mesh file %s.glb\n", name);
        const char *out = test_tmp_path("dropped.pfm");
        static char text[OUTPUT_CAP];
        char want[512];
        remove(out);
        CHECK_MSG(render_to(scene, out, false, text) == 0, "%s", text);
        snprintf(want, sizeof want, "dropped.scene:6:1: warning: %s.glb: %s", name, c->says);
        CHECK_MSG(strstr(text, want) != NULL, "expected '%s' in:\n%s", want, text);
        CHECK(test_file_exists(out));
        remove(out);
        CHECK_MSG(render_to(scene, out, true, text) == 1, "--strict: %s", text);
        /* Refused: what is not modelled, then the refusal, not what a
         * render would use instead (the part after the first "; "). */
        const char *instead = strstr(c->says, "; ");
        int what = instead ? (int)(instead - c->says) : (int)strlen(c->says);
        snprintf(want, sizeof want, "dropped.scene:6:1: error: %s.glb: %.*s", name, what, c->says);
        const char *line = strstr(text, want);
        const char *refusal = line ? strstr(line, "; ") : NULL;
        CHECK_MSG(
            refusal && strncmp(refusal, "; --strict refuses the scene\n", 29) == 0
                && refusal < strchr(line, '\n'),
            "expected '%s; --strict refuses the scene' in:\n%s",
            want,
            text);
        CHECK_MSG(!test_file_exists(out), "--strict wrote an image");
    }
}

/* Two materials with different extensions (as ToyCar's clearcoat and
 * sheen): each list is named in its own note, not only the first
 * material's. */
TEST(every_material_extension_is_named)
{
    REQUIRE_GLTF();
    static const double centre[3] = {0, 0.2, 0};
    struct meshgen_mesh m = meshgen_icosphere(1, 0.5, centre);
    const char *path = test_tmp_path("two_coats.glb");
    struct meshgen_glb_options opts = {
        .material = "{\"name\":\"paint\",\"pbrMetallicRoughness\":{\"metallicFactor\":0},"
                    "\"extensions\":{\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1}}},"
                    "{\"name\":\"seat\",\"pbrMetallicRoughness\":{\"metallicFactor\":0},"
                    "\"extensions\":{\"KHR_materials_sheen\":{\"sheenColorFactor\":[1,1,1]}}}",
        .meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},"
                  "\"indices\":2,\"material\":1}]}",
        .nodes = "{\"mesh\":1,\"translation\":[1.2,0,0]}",
        .n_nodes = 1,
    };
    bool ok = m.n_triangles > 0 && meshgen_write_glb(&m, path, &opts);
    meshgen_free(&m);
    CHECK_MSG(ok, "cannot write %s", path);
    const char *scene = stagecheck_scene("coats.scene", SCENE_HEAD "mesh file two_coats.glb\n");
    static char text[OUTPUT_CAP];
    CHECK_MSG(render_to(scene, test_tmp_path("coats.pfm"), false, text) == 0, "%s", text);
    CHECK_MSG(
        strstr(text, "material 'paint': KHR_materials_clearcoat not modelled; ignored")
            && strstr(text, "material 'seat': KHR_materials_sheen not modelled; ignored"),
        "both extensions named, each with its material:\n%s",
        text);
}

struct file_case {
    const char *name;
    struct meshgen_glb_options opts;
    const char *says;
};

/* What of a file no stage models beside its materials, as files made
 * elsewhere carry it (BrainStem's skin and animation, SimpleInstancing's
 * instances, a texture transform, a lamp's light). */
static const struct file_case file_cases[] = {
    {"skinned",
     {.members = "\"skins\":[{\"joints\":[0]}]"},
     "1 skin(s) not modelled; the skinned meshes as stored, in their bind pose"},
    {"animated",
     {.members = "\"animations\":[{\"channels\":[],\"samplers\":[]}]"},
     "1 animation(s) not modelled; the nodes' own transforms, no frame of an animation"},
    {"morphed",
     {.meshes = "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2,"
                "\"targets\":[{\"POSITION\":0}]}]}",
      .nodes = "{\"mesh\":1,\"translation\":[1.2,0,0]}",
      .n_nodes = 1},
     "morph targets not modelled; the base meshes, the targets' weights ignored"},
    {"instanced",
     {.members = "\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"]",
      .nodes = "{\"mesh\":0,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":"
               "{\"TRANSLATION\":0}}}}",
      .n_nodes = 1},
     "EXT_mesh_gpu_instancing (1 node(s)) not modelled; one instance each"},
    {"transformed",
     {.members = "\"extensionsUsed\":[\"KHR_texture_transform\"]"},
     "extension 'KHR_texture_transform' not modelled; ignored"},
    {"lamp",
     {.members =
          "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":"
          "{\"lights\":[{\"type\":\"point\",\"intensity\":1}]}}",
      .nodes = "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}",
      .n_nodes = 1},
     "1 KHR_lights_punctual light(s) not placed by a mesh line; ignored"},
};

TEST(each_dropped_file_feature_warns_and_strict_refuses)
{
    REQUIRE_GLTF();
    static const double centre[3] = {0, 0.2, 0};
    for (size_t i = 0; i < sizeof file_cases / sizeof file_cases[0]; i++) {
        const struct file_case *c = &file_cases[i];
        struct meshgen_mesh m = meshgen_icosphere(1, 0.5, centre);
        char file[64];
        snprintf(file, sizeof file, "%s.glb", c->name);
        bool ok = m.n_triangles > 0 && meshgen_write_glb(&m, test_tmp_path(file), &c->opts);
        meshgen_free(&m);
        CHECK_MSG(ok, "cannot write %s", file);
        const char *scene = stagecheck_scene("file.scene", SCENE_HEAD "mesh file %s\n", file);
        const char *out = test_tmp_path("file.pfm");
        static char text[OUTPUT_CAP];
        char want[512];
        remove(out);
        CHECK_MSG(render_to(scene, out, false, text) == 0, "%s: %s", c->name, text);
        /* At the file's name (line 6, column 11). */
        snprintf(want, sizeof want, "file.scene:6:11: warning: %s: %s", file, c->says);
        CHECK_MSG(strstr(text, want) != NULL, "expected '%s' in:\n%s", want, text);
        CHECK_MSG(render_to(scene, out, true, text) == 1, "%s: --strict: %s", c->name, text);
    }
}

/* Textures stand as their images' mean colour times the factor (no stage
 * maps a texture): a base colour texture half lit with the sRGB codes
 * (204, 102, 51) renders bit for bit as the diffuse albedo of half their
 * linear values times baseColorFactor; an emissive texture that glows on a
 * quarter of its texels leaves a surface that reflects its base colour, as
 * written by hand, its glow dropped; each says so, and --strict refuses. */
TEST(textures_render_as_their_mean_colour)
{
    REQUIRE_GLTF();
    CHECK(test_write_texture("half.png", 4) && test_write_texture("quarter.png", 2));
    const char *members = "\"textures\":[{\"source\":0},{\"source\":1}],"
                          "\"images\":[{\"uri\":\"half.png\"},{\"uri\":\"quarter.png\"}]";
    struct meshgen_glb_options opts = {.members = members};

    struct {
        const char *name, *material, *says;
        double albedo[3];
    } cases[] = {
        {"painted",
         "{\"name\":\"painted\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
         "\"baseColorFactor\":[1,0.5,1,1],\"metallicFactor\":0}}",
         "material 'painted': baseColorTexture not modelled; using its mean",
         {test_srgb8_linear(204) / 2, test_srgb8_linear(102) / 2 * 0.5, test_srgb8_linear(51) / 2}},
        {"helmet",
         "{\"name\":\"helmet\",\"emissiveTexture\":{\"index\":1},\"emissiveFactor\":[1,1,1],"
         "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.6,0.3,0.2,1],\"metallicFactor\":0}}",
         "material 'helmet': emissiveTexture not modelled; its glow",
         {0.6, 0.3, 0.2}},
    };

    static const double centre[3] = {0, 0.2, 0};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct meshgen_mesh m = meshgen_icosphere(2, 0.5, centre);
        char file[64];
        snprintf(file, sizeof file, "%s.glb", cases[i].name);
        opts.material = cases[i].material;
        bool written = m.n_triangles > 0 && meshgen_write_glb(&m, test_tmp_path(file), &opts);
        meshgen_free(&m);
        const char *from_file =
            stagecheck_scene("tex_file.scene", SCENE_HEAD "mesh file %s\n", file);
        const char *by_hand = stagecheck_scene(
            "tex_hand.scene",
            SCENE_HEAD "material m diffuse albedo %.17g %.17g %.17g\nmesh file %s material m\n",
            cases[i].albedo[0],
            cases[i].albedo[1],
            cases[i].albedo[2],
            file);
        if (!written || !from_file || !by_hand) {
            CHECK_MSG(false, "%s: cannot write the files", cases[i].name);
            continue;
        }
        const char *a = test_tmp_path("tex_file.pfm");
        const char *b = test_tmp_path("tex_hand.pfm");
        static char text[OUTPUT_CAP];
        static char hand[OUTPUT_CAP];
        CHECK_MSG(render_to(from_file, a, false, text) == 0, "%s", text);
        CHECK_MSG(
            strstr(text, cases[i].says) != NULL,
            "expected '%s' in:\n%s",
            cases[i].says,
            text);
        CHECK_MSG(render_to(by_hand, b, false, hand) == 0, "%s", hand);
        CHECK_MSG(test_same_file(a, b), "%s: not the image of its mean colour", cases[i].name);
        CHECK_MSG(render_to(from_file, a, true, text) == 1, "--strict: %s", text);
    }
}

TEST_MAIN(
    TEST_ENTRY(textures_render_as_their_mean_colour),
    TEST_ENTRY(each_kind_renders_as_the_scene_written_by_hand),
    TEST_ENTRY(each_dropped_file_feature_warns_and_strict_refuses),
    TEST_ENTRY(every_material_extension_is_named),
    TEST_ENTRY(material_on_the_line_overrides_the_file),
    TEST_ENTRY(each_dropped_kind_warns_and_strict_refuses))
