// The camera per pass: the scene's Camera (look-from, look-at, field of view,
// lens) turned into the vectors a pass needs, and the moves the preview
// window makes. A camera change touches nothing on the device but the pass's
// push constants.
#pragma once

#include <glm/vec3.hpp>

#include "scene/scene.h"
#include "shared/shared.h"

namespace octrace {

// The camera of "Ray Tracing in One Weekend" v4, in double: a viewport on the
// focus plane, `vfov` tall, seen from a thin lens of diameter `aperture` at
// lookfrom. Image point (x, y) in pixels (top row first) is pixel00 + x *
// pixel_du + y * pixel_dv; lens point (a, b) in the unit disc is origin +
// lens_radius * (a * lens_u + b * lens_v).
struct CameraFrame {
  glm::dvec3 origin, pixel00, pixel_du, pixel_dv, lens_u, lens_v;
  double lens_radius = 0;

  // The direction through image point (x, y) from the lens centre.
  glm::dvec3 dir(double x, double y) const;
};
CameraFrame camera_frame(const Camera& camera, int width, int height);

// Writes the camera fields of a pass (rounded to float, as the shader reads them).
void set_pass_camera(gpu::PassParams& pass, const Camera& camera, int width, int height);

// Moves for the preview window. orbit: yaw about vup and pitch about the
// camera's right axis, around lookat, stopping short of the poles. pan: moves
// lookfrom and lookat together in the view plane by (dx, dy) pixels of an
// image `height` tall, so the look-at point follows the cursor. zoom: scales
// the distance to lookat (and the focus distance, so what was in focus stays
// so) by 0.9^steps.
void orbit(Camera& c, float yaw, float pitch);
void pan(Camera& c, float dx, float dy, int height);
void zoom(Camera& c, float steps);

}  // namespace octrace
