// Resolve for the preview window: the mean of the accumulation (see the
// layout in shared.h) as 8-bit sRGB, packed one uint per pixel in the byte
// order of the swapchain image it is copied into. Bytes match what
// write_image puts in a PNG (renderer/io/image.cpp), up to float rounding: NaN
// and negatives to 0, clamp to 1, sRGB-encode, round to nearest.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/shared.h"

layout(local_size_x = WORKGROUP_SIZE, local_size_y = WORKGROUP_SIZE) in;

layout(constant_id = RESOLVE_SPEC_SWAP_RB) const bool SWAP_RB = false;  // B8G8R8A8 swapchains

layout(std430, binding = RESOLVE_BINDING_ACCUM_SUM) readonly buffer AccumSumBuf { vec4 accum_sum[]; };
layout(std430, binding = RESOLVE_BINDING_ACCUM_COMP) readonly buffer AccumCompBuf { vec4 accum_comp[]; };
layout(std430, binding = RESOLVE_BINDING_PIXELS) writeonly buffer PixelBuf { uint pixels[]; };

layout(push_constant) uniform Push { ResolveParams size; };

// IEC 61966-2-1 transfer function, as srgb_encode in renderer/io/image.cpp.
float srgb_encode(float v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

uint to_byte(float linear) {
  float v = linear > 0.0 ? min(linear, 1.0) : 0.0;
  return uint(srgb_encode(v) * 255.0 + 0.5);
}

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= size.width || p.y >= size.height) return;
  uint i = p.y * size.width + p.x;
  vec4 sum = accum_sum[i];
  // The Kahan sum is sum - comp (comp holds what the float sum overshot).
  vec3 mean = sum.w > 0.0 ? (sum.rgb - accum_comp[i].rgb) / sum.w : vec3(0.0);
  uvec3 c = uvec3(to_byte(mean.r), to_byte(mean.g), to_byte(mean.b));
  if (SWAP_RB) c = c.bgr;
  pixels[i] = c.r | (c.g << 8) | (c.b << 16) | (255u << 24);
}
