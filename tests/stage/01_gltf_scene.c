/*
 * 01_gltf_scene.c - `render file.glb`: a glTF file as the whole scene
 * (docs/scene-format.md, "A glTF file as the scene"), through the stage's
 * binary; every stage.
 *
 *  - The camera and a KHR_lights_punctual point light come from the file:
 *    the render is bit for bit that of the scene written by hand with the
 *    same camera (fov = yfov in degrees, the aspect ratio from the camera,
 *    the width from -W) and a point light of intensity candela / 683 W/sr.
 *    --camera NAME takes another camera; an unknown name is refused with
 *    the list of the file's cameras.
 *  - Spot and directional lights are warned about and ignored; --strict
 *    refuses them.  A file without a camera is refused with a message
 *    saying how to add one.
 *  - Duck.glb (scenes/models) renders from the file alone: its camera, a
 *    headlight (it has no light), a warning for its texture.
 *  - .gltf with its buffer in a data: URI or in a .bin beside it renders;
 *    buffers outside the model's directory (.., absolute paths, file:
 *    URIs) are refused, exit 1, no image.
 */
#include <string.h>

#include "check.h"
#include "meshgen.h"
#include "stagecheck.h"
#include "testlib.h"

#define OUTPUT_CAP 8192
#define YFOV 0.7
#define RAD_TO_DEG (180.0 / 3.14159265358979323846)

/* Two cameras (front: at (0, 1, 3) looking along -z; side: at (3, 1, 0)
 * looking along -x, a quarter turn about y, as a matrix so that it is
 * exact), and a point light of 1366 cd coloured (1, 0.5, 0.25). */
#define CAMERA_NODES \
    "{\"name\":\"front\",\"camera\":0,\"translation\":[0,1,3]}," \
    "{\"name\":\"side\",\"camera\":1,\"matrix\":[0,0,-1,0,0,1,0,0,1,0,0,0,3,1,0,1]}," \
    "{\"name\":\"bulb\",\"translation\":[1,3,2],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}"
#define CAMERAS \
    "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.7,\"aspectRatio\":1.25," \
    "\"znear\":0.1}},{\"name\":\"side\",\"type\":\"perspective\",\"perspective\":{\"yfov\":0.7," \
    "\"aspectRatio\":1.25,\"znear\":0.1}}]"
#define LIGHTS(more) \
    "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":" \
    "{\"lights\":[{\"type\":\"point\",\"color\":[1,0.5,0.25],\"intensity\":1366}" more "]}}"

static const char *const clay =
    "{\"name\":\"clay\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.6,0.3,0.2,1],"
    "\"metallicFactor\":0,\"roughnessFactor\":1}}";

/* An icosphere and a floor-sized box in one mesh, with the nodes and
 * members given. */
static const char *
write_file(const char *name, const char *nodes, int n_nodes, const char *members)
{
    static const double centre[3] = {0, 0.5, 0};
    struct meshgen_mesh m = meshgen_icosphere(2, 0.5, centre);
    char file[64];
    snprintf(file, sizeof file, "%s.glb", name);
    const char *path = test_tmp_path(file);
    struct meshgen_glb_options opts = {
        .material = clay,
        .nodes = nodes,
        .n_nodes = n_nodes,
        .members = members,
    };
    bool ok = m.n_triangles > 0 && meshgen_write_glb(&m, path, &opts);
    meshgen_free(&m);
    CHECK_MSG(ok, "cannot write %s", path);
    return ok ? path : NULL;
}

static int
run(const char *scene, const char *out, const char *const extra[], char *text)
{
    const char *args[16] = {"-o", out, "-W", "40"};
    int n = 4;
    for (int i = 0; extra && extra[i] && n < 15; i++) {
        args[n++] = extra[i];
    }
    args[n] = NULL;
    return test_render(scene, args, text, OUTPUT_CAP);
}

/* The scene written by hand: the file's mesh, the camera at origin
 * looking at target, the light in W/sr. */
static const char *
hand_scene(const char *name, const char *file, const char *origin, const char *target)
{
    return stagecheck_scene(
        name,
        "camera origin %s target %s up 0 1 0 fov %.17g\n"
        "image width 40 height 32\n"
        "material m diffuse albedo 0.6 0.3 0.2\n"
        "mesh file %s material m\n"
        "point_light position 1 3 2 intensity 2 1 0.5\n",
        origin,
        target,
        YFOV * RAD_TO_DEG,
        file);
}

TEST(camera_and_point_light_from_the_file)
{
    REQUIRE_GLTF();
    const char *glb = write_file("lit", CAMERA_NODES, 3, CAMERAS "," LIGHTS(""));
    const char *front = hand_scene("front.scene", "lit.glb", "0 1 3", "0 1 2");
    const char *side = hand_scene("side.scene", "lit.glb", "3 1 0", "2 1 0");
    static char text[OUTPUT_CAP];
    const char *a = test_tmp_path("a.pfm");
    const char *b = test_tmp_path("b.pfm");
    if (!glb || !front || !side) {
        CHECK(false);
        return;
    }
    CHECK_MSG(run(glb, a, NULL, text) == 0, "%s", text);
    CHECK_MSG(strstr(text, "warning") == NULL, "%s", text);
    CHECK_MSG(run(front, b, NULL, text) == 0, "%s", text);
    CHECK_MSG(test_same_file(a, b), "the file's first camera and light differ from the scene's");
    const char *const by_name[] = {"--camera", "side", NULL};
    CHECK_MSG(run(glb, a, by_name, text) == 0, "%s", text);
    CHECK_MSG(run(side, b, NULL, text) == 0, "%s", text);
    CHECK_MSG(test_same_file(a, b), "--camera side differs from the scene's side camera");
    const char *const unknown[] = {"--camera", "back", NULL};
    CHECK(run(glb, a, unknown, text) == 1);
    CHECK_MSG(
        strstr(text, "no camera named 'back' in the file (its cameras: 'front', 'side')"),
        "%s",
        text);
}

TEST(spot_and_directional_lights_warn_and_strict_refuses)
{
    REQUIRE_GLTF();
    char nodes[1024];
    snprintf(
        nodes,
        sizeof nodes,
        "%s,{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
        "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}}",
        CAMERA_NODES);
    const char *lights = CAMERAS "," LIGHTS(",{\"name\":\"stage\",\"type\":\"spot\",\"spot\":{}},"
                                            "{\"name\":\"sun\",\"type\":\"directional\"}");
    const char *glb = write_file("spot", nodes, 5, lights);
    static char text[OUTPUT_CAP];
    const char *out = test_tmp_path("spot.pfm");
    if (!glb) {
        return;
    }
    CHECK_MSG(run(glb, out, NULL, text) == 0, "%s", text);
    CHECK_MSG(
        strstr(text, "warning: spot.glb: spot light 'stage' not modelled; ignored"),
        "%s",
        text);
    CHECK_MSG(strstr(text, "warning: spot.glb: directional light 'sun' not modelled"), "%s", text);
    remove(out);
    const char *const strict[] = {"--strict", NULL};
    CHECK_MSG(run(glb, out, strict, text) == 1, "%s", text);
    CHECK_MSG(
        strstr(text, "error: spot.glb: spot light 'stage' not modelled; --strict refuses the scene")
            && !strstr(text, "ignored"),
        "%s",
        text);
    CHECK(!test_file_exists(out));
}

TEST(a_file_without_camera_is_refused)
{
    REQUIRE_GLTF();
    const char *glb = write_file("nocam", NULL, 0, NULL);
    static char text[OUTPUT_CAP];
    const char *out = test_tmp_path("nocam.pfm");
    if (!glb) {
        return;
    }
    CHECK(run(glb, out, NULL, text) == 1);
    CHECK_MSG(strstr(text, "nocam.glb: error: the file has no camera: add one"), "%s", text);
    CHECK(!test_file_exists(out));
}

TEST(duck_renders_from_the_file_alone)
{
    REQUIRE_GLTF();
    const char *duck = test_root_path("scenes/models/Duck.glb");
    const char *out = test_tmp_path("duck.pfm");
    static char text[OUTPUT_CAP];
    CHECK_MSG(run(duck, out, NULL, text) == 0, "%s", text);
    CHECK_MSG(
        strstr(
            text,
            "warning: Duck.glb: material 'blinn3-fx': baseColorTexture not modelled; "
            "using its mean (0.915, 0.601, 0.0604)"),
        "%s",
        text);
    struct image img = {0};
    const char *const args[] = {"-W", "40", NULL};
    CHECK(test_render_image(duck, args, &img));
    /* 40 wide, the camera's aspect ratio 1.5: 27 high; the duck is lit. */
    CHECK(img.width == 40 && img.height == 27);
    double brightest = 0;
    size_t at = 0;
    for (size_t i = 0; i < 3 * (size_t)img.width * (size_t)img.height; i++) {
        at = img.rgb[i] > brightest ? i - i % 3 : at;
        brightest = img.rgb[i] > brightest ? img.rgb[i] : brightest;
    }
    CHECK_MSG(brightest > 0.1, "the duck is dark: %g", brightest);
    /* Yellow, its texture's mean, not white: red over blue as 0.915 to 0.0604. */
    CHECK_MSG(
        img.rgb[at] > 10 * img.rgb[at + 2],
        "not yellow: %g %g %g",
        img.rgb[at],
        img.rgb[at + 1],
        img.rgb[at + 2]);
    image_free(&img);
}

/* A .gltf of one triangle whose buffer's uri is `uri`. */
static const char *
write_gltf(const char *name, const char *uri)
{
    const char *path = test_tmp_path(name);
    char text[2048];
    snprintf(
        text,
        sizeof text,
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
        "\"nodes\":[{\"mesh\":0},{\"camera\":0,\"translation\":[0,3,0],\"rotation\":"
        "[-0.70710678118654752,0,0,0.70710678118654752]}],"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":0.1}}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"%s\"}]}",
        uri);
    CHECK(test_write_file(path, text));
    return path;
}

#define TRIANGLE_BASE64 "AACAvwAAAAAAAIC/AACAPwAAAAAAAIC/AAAAAAAAAAAAAIA/"

TEST(gltf_buffers_inside_the_directory_only)
{
    REQUIRE_GLTF();
    static char text[OUTPUT_CAP];
    const char *out = test_tmp_path("gltf.pfm");
    const char *data =
        write_gltf("data.gltf", "data:application/octet-stream;base64," TRIANGLE_BASE64);
    CHECK_MSG(run(data, out, NULL, text) == 0, "a data: URI: %s", text);
    /* The same bytes in a .bin beside the .gltf. */
    static const float triangle[9] = {-1, 0, -1, 1, 0, -1, 0, 0, 1};
    FILE *f = fopen(test_tmp_path("tri.bin"), "wb");
    CHECK(f && fwrite(triangle, sizeof triangle, 1, f) == 1);
    if (f) {
        fclose(f);
    }
    const char *beside = write_gltf("beside.gltf", "tri.bin");
    CHECK_MSG(run(beside, out, NULL, text) == 0, "a .bin beside it: %s", text);
    static const char *const hostile[] = {
        "../tri.bin",
        "/etc/passwd",
        "file:///etc/passwd",
        "sub/../../tri.bin",
        "%2e%2e/tri.bin",
    };
    for (size_t i = 0; i < sizeof hostile / sizeof hostile[0]; i++) {
        const char *gltf = write_gltf("hostile.gltf", hostile[i]);
        remove(out);
        CHECK_MSG(run(gltf, out, NULL, text) == 1, "'%s' was accepted: %s", hostile[i], text);
        CHECK_MSG(strstr(text, "hostile.gltf: error: "), "%s", text);
        CHECK_MSG(strstr(text, "external file"), "'%s': %s", hostile[i], text);
        CHECK(!test_file_exists(out));
    }
}

TEST_MAIN(
    TEST_ENTRY(camera_and_point_light_from_the_file),
    TEST_ENTRY(spot_and_directional_lights_warn_and_strict_refuses),
    TEST_ENTRY(a_file_without_camera_is_refused),
    TEST_ENTRY(duck_renders_from_the_file_alone),
    TEST_ENTRY(gltf_buffers_inside_the_directory_only))
