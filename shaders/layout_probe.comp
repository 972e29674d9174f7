// Writes a distinct value into every field of every shared struct, as the
// GLSL compiler lays them out. The layout test reads the buffers back through
// the C++ structs: any disagreement in offsets shows as a wrong value.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = 0) buffer B0 { FrameParams frame; };
layout(std430, binding = 1) buffer B1 { GpuSphere spheres[2]; };
layout(std430, binding = 2) buffer B2 { GpuMaterial materials[2]; };
layout(std430, binding = 3) buffer B3 { RenderStats stats[2]; };

void main() {
  frame.cam_origin = vec3(1, 2, 3);
  frame.lens_radius = 4;
  frame.lens_u = vec3(5, 6, 7);
  frame.width = 8;
  frame.lens_v = vec3(9, 10, 11);
  frame.height = 12;
  frame.pixel00 = vec3(13, 14, 15);
  frame.max_depth = 16;
  frame.pixel_du = vec3(17, 18, 19);
  frame.sample_seed = 20;
  frame.pixel_dv = vec3(21, 22, 23);
  frame.sphere_count = 24;
  frame.sky_a = vec3(25, 26, 27);
  frame.sky_type = 28;
  frame.sky_b = vec3(29, 30, 31);
  frame.big_count = 32;
  for (int i = 0; i < 2; ++i) {
    float o = 100.0 * float(i + 1);
    spheres[i].center = vec3(o + 1, o + 2, o + 3);
    spheres[i].radius = o + 4;
    materials[i].color = vec3(o + 5, o + 6, o + 7);
    materials[i].type = uint(o) + 8;
    materials[i].fuzz = o + 9;
    materials[i].ior = o + 10;
    materials[i].pad0 = uint(o) + 11;
    materials[i].pad1 = uint(o) + 12;
    stats[i].nonfinite_samples = uint(o) + 13;
    stats[i].pad0 = uint(o) + 14;
    stats[i].pad1 = uint(o) + 15;
    stats[i].pad2 = uint(o) + 16;
  }
}
