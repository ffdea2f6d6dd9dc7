#pragma once
// A bounding volume hierarchy over the lights that have a place (point, spot and area lights),
// for choosing one light for a shaded point in proportion to an estimate of what it sends there.
// Each node bounds its lights' positions (a box), their summed strength, and the directions they
// emit in (a cone); the importance of a node at a point is an upper-bound-minded estimate of the
// irradiance its lights could give (Conty Estevez and Kulla, "Importance Sampling of Many Lights
// with Adaptive Tree Splitting", 2018; the same idea as pbrt-v4's BVH light sampler and Cycles'
// light tree). Descending the tree, a child is taken with probability proportional to its
// importance; a node whose lights cannot reach the point (all behind it, outside their cones)
// has importance 0 and is never chosen. Build and formulas: docs/architecture.md, "Light BVH".
#include <cstdint>
#include <vector>

#include "glint/math/bounds.h"
#include "glint/math/vector.h"

namespace glint {

/// What a light, or a node's lights, emit, as bounds: where (box), how strongly (phi: a radiant
/// intensity, W/sr, that sums over lights; for an area light its radiance times its area seen
/// face on), and in which directions: within theta_o of the unit axis w, each direction spreading
/// by up to theta_e more (a flat emitter: theta_o = 0, theta_e = pi/2; a point light: theta_o =
/// pi). A two-sided emitter emits around -w too.
struct LightBounds {
    Bounds3 box;
    float phi = 0;
    Vector3 w{0, 0, 1};
    float cos_o = 1;  ///< cos theta_o
    float cos_e = 0;  ///< cos theta_e
    bool two_sided = false;
};

/// Bounds of the union (the cone: the smallest that holds both cones).
LightBounds unite(const LightBounds& a, const LightBounds& b);

/// LightBounds as the traversal reads them: the box by its bounding sphere, the sine of
/// theta_o kept beside its cosine.
struct PackedLightBounds {
    Point3 centre;
    float radius = 0;
    Vector3 w{0, 0, 1};
    float phi = 0;
    float cos_o = 1, sin_o = 0, cos_e = 0;
    bool two_sided = false;
    static PackedLightBounds from(const LightBounds& b);
};

/// The estimate of what lights within `b` send to point p on a surface with unit normal n (a zero
/// normal: a point in a medium, which receives from every side): phi cos(theta') cos(theta_i') /
/// d^2, with d the distance to the box's centre (at least the box's half diagonal), theta' the
/// smallest angle between an emitted direction and the direction to p that the box allows, and
/// theta_i' the smallest angle between n (either side) and a direction into the box. 0 when
/// theta' is beyond theta_e (a hard-edged spot light, theta_e = 0, counts where theta' = 0).
float importance(const LightBounds& b, Point3 p, Normal3 n);
/// The same (the box by its bounding sphere, as importance(LightBounds) does too).
float importance(const PackedLightBounds& b, Point3 p, Normal3 n);

/// The orientation measure of a cone (the surface area orientation heuristic's M_Omega): the
/// integral over directions of cos weighted by how far outside theta_o they are, 2 pi (1 - cos
/// theta_o) inside plus the falloff band out to theta_o + theta_e.
float orientation_measure(float cos_o, float cos_e);

inline constexpr std::uint32_t kNoBvhLight = 0xffffffffU;

class LightBvh {
public:
    /// bounds[i]: light i's. Lights whose phi is not positive are left out (never chosen).
    void build(const std::vector<LightBounds>& bounds);
    bool empty() const { return nodes_.empty(); }
    std::size_t node_count() const { return nodes_.size(); }

    /// A light for point p and normal n: `pmf` receives its probability. kNoBvhLight (pmf 0) when
    /// no light can reach p.
    std::uint32_t sample(Point3 p, Normal3 n, float u, float* pmf) const;
    /// The probability with which sample(p, n, ...) returns `light`.
    float pmf(Point3 p, Normal3 n, std::uint32_t light) const;

private:
    struct Node {
        PackedLightBounds bounds;
        std::uint32_t index = 0;  ///< a leaf's light, an inner node's second child (the first follows it)
        bool leaf = false;
    };
    struct Item {
        LightBounds bounds;
        Point3 centroid;
        std::uint32_t light;
    };
    void build_node(std::vector<Item>& items, std::size_t begin, std::size_t end, int depth,
                    std::uint64_t trail);
    std::vector<Node> nodes_;
    /// Per light: the path from the root to its leaf, bit k set when the k-th step takes the
    /// second child; depth_ 0xff for lights left out.
    std::vector<std::uint64_t> trail_;
    std::vector<std::uint8_t> depth_;
};

}  // namespace glint
