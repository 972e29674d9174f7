#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

namespace octrace {

namespace {

// Rotates v about the unit axis k by angle a (Rodrigues' formula).
glm::vec3 rotate(glm::vec3 v, glm::vec3 k, float a) {
  return v * std::cos(a) + glm::cross(k, v) * std::sin(a) + k * glm::dot(k, v) * (1.0f - std::cos(a));
}

}  // namespace

glm::dvec3 CameraFrame::dir(double x, double y) const {
  return glm::normalize(pixel00 + x * pixel_du + y * pixel_dv - origin);
}

CameraFrame camera_frame(const Camera& c, int width, int height) {
  glm::dvec3 from(c.lookfrom), at(c.lookat), vup(c.vup);
  double h = std::tan(glm::radians(double(c.vfov)) / 2.0);
  double viewport_h = 2.0 * h * c.focus_dist;
  double viewport_w = viewport_h * double(width) / double(height);
  glm::dvec3 w = glm::normalize(from - at);
  glm::dvec3 u = glm::normalize(glm::cross(vup, w));
  glm::dvec3 v = glm::cross(w, u);
  glm::dvec3 horizontal = viewport_w * u;
  glm::dvec3 vertical = -viewport_h * v;  // rows go down the image
  CameraFrame f;
  f.origin = from;
  f.pixel00 = from - double(c.focus_dist) * w - horizontal / 2.0 - vertical / 2.0;
  f.pixel_du = horizontal / double(width);
  f.pixel_dv = vertical / double(height);
  f.lens_u = u;
  f.lens_v = v;
  f.lens_radius = c.aperture / 2.0f;
  return f;
}

void set_pass_camera(gpu::PassParams& pass, const Camera& camera, int width, int height) {
  const CameraFrame f = camera_frame(camera, width, height);
  pass.cam_origin = glm::vec3(f.origin);
  pass.lens_radius = float(f.lens_radius);
  pass.lens_u = glm::vec3(f.lens_u);
  pass.lens_v = glm::vec3(f.lens_v);
  pass.pixel00 = glm::vec3(f.pixel00);
  pass.pixel_du = glm::vec3(f.pixel_du);
  pass.pixel_dv = glm::vec3(f.pixel_dv);
}

void orbit(Camera& c, float yaw, float pitch) {
  glm::vec3 up = glm::normalize(c.vup);
  glm::vec3 offset = rotate(c.lookfrom - c.lookat, up, yaw);
  glm::vec3 right = glm::normalize(glm::cross(up, offset));
  float angle = std::acos(std::clamp(glm::dot(glm::normalize(offset), up), -1.0f, 1.0f));
  const float margin = 0.01f;
  pitch = std::clamp(pitch, margin - angle, glm::pi<float>() - margin - angle);
  c.lookfrom = c.lookat + rotate(offset, right, pitch);
}

void pan(Camera& c, float dx, float dy, int height) {
  glm::vec3 w = c.lookfrom - c.lookat;
  float per_pixel = 2.0f * std::tan(glm::radians(c.vfov) / 2.0f) * glm::length(w) / float(height);
  glm::vec3 u = glm::normalize(glm::cross(c.vup, w));
  glm::vec3 v = glm::normalize(glm::cross(w, u));
  glm::vec3 delta = (-dx * u + dy * v) * per_pixel;
  c.lookfrom += delta;
  c.lookat += delta;
}

void zoom(Camera& c, float steps) {
  float f = std::pow(0.9f, steps);
  c.lookfrom = c.lookat + (c.lookfrom - c.lookat) * f;
  c.focus_dist *= f;
}

}  // namespace octrace
