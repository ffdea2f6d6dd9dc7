#include "glint/formats/scene_yaml.h"

#include <gtest/gtest.h>

#include "glint/builder/build.h"

namespace glint {
namespace {

// Parses and builds `text` as scene.yaml; returns the full error text ("" if it succeeded).
std::string errors_of(const std::string& text, const Overrides& overrides = {}, const InlineArrays* arrays = nullptr) {
    auto sources = std::make_shared<SourceFiles>();
    try {
        const SceneDescription d = parse_scene(text, "scene.yaml", sources, 0, arrays);
        build(d, overrides, sources);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

// The caret line under a token of `length` characters at 1-based `column` (source lines are
// quoted with a 4-space indent).
std::string caret(int column, int length) {
    return std::string(static_cast<std::size_t>(4 + column - 1), ' ') + "^" +
           std::string(static_cast<std::size_t>(length - 1), '~') + "\n";
}

TEST(SceneYaml, MisspeltKeyReportsLineColumnAndSuggestion) {
    const std::string text =
        "objects:\n"
        "  - type: sphere\n"
        "    center: [0, 0, 1]\n"
        "    radiuss: 1\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:4:5: error: sphere: unknown key 'radiuss'; did you mean 'radius'? "
              "(known: type, center, radius, material, transform, interior, exterior)\n"
              "        radiuss: 1\n" +
                  caret(5, 7) +
                  "scene.yaml:2:5: error: sphere: missing required key 'radius'\n"
                  "      - type: sphere\n" +
                  caret(5, 4));
}

TEST(SceneYaml, UnknownMaterialReportsLineAndColumn) {
    const std::string text =
        "materials:\n"
        "  red: {color: [1, 0, 0]}\n"
        "  chrome2: {color: [1, 1, 1], shininess: 1}\n"
        "objects:\n"
        "  - {type: sphere, center: [0, 0, 1], radius: 1, material: chrome}\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:5:60: error: unknown material 'chrome'; did you mean 'chrome2'? "
              "(known: red, chrome2)\n"
              "      - {type: sphere, center: [0, 0, 1], radius: 1, material: chrome}\n" +
                  caret(60, 6));
}

TEST(SceneYaml, WrongTypesAreReported) {
    const std::string text =
        "objects:\n"
        "  - {type: sphere, center: [0, 0], radius: big}\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:2:28: error: expected a list of 3 numbers [x, y, z], got a list of 2\n"
              "      - {type: sphere, center: [0, 0], radius: big}\n" +
                  caret(28, 6) +
                  "scene.yaml:2:44: error: expected a number, got 'big'\n"
                  "      - {type: sphere, center: [0, 0], radius: big}\n" +
                  caret(44, 3));
}

TEST(SceneYaml, OutOfRangeValuesAreReported) {
    const std::string text =
        "film: {width: -5, height: 10}\n"
        "objects:\n"
        "  - {type: sphere, center: [0, 0, 1], radius: 0}\n"
        "  - {type: sphere, center: [0, 0, 1], radius: -1}\n"
        "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 0]}\n"
        "materials:\n"
        "  m: {color: {type: checker, size: -1, even: [1, 1, 1], odd: [0, 0, 0]}, shininess: 2}\n";
    const std::string e = errors_of(text);
    EXPECT_NE(e.find("scene.yaml:1:15: error: width must be in [1, 65536], got -5\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:3:47: error: radius must be > 0, got 0\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:4:47: error: radius must be > 0, got -1\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:5:45: error: normal must not be zero-length\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:7:36: error: size must be > 0, got -1\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:7:85: error: shininess must be in [0, 1], got 2\n"), std::string::npos) << e;
}

// A checker's uv mapping: only on uv, two numbers each, and a space it knows.
TEST(SceneYaml, CheckerUvKeysAreCheckedWhereTheyStand) {
    const std::string e = errors_of(
        "materials:\n"
        "  a: {color: {type: checker, even: [1, 1, 1], odd: [0, 0, 0], uv_scale: [2, 2]}}\n"
        "  b: {color: {type: checker, even: [1, 1, 1], odd: [0, 0, 0], space: uv, uv_offset: [1, 2, 3]}}\n"
        "  c: {color: {type: checker, even: [1, 1, 1], odd: [0, 0, 0], space: xyz}}\n");
    EXPECT_NE(e.find("scene.yaml:2:73: error: checker texture: 'uv_scale' needs 'space: uv'\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:3:85: error: uv_offset: expected a list of 2 numbers [u, v], got a list of 3\n"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("scene.yaml:4:70: error: unknown space 'xyz' (known: world, uv)\n"), std::string::npos) << e;
    EXPECT_EQ(errors_of("materials:\n  a: {color: {type: checker, even: [1, 1, 1], odd: [0, 0, 0], space: uv, uv_scale: [2, 0.5]}}\n"),
              "");
}

TEST(SceneYaml, NonFiniteNumbersAreReported) {
    const std::string text =
        "lights:\n"
        "  - {type: directional, direction: [.nan, -1, 1]}\n"
        "  - {type: point, position: [0, .inf, 0]}\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:2:37: error: expected a finite number, got '.nan'\n"
              "      - {type: directional, direction: [.nan, -1, 1]}\n" +
                  caret(37, 4) +
                  "scene.yaml:3:33: error: expected a finite number, got '.inf'\n"
                  "      - {type: point, position: [0, .inf, 0]}\n" +
                  caret(33, 4));
}

TEST(SceneYaml, NumbersBeyondFloatRangeAreReported) {
    const std::string text = "background: {type: constant, color: [1e39, 0, 0]}\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:1:38: error: number '1e39' is out of range (largest magnitude: "
              "3.4e+38)\n"
              "    background: {type: constant, color: [1e39, 0, 0]}\n" +
                  caret(38, 4));
}

TEST(SceneYaml, UnknownTypeSuggestsTheClosest) {
    const std::string text = "objects:\n  - {type: sphre, center: [0, 0, 1], radius: 1}\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:2:12: error: unknown object type 'sphre'; did you mean 'sphere'? "
              "(known: sphere, plane, quad, disk, triangle, polygon, box, mesh)\n"
              "      - {type: sphre, center: [0, 0, 1], radius: 1}\n" +
                  caret(12, 5));
}

TEST(SceneYaml, YamlSyntaxErrorPointsAtTheSpot) {
    const std::string e = errors_of("camera:\n  position: [0, 0, -1\n");
    EXPECT_EQ(e.rfind("scene.yaml:", 0), 0u) << e;
    EXPECT_NE(e.find("error: invalid YAML: "), std::string::npos) << e;
}

TEST(SceneYaml, DuplicateKeysAreErrors) {
    const std::string text = "film: {width: 10, width: 20}\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:1:19: error: film: duplicate key 'width'\n"
              "    film: {width: 10, width: 20}\n" +
                  caret(19, 5));
}

TEST(SceneYaml, UnknownTopLevelKeyIsAnError) {
    EXPECT_EQ(errors_of("objets: []\n"),
              "scene.yaml:1:1: error: scene: unknown key 'objets'; did you mean 'objects'? "
              "(known: camera, film, sampler, integrator, background, lights, materials, "
              "media, medium, objects, animation)\n"
              "    objets: []\n" +
                  caret(1, 6));
}

TEST(SceneYaml, AbsurdFilmIsRefusedBeforeAllocation) {
    EXPECT_EQ(errors_of("film: {width: 60000, height: 60000}\n"),
              "scene.yaml:1:15: error: a film of 60000 x 60000: 3600000000 film pixels exceed the limit of "
              "134217728 (raise it with --limit film-pixels=N)\n"
              "    film: {width: 60000, height: 60000}\n" +
                  caret(15, 5));
    Overrides huge;
    huge.width = 1000000;
    huge.height = 1000000;
    EXPECT_EQ(errors_of("{}\n", huge),
              "<command line>: error: --width must be in [1, 65536], got 1000000\n"
              "<command line>: error: --height must be in [1, 65536], got 1000000\n");
}

TEST(SceneYaml, MissingFileIsAnError) {
    auto sources = std::make_shared<SourceFiles>();
    try {
        load_scene_file("/nonexistent/scene.yaml", sources);
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_STREQ(e.what(),
                     "/nonexistent/scene.yaml: error: cannot open scene file: No such file or "
                     "directory\n");
    }
}

TEST(SceneYaml, BoxIsSixOutwardFacingQuads) {
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(
        parse_scene("objects: [{type: box, min: [1, 2, 3], max: [4, 6, 8]}]\n", "s.yaml", sources),
        {}, sources);
    ASSERT_EQ(job.scene.quads.size(), 6u);
    const Point3 centre{2.5f, 4, 5.5f};
    Float area = 0;
    for (const Quad& q : job.scene.quads) {
        const Point3 face_centre = q.corner + (q.edge1 + q.edge2) * 0.5f;
        EXPECT_GT(dot(q.normal(), face_centre - centre), 0);  // outward
        area += q.area();
    }
    EXPECT_NEAR(area, 2 * (3 * 4 + 4 * 5 + 3 * 5), 1e-4);  // 2(ab + bc + ca)
}

TEST(SceneYaml, DegenerateShapesAreReported) {
    const std::string text =
        "objects:\n"
        "  - {type: quad, corner: [0, 0, 0], edge1: [1, 0, 0], edge2: [2, 0, 0]}\n"
        "  - {type: triangle, vertices: [[0, 0, 0], [1, 1, 1], [2, 2, 2]]}\n"
        "  - {type: box, min: [0, 0, 0], max: [1, 0, 1]}\n"
        "  - {type: disk, center: [0, 0, 0], normal: [0, 1, 0], radius: 0}\n"
        "  - {type: triangle, vertices: [[0, 0, 0], [1, 1, 1]]}\n";
    const std::string e = errors_of(text);
    EXPECT_NE(e.find("scene.yaml:2:62: error: quad: edge1 and edge2 must not be parallel\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:3:32: error: triangle: the vertices are collinear (zero area)\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:4:38: error: box: max must exceed min on every axis\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:5:64: error: radius must be > 0, got 0\n"), std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:6:32: error: triangle: expected a list of 3 vertices, got a list of 2\n"), std::string::npos) << e;
}

TEST(SceneYaml, ToneMappingKeys) {
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(
        parse_scene("film: {tonemap: aces, exposure: -1.5, encoding: raw}\n", "s.yaml", sources),
        {}, sources);
    EXPECT_EQ(job.display.curve, ToneCurve::kAces);
    EXPECT_EQ(job.display.exposure, -1.5f);
    EXPECT_EQ(job.display.encoding, Encoding::kRaw);
    const std::string e = errors_of("film: {tonemap: filmic, exposure: 100}\n");
    EXPECT_NE(e.find("scene.yaml:1:17: error: unknown tonemap 'filmic' (known: clamp, reinhard, aces)\n"),
              std::string::npos) << e;
    EXPECT_NE(e.find("scene.yaml:1:35: error: exposure must be in [-64, 64], got 100\n"),
              std::string::npos) << e;
}

TEST(SceneYaml, OrthographicCameraWindowAndCrop) {
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene(
        "camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], projection: orthographic,\n"
        "         height: 3, window: [-1, 0, -0.5, 1]}\n"
        "film: {width: 64, height: 32, crop_pixels: [8, 40, 0, 16], scale: 2}\n",
        "scene.yaml", sources);
    const auto& c = std::get<LookAtCameraDesc>(d.camera);
    EXPECT_TRUE(c.orthographic);
    EXPECT_EQ(c.height, 3);
    ASSERT_TRUE(c.window);
    EXPECT_EQ((*c.window)[2], -0.5f);
    const RenderJob job = build(d, {}, sources);
    EXPECT_EQ(job.film_width, 32);
    EXPECT_EQ(job.film_height, 16);
    EXPECT_EQ(job.options.offset_x, 8);
    EXPECT_EQ(job.options.scale, 2);
    EXPECT_NE(errors_of("camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], height: 3}\n")
                  .find("scene.yaml:1:66: error: look_at camera: 'height' is for projection: orthographic"),
              std::string::npos);
    EXPECT_NE(errors_of("camera: {type: look_at, from: [0, 0, -5], to: [0, 0, 0], window: [1, 0, 0, 1]}\n")
                  .find("scene.yaml:1:66: error: window: needs x0 < x1 and y0 < y1"),
              std::string::npos);
    EXPECT_NE(errors_of("film: {crop: [0, 1.5, 0, 1]}\n").find("scene.yaml:1:14: error: crop: fractions"),
              std::string::npos);
    EXPECT_NE(errors_of("film: {width: 10, crop_pixels: [20, 30, 0, 5]}\n")
                  .find("scene.yaml:1:32: error: the crop holds no pixel of the 10 x 360 frame"),
              std::string::npos);
}

TEST(SceneYaml, JsonIsAccepted) {
    const std::string json = R"({
  "camera": {"type": "look_at", "from": [0, 1, -5], "to": [0, 0, 0], "fov": 40},
  "film": {"width": 32, "height": 16},
  "integrator": {"type": "whitted", "max_depth": 2},
  "materials": {"red": {"color": [1, 0, 0], "shininess": 0.5}},
  "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "red"}]
})";
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene(json, "scene.json", sources);
    const RenderJob job = build(d, {}, sources);
    EXPECT_EQ(job.width, 32);
    ASSERT_EQ(job.scene.spheres.size(), 1u);
    EXPECT_EQ(job.scene.spheres[0].radius, 1);
    const auto& m = std::get<ArticleMaterial>(job.scene.materials[job.scene.spheres[0].material]);
    EXPECT_EQ(m.shininess, 0.5f);
}

TEST(SceneYaml, DefaultsAndOverridesApply) {
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene("sampler: {spp: 4, seed: 9}\n", "s.yaml", sources);
    Overrides o;
    o.spp = 2;
    o.width = 20;
    const RenderJob job = build(d, o, sources);
    EXPECT_EQ(job.options.spp, 2);
    EXPECT_EQ(job.options.seed, 9u);
    EXPECT_EQ(job.width, 20);
    EXPECT_EQ(job.height, 360);
    EXPECT_EQ(job.display.encoding, Encoding::kSrgb);
    EXPECT_EQ(job.display.curve, ToneCurve::kClamp);
    EXPECT_EQ(job.display.exposure, 0.0f);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(SceneYaml, PathTracerMaterialsAndLightsParse) {
    const std::string text =
        "integrator: {type: path, max_depth: 7, rr_depth: 2, clamp: 10, strategy: light}\n"
        "lights:\n"
        "  - {type: spot, position: [0, 3, 0], direction: [0, -1, 0], cone_angle: 40, "
        "falloff_start: 30}\n"
        "  - {type: directional, direction: [0, -1, 0], angular_diameter: 0.5}\n"
        "materials:\n"
        "  a: {type: diffuse, albedo: 0.5}\n"
        "  b: {type: conductor, metal: gold, roughness: 0.3}\n"
        "  c: {type: conductor, eta: [1, 1, 1], k: [3, 3, 3]}\n"
        "  d: {type: conductor, reflectance: [0.9, 0.8, 0.7]}\n"
        "  e: {type: dielectric, ior: 1.33, roughness: 0.1, thin: true}\n"
        "  f: {type: plastic, albedo: [0.1, 0.2, 0.3], roughness: 0.2}\n"
        "  g: {type: pbr, base_color: [1, 1, 1], metallic: 0.5, transmission: 0.2, "
        "emission: [1, 2, 3], two_sided: true}\n"
        "objects:\n"
        "  - {type: polygon, vertices: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [-0.5, 0.5, 0]], "
        "material: g}\n";
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(parse_scene(text, "scene.yaml", sources), {}, sources);
    EXPECT_EQ(job.scene.triangles.size(), 3u);  // a pentagon: a fan of three
    EXPECT_EQ(job.scene.materials.size(), 7u);
    EXPECT_TRUE(std::holds_alternative<PbrMaterial>(job.scene.materials[6]));
    EXPECT_EQ(job.scene.emission[6].radiance, (Color{1, 2, 3}));
    EXPECT_TRUE(job.scene.emission[6].two_sided);
    // Three emitting triangles and two file lights; the sky is the environment.
    EXPECT_EQ(job.scene.light_sampler().count(), 6u);
    const auto& spot = std::get<SpotLight>(job.scene.lights[0]);
    EXPECT_NEAR(spot.cos_outer, std::cos(40 * 3.14159265f / 180), 1e-6f);
    EXPECT_TRUE(std::get<DirectionalLight>(job.scene.lights[1]).soft());
}

TEST(SceneYaml, PathTracerMistakesAreReported) {
    const std::string text =
        "integrator: {type: path, strategy: both}\n"
        "lights:\n"
        "  - {type: spot, position: [0, 3, 0], direction: [0, -1, 0], cone_angle: 20, "
        "falloff_start: 30}\n"
        "materials:\n"
        "  a: {type: conductor, metal: gld}\n"
        "  b: {type: conductor, metal: gold, reflectance: 1}\n"
        "  c: {type: glass}\n";
    EXPECT_EQ(errors_of(text),
              "scene.yaml:1:36: error: unknown strategy 'both' (known: mis, light, bsdf)\n"
              "    integrator: {type: path, strategy: both}\n" +
                  caret(36, 4) +
                  "scene.yaml:3:93: error: spot light: falloff_start must not exceed cone_angle\n"
                  "      - {type: spot, position: [0, 3, 0], direction: [0, -1, 0], cone_angle: "
                  "20, falloff_start: 30}\n" +
                  caret(93, 2) +
                  "scene.yaml:5:31: error: unknown metal 'gld'; did you mean 'gold'? (known: "
                  "aluminium, chromium, copper, gold, iron, platinum, silver)\n"
                  "      a: {type: conductor, metal: gld}\n" +
                  caret(31, 3) +
                  "scene.yaml:6:6: error: material 'b': give one of 'metal', 'eta' and 'k', or "
                  "'reflectance'\n"
                  "      b: {type: conductor, metal: gold, reflectance: 1}\n" +
                  caret(6, 46) +
                  "scene.yaml:7:13: error: unknown material type 'glass' "
                  "(known: article, diffuse, conductor, dielectric, plastic, pbr, interface, diffuse_transmission, mix, coated_diffuse, coated_conductor)\n"
                  "      c: {type: glass}\n" +
                  caret(13, 5));
}

}  // namespace
}  // namespace glint

namespace glint {

TEST(SceneYamlLimits, FlowCollectionsNestedTooDeeplyAreAnErrorAtTheBracket) {
    const std::string e = errors_of("objects: " + std::string(300, '[') + std::string(300, ']') + "\n");
    EXPECT_EQ(e.rfind("scene.yaml:1:266: error: 257 levels of nesting exceed the limit of 256 (raise it with --limit nesting=N)", 0), 0u) << e.substr(0, 200);
    // Brackets inside quotes and comments are not nesting.
    EXPECT_EQ(errors_of("# " + std::string(300, '[') + "\nfilm: {width: 8, height: 6}\n"), "");
}

}  // namespace glint

namespace glint {
namespace {

// Found by fuzz_scene in CI: a transform step whose key is a sequence, not a name, made yaml-cpp
// throw its own conversion error out of the parser. Now a located error.
TEST(SceneYaml, ATransformStepKeyThatIsNotANameIsALocatedError) {
    const std::string e = errors_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1,\n"
                                    "     transform: [{[1, 2]: [0, 0, 1]}]}\n");
    EXPECT_NE(e.find("scene.yaml:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("transform: expected a one-key map"), std::string::npos) << e;
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// A mesh given in the scene itself, as lists: its triangles as written, in object space.
TEST(SceneYamlInlineMesh, ListsBecomeTheMesh) {
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene(
        "objects:\n"
        "  - type: mesh\n"
        "    positions: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]\n"
        "    indices: [0, 1, 2, 0, 2, 3]\n"
        "    uvs: [0, 0, 1, 0, 1, 1, 0, 1]\n",
        "scene.yaml", sources);
    ASSERT_EQ(d.objects.size(), 1u);
    const auto* m = std::get_if<InlineMeshDesc>(&d.objects[0].shape);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->mesh->triangle_count(), 2u);
    EXPECT_EQ(m->mesh->positions[2], (Point3{1, 1, 0}));
    EXPECT_EQ(m->mesh->indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(m->mesh->uvs.size(), 4u);
    EXPECT_EQ(m->mesh->uvs[3].y, 1.0f);
    EXPECT_TRUE(m->mesh->normals.empty());
}

// Arrays handed over beside the text (the Python module's numpy arrays) read as lists do.
TEST(SceneYamlInlineMesh, ArraysBesideTheTextAreReadAsLists) {
    const float p[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::uint32_t i[] = {0, 1, 2, 0, 2, 3};
    const InlineArrays arrays{{p, nullptr, 4, 3}, {nullptr, i, 2, 3}};
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene(
        "objects: [{type: mesh, positions: '<array 0>', indices: '<array 1>'}]\n", "scene.yaml", sources, 0, &arrays);
    const auto* m = std::get_if<InlineMeshDesc>(&d.objects.at(0).shape);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->mesh->positions[1], (Point3{1, 0, 0}));
    EXPECT_EQ(m->mesh->indices.size(), 6u);
    // Without the arrays, or with the kinds swapped, the placeholders are errors at the key.
    EXPECT_NE(errors_of("objects: [{type: mesh, positions: '<array 0>', indices: [0, 1, 2]}]\n")
                  .find("scene.yaml:1:35: error: mesh: 'positions' must be a list of numbers (no array 0 was given"),
              std::string::npos);
    const std::string swapped =
        errors_of("objects: [{type: mesh, positions: '<array 1>', indices: '<array 0>'}]\n", {}, &arrays);
    EXPECT_NE(swapped.find("'positions' must hold numbers"), std::string::npos) << swapped;
}

// Two objects naming the same arrays are instances of one mesh; lists are not compared.
TEST(SceneYamlInlineMesh, ObjectsNamingTheSameArraysShareTheMesh) {
    const float p[] = {0, 0, 0, 1, 0, 0, 1, 1, 0};
    const std::uint32_t i[] = {0, 1, 2};
    const InlineArrays arrays{{p, nullptr, 3, 3}, {nullptr, i, 1, 3}};
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = parse_scene(
        "objects:\n"
        "  - {type: mesh, positions: '<array 0>', indices: '<array 1>'}\n"
        "  - {type: mesh, positions: '<array 0>', indices: '<array 1>', transform: {translate: [2, 0, 0]}}\n"
        "  - {type: mesh, positions: '<array 0>', indices: [0, 1, 2]}\n",
        "scene.yaml", sources, 0, &arrays);
    ASSERT_EQ(d.objects.size(), 3u);
    const auto mesh = [&](int k) { return std::get<InlineMeshDesc>(d.objects[k].shape).mesh.get(); };
    EXPECT_EQ(mesh(0), mesh(1));
    EXPECT_NE(mesh(0), mesh(2));
}

TEST(SceneYamlInlineMesh, MistakesAreLocated) {
    EXPECT_NE(errors_of("objects: [{type: mesh, positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], indices: [0, 1, 3]}]\n")
                  .find("scene.yaml:1:73: error: mesh: triangle 0 uses vertex 3, but there are 3 vertices"),
              std::string::npos);
    EXPECT_NE(errors_of("objects: [{type: mesh, positions: [], indices: []}]\n").find("must not be empty"),
              std::string::npos);
    EXPECT_NE(errors_of("objects: [{type: mesh, positions: [0, 0, 0, 1, 0], indices: [0, 1, 2]}]\n")
                  .find("'positions' holds 5 numbers, not a multiple of 3"),
              std::string::npos);
    EXPECT_NE(errors_of("objects: [{type: mesh, file: a.ply, positions: [0, 0, 0], indices: [0, 0, 0]}]\n")
                  .find("give 'file' or 'positions'"),
              std::string::npos);
    EXPECT_NE(errors_of("objects: [{type: mesh, positions: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], indices: [0, 1, 2],"
                        " normals: [[0, 0, 1]]}]\n")
                  .find("'normals' has 1 rows for 3 positions"),
              std::string::npos);
    EXPECT_NE(errors_of("objects: [{type: mesh, positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], indices: [0, 1, -2]}]\n")
                  .find("indices"),
              std::string::npos);
}

}  // namespace
}  // namespace glint
