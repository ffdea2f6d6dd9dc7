// Meshes in scene files: placement by transforms, material overrides, errors that point at the
// line, the model search path, and the two acceleration backends rendering the same image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "glint/film/film.h"
#include "glint/builder/build.h"
#include "glint/formats/scene_yaml.h"
#include "glint/render/render.h"
#include "testing.h"

namespace glint {
namespace {

RenderJob build_text(const std::string& text, const std::string& path, Overrides o = {}) {
    auto sources = std::make_shared<SourceFiles>();
    return build(parse_scene(text, path, sources), o, sources);
}

std::string errors_of(const std::string& text, const std::string& path = "scene.yaml") {
    try {
        build_text(text, path);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

const char* kTetPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST(MeshScene, TransformsPlaceInstancesThatShareOneMesh) {
    testing::TempDir dir;
    std::ofstream(dir / "tet.ply") << kTetPly;
    const std::string text =
        "materials: {red: {type: diffuse, albedo: [1, 0, 0]}}\n"
        "objects:\n"
        "  - {type: mesh, file: tet.ply}\n"
        "  - type: mesh\n"
        "    file: tet.ply\n"
        "    material: red\n"
        "    transform: [{scale: [2, 1, 1]}, {rotate: {angle: 90, axis: [0, 0, 1]}}, {translate: [10, 0, 0]}]\n"
        "  - {type: sphere, center: [0, 0, 0], radius: 1, transform: [{scale: 3}, {translate: [0, 5, 0]}]}\n"
        "  - {type: quad, corner: [0, 0, 0], edge1: [1, 0, 0], edge2: [0, 1, 0], transform: {scale: [-1, 1, 1]}}\n";
    const RenderJob job = build_text(text, (dir / "scene.yaml").string());
    const Scene& s = job.scene;
    ASSERT_EQ(s.meshes.size(), 1u);  // one file, loaded once
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_FALSE(s.instances[0].material.has_value());
    ASSERT_TRUE(s.instances[1].material.has_value());
    // By hand: (1, 0, 0) -> scale (2, 0, 0) -> rotate 90 about z (0, 2, 0) -> (10, 2, 0).
    const Point3 p = s.instances[1].transform.point({1, 0, 0});
    EXPECT_NEAR(p.x, 10, 1e-5f);
    EXPECT_NEAR(p.y, 2, 1e-5f);
    // The sphere: centre (0, 5, 0), radius 3.
    EXPECT_NEAR(s.spheres.at(0).center.y, 5, 1e-6f);
    EXPECT_NEAR(s.spheres.at(0).radius, 3, 1e-6f);
    // The mirrored quad keeps its front side: normal still +z... as its own transform's inverse
    // transpose says (a mirror in x leaves z alone).
    EXPECT_GT(s.quads.at(0).normal().z, 0);
    // A ray straight down (-y) at x = 9.75, z = 0.25 passes through the second instance (the
    // tetrahedron scaled by 2 along x, turned onto y, moved to x = 10), and through nothing else.
    const Ray r{{10 - 0.25f, 5, 0.25f}, {0, -1, 0}};
    const auto hit = s.intersect(r);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->kind, ShapeKind::kMesh);
    EXPECT_EQ(hit->index, 1u);
}

TEST(MeshScene, ErrorsPointAtTheLine) {
    EXPECT_EQ(errors_of("objects:\n  - {type: mesh, file: nowhere.ply}\n").rfind(
                  "scene.yaml:2:24: error: mesh file 'nowhere.ply' not found (looked in: .", 0),
              0u)
        << errors_of("objects:\n  - {type: mesh, file: nowhere.ply}\n");
    const std::string bad_step =
        errors_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1, transform: {tranlate: [1, 0, 0]}}\n");
    EXPECT_NE(bad_step.find("scene.yaml:2:61: error: unknown transform step 'tranlate'; did you mean 'translate'?"),
              std::string::npos)
        << bad_step;
    const std::string sphere_scale =
        errors_of("objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1,\n     transform: {scale: [1, 2, 1]}}\n");
    EXPECT_NE(sphere_scale.find("scene.yaml:3:17: error: a sphere's transform must scale uniformly"),
              std::string::npos)
        << sphere_scale;
    const std::string singular = errors_of(
        "objects:\n  - {type: quad, corner: [0, 0, 0], edge1: [1, 0, 0], edge2: [0, 1, 0],\n"
        "     transform: {matrix: [[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0]]}}\n");
    EXPECT_NE(singular.find("scene.yaml:3:26: error: transform: the matrix is singular"), std::string::npos)
        << singular;
    // A broken mesh file: the error names the scene line and the file's own line.
    testing::TempDir dir;
    std::ofstream(dir / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n";
    const std::string broken =
        errors_of("objects:\n  - {type: mesh, file: broken.ply}\n", (dir / "scene.yaml").string());
    EXPECT_NE(broken.find("broken.ply:3: the vertex element needs properties x, y and z"), std::string::npos)
        << broken;
}

TEST(MeshScene, ModelSearchPathFindsFilesOutsideTheSceneFolder) {
    testing::TempDir dir;
    std::filesystem::create_directories(dir / "models");
    std::ofstream(dir / "models" / "tet.ply") << kTetPly;
    const std::string text = "objects:\n  - {type: mesh, file: tet.ply}\n";
    ::setenv("GLINT_MODEL_PATH", ("/nonexistent:" + (dir / "models").string()).c_str(), 1);
    EXPECT_EQ(build_text(text, (dir / "scene.yaml").string()).scene.instances.size(), 1u);
    ::unsetenv("GLINT_MODEL_PATH");
    EXPECT_NE(errors_of(text, (dir / "scene.yaml").string()).find("not found"), std::string::npos);
}

#if GLINT_EMBREE
TEST(MeshScene, BvhAndEmbreeRenderTheSameImage) {
    // The bunny in the Cornell box, path traced: the two backends differ only where a ray grazes
    // an edge (Embree's test is not watertight) and in the last bits of t. Their difference must be
    // far below the image's own noise, measured as the difference between two seeds.
    const std::filesystem::path scene = std::filesystem::path(GLINT_SOURCE_DIR) / "scenes/bunny.yaml";
    if (!std::filesystem::exists(std::filesystem::path(GLINT_TEST_MODEL_DIR) / "stanford-bunny.ply"))
        GTEST_SKIP() << "no bunny in " << GLINT_TEST_MODEL_DIR;
    const auto render_with = [&](AccelKind accel, std::uint64_t seed) {
        auto sources = std::make_shared<SourceFiles>();
        Overrides o;
        o.width = 64;
        o.height = 64;
        o.spp = 8;
        o.seed = seed;
        o.accel = accel;
        RenderJob job = build(load_scene_file(scene.string(), sources), o, sources);
        Film film(job.film_width, job.film_height);
        render(job.scene, job.camera, *job.integrator, job.options, film, nullptr);
        return film.pixels();
    };
    const auto rmse = [](const BigVector<Color>& a, const BigVector<Color>& b) {
        double s = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            const Color d = a[i] - b[i];
            s += d.r * d.r + d.g * d.g + d.b * d.b;
        }
        return std::sqrt(s / (3.0 * a.size()));
    };
    const auto bvh = render_with(AccelKind::kBvh, 1);
    const auto embree = render_with(AccelKind::kEmbree, 1);
    const auto other_seed = render_with(AccelKind::kBvh, 2);
    const double backends = rmse(bvh, embree), noise = rmse(bvh, other_seed);
    EXPECT_GT(noise, 0.005);
    EXPECT_LT(backends, noise / 10) << "backends " << backends << ", noise " << noise;
}
#endif

}  // namespace
}  // namespace glint
