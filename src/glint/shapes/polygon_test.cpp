// Polygon triangulation against an independent measure: the triangles of a simple polygon tile
// it exactly, so their areas (all with the polygon's winding) sum to its shoelace area.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "glint/shapes/polygon.h"

namespace glint {
namespace {

struct Result {
    double area = 0;          // sum of the triangles' signed areas (in the polygon's plane)
    double absolute = 0;      // sum of their absolute areas
    std::size_t triangles = 0;
};

// Triangulates the polygon `xy` (counter-clockwise seen from +z, placed at height z) and measures.
Result triangulate(const std::vector<std::pair<double, double>>& xy, float z = 0) {
    std::vector<Point3> positions;
    std::vector<std::uint32_t> corners;
    for (const auto& [x, y] : xy) {
        corners.push_back(static_cast<std::uint32_t>(positions.size()));
        positions.push_back({float(x), float(y), z});
    }
    std::vector<std::uint32_t> tris;
    triangulate_polygon(corners, positions, tris);
    Result r;
    r.triangles = tris.size() / 3;
    for (std::size_t t = 0; t < tris.size(); t += 3) {
        const Point3 a = positions[tris[t]], b = positions[tris[t + 1]], c = positions[tris[t + 2]];
        const double s = 0.5 * ((double(b.x) - a.x) * (double(c.y) - a.y) - (double(b.y) - a.y) * (double(c.x) - a.x));
        r.area += s;
        r.absolute += std::abs(s);
    }
    return r;
}

double shoelace(const std::vector<std::pair<double, double>>& xy) {
    double a = 0;
    for (std::size_t i = 0; i < xy.size(); ++i) {
        const auto& [x0, y0] = xy[i];
        const auto& [x1, y1] = xy[(i + 1) % xy.size()];
        a += x0 * y1 - x1 * y0;
    }
    return 0.5 * a;
}

void expect_tiles(const std::vector<std::pair<double, double>>& xy) {
    const Result r = triangulate(xy);
    const double want = shoelace(xy);
    EXPECT_EQ(r.triangles, xy.size() - 2);
    EXPECT_NEAR(r.area, want, 1e-6 * std::abs(want)) << "signed area";
    // No triangle flipped or overlapping: the absolute areas sum to the same.
    EXPECT_NEAR(r.absolute, std::abs(want), 1e-6 * std::abs(want)) << "absolute area";
}

TEST(Polygon, ConvexCircleOf360Corners) {
    std::vector<std::pair<double, double>> xy;
    for (int k = 0; k < 360; ++k) xy.emplace_back(std::cos(k * std::numbers::pi / 180), std::sin(k * std::numbers::pi / 180));
    expect_tiles(xy);
}

TEST(Polygon, ConcaveLShape) { expect_tiles({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}); }

TEST(Polygon, ConcaveStarOf300Corners) {
    std::vector<std::pair<double, double>> xy;
    for (int k = 0; k < 300; ++k) {
        const double r = k % 2 ? 0.3 : 1.0, a = 2 * std::numbers::pi * k / 300;
        xy.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    expect_tiles(xy);
}

TEST(Polygon, ConcaveCombOf1000Corners) {
    // Teeth up from a base: deep notches, many reflex corners.
    std::vector<std::pair<double, double>> xy{{0, 0}};
    const int teeth = 249;
    for (int t = 0; t < teeth; ++t) {
        xy.emplace_back(t + 0.0, 5.0 + (t % 7));
        xy.emplace_back(t + 0.5, 5.0 + (t % 7));
        xy.emplace_back(t + 0.5, 1.0);
        xy.emplace_back(t + 1.0, 1.0);
    }
    xy.emplace_back(teeth, 0);
    expect_tiles(xy);
}

TEST(Polygon, ClockwiseWindingIsKept) {
    // The same L, clockwise: the triangles keep the polygon's winding (negative area).
    std::vector<std::pair<double, double>> xy{{0, 0}, {0, 2}, {1, 2}, {1, 1}, {2, 1}, {2, 0}};
    const Result r = triangulate(xy);
    EXPECT_NEAR(r.area, shoelace(xy), 1e-9);
    EXPECT_NEAR(r.absolute, std::abs(shoelace(xy)), 1e-9);
}

TEST(Polygon, SelfIntersectingAndDegenerateStillEnd) {
    // A bow tie and a polygon of repeated points: not simple, but each still gives n - 2 triangles.
    EXPECT_EQ(triangulate({{0, 0}, {1, 1}, {1, 0}, {0, 1}}).triangles, 2u);
    EXPECT_EQ(triangulate({{0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}}).triangles, 3u);
}

TEST(Polygon, FacesOfAnyCountWithTheirFace) {
    std::vector<Point3> p;
    for (int k = 0; k < 300; ++k) p.push_back({std::cos(k * 0.021f), std::sin(k * 0.021f), 0});
    std::vector<std::uint32_t> corners, tris, face_of;
    for (std::uint32_t k = 0; k < 300; ++k) corners.push_back(k);
    corners.insert(corners.end(), {0, 1});  // a two-corner face: skipped
    EXPECT_EQ(triangulate_faces({300, 2}, corners, p, tris, &face_of), 1u);
    EXPECT_EQ(tris.size(), 3u * 298);
    EXPECT_EQ(face_of, std::vector<std::uint32_t>(298, 0));
    EXPECT_THROW(triangulate_faces({3}, {0, 1, 300}, p, tris), std::invalid_argument);
}

}  // namespace
}  // namespace glint
