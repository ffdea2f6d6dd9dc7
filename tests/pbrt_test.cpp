// The pbrt-v4 reader: errors at hand-counted line:column, transforms against hand-computed points,
// the camera's handedness and field of view, instancing, warnings and --strict, truncated files,
// and the Cornell box written as pbrt rendering bit-identical to scenes/cornell-box.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "glint/background.h"
#include "glint/builder/build.h"
#include "glint/base/limits.h"
#include "glint/assets/mesh_import.h"
#include "glint/formats/pbrt.h"
#include "glint/formats/scene_writer.h"
#include "glint/formats/scene_yaml.h"
#include "glint/materials/metals.h"
#include "glint/render/render.h"

#include "testing.h"

namespace glint {
namespace {

SceneDescription parse(const std::string& text, bool strict = false) {
    return parse_pbrt(text, "test.pbrt", std::make_shared<SourceFiles>(), PbrtOptions{strict});
}

// An orthographic view 2 units across (20 x 20 pixels, `spp` independent samples) of whatever
// follows, in black diffuse, before a white sky of radiance 1.
std::string ortho_black_in_white_sky(int spp) {
    return R"(LookAt 0 0 -5  0 0 0  0 1 0
Camera "orthographic"
Film "rgb" "integer xresolution" [ 20 ] "integer yresolution" [ 20 ]
Sampler "independent" "integer pixelsamples" [ )" + std::to_string(spp) + R"( ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
Material "diffuse" "rgb reflectance" [ 0 0 0 ]
)";
}

// Builds and renders a parsed scene with its own film and sampler.
// In RGB (pbrt files default to spectral mode): the tests here check geometry and transport
// against exact values; tests/../spectra/spectrum_test.cpp checks spectral mode.
Film render_description(const SceneDescription& d) {
    auto sources = std::make_shared<SourceFiles>();
    Overrides rgb;
    rgb.spectral = false;
    const RenderJob job = build(d, rgb, sources);
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    return film;
}

// The first error's "file:line:col: message" line.
std::string first_error(const std::string& text, bool strict = false) {
    try {
        parse(text, strict);
    } catch (const SceneError& e) {
        const Diagnostic& d = e.diagnostics().front();
        return d.loc.file + ":" + std::to_string(d.loc.line) + ":" + std::to_string(d.loc.column) + ": " + d.message;
    }
    return "no error";
}

TEST(Pbrt, ErrorsPointAtTheirToken) {
    // Hand-counted positions.
    EXPECT_EQ(first_error("WorldBegin\n  Shpe \"sphere\"\n"),
              "test.pbrt:2:3: unknown directive 'Shpe'; did you mean 'Shape'?");
    EXPECT_EQ(first_error("WorldBegin\nShape \"sphere\" \"float radus\" [ 2 ]\n"),
              "test.pbrt:2:16: Shape \"sphere\": unknown parameter \"float radus\"");
    EXPECT_EQ(first_error("WorldBegin\nShape \"sphere\" \"flot radius\" 2\n"),
              "test.pbrt:2:16: unknown parameter type 'flot'; did you mean 'float'?");
    EXPECT_EQ(first_error("WorldBegin\nShape \"sphere\" \"string radius\" \"big\"\n"),
              "test.pbrt:2:16: \"radius\" must be a float, not string");
    EXPECT_EQ(first_error("Film \"rgb\" \"string filename\" \"a.exr\n"), "test.pbrt:1:30: unterminated string");
    EXPECT_EQ(first_error("WorldBegin\nAttributeEnd\n"), "test.pbrt:2:1: AttributeEnd without AttributeBegin");
    EXPECT_EQ(first_error("AttributeBegin\nWorldBegin\n"), "test.pbrt:1:1: AttributeBegin without AttributeEnd");
    EXPECT_EQ(first_error("Translate 1 2\n"), "test.pbrt:1:1: Translate takes 3 numbers, found 2");
    EXPECT_EQ(first_error("LookAt 0 0 0  0 0 0  0 1 0\n"),
              "test.pbrt:1:1: LookAt: the eye is at the target, or up is parallel to the view direction");
    EXPECT_EQ(first_error("WorldBegin\nNamedMaterial \"glas\"\n"),
              "test.pbrt:2:1: unknown named material \"glas\"");
    EXPECT_EQ(first_error("WorldBegin\n  Include \"missing.pbrt\"\n").rfind("test.pbrt:2:3: Include: cannot open", 0), 0u);
    EXPECT_EQ(first_error("WorldBegin\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 3 ]\n"),
              "test.pbrt:2:55: trianglemesh: vertex index 3 out of range (3 vertices)");
    EXPECT_EQ(first_error("Sampler \"halton\" \"integer pixelsamples\" [ 0 ]\n"),
              "test.pbrt:1:18: pixelsamples must be at least 1");
    EXPECT_EQ(first_error("WorldBegin\nShape \"sphere\" \"float radius\" [ 1 \n"),
              "test.pbrt:2:31: '[' without a matching ']'");
}

TEST(Pbrt, ParameterValuesOfEveryForm) {
    const SceneDescription d = parse(R"(WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "blackbody L" 6500 "bool twosided" true "float scale" [ 2 ]
  Shape "sphere" "float radius" 0.5
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 1 2 3 ] "bool twosided" [ "false" ]
  Shape "disk"
AttributeEnd
MakeNamedMaterial "gold" "string type" [ "conductor" ] "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"
)");
    ASSERT_EQ(d.objects.size(), 2u);
    const auto material_of = [&](const ObjectDesc& o) {
        const std::string& n = std::get<std::string>(o.material.value);
        return std::find_if(d.materials.begin(), d.materials.end(), [&](const NamedMaterial& m) { return m.name == n; })->material;
    };
    const Emission a = material_of(d.objects[0]).emission, b = material_of(d.objects[1]).emission;
    EXPECT_TRUE(a.two_sided);
    EXPECT_FALSE(b.two_sided);
    // A blackbody light is normalised to luminance 1, then scaled.
    EXPECT_NEAR(0.2126f * a.radiance.r + 0.7152f * a.radiance.g + 0.0722f * a.radiance.b, 2, 1e-4);
    EXPECT_EQ(b.radiance, (Color{1, 2, 3}));
    const auto gold = std::find_if(d.materials.begin(), d.materials.end(),
                                   [](const NamedMaterial& m) { return m.material.kind == MaterialDesc::Kind::kConductor; });
    ASSERT_NE(gold, d.materials.end());
    EXPECT_EQ(gold->material.eta, kMetals[3].eta);  // gold
    EXPECT_EQ(gold->material.k, kMetals[3].k);
}

// Spectra (issue 36): named glasses and metals are read as spectra for spectral mode (under
// --strict, with no warning); inline pairs and .spd files too; malformed ones point at the value.
TEST(Pbrt, SpectraAreReadOrAreLocatedErrors) {
    const SceneDescription d = parse(R"(WorldBegin
MakeNamedMaterial "glass" "string type" [ "dielectric" ] "spectrum eta" "glass-BK7"
MakeNamedMaterial "brass" "string type" [ "conductor" ] "spectrum eta" "metal-CuZn-eta" "spectrum k" [ 300 3 800 4 ]
)", true);
    ASSERT_EQ(d.materials.size(), 2u);
    const MaterialDesc& glass = d.materials[0].material;
    ASSERT_TRUE(glass.ior_spectrum);
    EXPECT_NEAR(glass.ior, 1.5168, 5e-4);  // BK7's n_d
    EXPECT_FALSE(glass.ior_spectrum->constant());
    const MaterialDesc& brass = d.materials[1].material;
    ASSERT_TRUE(brass.eta_spectrum && brass.k_spectrum);
    EXPECT_FLOAT_EQ((*brass.k_spectrum)(550), 3.5f);  // halfway along the inline pairs
    EXPECT_FLOAT_EQ(brass.k.g, 3.5f);                 // RGB mode: the values at 650, 550, 450 nm
    EXPECT_EQ(first_error("WorldBegin\nMaterial \"conductor\" \"spectrum eta\" [ 400 1 300 2 ]\n"),
              "test.pbrt:2:22: \"eta\": the wavelengths of a spectrum must increase (300 after 400)");
    EXPECT_EQ(first_error("WorldBegin\nMaterial \"conductor\" \"spectrum eta\" [ 400 -1 500 2 ]\n"),
              "test.pbrt:2:22: \"eta\": value -1 at 400 nm; a spectrum's values are finite and not negative");
    EXPECT_EQ(first_error("WorldBegin\nMaterial \"conductor\" \"spectrum eta\" [ 400 1 500 ]\n"),
              "test.pbrt:2:22: \"eta\": a spectrum is wavelength-value pairs; got 3 values");
    // A .spd file (pbrt's form: pairs, '#' comments), as killeroo-gold.pbrt names spds/Au.eta.spd.
    const testing::TempDir tmp;
    const std::string spd = (tmp.path() / "k.spd").string();
    std::ofstream(spd) << "# wavelength k\n400 1.5\n600 2.5 # a comment\n";
    const SceneDescription f = parse("WorldBegin\nMakeNamedMaterial \"m\" \"string type\" [ \"conductor\" ] \"spectrum k\" \"" + spd + "\"\n", true);
    ASSERT_TRUE(f.materials.at(0).material.k_spectrum);
    EXPECT_FLOAT_EQ((*f.materials[0].material.k_spectrum)(500), 2.0f);
    EXPECT_EQ(first_error("WorldBegin\nMaterial \"conductor\" \"spectrum eta\" \"no.spd\"\n").rfind(
                  "test.pbrt:2:22: \"eta\": \"no.spd\" is neither a spectrum pbrt-v4 names nor a file that can be read", 0),
              0u);
}

TEST(Pbrt, UnsupportedIsAWarningOrUnderStrictAnError) {
    const std::string text = "WorldBegin\nMaterial \"measured\" \"string filename\" \"x.bsdf\"\nShape \"sphere\"\n";
    const SceneDescription d = parse(text);
    ASSERT_EQ(d.warnings.size(), 1u);
    EXPECT_EQ(d.warnings[0].loc.line, 2);
    EXPECT_EQ(d.warnings[0].loc.column, 1);
    EXPECT_EQ(d.warnings[0].message, "material \"measured\" not supported; using diffuse 0.5");
    EXPECT_EQ(first_error(text, true), "test.pbrt:2:1: material \"measured\" not supported; using diffuse 0.5 (--strict)");
}

// coateddiffuse and coatedconductor become glint's layered materials with every parameter
// pbrt-v4 reads (its defaults where absent); roughness remapped as pbrt-v4 does (alpha = sqrt r).
TEST(Pbrt, CoatedMaterialsKeepTheirLayers) {
    const SceneDescription d = parse(R"(WorldBegin
MakeNamedMaterial "a" "string type" "coateddiffuse" "rgb reflectance" [ 0.2 0.4 0.6 ] "float roughness" 0.0625
  "float eta" 1.33 "float thickness" 0.05 "rgb albedo" [ 0.5 0.5 0.5 ] "float g" 0.3 "integer maxdepth" 20 "integer nsamples" 4
MakeNamedMaterial "b" "string type" "coateddiffuse"
MakeNamedMaterial "c" "string type" "coatedconductor" "float interface.roughness" 0.0016 "float interface.eta" 1.6
  "spectrum conductor.eta" "metal-Au-eta" "spectrum conductor.k" "metal-Au-k" "float conductor.roughness" 0.01
)");
    const auto named = [&](const char* name) {
        return std::find_if(d.materials.begin(), d.materials.end(), [&](const NamedMaterial& m) { return m.name == name; })->material;
    };
    const MaterialDesc a = named("a"), b = named("b"), c = named("c");
    EXPECT_EQ(a.kind, MaterialDesc::Kind::kCoated);
    EXPECT_FALSE(a.coated_conductor);
    EXPECT_EQ(a.color.value, (Color{0.2f, 0.4f, 0.6f}));
    EXPECT_NEAR(a.coat_roughness, 0.5f, 1e-6f);  // alpha = sqrt(0.0625) = 0.25, roughness = 0.5
    EXPECT_FLOAT_EQ(a.ior, 1.33f);
    EXPECT_FLOAT_EQ(a.thickness, 0.05f);
    EXPECT_EQ(a.layer_albedo, (Color{0.5f}));
    EXPECT_FLOAT_EQ(a.g, 0.3f);
    EXPECT_EQ(a.layer_depth, 20);
    EXPECT_EQ(a.layer_samples, 4);
    // pbrt-v4's defaults.
    EXPECT_EQ(b.color.value, (Color{0.5f}));
    EXPECT_EQ(b.coat_roughness, 0);
    EXPECT_FLOAT_EQ(b.ior, 1.5f);
    EXPECT_FLOAT_EQ(b.thickness, 0.01f);
    EXPECT_EQ(b.layer_albedo, (Color{0}));
    EXPECT_EQ(b.layer_depth, 10);
    EXPECT_EQ(b.layer_samples, 1);
    EXPECT_EQ(c.kind, MaterialDesc::Kind::kCoated);
    EXPECT_TRUE(c.coated_conductor);
    EXPECT_NEAR(c.coat_roughness, 0.2f, 1e-6f);  // sqrt(sqrt(0.0016))
    EXPECT_NEAR(c.roughness, std::sqrt(0.1f), 1e-6f);
    EXPECT_FLOAT_EQ(c.ior, 1.6f);
    EXPECT_EQ(c.eta, kMetals[3].eta);
    EXPECT_TRUE(d.warnings.empty());
    EXPECT_EQ(first_error("WorldBegin\nMaterial \"coateddiffuse\" \"integer nsamples\" 0\n"),
              "test.pbrt:2:26: nsamples: must be in [1, 100]");
}

// Parameter names as pbrt-v4 spells them: the spot light's cone edge is conedeltaangle
// (conedelta is unknown to pbrt-v4, and so to glint); the film's imaging ratio reads iso only.
TEST(Pbrt, ParameterNamesArePbrtV4s) {
    const SceneDescription d = parse("WorldBegin\nLightSource \"spot\" \"float coneangle\" 40 \"float conedeltaangle\" 10\n");
    const auto& spot = std::get<SpotLight>(d.lights.at(0));
    EXPECT_NEAR(spot.cos_outer, std::cos(40 * std::numbers::pi / 180), 1e-6);
    EXPECT_NEAR(spot.cos_inner, std::cos(30 * std::numbers::pi / 180), 1e-6);
    EXPECT_EQ(first_error("WorldBegin\nLightSource \"spot\" \"float conedelta\" 10\n"),
              "test.pbrt:2:20: LightSource \"spot\": unknown parameter \"float conedelta\"");
    // A 3D checkerboard's cells are 1 in its own space, scaled by the transform at the Texture
    // directive; uscale belongs to (u, v) lookups only, and is unknown here, as in pbrt-v4.
    const SceneDescription c = parse("WorldBegin\nAttributeBegin\nScale 0.5 0.5 0.5\n"
                                     "Texture \"c\" \"spectrum\" \"checkerboard\" \"integer dimension\" 3\nAttributeEnd\n"
                                     "MakeNamedMaterial \"m\" \"string type\" \"diffuse\" \"texture reflectance\" \"c\"\n");
    ASSERT_EQ(c.materials.size(), 1u);
    EXPECT_EQ(c.materials[0].material.color.kind, TextureDesc::Kind::kChecker);
    EXPECT_FLOAT_EQ(c.materials[0].material.color.checker.size, 0.5f);
    EXPECT_TRUE(c.warnings.empty());
    EXPECT_NE(first_error("WorldBegin\nTexture \"c\" \"float\" \"checkerboard\" \"integer dimension\" 3 \"float uscale\" 4\n")
                  .find("unknown parameter \"float uscale\""),
              std::string::npos);
    // A 2D checkerboard (pbrt-v4's default dimension) is glint's checker on uv, with the mapping's
    // scales and offsets.
    const SceneDescription u = parse("WorldBegin\nTexture \"c\" \"spectrum\" \"checkerboard\" \"float uscale\" 8 "
                                     "\"float vscale\" 4 \"float udelta\" 0.5 \"float vdelta\" -0.25 \"rgb tex1\" [0.2 0.2 0.2]\n"
                                     "MakeNamedMaterial \"m\" \"string type\" \"diffuse\" \"texture reflectance\" \"c\"\n");
    ASSERT_EQ(u.materials.size(), 1u);
    const CheckerTexture& k = u.materials[0].material.color.checker;
    EXPECT_TRUE(k.on_uv);
    EXPECT_EQ(k.size, 1.0f);
    EXPECT_EQ(k.u_scale, 8.0f);
    EXPECT_EQ(k.v_scale, 4.0f);
    EXPECT_EQ(k.u_offset, 0.5f);
    EXPECT_EQ(k.v_offset, -0.25f);
    EXPECT_EQ(k.even, Color{0.2f});
    EXPECT_EQ(k.odd, Color{0.0f});
    EXPECT_TRUE(u.warnings.empty()) << u.warnings[0].message;
    const SceneDescription f = parse("Film \"rgb\" \"float iso\" 200 \"float fnumber\" 2\nWorldBegin\n");
    ASSERT_EQ(f.warnings.size(), 1u);
    EXPECT_NE(f.warnings[0].message.find("fnumber"), std::string::npos) << f.warnings[0].message;
}

Point3 apply(const ObjectDesc& o, Point3 p) { return o.transform ? o.transform->to_world.apply(p) : p; }

void expect_point(Point3 got, Point3 want) {
    EXPECT_NEAR(got.x, want.x, 1e-5f);
    EXPECT_NEAR(got.y, want.y, 1e-5f);
    EXPECT_NEAR(got.z, want.z, 1e-5f);
}

TEST(Pbrt, TransformsComposeAsInPbrt) {
    // CTM = T(1,2,3) R(90 about z) S(2,1,1): the object point (1,0,0) -> S (2,0,0) -> R (0,2,0) -> T (1,4,3).
    const SceneDescription d = parse(R"(WorldBegin
AttributeBegin
  Translate 1 2 3
  Rotate 90 0 0 1
  Scale 2 1 1
  Shape "sphere"
AttributeEnd
Shape "sphere"
TransformBegin
  ConcatTransform [ 1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1 ]
  CoordinateSystem "moved"
TransformEnd
CoordSysTransform "moved"
Shape "sphere"
Transform [ 0 1 0 0  -1 0 0 0  0 0 1 0  0 0 0 1 ]
Shape "sphere"
)");
    ASSERT_EQ(d.objects.size(), 4u);
    expect_point(apply(d.objects[0], {1, 0, 0}), {1, 4, 3});
    EXPECT_FALSE(d.objects[1].transform);  // AttributeEnd restored the identity
    expect_point(apply(d.objects[2], {0, 0, 0}), {5, 6, 7});  // a column-major matrix: translation last
    expect_point(apply(d.objects[3], {1, 0, 0}), {0, 1, 0});  // columns: x -> (0, 1, 0)
}

TEST(Pbrt, CameraFromLookAtWithHandednessAndShorterAxisFov) {
    const SceneDescription d = parse(R"(LookAt 1 2 3  1 2 10  0 1 0
Camera "perspective" "float fov" [ 60 ]
Film "rgb" "integer xresolution" [ 100 ] "integer yresolution" [ 200 ]
WorldBegin
)");
    const auto& cam = std::get<LookAtCameraDesc>(d.camera);
    expect_point(cam.from, {1, 2, 3});
    expect_point(cam.to, {1, 2, 4});
    EXPECT_FALSE(cam.right_handed);
    // Portrait: pbrt's 60 degrees span the width; glint's fov is vertical: 2 atan(2 tan 30).
    EXPECT_NEAR(cam.fov, 2 * std::atan(2 * std::tan(30 * M_PI / 180)) * 180 / M_PI, 1e-3);
    const SceneDescription m = parse("Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n");
    EXPECT_TRUE(std::get<LookAtCameraDesc>(m.camera).right_handed);
}

TEST(Pbrt, OrthographicCameraScreenWindowCropAndImagingRatio) {
    const SceneDescription d = parse(R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "orthographic" "float screenwindow" [ -2 2 -1 1 ] "float shutteropen" 0 "float shutterclose" 0.5
Film "rgb" "integer xresolution" [ 100 ] "integer yresolution" [ 200 ] "float iso" 400
  "float cropwindow" [ 0 0.5 0.25 1 ]
WorldBegin
)");
    const auto& cam = std::get<LookAtCameraDesc>(d.camera);
    EXPECT_TRUE(cam.orthographic);
    // Portrait: pbrt's shorter axis (x) spans [-1, 1]; glint's units are half the height, 2x as
    // long, so the window halves and the visible height is 4.
    EXPECT_FLOAT_EQ(cam.height, 4);
    ASSERT_TRUE(cam.window);
    EXPECT_FLOAT_EQ((*cam.window)[0], -1);
    EXPECT_FLOAT_EQ((*cam.window)[1], 1);
    EXPECT_FLOAT_EQ((*cam.window)[2], -0.5f);
    EXPECT_FLOAT_EQ((*cam.window)[3], 0.5f);
    ASSERT_TRUE(d.film.crop_window);
    EXPECT_EQ(d.film.crop_window->value[3], 1);
    EXPECT_FLOAT_EQ(d.film.scale, 0.5f * 4);  // exposure 0.5 s x iso 400 / 100
    EXPECT_EQ(first_error("Camera \"perspective\" \"float screenwindow\" [ 1 -1 0 1 ]\n"),
              "test.pbrt:1:22: screenwindow: expected [x0 x1 y0 y1] with x0 < x1 and y0 < y1");
}

// An orthographic view of a black sphere of radius 0.9 before a white sky, 2 units across on a
// 20 x 20 film: pixel centres within 0.9 of the axis see the sphere (0), the others the sky (1).
// A perspective camera from the same place would show a much smaller disk.
TEST(Pbrt, OrthographicViewOfASphereIsItsSilhouette) {
    const Film film = render_description(parse(ortho_black_in_white_sky(1) + R"(Shape "sphere" "float radius" [ 0.9 ]
)"));
    int checked = 0;
    for (int row = 0; row < 20; ++row)
        for (int col = 0; col < 20; ++col) {
            const double x = -1 + (col + 0.5) * 0.1, y = 1 - (row + 0.5) * 0.1, r = std::hypot(x, y);
            if (std::abs(r - 0.9) < 0.01) continue;
            EXPECT_EQ(film.at(col, row).g, r < 0.9 ? 0.0f : 1.0f) << col << "," << row;
            ++checked;
        }
    EXPECT_GT(checked, 390);
}

// pbrt's front side: the geometric normal of the (object-space) winding carried by the inverse
// transpose, so a mirroring transform keeps it, and ReverseOrientation flips it.
TEST(Pbrt, FrontSidesFollowPbrt) {
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(parse_pbrt(R"(WorldBegin
AttributeBegin
  Scale -1 1 1
  Shape "bilinearmesh" "point3 P" [ 0 0 0  0 0 1  1 0 0  1 0 1 ]
  Shape "trianglemesh" "point3 P" [ 0 0 0  0 0 1  1 0 0 ]
AttributeEnd
ReverseOrientation
Shape "bilinearmesh" "point3 P" [ 0 0 0  0 0 1  1 0 0  1 0 1 ]
)", "test.pbrt", sources), {}, sources);
    // (0,0,1) x (1,0,0) = (0, 1, 0): the patch and the triangle face +y in object space.
    ASSERT_EQ(job.scene.quads.size(), 2u);
    ASSERT_EQ(job.scene.triangles.size(), 1u);
    EXPECT_GT(job.scene.quads[0].n_raw.y, 0);  // mirrored in x: still +y
    const Triangle& t = job.scene.triangles[0];
    EXPECT_GT(cross(t.p1 - t.p0, t.p2 - t.p0).y, 0);
    EXPECT_LT(job.scene.quads[1].n_raw.y, 0);  // ReverseOrientation
}

TEST(Pbrt, ObjectInstancesShareOneMesh) {
    std::string mesh = "Shape \"trianglemesh\" \"point3 P\" [";
    std::string idx;
    for (int i = 0; i < 12; ++i) {  // 12 triangles: a mesh, not loose triangles
        mesh += " " + std::to_string(i) + " 0 0  " + std::to_string(i) + " 1 0  " + std::to_string(i + 1) + " 0 0";
        idx += " " + std::to_string(3 * i) + " " + std::to_string(3 * i + 1) + " " + std::to_string(3 * i + 2);
    }
    mesh += " ] \"integer indices\" [" + idx + " ]\n";
    const std::string text = "LookAt 0 0 -10  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\nObjectBegin \"row\"\n" +
                             mesh + "ObjectEnd\nObjectInstance \"row\"\nTranslate 0 5 0\nObjectInstance \"row\"\n"
                             "Translate 0 5 0\nObjectInstance \"row\"\n";
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(parse_pbrt(text, "test.pbrt", sources), {}, sources);
    EXPECT_EQ(job.scene.meshes.size(), 1u);
    ASSERT_EQ(job.scene.instances.size(), 3u);
    expect_point(job.scene.instances[2].transform.to_world.apply(Point3{0, 0, 0}), {0, 10, 0});
}

TEST(Pbrt, CylinderAndLoopSubdivisionBecomeMeshes) {
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(parse_pbrt(R"(WorldBegin
Shape "cylinder" "float radius" 2 "float zmin" -1 "float zmax" 1
Translate 10 0 0
Shape "loopsubdiv" "integer levels" 2 "point3 P" [ 1 0 0  -1 0 0  0 1 0  0 -1 0  0 0 1  0 0 -1 ]
  "integer indices" [ 0 2 4  2 1 4  1 3 4  3 0 4  2 0 5  1 2 5  3 1 5  0 3 5 ]
)", "test.pbrt", sources), {}, sources);
    ASSERT_EQ(job.scene.meshes.size(), 2u);
    EXPECT_EQ(job.scene.meshes[1].triangle_count(), 8u * 16u);
    // A ray at height 0.3 meets the cylinder of radius 2 at x = sqrt(4 - 0.09), within the
    // tessellation's sagitta r (1 - cos(pi / 256)) = 1.5e-4.
    const auto hit = job.scene.intersect(Ray{{5, 0.3f, 0.2f}, {-1, 0, 0}});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5 - std::sqrt(4 - 0.09), 2e-4);
}

// A gzip-compressed PLY (written here with the system's gzip) reads as the PLY does, from a
// plymesh in a pbrt file too; a truncated one is an error naming the file.
TEST(Pbrt, PlyGzReadsAsThePly) {
    const std::filesystem::path model = std::filesystem::path(GLINT_TEST_MODEL_DIR) / "stanford-bunny.ply";
    if (!std::filesystem::exists(model)) GTEST_SKIP() << "no " << model;
    const testing::TempDir tmp;  // removed at the end of the test, whatever fails
    const std::filesystem::path& dir = tmp.path();
    std::filesystem::copy_file(model, dir / "bunny.ply", std::filesystem::copy_options::overwrite_existing);
    ASSERT_EQ(std::system(("gzip -kf '" + (dir / "bunny.ply").string() + "'").c_str()), 0);
    const ImportedFile plain = import_ply(dir / "bunny.ply");
    const ImportedFile gz = import_mesh_file(dir / "bunny.ply.gz");
    ASSERT_EQ(gz.meshes.size(), 1u);
    EXPECT_EQ(gz.meshes[0].positions.size(), plain.meshes[0].positions.size());
    EXPECT_EQ(gz.meshes[0].indices, plain.meshes[0].indices);
    EXPECT_EQ(gz.meshes[0].positions.back().x, plain.meshes[0].positions.back().x);
    {
        std::ofstream(dir / "scene.pbrt") << "WorldBegin\nShape \"plymesh\" \"string filename\" \"bunny.ply.gz\"\n";
        auto sources = std::make_shared<SourceFiles>();
        const RenderJob job = build(load_scene_file((dir / "scene.pbrt").string(), sources), {}, sources);
        ASSERT_EQ(job.scene.meshes.size(), 1u);
        EXPECT_EQ(job.scene.meshes[0].triangle_count(), plain.meshes[0].triangle_count());
    }
    // Truncated: half the compressed bytes.
    const auto size = std::filesystem::file_size(dir / "bunny.ply.gz");
    std::filesystem::resize_file(dir / "bunny.ply.gz", size / 2);
    try {
        import_mesh_file(dir / "bunny.ply.gz");
        ADD_FAILURE() << "a truncated .ply.gz was read";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("bunny.ply.gz: byte"), std::string::npos) << e.what();
    }
}

TEST(Pbrt, EveryTruncationIsAnErrorOrAScene) {
    for (const char* name : {"scenes/pbrt/cornell-room.pbrt", "scenes/pbrt/materials.pbrt"}) {
        const std::string text = testing::read_file(std::filesystem::path(GLINT_SOURCE_DIR) / name);
        ASSERT_FALSE(text.empty()) << name;
        int ok = 0, errors = 0;
        for (std::size_t n = 0; n <= text.size(); n += 3) {
            try {
                parse(text.substr(0, n));
                ++ok;
            } catch (const SceneError&) {
                ++errors;
            }
        }
        EXPECT_GT(ok, 0) << name;
        EXPECT_GT(errors, 0) << name;
    }
}

// The Cornell box as pbrt and as glint YAML: the same shapes, materials, light and camera, so
// the same image bit for bit (a smaller film and fewer samples than the files ask, by override).
TEST(Pbrt, CornellBoxRendersBitIdenticalToTheYamlScene) {
    const std::filesystem::path root(GLINT_SOURCE_DIR);
    Overrides o;
    o.width = 48;
    o.height = 48;
    o.spp = 4;
    o.spectral = false;  // the YAML scene is RGB
    const auto render_file = [&](const std::filesystem::path& p) {
        auto sources = std::make_shared<SourceFiles>();
        const RenderJob job = build(load_scene_file(p.string(), sources), o, sources);
        Film film(job.film_width, job.film_height);
        render(job.scene, job.camera, *job.integrator, job.options, film);
        return film;
    };
    const Film a = render_file(root / "scenes/pbrt/cornell-box.pbrt");
    const Film b = render_file(root / "scenes/cornell-box.yaml");
    ASSERT_EQ(a.pixels().size(), b.pixels().size());
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        EXPECT_EQ(a.pixels()[i].r, b.pixels()[i].r) << "pixel " << i;
        EXPECT_EQ(a.pixels()[i].g, b.pixels()[i].g) << "pixel " << i;
        EXPECT_EQ(a.pixels()[i].b, b.pixels()[i].b) << "pixel " << i;
        sum += a.pixels()[i].r;
    }
    EXPECT_GT(sum, 0);  // not two black images
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// glint convert: the Cornell box written as YAML renders what the pbrt file renders, bit for
// bit; a scene with an inline mesh (a Loop surface) gets a PLY file that reads back the same.
TEST(Pbrt, ConvertedScenesRenderTheSame) {
    const std::filesystem::path root(GLINT_SOURCE_DIR);
    const testing::TempDir tmp;  // removed at the end of the test, whatever fails
    const std::filesystem::path& dir = tmp.path();
    Overrides o;
    o.width = 40;
    o.height = 40;
    o.spp = 4;
    o.spectral = false;
    const auto render_desc = [&](const SceneDescription& d, const std::shared_ptr<SourceFiles>& sources) {
        const RenderJob job = build(d, o, sources);
        Film film(job.film_width, job.film_height);
        render(job.scene, job.camera, *job.integrator, job.options, film);
        return film;
    };
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription pbrt = load_scene_file((root / "scenes/pbrt/cornell-box.pbrt").string(), sources);
    const WrittenScene w = write_scene_yaml(pbrt, dir / "cornell.yaml");
    EXPECT_TRUE(w.meshes.empty());
    const SceneDescription yaml = parse_scene(w.yaml, (dir / "cornell.yaml").string(), sources);
    const Film a = render_desc(pbrt, sources), b = render_desc(yaml, sources);
    ASSERT_EQ(a.pixels().size(), b.pixels().size());
    for (std::size_t i = 0; i < a.pixels().size(); ++i) ASSERT_EQ(a.pixels()[i], b.pixels()[i]) << "pixel " << i;

    const SceneDescription subdiv = parse_pbrt(R"(WorldBegin
Translate 1 2 3
Shape "loopsubdiv" "integer levels" 2 "point3 P" [ 1 0 0  -1 0 0  0 1 0  0 -1 0  0 0 1  0 0 -1 ]
  "integer indices" [ 0 2 4  2 1 4  1 3 4  3 0 4  2 0 5  1 2 5  3 1 5  0 3 5 ]
)", (dir / "subdiv.pbrt").string(), sources);
    const WrittenScene ws = write_scene_yaml(subdiv, dir / "subdiv.yaml");
    ASSERT_EQ(ws.meshes.size(), 1u);
    std::ofstream(dir / "subdiv.yaml") << ws.yaml;
    const RenderJob from_pbrt = build(subdiv, {}, sources);
    const RenderJob from_yaml = build(load_scene_file((dir / "subdiv.yaml").string(), sources), {}, sources);
    ASSERT_EQ(from_yaml.scene.meshes.size(), 1u);
    EXPECT_EQ(from_yaml.scene.meshes[0].positions, from_pbrt.scene.meshes[0].positions);
    EXPECT_EQ(from_yaml.scene.meshes[0].indices, from_pbrt.scene.meshes[0].indices);
    const auto hit_a = from_pbrt.scene.intersect(Ray{{1.1f, 2.2f, -5}, {0, 0, 1}});
    const auto hit_b = from_yaml.scene.intersect(Ray{{1.1f, 2.2f, -5}, {0, 0, 1}});
    ASSERT_TRUE(hit_a && hit_b);
    EXPECT_EQ(hit_a->t, hit_b->t);

    // The rest of what pbrt files bring (alpha, mix, diffusetransmission, a uniformgrid written
    // as a .vdb, power, illuminance) survives the trip: the same image.
    const SceneDescription features = load_scene_file((root / "scenes/pbrt/features.pbrt").string(), sources);
    const WrittenScene wf = write_scene_yaml(features, dir / "features.yaml");
    EXPECT_EQ(wf.meshes.size(), 4u);  // three meshes and the grid
    std::ofstream(dir / "features.yaml") << wf.yaml;
    const Film fa = render_desc(features, sources);
    const Film fb = render_desc(load_scene_file((dir / "features.yaml").string(), sources), sources);
    ASSERT_EQ(fa.pixels().size(), fb.pixels().size());
    for (std::size_t i = 0; i < fa.pixels().size(); ++i) ASSERT_EQ(fa.pixels()[i], fb.pixels()[i]) << "pixel " << i;
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// pbrt-v4's equal-area octahedral map: known points, equal areas (uniform directions fill an
// 8 x 8 grid of the square evenly), and the resampling to lat-long with pbrt's usual
// `Rotate -90 1 0 0` (the map's +z pole becomes world +y).
TEST(Pbrt, EqualAreaEnvironmentMaps) {
    const auto at = [](Vector3 d, float u, float v) {
        const Point2 p = equal_area_sphere_to_square(d);
        EXPECT_NEAR(p.x, u, 1e-6f) << d.x << " " << d.y << " " << d.z;
        EXPECT_NEAR(p.y, v, 1e-6f) << d.x << " " << d.y << " " << d.z;
    };
    at({0, 0, 1}, 0.5f, 0.5f);
    at({1, 0, 0}, 1, 0.5f);
    at({-1, 0, 0}, 0, 0.5f);
    at({0, 1, 0}, 0.5f, 1);
    at({0, -1, 0}, 0.5f, 0);
    const Point2 south = equal_area_sphere_to_square({0, 0, -1});
    EXPECT_TRUE((south.x == 0 || south.x == 1) && (south.y == 0 || south.y == 1));
    std::array<int, 64> cells{};
    std::uint32_t state = 99;
    const auto rnd = [&] {
        state = state * 1664525u + 1013904223u;
        return (state >> 8) * (1.0f / 16777216.0f);
    };
    const int n = 640000;
    for (int i = 0; i < n; ++i) {
        const float z = 1 - 2 * rnd(), phi = 2 * float(M_PI) * rnd(), r = std::sqrt(std::max(0.0f, 1 - z * z));
        const Point2 p = equal_area_sphere_to_square({r * std::cos(phi), r * std::sin(phi), z});
        ++cells[std::size_t(std::min(7, int(p.y * 8)) * 8 + std::min(7, int(p.x * 8)))];
    }
    for (int c : cells) EXPECT_NEAR(c, n / 64, 5 * std::sqrt(n / 64.0)) << "cell count";

    Image square{64, 64, std::vector<Color>(64 * 64), {}};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float u = 2 * (x + 0.5f) / 64 - 1, v = 2 * (y + 0.5f) / 64 - 1;
            square.texels[std::size_t(y * 64 + x)] = Color{std::abs(u) + std::abs(v) < 1 ? 1.0f : 0.0f};
        }
    // world_to_light = Rotate(+90 about x), the inverse of pbrt's Rotate -90 1 0 0.
    const Transform r = Transform::rotate(90, {1, 0, 0});
    const EnvironmentMap env = EnvironmentMap::make(equal_area_to_latlong(square, r.to_world), 1);
    EXPECT_EQ(env.image.width, 128);
    EXPECT_NEAR(env.eval(normalize(Vector3{0.3f, 1, 0.2f})).r, 1, 1e-6f);   // up: the map's +z half
    EXPECT_NEAR(env.eval(normalize(Vector3{-0.2f, -1, 0.5f})).r, 0, 1e-6f);  // down
    EXPECT_NEAR(r.to_world.apply(Vector3{0, 1, 0}).z, 1, 1e-6f);  // the rotation is the one meant

    // A uniform sky of luminance 1 gives an illuminance of pi on a surface facing any way.
    const Image white{256, 128, std::vector<Color>(256 * 128, Color{1}), {}};
    for (Vector3 up : {Vector3{0, 1, 0}, Vector3{0, 0, 1}, normalize(Vector3{1, -2, 0.5f})})
        EXPECT_NEAR(illuminance(white, up), M_PI, 2e-3);
}

TEST(Pbrt, MixAndDiffuseTransmissionMaterials) {
    const SceneDescription d = parse(R"(WorldBegin
MakeNamedMaterial "red" "string type" "diffuse" "rgb reflectance" [ 0.8 0.1 0.1 ]
MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"
Material "mix" "string materials" [ "red" "gold" ] "float amount" [ 0.3 ]
Shape "sphere"
Material "diffusetransmission" "rgb transmittance" [ 0.5 0.25 1 ] "float scale" [ 0.5 ]
Shape "sphere"
)");
    ASSERT_EQ(d.objects.size(), 2u);
    const auto material_of = [&](const ObjectDesc& o) {
        const std::string& name = std::get<std::string>(o.material.value);
        return std::find_if(d.materials.begin(), d.materials.end(), [&](const NamedMaterial& m) { return m.name == name; })->material;
    };
    const MaterialDesc mix = material_of(d.objects[0]);
    ASSERT_EQ(mix.kind, MaterialDesc::Kind::kMix);
    ASSERT_EQ(mix.mix.size(), 2u);
    EXPECT_EQ(mix.mix[0].value, "red");
    EXPECT_EQ(mix.mix[1].value, "gold");
    ASSERT_TRUE(mix.amount);
    EXPECT_FLOAT_EQ(mix.amount->value.g, 0.3f);
    const MaterialDesc dt = material_of(d.objects[1]);
    ASSERT_EQ(dt.kind, MaterialDesc::Kind::kDiffuseTransmission);
    EXPECT_FLOAT_EQ(dt.color.value.r, 0.125f);  // the default reflectance 0.25, scaled
    ASSERT_TRUE(dt.transmittance);
    EXPECT_FLOAT_EQ(dt.transmittance->value.b, 0.5f);
    EXPECT_TRUE(d.warnings.empty());
    auto sources = std::make_shared<SourceFiles>();
    const RenderJob job = build(d, {}, sources);  // resolves the mix
    EXPECT_EQ(first_error("WorldBegin\nMaterial \"mix\" \"string materials\" [ \"a\" \"b\" ]\n"),
              "test.pbrt:2:16: mix: unknown material \"a\"");
}

// pbrt's "alpha": a constant 0.25 on a black square filling an orthographic view of a white sky
// lets 3/4 of the rays through (a hash per ray decides), so the image averages 0.75; alpha 0
// removes a shape, alpha on a sphere is a warning.
TEST(Pbrt, AlphaCutsOutStochastically) {
    const SceneDescription d = parse(ortho_black_in_white_sky(16) + R"(Shape "trianglemesh" "point3 P" [ -2 -2 0  2 -2 0  2 2 0  -2 2 0 ] "integer indices" [ 0 1 2  0 2 3 ]
  "point2 uv" [ 0 0  1 0  1 1  0 1 ] "float alpha" [ 0.25 ]
Shape "sphere" "float radius" [ 0.5 ] "float alpha" [ 0 ]
Translate 50 0 0
Shape "sphere" "float radius" [ 0.5 ] "float alpha" [ 0.5 ]
)");
    ASSERT_EQ(d.objects.size(), 2u);  // the alpha-0 sphere is gone
    ASSERT_TRUE(d.objects[0].alpha);
    EXPECT_TRUE(d.objects[0].alpha->stochastic);
    ASSERT_EQ(d.warnings.size(), 1u);
    EXPECT_NE(d.warnings[0].message.find("\"alpha\" on a sphere"), std::string::npos);
    const Film film = render_description(d);
    double sum = 0;
    for (const Color& c : film.pixels()) sum += c.g;
    // 6400 rays: the mean's standard deviation is sqrt(0.75 x 0.25 / 6400) = 0.0054.
    EXPECT_NEAR(sum / 400, 0.75, 0.03);
}

// pbrt-v4's uniformgrid medium: samples x fastest, sample (i, j, k) at p0 + (p1 - p0)(i + 1/2)/n
// in the medium's space (here translated by (10, 0, 0)).
TEST(Pbrt, UniformGridMediumBecomesAVoxelGrid) {
    const SceneDescription d = parse(R"(WorldBegin
AttributeBegin
  Translate 10 0 0
  MakeNamedMedium "smoke" "string type" "uniformgrid" "integer nx" 2 "integer ny" 3 "integer nz" 1
    "float density" [ 0 1 2 3 4 5 ] "point3 p0" [ 0 0 0 ] "point3 p1" [ 2 3 0.5 ] "rgb sigma_s" [ 0.5 0.5 0.5 ]
AttributeEnd
)");
    ASSERT_EQ(d.media.size(), 1u);
    const MediumDesc& m = d.media[0].medium;
    ASSERT_EQ(m.kind, MediumDesc::Kind::kGrid);
    ASSERT_TRUE(m.inline_density && m.transform);
    EXPECT_EQ(m.inline_density->voxel(1, 0, 0), 1);
    EXPECT_EQ(m.inline_density->voxel(0, 2, 0), 4);
    EXPECT_EQ(m.inline_density->voxel(1, 2, 0), 5);
    expect_point(m.transform->point({0, 0, 0}), {10.5f, 0.5f, 0.25f});
    expect_point(m.transform->point({1, 2, 0}), {11.5f, 2.5f, 0.25f});
    EXPECT_EQ(m.sigma_s.g, 0.5f);
    EXPECT_EQ(m.sigma_a.g, 1);  // pbrt's grid default
    EXPECT_EQ(first_error("MakeNamedMedium \"m\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"float density\" [ 1 ]\n"),
              "test.pbrt:1:64: uniformgrid: 1 density values for nx x ny x nz = 2");
}

// A real scene of the pbrt-v4 collection: the killeroos (killeroos/killeroo-simple.pbrt and its
// geometry/killeroo.pbrt, a loopsubdiv control mesh, kept in ../shared/models when present). It
// reads without a warning; each killeroo is Loop-subdivided once, so it has 4F triangles and V + E
// vertices, F, V and E counted here from the file's own arrays.
TEST(Pbrt, KillerooSceneFromThePbrtV4Collection) {
    const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_MODEL_DIR) / "pbrt-v4-scenes" / "killeroos";
    if (!std::filesystem::exists(dir / "killeroo-simple.pbrt")) GTEST_SKIP() << "no " << dir.string();
    auto sources = std::make_shared<SourceFiles>();
    const SceneDescription d = load_pbrt_file((dir / "killeroo-simple.pbrt").string(), sources, PbrtOptions{true});
    EXPECT_TRUE(d.warnings.empty());
    // The control mesh's counts, from its text.
    const std::string geometry = testing::read_file(dir / "geometry" / "killeroo.pbrt");
    const auto array = [&](const std::string& name) {
        const std::size_t open = geometry.find('[', geometry.find(name)), close = geometry.find(']', open);
        std::istringstream in(geometry.substr(open + 1, close - open - 1));
        std::vector<double> v;
        for (double x; in >> x;) v.push_back(x);
        return v;
    };
    const std::vector<double> P = array("\"point3 P\""), indices = array("\"integer indices\"");
    const std::size_t V = P.size() / 3, F = indices.size() / 3;
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (std::size_t f = 0; f < F; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto a = std::uint32_t(indices[3 * f + std::size_t(k)]), b = std::uint32_t(indices[3 * f + std::size_t((k + 1) % 3)]);
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    int killeroos = 0;
    for (const ObjectDesc& o : d.objects)
        if (const auto* m = std::get_if<InlineMeshDesc>(&o.shape); m && m->mesh->triangle_count() > 100) {
            ++killeroos;
            EXPECT_EQ(m->mesh->triangle_count(), 4 * F);
            EXPECT_EQ(m->mesh->positions.size(), V + edges.size());
        }
    EXPECT_EQ(killeroos, 2);
    Overrides o;
    o.width = 40;
    o.height = 40;
    o.spp = 2;
    const RenderJob job = build(d, o, sources);
    Film film(job.film_width, job.film_height);
    render(job.scene, job.camera, *job.integrator, job.options, film);
    double sum = 0;
    for (const Color& c : film.pixels()) {
        ASSERT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
        sum += c.g;
    }
    EXPECT_GT(sum, 0);
}

// pbrt-v4's "power" and "illuminance", against the closed forms of each light's emitted power.
TEST(Pbrt, LightPowerAndIlluminance) {
    const SceneDescription d = parse(R"(WorldBegin
LightSource "point" "rgb I" [ 1 0.5 1 ] "float power" [ 25.132741228718345 ]
LightSource "spot" "float coneangle" [ 60 ] "float conedeltaangle" [ 0 ] "float power" [ 3.141592653589793 ]
LightSource "distant" "float illuminance" [ 3 ]
LightSource "infinite" "rgb L" [ 1 1 1 ] "float illuminance" [ 6.283185307179586 ]
AttributeBegin
  AreaLightSource "diffuse" "float power" [ 100 ]
  Shape "sphere" "float radius" [ 2 ]
AttributeEnd
AttributeBegin
  Scale 2 2 2
  AreaLightSource "diffuse" "float power" [ 10 ] "bool twosided" true
  Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  1 1 0  0 1 0 ] "integer indices" [ 0 1 2  0 2 3 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "float power" [ 10 ]
  Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  1 1 0  0 3 0 ] "integer indices" [ 0 1 2  0 2 3 ]
AttributeEnd
)");
    ASSERT_EQ(d.lights.size(), 3u);
    const Color point = std::get<PointLight>(d.lights[0]).intensity;  // 8 pi / (4 pi) = 2
    EXPECT_NEAR(point.r, 2, 1e-5);
    EXPECT_NEAR(point.g, 1, 1e-5);
    // Spot of 60 degrees, no falloff: 2 pi (1 - cos 60) = pi sr, so I = 1.
    EXPECT_NEAR(std::get<SpotLight>(d.lights[1]).intensity.g, 1, 1e-5);
    EXPECT_NEAR(std::get<DirectionalLight>(d.lights[2]).intensity.b, 3, 1e-6);
    EXPECT_NEAR(std::get<ConstantBackground>(d.background).color.r, 2, 1e-6);  // E = pi L
    const auto radiance = [&](const std::string& name) {
        for (const NamedMaterial& m : d.materials)
            if (m.name == name) return m.material.emission.radiance.g;
        return -1.0f;
    };
    std::vector<std::string> emitters;
    for (const ObjectDesc& o : d.objects) emitters.push_back(std::get<std::string>(o.material.value));
    ASSERT_EQ(emitters.size(), 5u);
    // Sphere: 100 / (pi x 16 pi). Square of two triangles of world area 2 each, two-sided:
    // every triangle emits 10, so L = 10 / (2 x pi x 2).
    EXPECT_NEAR(radiance(emitters[0]), 100 / (16 * M_PI * M_PI), 1e-5);
    EXPECT_NEAR(radiance(emitters[1]), 10 / (4 * M_PI), 1e-6);
    EXPECT_EQ(emitters[1], emitters[2]);
    // Triangles of areas 0.5 and 1.5: their mean, and a warning that pbrt's radiance differs.
    EXPECT_NEAR(radiance(emitters[3]), 10 / M_PI, 1e-5);
    EXPECT_TRUE(std::any_of(d.warnings.begin(), d.warnings.end(),
                            [](const Diagnostic& w) { return w.message.find("different areas") != std::string::npos; }));
}

}  // namespace
}  // namespace glint

namespace glint {

// Issue 16: nesting is a limit with a name and a flag, in pbrt files (AttributeBegin,
// TransformBegin) and glTF node trees alike.
TEST(PbrtLimits, NestingDeeperThanTheLimitIsAnErrorAtTheBlock) {
    const long long saved = limit(Limit::kNesting);
    set_limit(Limit::kNesting, 3);
    auto sources = std::make_shared<SourceFiles>();
    try {
        parse_pbrt("WorldBegin\nAttributeBegin\nTransformBegin\nAttributeBegin\n  AttributeBegin\n", "deep.pbrt", sources);
        ADD_FAILURE() << "no error";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("deep.pbrt:5:3: error: AttributeBegin: 4 levels of nesting exceed the limit "
                                             "of 3 (raise it with --limit nesting=N)"),
                  std::string::npos) << e.what();
    }
    EXPECT_NO_THROW(parse_pbrt("WorldBegin\nAttributeBegin\nTransformBegin\nAttributeBegin\nAttributeEnd\nTransformEnd\n"
                               "AttributeEnd\n", "ok.pbrt", sources));
    set_limit(Limit::kNesting, saved);
}

}  // namespace glint
