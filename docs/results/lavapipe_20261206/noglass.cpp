// Writes the rtiow field of N spheres as JSON: as generated, and with every glass material made lambertian.
#include <cstdio>
#include <cstdlib>
#include "scene/scene.h"
using namespace octrace;
int main(int argc, char** argv) {
  Scene scene = make_rtiow_scene({std::strtoull(argv[1], nullptr, 10), float(std::atof(argv[2])), 1});
  save_scene_json(scene, argv[3]);
  size_t n = 0;
  for (Material& m : scene.materials)
    if (m.type == MaterialType::Dielectric) { m.type = MaterialType::Lambertian; m.albedo = glm::vec3(0.8f); ++n; }
  save_scene_json(scene, argv[4]);
  std::printf("%zu glass materials made lambertian of %zu\n", n, scene.materials.size());
}
