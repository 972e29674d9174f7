#include <cstdio>
#include <cstring>
#include <cmath>
#include <vector>
#include "scene/scene.h"
#include "render/gpu_scene.h"
#include "accel/hidden_parts.h"
using namespace octrace;
static float fb(unsigned u){ float f; std::memcpy(&f,&u,4); return f; }
int main(int argc, char** argv) {
  Scene scene = make_rtiow_scene({1000000, 0.1f, 1});
  auto occ = sphere_occluders(scene);
  auto boxes = primitive_boxes(scene, HiddenParts::Cull, nullptr);
  unsigned ob[3], db[3];
  for (int k = 0; k < 3; ++k) { ob[k] = strtoul(argv[1 + k], 0, 16); db[k] = strtoul(argv[4 + k], 0, 16); }
  glm::dvec3 o(fb(ob[0]), fb(ob[1]), fb(ob[2])), d(fb(db[0]), fb(db[1]), fb(db[2]));
  printf("origin %.9g %.9g %.9g dir %.9g %.9g %.9g\n", o.x, o.y, o.z, d.x, d.y, d.z);
  double tmax = atof(argv[7]);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    glm::dvec3 c(s.center); double r = s.radius;
    glm::dvec3 f = o - c; double b = -glm::dot(f, d); glm::dvec3 l = f + b * d;
    double disc = r * r - glm::dot(l, l);
    double cpow = glm::dot(f, f) - r * r;
    if (cpow < 0) printf("  ORIGIN INSIDE sphere %zu (power %.3g, occludes %d, material %u)\n", i, cpow, occ[i], s.material);
    if (disc < 0) continue;
    double t0 = b - std::sqrt(disc), t1 = b + std::sqrt(disc);
    if (t1 < -1e-3 || t0 > tmax) continue;
    printf("sphere %zu c %.7g %.7g %.7g r %.7g occ %d mat %u roots %.9g %.9g\n", i, c.x, c.y, c.z, r, occ[i], s.material, t0, t1);
    const Aabb& bx = boxes[i];
    printf("   box lo %.7g %.7g %.7g hi %.7g %.7g %.7g\n", bx.lo.x, bx.lo.y, bx.lo.z, bx.hi.x, bx.hi.y, bx.hi.z);
    for (double t : {t0, t1}) {
      if (t < -1e-3 || t > tmax) continue;
      glm::dvec3 p = o + t * d;
      bool in = p.x >= bx.lo.x && p.x <= bx.hi.x && p.y >= bx.lo.y && p.y <= bx.hi.y && p.z >= bx.lo.z && p.z <= bx.hi.z;
      printf("   t %.9g p %.9g %.9g %.9g in_box %d; inside:", t, p.x, p.y, p.z, in);
      for (size_t j = 0; j < scene.spheres.size(); ++j) {
        if (j == i) continue;
        glm::dvec3 q = p - glm::dvec3(scene.spheres[j].center);
        double pw = glm::dot(q, q) - double(scene.spheres[j].radius) * scene.spheres[j].radius;
        if (pw < 0) printf(" %zu(occ %d, depth %.3g)", j, occ[j], -pw / (2 * scene.spheres[j].radius));
      }
      printf("\n");
    }
  }
}
