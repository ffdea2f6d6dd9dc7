#include "glint/cameras/camera.h"

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

}  // namespace glint
