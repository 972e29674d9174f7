// Runs the environment map's GLSL functions (shading/envmap.glsl) on the
// device for tests/render/envmap_render_test.cpp, which holds them to the
// host mirror (scene/envmap.h): invocation i draws two uniform numbers from
// the shared RNG (shared/rng.h, seed 11, pixel i) and writes
//   out[3i]     = (dir, pdf) from envmap_sample,
//   out[3i + 1] = (envmap_pdf(dir), 1 if envmap_sample found a sample, envmap_uv(dir)),
//   out[3i + 2] = (envmap_radiance(dir), 0);
// invocation 0 also writes, for the poles (0, 1, 0) and (0, -1, 0),
//   out[3n + j] = (envmap_radiance(pole), envmap_pdf(pole)), n invocations.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer SceneBuf { SceneParams scene; };
layout(std430, binding = 1) readonly buffer EnvmapTexelBuf { float envmap_texels[]; };
layout(std430, binding = 2) readonly buffer EnvmapMarginalBuf { float envmap_marginal[]; };
layout(std430, binding = 3) readonly buffer EnvmapConditionalBuf { float envmap_conditional[]; };
layout(std430, binding = 4) writeonly buffer OutBuf { vec4 probe_out[]; };

#include "shared/rng.h"
#include "shading/envmap.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  Rng rng = rng_init(11u, i, 0u, 0u);
  float u0 = rng_next(rng);
  vec2 u = vec2(u0, rng_next(rng));
  vec3 dir;
  float pdf;
  bool ok = envmap_sample(u, dir, pdf);
  probe_out[3u * i] = vec4(dir, pdf);
  probe_out[3u * i + 1u] = vec4(envmap_pdf(dir), ok ? 1.0 : 0.0, envmap_uv(dir));
  probe_out[3u * i + 2u] = vec4(envmap_radiance(dir), 0.0);
  if (i == 0u) {
    uint n = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    probe_out[3u * n] = vec4(envmap_radiance(vec3(0.0, 1.0, 0.0)), envmap_pdf(vec3(0.0, 1.0, 0.0)));
    probe_out[3u * n + 1u] = vec4(envmap_radiance(vec3(0.0, -1.0, 0.0)), envmap_pdf(vec3(0.0, -1.0, 0.0)));
  }
}
