// The materials of "Ray Tracing in One Weekend" v4, as the shading code reads
// them in the variant's precision. The includer declares `materials`.
#ifndef OCTRACE_MATERIALS_GLSL
#define OCTRACE_MATERIALS_GLSL

#include "shading/precision.glsl"

struct Material {
  real3 color;  // albedo or radiance
  uint type;    // MAT_*
  real fuzz;
  real ior;
};

Material load_material(uint i) {
#if OCTRACE_PRECISION >= 1
  GpuMaterialHalf m = materials[i];
  return Material(m.color_type.rgb, uint(m.color_type.a), m.params.x, m.params.y);
#else
  GpuMaterial m = materials[i];
  return Material(m.color, m.type, m.fuzz, m.ior);
#endif
}

// Schlick's approximation of the Fresnel reflectance.
dreal schlick(dreal cosine, dreal eta) {
  dreal r0 = (dreal(1.0) - eta) / (dreal(1.0) + eta);
  r0 = r0 * r0;
  dreal x = dreal(1.0) - cosine;
  return r0 + (dreal(1.0) - r0) * (x * x) * (x * x) * x;
}

#endif
