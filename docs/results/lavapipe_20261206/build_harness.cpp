// Times the top level's octree build over the 1M field's visible boxes, with and without the surfaces.
#include <chrono>
#include <cstdio>
#include "scene/scene.h"
#include "render/gpu_scene.h"
#include "accel/octree.h"
#include "accel/clip.h"
using namespace octrace;
int main(int argc, char** argv) {
  Scene scene = make_rtiow_scene({1000000, 0.1f, 1});
  auto boxes = primitive_boxes(scene, HiddenParts::Cull, nullptr);
  const size_t n = scene.spheres.size();
  const ClipFn surfaces = [&](uint32_t prim, const Aabb& cell, Aabb& part) {
    const Aabb& b = boxes[prim];
    const Aabb within{glm::max(cell.lo, b.lo), glm::min(cell.hi, b.hi)};
    if (prim >= n) { part = within; return true; }
    if (!(within.lo.x <= within.hi.x && within.lo.y <= within.hi.y && within.lo.z <= within.hi.z)) return false;
    return clip_sphere_surface(scene.spheres[prim].center, scene.spheres[prim].radius, within, part);
  };
  OctreeParams p; p.leaf_size = 10;
  for (int rep = 0; rep < 3; ++rep) {
    for (int mode = 0; mode < 3; ++mode) {
      auto t0 = std::chrono::steady_clock::now();
      Octree t = mode == 0 ? build_octree(boxes, p) : build_octree(boxes, p, surfaces, {}, mode == 2);
      double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      std::printf("mode %d: %.1f ms, %zu nodes, %zu refs\n", mode, ms, t.nodes.size(), t.refs.size());
    }
  }
}
