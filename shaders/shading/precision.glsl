// The precision variant, set by one macro, OCTRACE_PRECISION, when the
// pipeline's SPIR-V is compiled (shaders/CMakeLists.txt builds each level).
// It sets the types the shading code uses:
//   real, real3   colours: throughput, path radiance, albedo, emission, sky,
//                 Fresnel (Schlick), fuzz and ior;
//   dreal, dreal3 scattering directions: normal + unit vector, reflect,
//                 refract, the dielectric's angles.
// Level 0 fp32: everything fp32.
// Level 1 fp16: real is half; materials are read from 16-bit storage.
// Level 2 fp16-all: real and dreal are half.
// Never half, at any level: positions, distances t, the ray/sphere test
// (the ground's r^2 = 1e6 exceeds half's largest value, 65504: the study's
// fp16 ground vanished as inf - inf = NaN), sphere storage, octree bounds,
// the ray direction used for intersection (re-normalised in fp32) and the
// accumulation buffers. docs/precision.md has the table and the measurements.
#ifndef OCTRACE_PRECISION_GLSL
#define OCTRACE_PRECISION_GLSL

#if OCTRACE_PRECISION >= 1
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#extension GL_EXT_shader_16bit_storage : require
#define real float16_t
#define real3 f16vec3
#else
#define real float
#define real3 vec3
#endif

#if OCTRACE_PRECISION >= 2
#define dreal float16_t
#define dreal3 f16vec3
#else
#define dreal float
#define dreal3 vec3
#endif

#endif
