// Counter-based random numbers, written once for GLSL and C++ (the tests
// replay the shader's numbers on the host). Each (sample seed, pixel, sample,
// bounce) keys its own stream, so a path's numbers do not depend on how many
// numbers other bounces, other pixels or other code paths drew: a render is
// reproducible, and the octree and brute force (or any specialised pipeline)
// see the same numbers. Hash: pcg4d (Jarzynski & Olano 2020, "Hash Functions
// for GPU Rendering", JCGT 9(3)); within a bounce, a PCG-style permuted LCG
// steps on.
#ifndef OCTRACE_RNG_H
#define OCTRACE_RNG_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/vec4.hpp>
namespace octrace::gpu {
using uint = uint32_t;
using uvec4 = glm::uvec4;
#define OCT_RNG_CONST(type, name, value) inline constexpr type name = value
#define OCT_INOUT(type) type&
#define OCT_INLINE inline
#else
#define OCT_RNG_CONST(type, name, value) const type name = value
#define OCT_INOUT(type) inout type
#define OCT_INLINE
#endif

OCT_INLINE uvec4 pcg4d(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  return v;
}

// Camera rays use bounce key CAMERA_BOUNCE so that bounce 0's scattering has
// a stream of its own.
OCT_RNG_CONST(uint, CAMERA_BOUNCE, 0xffffffffu);

struct Rng {
  uint state;
};

OCT_INLINE Rng rng_init(uint seed, uint pixel, uint sample_index, uint bounce) {
  uvec4 h = pcg4d(uvec4(pixel, sample_index, bounce, seed));
  return Rng(h.x ^ h.z);
}

// A uniform float in [0, 1): the top 24 bits, exact in fp32.
OCT_INLINE float rng_next(OCT_INOUT(Rng) rng) {
  rng.state = rng.state * 747796405u + 2891336453u;
  uint word = ((rng.state >> ((rng.state >> 28u) + 4u)) ^ rng.state) * 277803737u;
  word = (word >> 22u) ^ word;
  return float(word >> 8u) * (1.0f / 16777216.0f);
}

#ifdef __cplusplus
}  // namespace octrace::gpu
#endif
#undef OCT_RNG_CONST
#undef OCT_INOUT
#undef OCT_INLINE

#endif  // OCTRACE_RNG_H
