// The materials of "Ray Tracing in One Weekend" v4 and glTF's
// metallic-roughness material (shading/pbr.glsl), as the shading code reads
// them in the variant's precision, and the textures and emission of glTF's
// materials (lambertian and pbr). The includer declares `materials`,
// `textures` and `texels`, and the specialization constants HAS_TEXTURES and
// HAS_SURFACE_EMISSION.
#ifndef OCTRACE_MATERIALS_GLSL
#define OCTRACE_MATERIALS_GLSL

#include "shading/precision.glsl"
#include "shading/texture.glsl"

struct Material {
  uint index;   // in the material array (its texture transforms are read by it)
  real3 color;  // albedo, base colour or radiance
  uint type;    // MAT_*
  real fuzz;
  real ior;
  uint base_color_texture;  // NO_TEXTURE: none
  uint emission_texture;
  real3 emission;           // lambertian, pbr: emitted besides reflecting
  uint metallic_roughness_texture;
  real metallic;
  real roughness;
  uint normal_texture;
  float normal_scale;
};

Material load_material(uint i) {
#if OCTRACE_PRECISION >= 1
  GpuMaterialHalf m = material_at(i);
  return Material(i, m.color_type.rgb, uint(m.color_type.a), m.params.x, m.params.y, m.base_color_texture,
                  m.emission_texture, m.emission.rgb, m.metallic_roughness_texture, m.params.z, m.params.w,
                  m.normal_texture, m.normal_scale);
#else
  GpuMaterial m = material_at(i);
  return Material(i, m.color, m.type, m.fuzz, m.ior, m.base_color_texture, m.emission_texture, m.emission,
                  m.metallic_roughness_texture, m.metallic, m.roughness, m.normal_texture, m.normal_scale);
#endif
}

// Texture `index` of material m's slot TEXTURE_SLOT_* at the surface's uv,
// through the slot's uv transform (KHR_texture_transform; shared.h).
vec3 sample_material_texture(Material m, uint slot, uint index, vec2 uv, bool srgb) {
  GpuUvTransform t = texture_transforms[m.index * TEXTURE_SLOTS + slot];
  return sample_texture(index, t.x_axis * uv.x + t.y_axis * uv.y + t.offset, srgb);
}

// A lambertian material's albedo, or a pbr material's base colour, at
// texture coordinates uv: the colour times its base colour texture (glTF
// 3.9.2), if it has one.
real3 base_color(Material m, vec2 uv) {
  real3 albedo = m.color;
  if (HAS_TEXTURES && m.base_color_texture != NO_TEXTURE)
    albedo *= real3(sample_material_texture(m, TEXTURE_SLOT_BASE_COLOR, m.base_color_texture, uv, true));
  return albedo;
}

// What a lambertian or pbr surface emits at uv: the emission times its
// emission texture (glTF 3.9.3), if it has one.
real3 surface_emission(Material m, vec2 uv) {
  real3 emission = m.emission;
  if (HAS_TEXTURES && m.emission_texture != NO_TEXTURE)
    emission *= real3(sample_material_texture(m, TEXTURE_SLOT_EMISSION, m.emission_texture, uv, true));
  return emission;
}

// The shading normal under material m's normal map (glTF 3.9.4): the
// texel's rgb in [0, 1] is a tangent-space normal 2 rgb - 1, its x and y
// times normal_scale, in the frame T (dp/du made orthogonal to the
// unmapped shading normal ns), B (ns x T, turned away from dp/dv), ns.
// glTF's normal maps have "+X right and +Y up" in the image, whose v grows
// downwards (v = 0 is the top row): +Y is the direction of decreasing v.
// For uvs laid out as the image (not mirrored) B = ns x T, as the Khronos
// sample viewer computes it and as a file's TANGENT with w = +1 gives
// (3.7.2.1); turning B against dp/dv keeps that right for mirrored uvs too.
// A file's TANGENT passes dpdv = -(its bitangent) (geometry/triangle.glsl).
// Without a frame (a primitive without uvs, or uvs without area) or for a
// degenerate result, ns stays.
vec3 mapped_normal(Material m, vec3 ns, vec2 uv, vec3 dpdu, vec3 dpdv) {
  vec3 c = sample_material_texture(m, TEXTURE_SLOT_NORMAL, m.normal_texture, uv, false);
  vec3 t = 2.0 * c - 1.0;
  t.xy *= m.normal_scale;
  vec3 tangent = dpdu - ns * dot(ns, dpdu);
  float len = length(tangent);
  if (!(len > 0.0) || isinf(len)) return ns;
  tangent /= len;
  vec3 bitangent = cross(ns, tangent);
  if (dot(bitangent, dpdv) > 0.0) bitangent = -bitangent;
  return safe_normalize(t.x * tangent + t.y * bitangent + t.z * ns, ns);
}

// Schlick's approximation of the Fresnel reflectance.
dreal schlick(dreal cosine, dreal eta) {
  dreal r0 = (dreal(1.0) - eta) / (dreal(1.0) + eta);
  r0 = r0 * r0;
  dreal x = dreal(1.0) - cosine;
  return r0 + (dreal(1.0) - r0) * (x * x) * (x * x) * x;
}

#endif
