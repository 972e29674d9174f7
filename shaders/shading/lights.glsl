// Light sampling for next-event estimation (NEE): pick a light from the
// light list by power (its alias table; render/lights.h), sample a direction
// toward it, and the shadow ray that says whether it is seen. With BSDF
// sampling the two strategies are combined by multiple importance sampling
// with the power heuristic (Veach 1997, "Robust Monte Carlo Methods for
// Light Transport Simulation", ch. 9; beta = 2): a light's contribution
// found by NEE is weighted by pl^2 / (pl^2 + pb^2), the same light reached by
// a BSDF-sampled ray by pb^2 / (pl^2 + pb^2), with pl the light strategy's
// and pb the BSDF's solid-angle density of the direction. Delta lights
// (point, spot, directional) are reached by NEE only: weight 1.
// The sky's envmap is a light too (render/lights.h: the list's last entry,
// picked by its power), sampled by its 2D CDF (shading/envmap.glsl); its
// shadow ray looks to infinity, and a BSDF-sampled ray that escapes to it is
// weighted against pmf x envmap_pdf (sky_weight).
// An emissive mesh triangle is a light too (one per triangle and instance),
// sampled by area and reached by BSDF-sampled rays that hit it, weighted
// against pmf x its solid-angle pdf (emission_weight).
// The includer declares `scene`, `lights`, `sphere_lights`,
// `triangle_lights`, `spheres`, `sphere_materials`, `instances`, `meshes`,
// the specialization constants HAS_PUNCTUAL, SKY_LIGHT, HAS_SPHERE_LIGHTS
// and HAS_TRIANGLE_LIGHTS, and includes accel/closest_hit.glsl and
// shading/sky.glsl before this file.
#ifndef OCTRACE_LIGHTS_GLSL
#define OCTRACE_LIGHTS_GLSL

#include "shading/materials.glsl"
#include "shading/pbr.glsl"
#include "shared/rng.h"

// The power heuristic's weight of a strategy of density a against one of
// density b, written as 1 / (1 + (b/a)^2) so that neither square overflows;
// 0 where a is 0.
float power_heuristic(float a, float b) {
  if (!(a > 0.0)) return 0.0;
  float r = b / a;
  return 1.0 / (1.0 + r * r);
}

// sin^2 of the cone's half-angle below which the cone is sampled in the
// small-angle form (1.5 degrees; pbrt-v4, Sphere::Sample): there 1 - cos
// cancels in fp32.
const float SPHERE_SMALL_CONE = 0.00068523;

// 1 - cos(theta_max) of the cone that a sphere of radius r whose centre is
// dist2 (squared) away subtends, as the sampler uses it.
float cone_one_minus_cos(float r, float dist2) {
  float sin2_max = r * r / dist2;
  if (sin2_max < SPHERE_SMALL_CONE) return 0.5 * sin2_max;
  return 1.0 - sqrt(max(0.0, 1.0 - sin2_max));
}

// Samples a direction from p toward a sphere light (centre c, radius r), and
// its solid-angle pdf (pbrt-v4, section 6.2.4, Sphere::Sample(ctx, u)):
// from outside, uniformly in the cone of directions that see the sphere
// (pdf 1 / (2 pi (1 - cos theta_max))), by the direction only: the shadow
// ray finds the point. From inside or on the sphere (every direction sees
// it) a point uniform on its area, pdf 1 / A converted to solid angle by
// dist^2 / |cos| at the point. False when no direction comes of it (p at
// the sampled point, or a sample seen edge-on).
bool sample_sphere_light(vec3 p, vec3 c, float r, float u1, float u2, out vec3 dir, out float pdf) {
  vec3 d = c - p;
  float dist2 = dot(d, d);
  dir = vec3(0.0, 0.0, 1.0);
  pdf = 0.0;
  if (dist2 <= r * r) {
    float z = 1.0 - 2.0 * u1;
    float phi = 2.0 * PI * u2;
    float s = sqrt(max(0.0, 1.0 - z * z));
    vec3 nl = vec3(s * cos(phi), s * sin(phi), z);
    vec3 w = c + r * nl - p;
    float l2 = dot(w, w);
    if (!(l2 > 0.0)) return false;
    dir = w * inversesqrt(l2);
    float cos_l = abs(dot(nl, dir));
    if (!(cos_l > 0.0)) return false;
    pdf = l2 / (cos_l * 4.0 * PI * r * r);
    return !isinf(pdf);
  }
  float sin2_max = r * r / dist2;
  float cos_t, sin2_t;
  if (sin2_max < SPHERE_SMALL_CONE) {
    // sin^2 uniform over [0, sin^2 theta_max]: for small angles the same as
    // cos uniform over [cos theta_max, 1], without the cancellation.
    sin2_t = sin2_max * u1;
    cos_t = sqrt(1.0 - sin2_t);
  } else {
    float cos_max = sqrt(max(0.0, 1.0 - sin2_max));
    cos_t = (cos_max - 1.0) * u1 + 1.0;
    sin2_t = max(0.0, 1.0 - cos_t * cos_t);
  }
  float sin_t = sqrt(sin2_t);
  float phi = 2.0 * PI * u2;
  vec3 axis = d * inversesqrt(dist2);
  vec3 t, b;
  pbr_basis(axis, t, b);
  dir = normalize(sin_t * cos(phi) * t + sin_t * sin(phi) * b + cos_t * axis);
  pdf = 1.0 / (2.0 * PI * cone_one_minus_cos(r, dist2));
  return !isinf(pdf);
}

// The solid-angle pdf with which sample_sphere_light, from p, gives the
// direction `dir` that meets the sphere at distance t, where its unit normal
// is `nl`.
float sphere_light_pdf(vec3 p, vec3 c, float r, vec3 dir, float t, vec3 nl) {
  vec3 d = c - p;
  float dist2 = dot(d, d);
  if (dist2 <= r * r) {
    float cos_l = abs(dot(nl, dir));
    return cos_l > 0.0 ? t * t / (cos_l * 4.0 * PI * r * r) : 0.0;
  }
  return 1.0 / (2.0 * PI * cone_one_minus_cos(r, dist2));
}

// What a sphere light emits: its material's radiance (emissive) or emission
// (lambertian, pbr), as a path that hits it reads it.
real3 sphere_light_radiance(uint sphere) {
  Material m = load_material(sphere_material_at(sphere));
  return m.type == MAT_EMISSIVE ? m.color : m.emission;
}

// Barycentrics (of v0, v1, v2) of a point uniform on a triangle's area,
// from two numbers uniform in [0, 1): the square-root warp b0 = 1 - sqrt(u1),
// b1 = u2 sqrt(u1) (Turk 1990, "Generating Random Points in Triangles",
// Graphics Gems; pbrt-v3, section 13.6.5, UniformSampleTriangle).
vec3 sample_triangle_barycentrics(float u1, float u2) {
  float su = sqrt(u1);
  float b0 = 1.0 - su, b1 = u2 * su;
  return vec3(b0, b1, 1.0 - b0 - b1);
}

// Triangle light l's triangle, as an index into the triangle array.
uint triangle_light_triangle(GpuLight l) { return meshes[instances[l.instance].mesh].first_triangle + l.triangle; }

// What triangle `tri` emits at barycentrics b, as a path that hits it reads
// it (path_trace.comp): an emissive material's radiance; a lambertian or pbr
// material's surface_emission at the uv there, texture included.
real3 triangle_light_radiance(uint tri, vec3 b) {
  Material m = load_material(triangle_at(tri).material);
  if (HAS_EMISSIVE && m.type == MAT_EMISSIVE) return m.color;
  if (!HAS_SURFACE_EMISSION || (m.type != MAT_LAMBERTIAN && m.type != MAT_PBR)) return real3(0.0);
  vec2 uv = vec2(0.0);
  if (HAS_TEXTURES && scene.triangle_uvs != 0u) {
    GpuTriangleUvs u = triangle_uvs_at(tri);
    uv = b.x * u.uv0 + b.y * u.uv1 + b.z * u.uv2;
  }
  return surface_emission(m, uv);
}

// The light-list index of triangle hit `hit` (NO_LIGHT for a triangle that
// is no light), from the table shared.h (BINDING_TRIANGLE_LIGHTS) lays out.
uint triangle_light_index(Hit hit) {
  if (hit.inst >= triangle_lights[0]) return NO_LIGHT;
  uint start = triangle_lights[1u + hit.inst];
  if (start == NO_LIGHT) return NO_LIGHT;
  return triangle_lights[start + hit.prim - instances[hit.inst].first_id];
}

// The solid-angle pdf of a point sampled uniformly on triangle light l (area
// A = l.radius) seen at distance dist along a direction whose cosine with
// the triangle's normal is cos_l: dist^2 / (A |cos_l|) (the area measure
// turned into solid angle; Veach 1997, eq. 8.10). 0 seen edge-on.
float triangle_light_pdf(GpuLight l, float dist, float cos_l) {
  float c = abs(cos_l);
  return c > 0.0 ? dist * dist / (l.radius * c) : 0.0;
}

// A light sample seen from a shading point.
struct LightSample {
  vec3 dir;      // unit, toward the light
  float t_max;   // how far the shadow ray looks (INF: sphere lights, directional)
  vec3 value;    // what the light brings along dir, over the sample's density: L / (pmf pdf) or I / (pmf r^2)
  float pdf;     // pmf x solid-angle pdf, for MIS; 0 for a delta light
  uint sphere;   // a sphere light's sphere; NO_PRIM for a punctual light
};

// Picks a light (alias table: two numbers) and samples it from p (two more):
// four numbers from `rng` whatever happens. False when the sample brings
// nothing (p outside a spot's cone, or no direction).
bool sample_light(vec3 p, inout Rng rng, out LightSample ls) {
  float u_pick = rng_next(rng), u_alias = rng_next(rng), u1 = rng_next(rng), u2 = rng_next(rng);
  uint i = min(uint(u_pick * float(scene.light_count)), scene.light_count - 1u);
  if (u_alias >= lights[i].alias_q) i = lights[i].alias;
  GpuLight l = lights[i];
  ls.dir = vec3(0.0, 0.0, 1.0);
  ls.t_max = INF;
  ls.value = vec3(0.0);
  ls.pdf = 0.0;
  ls.sphere = NO_PRIM;
  if (HAS_SPHERE_LIGHTS && l.type == LIGHT_SPHERE) {
    float pdf;
    if (!sample_sphere_light(p, l.position, l.radius, u1, u2, ls.dir, pdf)) return false;
    ls.pdf = l.pmf * pdf;
    ls.value = vec3(sphere_light_radiance(l.sphere)) / ls.pdf;
    ls.sphere = l.sphere;
    return true;
  }
  if (HAS_TRIANGLE_LIGHTS && l.type == LIGHT_TRIANGLE) {
    // A point uniform on the triangle (world-space vertices), seen from p;
    // the shadow ray stops just before it (a relative 1e-4, far above fp32
    // rounding of the intersection's t: the light's own triangle is not
    // found as a blocker).
    vec3 b = sample_triangle_barycentrics(u1, u2);
    vec3 w = b.x * l.position + b.y * l.direction + b.z * l.intensity - p;
    float dist2 = dot(w, w);
    if (!(dist2 > 0.0)) return false;
    float dist = sqrt(dist2);
    ls.dir = w / dist;
    ls.t_max = dist * (1.0 - 1e-4);
    // The normal as a hit computes it (geometry/triangle.glsl): its side
    // decides the back face of a single-sided material, which no ray hits
    // (accel/closest_hit.glsl) and so emits nothing.
    uint tri = triangle_light_triangle(l);
    GpuTriangle t = triangle_at(tri);
    vec3 ng = normal_to_world(instances[l.instance], cross(t.v1 - t.v0, t.v2 - t.v0));
    float cos_l = dot(ng, ls.dir) * inversesqrt(dot(ng, ng));
    if (HAS_SINGLE_SIDED && material_at(t.material).double_sided == 0u && !(cos_l < 0.0)) return false;
    float pdf = triangle_light_pdf(l, dist, cos_l);
    if (!(pdf > 0.0) || isinf(pdf)) return false;
    ls.pdf = l.pmf * pdf;
    ls.value = vec3(triangle_light_radiance(tri, b)) / ls.pdf;
    return true;
  }
  if (SKY_LIGHT && l.type == LIGHT_ENVMAP) {
    // A direction by the map's luminance x sin theta; the radiance is read
    // from the texel it falls in, as an escaping ray reads it.
    float pdf;
    if (!envmap_sample(vec2(u1, u2), ls.dir, pdf)) return false;
    ls.pdf = l.pmf * pdf;
    ls.value = envmap_radiance(ls.dir) / ls.pdf;
    return true;
  }
  if (!HAS_PUNCTUAL) return false;
  if (l.type == LIGHT_DIRECTIONAL) {
    ls.dir = -l.direction;
    ls.value = l.intensity / l.pmf;
    return true;
  }
  // Point and spot: irradiance I / r^2 at normal incidence.
  vec3 w = l.position - p;
  float r2 = dot(w, w);
  if (!(r2 > 0.0)) return false;
  float r = sqrt(r2);
  ls.dir = w / r;
  ls.t_max = r;
  float falloff = 1.0;
  if (l.type == LIGHT_SPOT) {
    // KHR_lights_punctual's spot attenuation: smoothstep-like in cos between
    // the cones, squared (the extension's README, "Inner and Outer Cone Angles").
    float scale = 1.0 / max(0.001, l.cos_inner - l.cos_outer);
    float a = clamp(dot(l.direction, -ls.dir) * scale - l.cos_outer * scale, 0.0, 1.0);
    falloff = a * a;
    if (!(falloff > 0.0)) return false;
  }
  ls.value = l.intensity * (falloff / (l.pmf * r2));
  return true;
}

// Whether the light sample is seen from the surface point p (geometric
// normal ng, the primitive `prim` hit at distance hit_t): the shadow ray
// leaves as a bounce would, and asks accel/closest_hit.glsl's any-hit
// question (occluded: the first blocker ends the walk). A sphere light is
// seen when nothing but its own sphere lies before the point where the ray
// meets that sphere (or anywhere on the ray, for a direction that grazes
// the sphere's edge and misses it by rounding: nothing lies between); a
// punctual light when nothing lies before it; the envmap when nothing lies
// on the ray.
bool light_visible(vec3 p, vec3 ng, float hit_t, uint prim, LightSample ls) {
  bool inward = dot(ls.dir, ng) < 0.0;
  Ray shadow = Ray(offset_ray_origin(p, inward ? -ng : ng, hit_t), ls.dir);
  float t_max = ls.t_max;
  if (ls.sphere != NO_PRIM) {
    Hit light;
    light.t = INF;
    light.prim = NO_PRIM;
    light.kind = PRIM_SPHERE;
    light.inst = 0u;
    test_sphere(shadow, ls.sphere, prim, inward, light);
    t_max = light.t;
  }
  return !occluded(shadow, prim, inward, t_max, ls.sphere);
}

// The MIS weight of what a BSDF-sampled ray from p (with solid-angle pdf
// bsdf_pdf) finds emitted at its hit, where light sampling from p could have
// found it too (the light strategy's density of that point, mirroring
// sample_light); 1 for an emitter that is no light of the list.
float emission_weight(vec3 p, float bsdf_pdf, Ray ray, Hit hit, Surface surf) {
  if (HAS_TRIANGLE_LIGHTS && (!HAS_SPHERES || hit.kind == PRIM_TRIANGLE)) {
    uint li = triangle_light_index(hit);
    if (li == NO_LIGHT) return 1.0;
    GpuLight l = lights[li];
    return power_heuristic(bsdf_pdf, l.pmf * triangle_light_pdf(l, hit.t, dot(surf.ng, ray.dir)));
  }
  if (!(HAS_SPHERE_LIGHTS && (!HAS_TRIANGLES || hit.kind == PRIM_SPHERE))) return 1.0;
  uint li = sphere_lights[hit.prim];
  if (li == NO_LIGHT) return 1.0;
  GpuLight l = lights[li];
  float pl = l.pmf * sphere_light_pdf(p, l.position, l.radius, ray.dir, hit.t, surf.ng);
  return power_heuristic(bsdf_pdf, pl);
}

// The MIS weight of the sky that a BSDF-sampled ray from a vertex that
// sampled a light (with solid-angle pdf bsdf_pdf) escapes to along dir: the
// light strategy's density there is the envmap's pmf x envmap_pdf(dir); 1
// for a sky that is no light (the list's last entry is another kind).
float sky_weight(float bsdf_pdf, vec3 dir) {
  uint last = scene.light_count - 1u;
  if (lights[last].type != LIGHT_ENVMAP) return 1.0;
  return power_heuristic(bsdf_pdf, lights[last].pmf * envmap_pdf(dir));
}

#endif
