// The sky: what a ray that leaves the scene brings back. The includer
// declares `scene` (SceneParams) and the specialization constant SKY.
#ifndef OCTRACE_SKY_GLSL
#define OCTRACE_SKY_GLSL

#include "shading/precision.glsl"

real3 sky_radiance(vec3 dir) {
  uint sky = SKY == SKY_RUNTIME ? scene.sky_type : SKY;
  if (sky == SKY_GRADIENT) {
    real t = real(0.5 * (dir.y + 1.0));
    return (real(1.0) - t) * real3(scene.sky_a) + t * real3(scene.sky_b);
  }
  if (sky == SKY_UNIFORM) return real3(scene.sky_a);
  return real3(0.0);
}

#endif
