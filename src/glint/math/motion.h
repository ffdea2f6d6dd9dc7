#pragma once
// Motion over the shutter: a transform that changes with time, given by keyframes at evenly
// spaced times over the shutter interval (key 0 at its opening, the last at its close; a ray's
// `time` is in [0, 1] across it). Between keys the transform is interpolated as pbrt-v4's
// AnimatedTransform does (Shoemake and Duff 1992): each key is decomposed into a translation T,
// a rotation R (a unit quaternion) and a stretch S (symmetric, scale and shear) by polar
// decomposition, M = T R S; T and S are blended linearly and R by slerp, so a rotating object
// turns along an arc instead of shrinking through the chord, as blending matrices would make it.
//
// The keys are whole placements (object-to-world transforms, as pbrt-v4's ActiveTransform gives
// at its start and end times, and as Embree's motion-blurred instances take them), so a shape
// turning about its own centre while its parent moves interpolates as one rigid motion.
// See docs/motion.md.
#include <array>
#include <vector>

#include "glint/math/bounds.h"
#include "glint/math/transform.h"

namespace glint {

/// How many key segments a shutter `frames` long is read at (glint's YAML keyframes, glTF
/// animations): four per frame, at least one, at most 64. Keys blend by rotation and translation,
/// so turns and moves at a steady rate are exact with any count; curves need a few per frame.
int shutter_segments(double frames);

/// The rotation by the smallest angle that turns unit direction `from` into unit direction `to`
/// (about their cross product; half a turn about a perpendicular axis when they are opposite).
Transform rotation_between(Vector3 from, Vector3 to);

/// Keys for a light that moves and turns: T(position k) R(direction 0 to direction k), placing a
/// light stored at the origin with direction 0. `positions` or `directions` may be empty (the
/// light stays at `still_at`, or turns not); otherwise both have one entry per key. A light's
/// position at a time is then the blended translation itself, exact between keys, and its
/// direction turns along the arc (a pivot away from the origin would wobble between keys).
std::vector<Transform> light_keys(const std::vector<Point3>& positions, const std::vector<Vector3>& directions,
                                  Point3 still_at = {0, 0, 0});

class Motion {
public:
    Motion() = default;
    /// Keys at times k / (n - 1), k = 0 .. n - 1 (one key: still). Every key must be invertible.
    explicit Motion(std::vector<Transform> keys);

    /// The transform at time t in [0, 1] (clamped).
    Transform at(Float t) const;
    /// A box that holds `b` moved by every transform of the interval: exact (the keys' boxes) when
    /// only the translation changes between keys; otherwise the boxes at 64 steps per segment,
    /// widened by the most any corner moves in one step (a point's path within a step is shorter
    /// than that for the rotations and stretches of one key's segment).
    Bounds3 swept_bounds(const Bounds3& b) const;
    /// Whether the keys differ at all.
    bool moves() const { return keys_.size() > 1; }
    std::size_t key_count() const { return keys_.size(); }
    const Transform& key(std::size_t k) const { return keys_[k]; }
    /// Key k's decomposition M = T R S: translation, rotation (w, x, y, z) and stretch (row-major).
    Vector3 translation(std::size_t k) const { return parts_[k].t; }
    std::array<double, 4> rotation(std::size_t k) const { return parts_[k].q; }
    std::array<std::array<double, 3>, 3> stretch(std::size_t k) const { return parts_[k].s; }

private:
    struct Parts {
        Vector3 t;
        std::array<double, 4> q;  ///< w, x, y, z
        std::array<std::array<double, 3>, 3> s;
    };
    std::vector<Transform> keys_;
    std::vector<Parts> parts_;
    bool translation_only_ = true;  ///< keys differ by translation alone: blend T, keep the rest
};

}  // namespace glint
