// Camera rays from the pass's camera (PassParams, push constants `pass`):
// a jittered point of the pixel on the focus plane, seen from a point of the
// lens disc. The includer declares HAS_DEFOCUS.
#ifndef OCTRACE_CAMERA_GLSL
#define OCTRACE_CAMERA_GLSL

#include "geometry/ray.glsl"
#include "sampling/warp.glsl"

Ray camera_ray(uvec2 pixel, uint pixel_index, uint sample_index) {
  Rng rng = rng_init(pass.sample_seed, pixel_index, sample_index, CAMERA_BOUNCE);
  vec2 jitter = vec2(rng_next(rng), rng_next(rng));
  vec2 lens = HAS_DEFOCUS ? random_in_unit_disk(rng) * pass.lens_radius : vec2(0.0);
  vec3 origin = pass.cam_origin + lens.x * pass.lens_u + lens.y * pass.lens_v;
  vec3 target = pass.pixel00 + (float(pixel.x) + jitter.x) * pass.pixel_du +
                (float(pixel.y) + jitter.y) * pass.pixel_dv;
  return Ray(origin, normalize(target - origin));
}

#endif
