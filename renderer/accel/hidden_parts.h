// The parts of spheres that no ray can hit first: those inside another
// opaque sphere. A build that is given the boxes of the other parts
// (visible_sphere_boxes) references a sphere only where a ray can meet it
// first, so that a dense field of overlapping spheres, where a point of the
// surface lies in the boxes of a hundred spheres, tests a handful.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "accel/aabb.h"

namespace octrace {

struct Ball {
  glm::vec3 center{0.0f};
  float radius = 1.0f;
};

struct HiddenPartsStats {
  uint64_t clipped = 0;  // spheres whose box shrank
  uint64_t hidden = 0;   // spheres with no part left (their box is the point at their centre)
  double ms = 0;         // wall time of visible_sphere_boxes
};

// For each ball i, a box that holds every point of its surface that lies
// inside no occluder j != i (occludes[j] != 0) by more than a margin (about
// 1e-4 of the occluder's radius plus 32 float ulps of its coordinates), and
// that lies within the ball's own box. Why that is enough: a ray that
// starts outside every occluder (the camera, a point of the boundary of
// their union) and enters one crosses the boundary of the union first, at
// a point of some sphere's surface that no occluder holds; so the nearest
// hit of every such ray lies on such a point, and a tree that references
// each sphere where those points are finds it (a hit elsewhere on a
// referenced sphere is still a hit of that sphere). That is exact
// arithmetic: a ray that starts a few ulps inside a neighbour at a seam can
// differ (optimisation log 125 traced it: a path that refracts into glass
// where it meets an occluder starts inside the occluder by the origin's
// offset). Occluders are the spheres rays never
// enter: opaque materials; a sphere that holds the camera's lens must not
// be one (the caller's rule, render/gpu_scene.cpp).
//
// How: a point p of sphere i's surface lies inside occluder j exactly when
// it is on j's side of their radical plane (|p - c_j|^2 - r_j^2 <
// |p - c_i|^2 - r_i^2, which is linear in p), so the visible part lies in
// the ball's box clipped by one half-space per overlapping occluder. The
// box is clipped one half-space at a time (the box of box and half-space,
// in double, rounded outward to float), over the occluders among the
// ball's nearest (a grid of about two occluders' centres a cell, the 27
// cells around the ball's centre; occluders 16 times the median radius or
// more are tested against every ball, at most kMaxLargeOccluders of them,
// the largest). Taking fewer
// occluders only leaves a box larger: never wrong. On a dense field of
// equal spheres on a grid the boxes become columns as wide as the grid's
// spacing (the spheres' power cells). A ball with nothing left gets the
// point box at its centre. Uses the host's threads; the result depends only
// on the input.
std::vector<Aabb> visible_sphere_boxes(std::span<const Ball> balls, std::span<const uint8_t> occludes,
                                       HiddenPartsStats* stats = nullptr);

inline constexpr uint32_t kMaxLargeOccluders = 64;

}  // namespace octrace
