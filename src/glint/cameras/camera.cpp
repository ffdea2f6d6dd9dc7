#include "glint/cameras/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {

CameraBasis camera_basis(Vector3 v, Vector3 up) {
    Vector3 right = cross(up, v);
    if (dot(right, right) < Float(1e-12) * dot(up, up) * dot(v, v)) {
        // V is (anti)parallel to up: use another reference axis.
        const Vector3 reference = std::abs(v.z) < Float(0.9) ? Vector3{0, 0, 1} : Vector3{1, 0, 0};
        right = cross(reference, v);
    }
    const Vector3 h = normalize(right);
    return {h, cross(v, h)};
}

Camera::Camera(Point3 position, Vector3 direction, Vector3 up, Float viewport_width,
               Float viewport_height, Float near_distance, int film_width, int film_height)
    : position_(position),
      v_(normalize(direction)),
      basis_(camera_basis(v_, up)),
      film_height_(static_cast<Float>(film_height)),
      near_(near_distance) {
    const Vector3 b = basis_.h * (-viewport_width / 2) - basis_.u * (viewport_height / 2);
    corner_ = b + v_ * near_distance;
    h_step_ = basis_.h * (viewport_width / static_cast<Float>(film_width));
    u_step_ = basis_.u * (viewport_height / static_cast<Float>(film_height));
}

void Camera::set_window(Float x0, Float x1, Float y0, Float y1, int film_width) {
    const Float sw = static_cast<Float>(film_width);
    const Float half = length(u_step_) * film_height_ / 2;
    const Vector3 centre = v_ * near_;
    corner_ = centre + basis_.h * (x0 * half) + basis_.u * (y0 * half);
    h_step_ = basis_.h * ((x1 - x0) * half / sw);
    u_step_ = basis_.u * ((y1 - y0) * half / film_height_);
}

Camera Camera::look_at(Point3 from, Point3 to, Vector3 up, Float vertical_fov_degrees,
                       int film_width, int film_height) {
    const Float h = 2 * std::tan(vertical_fov_degrees * std::numbers::pi_v<Float> / 360);
    const Float w = h * static_cast<Float>(film_width) / static_cast<Float>(film_height);
    return Camera(from, to - from, up, w, h, 1, film_width, film_height);
}

Camera Camera::orthographic(Point3 from, Vector3 direction, Vector3 up, Float height, int film_width,
                            int film_height) {
    const Float aspect = static_cast<Float>(film_width) / static_cast<Float>(film_height);
    Camera c(from, direction, up, height * aspect, height, 1, film_width, film_height);
    c.make_orthographic();
    return c;
}

Camera frame_box(const Bounds3& b, Vector3 towards_camera, Vector3 up, Float vfov_degrees, int film_width,
                 int film_height, Float margin) {
    const Vector3 v = -normalize(towards_camera);  // the view direction
    const CameraBasis basis = camera_basis(v, up);
    // Work in double: boxes far from the origin or very small must still frame exactly.
    const double cx = 0.5 * (double(b.lo.x) + double(b.hi.x)), cy = 0.5 * (double(b.lo.y) + double(b.hi.y)),
                 cz = 0.5 * (double(b.lo.z) + double(b.hi.z));
    const double tan_v = std::tan(double(vfov_degrees) * std::numbers::pi / 360) * double(margin);
    const double tan_h = tan_v * double(film_width) / double(film_height);
    // A corner at (x, y, z) in (H, U, V) relative to the centre is inside the frame when the
    // camera, at distance D behind the centre, has |x| <= tan_h (D + z) and |y| <= tan_v (D + z).
    double distance = 0, extent = 0, behind = 0;
    for (int i = 0; i < 8; ++i) {
        const double px = ((i & 1) ? b.hi.x : b.lo.x) - cx, py = ((i & 2) ? b.hi.y : b.lo.y) - cy,
                     pz = ((i & 4) ? b.hi.z : b.lo.z) - cz;
        const auto dot3 = [&](Vector3 a) { return px * a.x + py * a.y + pz * a.z; };
        const double x = dot3(basis.h), y = dot3(basis.u), z = dot3(v);
        distance = std::max({distance, std::abs(x) / tan_h - z, std::abs(y) / tan_v - z});
        extent = std::max(extent, std::sqrt(px * px + py * py + pz * pz));
        behind = std::max(behind, -z);
    }
    distance = std::max(distance, behind + 0.01 * extent);  // every corner strictly in front
    if (!(extent > 0)) distance = 1;  // a point: any distance shows it
    const Vector3 offset = -v * Float(distance);
    const Point3 from{Float(cx + double(offset.x)), Float(cy + double(offset.y)), Float(cz + double(offset.z))};
    const Point3 to{Float(cx), Float(cy), Float(cz)};
    if (from == to) return Camera::look_at(to - v, to, up, vfov_degrees, film_width, film_height);
    return Camera::look_at(from, to, up, vfov_degrees, film_width, film_height);
}

}  // namespace glint
