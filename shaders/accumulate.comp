// The sum of a dispatch of samples with the tail queue (path_trace.comp,
// PassParams.tail_depth): each pixel's values, tail_values[s][pixel], added
// to its accumulation state in sample order, as the whole paths add them.
// A shader of its own so that it compiles in milliseconds.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/shared.h"

layout(local_size_x = WORKGROUP_SIZE * WORKGROUP_SIZE) in;

layout(std430, binding = BINDING_ACCUM_SUM) buffer AccumSumBuf { vec4 accum_sum[]; };
layout(std430, binding = BINDING_ACCUM_COMP) buffer AccumCompBuf { vec4 accum_comp[]; };
layout(std430, binding = BINDING_ACCUM_SQ) buffer AccumSqBuf { vec4 accum_sq[]; };
layout(std430, binding = BINDING_STATS) buffer StatsBuf { RenderStats stats; };
layout(std430, binding = BINDING_TAIL_VALUES) readonly buffer TailValueBuf { vec4 tail_values[]; };

layout(push_constant) uniform Push { PassParams pass; };

#include "shared/accumulate.glsl"

// One invocation per pixel (an 8 x 8 tile per workgroup).
void main() {
  const uvec2 pixel = gl_WorkGroupID.xy * WORKGROUP_SIZE +
                      uvec2(gl_LocalInvocationIndex % WORKGROUP_SIZE, gl_LocalInvocationIndex / WORKGROUP_SIZE);
  if (pixel.x >= pass.width || pixel.y >= pass.height) return;
  const uint index = pixel.y * pass.width + pixel.x;
  const uint pixels = pass.width * pass.height;
  vec4 acc = accum_sum[index], sq = accum_sq[index];
  vec3 comp = accum_comp[index].rgb;
  for (uint s = 0u; s < pass.sample_count; ++s) {
    vec4 v = tail_values[s * pixels + index];
    add_sample(v.rgb, floatBitsToUint(v.w), acc, comp, sq);
  }
  accum_comp[index].rgb = comp;
  accum_sum[index] = acc;
  accum_sq[index] = sq;
}
