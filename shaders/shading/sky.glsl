// The sky: what a ray that leaves the scene brings back. The includer
// declares `scene` (SceneParams), the specialization constant SKY and, for
// SKY_ENVMAP, the envmap buffers (shading/envmap.glsl).
#ifndef OCTRACE_SKY_GLSL
#define OCTRACE_SKY_GLSL

#include "shading/precision.glsl"
#include "shading/envmap.glsl"

real3 sky_radiance(vec3 dir) {
  uint sky = SKY == SKY_RUNTIME ? scene.sky_type : SKY;
  if (sky == SKY_GRADIENT) {
    real t = real(0.5 * (dir.y + 1.0));
    return (real(1.0) - t) * real3(scene.sky_a) + t * real3(scene.sky_b);
  }
  if (sky == SKY_UNIFORM) return real3(scene.sky_a);
  // fp32 up to here: the host refuses an fp16 render whose strength x
  // brightest texel exceeds half's range (render/gpu_scene.h check_precision).
  if (sky == SKY_ENVMAP) return real3(envmap_radiance(dir));
  return real3(0.0);
}

#endif
