#pragma once
// The article's camera ("The Math of Ray Tracing", section 2), exactly:
//   P position, V unit view direction, w x h viewport at distance z along V.
//   H = normalize(up x V)  (the image's right)
//   U = V x H              (the image's up)
// CORRECTION: the article writes U = H x V, which points *down* (for V=(0,0,1): H=(1,0,0) and
// H x V = (0,-1,0)); its own worked example says U=(0,1,0), which is V x H. glint uses V x H.
// When V is parallel to `up` the cross product vanishes; glint then uses +z (or +x if V is along
// z) as the reference axis instead of dividing by zero.
//
//   B = -(w/2) H - (h/2) U              (bottom-left corner, relative to P + zV)
//   A = B + (w x/Sw) H + (h y/Sh) U + z V,   D = A/|A|
// with (x, y) measured from the bottom-left corner, y growing upward. Film positions in glint
// are (col, row) with row 0 at the top and pixel centres at +0.5, so x = col, y = Sh - row.
//
// The look_at + vertical-field-of-view form builds the same camera: V = normalize(to - from),
// z = 1, h = 2 tan(fov/2), w = h * Sw/Sh (square pixels).
//
// Thin lens (depth of field), on either form: with an aperture radius a > 0, the ray for a film
// point starts at a point of the lens disk P + a (lx H + ly U) and passes through the point where
// the pinhole ray meets the focus plane (the plane perpendicular to V at the focus distance), so
// everything on that plane is sharp. With a = 0 the ray is exactly the pinhole ray.
//
// Orthographic (pbrt's `orthographic`): the film point A gives the ray's origin instead of its
// direction: origin = P + A - zV, direction V; the viewport's size is then the visible extent in
// world units. A window (pbrt's `screenwindow`) shows part of the viewport: [x0, x1] x [y0, y1]
// in units of half the viewport's height, (0, 0) at its centre, y up.
#include <memory>

#include "glint/math/bounds.h"
#include "glint/math/motion.h"
#include "glint/ray.h"
#include "glint/samplers/warp.h"

namespace glint {

struct CameraBasis {
    Vector3 h;  ///< right
    Vector3 u;  ///< up
};

/// H and U for a unit view direction v and a world up vector, with the fallback above.
CameraBasis camera_basis(Vector3 v, Vector3 up);

/// What one pixel covers around a point, for texture filtering (pbrt-v4's approximation, used at
/// every hit, not only the camera's own): the ray from the camera through p and the rays through
/// the neighbouring pixels (one right, one up) meet p's tangent plane at p, p + dpdx and p + dpdy;
/// both are then scaled by `scale` (max(1/8, 1/sqrt(spp)): the pixel's samples already spread over
/// it). A thin lens is taken as its pinhole.
struct PixelFootprint {
    Point3 position;
    Vector3 view{0, 0, 1};
    Vector3 h_step, u_step;  ///< one pixel right and up, on the plane at `near` along view
    Float near = 1;
    bool orthographic = false;
    Float scale = 1;
    /// False (and nothing written) where p is behind the camera or the plane is edge-on.
    bool at(Point3 p, Normal3 n, Vector3& dpdx, Vector3& dpdy) const {
        const Vector3 to_p = p - position;
        const Float depth = dot(to_p, view);
        if (!orthographic && !(depth > 0)) return false;
        const Vector3 d = orthographic ? view : to_p * (near / depth);
        const auto along = [&](Vector3 step, Vector3& out) {
            // Perspective: the ray from the camera along d + step; orthographic: along d from p + step.
            const Vector3 dir = orthographic ? d : d + step;
            const Vector3 from_p = orthographic ? step : -to_p;  // the ray's origin, relative to p
            if (!meet_plane(from_p, dir, n, out)) return false;
            out = out * scale;
            return is_finite(out);
        };
        Vector3 x, y;
        if (!along(h_step, x) || !along(u_step, y)) return false;
        dpdx = x;
        dpdy = y;
        return true;
    }
    /// The offset rays that met a surface at p + dpdx and p + dpdy (from at()): from the camera
    /// through those points, or parallel to the view for an orthographic camera.
    RayDifferential differential(Point3 p, Vector3 dpdx, Vector3 dpdy) const {
        const Point3 px = p + dpdx, py = p + dpdy;
        return {px, py, orthographic ? view : px - position, orthographic ? view : py - position};
    }
};

class Camera {
public:
    Camera() = default;
    /// The article's parameters. `direction` and `up` need not be unit length (they are
    /// normalized here) but must be non-zero; the film size sets the pixel mapping.
    Camera(Point3 position, Vector3 direction, Vector3 up, Float viewport_width,
           Float viewport_height, Float near_distance, int film_width, int film_height);

    static Camera look_at(Point3 from, Point3 to, Vector3 up, Float vertical_fov_degrees,
                          int film_width, int film_height);
    /// An orthographic camera at `from` looking along `direction`, showing `height` world units
    /// vertically (the width follows the film's aspect ratio).
    static Camera orthographic(Point3 from, Vector3 direction, Vector3 up, Float height, int film_width,
                               int film_height);

    /// Turns the camera into a thin lens of `aperture_radius` focused at `focus_distance` along
    /// V (both > 0 to have an effect; aperture 0 keeps the pinhole).
    void set_lens(Float aperture_radius, Float focus_distance) {
        aperture_radius_ = aperture_radius;
        focus_distance_ = focus_distance;
    }
    Float aperture_radius() const { return aperture_radius_; }
    /// Rays parallel to V from the film points (see above).
    void make_orthographic() { orthographic_ = true; }
    bool orthographic() const { return orthographic_; }
    /// Shows only [x0, x1] x [y0, y1] of the viewport (see above); before make_right_handed.
    void set_window(Float x0, Float x1, Float y0, Float y1, int film_width);
    /// For right-handed scene data (the Cornell box's): H becomes -H, so the image is the
    /// mirror image of the left-handed one and right-handed data appears as in its own renders.
    void make_right_handed(int film_width) {
        corner_ = corner_ + h_step_ * static_cast<Float>(film_width);
        h_step_ = -h_step_;
        basis_.h = -basis_.h;
    }

    /// The camera ray through continuous film position (fx, fy): fx in [0, Sw) to the right,
    /// fy in [0, Sh) downward from the top edge. The pixel centre of (col, row) is
    /// (col + 0.5, row + 0.5).
    Ray generate_ray(Float fx, Float fy) const {
        const Float x = fx;
        const Float y = film_height_ - fy;
        const Vector3 a = corner_ + h_step_ * x + u_step_ * y;
        if (orthographic_) return Ray{position_ + (a - v_ * near_), v_};
        return Ray{position_, normalize(a)};
    }

    /// The same through a thin lens: `lens` in [0,1)^2 picks the point on the aperture
    /// (concentric disk map). Identical to generate_ray(fx, fy) when the aperture is 0.
    Ray generate_ray(Float fx, Float fy, Sample2 lens) const {
        const Ray pinhole = generate_ray(fx, fy);
        if (aperture_radius_ <= 0) return pinhole;
        const Point3 focus =
            pinhole.at(focus_distance_ / dot(pinhole.direction, v_));  // on the focus plane
        const Point2 d = sample_uniform_disk_concentric(lens);
        const Point3 origin =
            pinhole.origin + (basis_.h * d.x + basis_.u * d.y) * aperture_radius_;
        return Ray{origin, normalize(focus - origin)};
    }

    /// Moves the camera over the shutter: `frames` are its camera-to-world frames (math/motion.h),
    /// the first where this camera is; a ray is generated as at the opening, then carried by
    /// frames.at(time) after the inverse of the first frame.
    void set_motion(Motion frames) {
        if (!frames.moves()) {
            motion_ = nullptr;
            return;
        }
        opening_ = frames.key(0).to_object;
        motion_ = std::make_shared<const Motion>(std::move(frames));
    }
    bool moves() const { return motion_ != nullptr; }
    const Motion* motion() const { return motion_.get(); }
    /// `ray` (generated as at the opening) at time t in [0, 1] of the shutter: its time set, and
    /// carried by the camera's motion if it moves.
    Ray at_time(Ray ray, Float t) const {
        ray.time = t;
        if (!motion_) return ray;
        const Matrix34 d = motion_->at(t).to_world * opening_;
        ray.origin = d.apply(ray.origin);
        ray.direction = normalize(d.apply(ray.direction));
        return ray;
    }

    const CameraBasis& basis() const { return basis_; }
    /// Camera to world: right, up and view direction as the columns, the position last
    /// (nullopt for a degenerate basis).
    std::optional<Transform> frame() const {
        Matrix34 m;
        for (int i = 0; i < 3; ++i) {
            m.m[i][0] = basis_.h[i];
            m.m[i][1] = basis_.u[i];
            m.m[i][2] = v_[i];
            m.m[i][3] = position_[i];
        }
        return Transform::from(m);
    }
    Vector3 view_direction() const { return v_; }
    /// The pixel footprint model of this camera, scaled by `scale`.
    PixelFootprint footprint(Float scale) const {
        return {position_, v_, h_step_, u_step_, near_, orthographic_, scale};
    }

private:
    Point3 position_;
    Vector3 v_{0, 0, 1};
    CameraBasis basis_{{1, 0, 0}, {0, 1, 0}};
    Vector3 corner_;  ///< B + zV
    Vector3 h_step_;  ///< (w/Sw) H
    Vector3 u_step_;  ///< (h/Sh) U
    Float film_height_ = 1;
    Float near_ = 1;
    bool orthographic_ = false;
    Float aperture_radius_ = 0;
    Float focus_distance_ = 1;
    std::shared_ptr<const Motion> motion_;  ///< null: still
    Matrix34 opening_;                      ///< world to the first frame
};

/// A perspective camera that shows every corner of box `b` with a margin: it looks at the box's
/// centre from direction `towards_camera` (from the centre to the camera), with vertical field of
/// view `vfov_degrees`, and stands just far enough away that each corner's image lies within
/// `margin` (in (0, 1]) of the frame's half-width and half-height. Exact for any size, position
/// and aspect ratio (the distance is solved corner by corner, not from a bounding sphere).
Camera frame_box(const Bounds3& b, Vector3 towards_camera, Vector3 up, Float vfov_degrees, int film_width,
                 int film_height, Float margin = Float(0.9));

}  // namespace glint
