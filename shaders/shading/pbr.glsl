// glTF 2.0's metallic-roughness material, as the specification's Appendix B
// defines it ("BRDF Implementation"):
//   alpha            = roughness^2
//   specular_brdf    = D(h) * V(wo, wi), D the Trowbridge-Reitz/GGX
//                      distribution, V = G2 / (4 |n.wo| |n.wi|) with G2 the
//                      height-correlated Smith masking-shadowing function
//   metal_brdf       = specular_brdf * (base + (1 - base) (1 - |wo.h|)^5)
//                      (Schlick's Fresnel, F0 = base colour)
//   dielectric_brdf  = mix(base / pi, specular_brdf, Fr), Fr = F0 + (1 - F0)
//                      (1 - |wo.h|)^5, F0 = ((ior - 1) / (ior + 1))^2 (0.04
//                      for glTF's ior 1.5)
//   material         = mix(dielectric_brdf, metal_brdf, metallic)
// wo points to the viewer, wi to the light, h = normalize(wo + wi).
//
// Sampling (one sample, either lobe): the specular lobe by the distribution of
// visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals", JCGT 7(4)), in the spherical-cap form of Dupuy & Benyoub 2023
// ("Sampling Visible GGX Normals with Spherical Caps", HPG); the diffuse lobe
// cosine-weighted. The lobe is chosen with probability proportional to its
// estimated weight at the macro-normal view angle, and the weight of the
// sample is f(wo, wi) cos / (p_spec pdf_spec(wi) + p_diff pdf_diff(wi)): the
// pdf of the direction under the mixture actually sampled (one-sample MIS
// with the balance heuristic, Veach 1997 ch. 9), so the estimator is
// unbiased whichever lobe produced wi.
//
// Precision: everything but the colours is fp32 in every variant (D spans
// 1 / (pi alpha^2) = 3e5 at the smallest alpha, beyond half's 65504; the
// masking terms divide small cosines at grazing angles; the directions must
// resolve a lobe of width alpha = 1e-3). The colour terms (base colour,
// Schlick's Fresnel colours) and the throughput are `real`: half in the fp16
// variants. The ratios f cos / pdf that multiply them are formed in fp32 and
// rounded once (docs/precision.md).
#ifndef OCTRACE_PBR_GLSL
#define OCTRACE_PBR_GLSL

#include "shading/materials.glsl"
#include "shared/rng.h"

// The smallest alpha shaded. roughness 0 is a perfect mirror (D a delta),
// which this sampler cannot weigh; clamping alpha to 1e-3 (roughness 0.032)
// turns it into a lobe about 0.06 degrees wide, which no pixel of a normal
// image resolves, while keeping D <= 1 / (pi 1e-6) = 3.2e5 finite in fp32.
// It is a bias: a roughness-0 surface renders as one of alpha 1e-3, whose
// albedo is at most ~1e-3 below the mirror's at grazing views.
const float PBR_MIN_ALPHA = 1e-3;

// Rec. 709 luminance, for the lobe choice only.
const vec3 PBR_LUMINANCE = vec3(0.2126, 0.7152, 0.0722);

// An orthonormal basis (t, b, n) around unit n, without the singularity of a
// fixed helper axis: Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited", JCGT 6(1), listing 3.
void pbr_basis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// GGX D for a unit half vector h in the local frame (z = normal): Walter et
// al. 2007 eq. 33, alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2), written as
// 1 / (pi alpha^2 (|h.xy|^2 / alpha^2 + h.z^2)^2) so that no 1 - cos^2
// cancels when alpha is small.
float ggx_d(vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float k = dot(h.xy, h.xy) / a2 + h.z * h.z;
  return 1.0 / (PI * a2 * k * k);
}

// sqrt(alpha^2 + (1 - alpha^2) z^2) for a direction at cos z to the normal:
// z (1 + 2 Lambda), with Smith's Lambda for GGX (Heitz 2014, "Understanding
// the Masking-Shadowing Function", eq. 72), in a form that stays finite at
// z = 0 (it is >= alpha). Then
//   G1(w)      = 1 / (1 + Lambda(w))            = 2 z / (z + s(z))
//   G2(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi))   (height-correlated, eq. 99)
//              = 2 zo zi / (s(zo) zi + s(zi) zo).
float smith_s(float z, float alpha) {
  float a2 = alpha * alpha;
  return sqrt(a2 + (1.0 - a2) * z * z);
}

// A visible normal for the view wo (local frame, wo.z > 0): Dupuy & Benyoub
// 2023, listing 3 (isotropic). Stretch the view to the configuration where
// alpha = 1, sample the spherical cap of normals it sees, unstretch.
vec3 sample_ggx_vndf(vec3 wo, float alpha, float u1, float u2) {
  vec3 v = normalize(vec3(alpha * wo.xy, wo.z));
  float phi = 2.0 * PI * u1;
  float z = (1.0 - u2) * (1.0 + v.z) - v.z;
  float sin_theta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
  vec3 h = vec3(sin_theta * cos(phi), sin_theta * sin(phi), z) + v;
  return normalize(vec3(alpha * h.xy, h.z));
}

float pow5(float x) {
  float x2 = x * x;
  return x2 * x2 * x;
}

// A pbr surface at a hit, as sampling and evaluation need it: its
// parameters after the textures, its local frame (t, b, n) with n the
// shading normal on the viewer's side, the view wo in that frame, and the
// probability p_spec of sampling the specular lobe.
struct PbrSurface {
  real3 base;
  float metallic;
  float alpha;
  float f0;
  vec3 t;
  vec3 b;
  vec3 n;
  vec3 wo;
  float p_spec;
};

// False when the view is exactly grazing or below the shading normal (no
// reflection is defined there).
bool pbr_surface(Material m, vec2 uv, vec3 n, vec3 to_viewer, out PbrSurface s) {
  s.base = base_color(m, uv);
  float metallic = float(m.metallic), roughness = float(m.roughness);
  if (HAS_TEXTURES && m.metallic_roughness_texture != NO_TEXTURE) {
    vec3 mr = sample_material_texture(m, TEXTURE_SLOT_METALLIC_ROUGHNESS, m.metallic_roughness_texture, uv, false);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  s.metallic = metallic;
  s.alpha = max(roughness * roughness, PBR_MIN_ALPHA);
  s.n = n;
  pbr_basis(n, s.t, s.b);
  s.wo = vec3(dot(to_viewer, s.t), dot(to_viewer, s.b), dot(to_viewer, n));
  s.p_spec = 1.0;
  s.f0 = 0.0;
  if (!(s.wo.z > 0.0)) return false;
  float ior = float(m.ior);
  float f0 = (ior - 1.0) / (ior + 1.0);
  s.f0 = f0 * f0;

  // Lobe choice: each lobe's weight estimated with Fresnel at the macro
  // normal (n.wo in place of h.wo), in luminance. The metal's Schlick colour
  // is linear in the base colour, so its luminance is lum(base) + (1 -
  // lum(base)) w. A diffuse estimate of 0 means no diffuse reflection at all
  // (metallic 1 or a black base): then p_spec = 1.
  float w_view = pow5(1.0 - s.wo.z);
  float lum_base = dot(vec3(s.base), PBR_LUMINANCE);
  float fr_view = s.f0 + (1.0 - s.f0) * w_view;
  float spec_est = (1.0 - metallic) * fr_view + metallic * (lum_base + (1.0 - lum_base) * w_view);
  float diff_est = (1.0 - metallic) * (1.0 - fr_view) * lum_base;
  s.p_spec = diff_est > 0.0 ? spec_est / (spec_est + diff_est) : 1.0;
  return true;
}

// The two lobes for a direction wi (local frame, wi.z > 0): f cos =
// spec_colour * spec + diff_colour * wi.z / pi, and pdf, the density of wi
// under the lobe mixture that pbr_sample draws from. False where pdf is 0.
struct PbrLobes {
  float spec;  // D G2 / (4 zo zi) * zi, without the Fresnel colour
  float pdf;
  real3 spec_colour;
  real3 diff_colour;
};

bool pbr_lobes(PbrSurface s, vec3 wi, out PbrLobes l) {
  vec3 h = normalize(s.wo + wi);
  float d = ggx_d(h, s.alpha);
  float so = smith_s(s.wo.z, s.alpha), si = smith_s(wi.z, s.alpha);
  // specular_brdf * cos = D G2 / (4 zo zi) * zi = D zi / (2 (so zi + si zo)).
  l.spec = d * wi.z / (2.0 * (so * wi.z + si * s.wo.z));
  // pdf of wi by the VNDF: D_wo(h) / (4 wo.h) with D_wo(h) = G1(wo) (wo.h)
  // D(h) / zo (Heitz 2018 eq. 3 and the reflection Jacobian) = D / (2 (zo + so)).
  l.pdf = s.p_spec * d / (2.0 * (s.wo.z + so)) + (1.0 - s.p_spec) * wi.z / PI;
  float w = pow5(1.0 - clamp(dot(s.wo, h), 0.0, 1.0));
  float fr = s.f0 + (1.0 - s.f0) * w;
  l.spec_colour = real((1.0 - s.metallic) * fr) + real(s.metallic) * (s.base + (real(1.0) - s.base) * real(w));
  l.diff_colour = real((1.0 - s.metallic) * (1.0 - fr)) * s.base;
  return l.pdf > 0.0;
}

// f(wo, wi) cos and the sampling pdf of world direction `dir` off the
// surface, for light sampling's MIS (Veach 1997 ch. 9); fp32. False where
// the BRDF is 0 (below the shading normal) or the pdf is.
bool pbr_eval(PbrSurface s, vec3 dir, out vec3 f_cos, out float pdf) {
  f_cos = vec3(0.0);
  pdf = 0.0;
  vec3 wi = vec3(dot(dir, s.t), dot(dir, s.b), dot(dir, s.n));
  if (!(wi.z > 0.0)) return false;
  PbrLobes l;
  if (!pbr_lobes(s, wi, l)) return false;
  f_cos = vec3(l.spec_colour) * l.spec + vec3(l.diff_colour) * (wi.z / PI);
  pdf = l.pdf;
  return true;
}

// Samples a direction `dir` (world space) off pbr surface s, its weight
// f cos / pdf and its pdf. False when there is none: the sample went below
// the surface (where f = 0: the path ends, as the integral over the upper
// hemisphere says). Draws three numbers from `rng` whatever happens.
bool sample_pbr(PbrSurface s, inout Rng rng, out vec3 dir, out real3 weight, out float pdf) {
  float u0 = rng_next(rng), u1 = rng_next(rng), u2 = rng_next(rng);
  dir = s.n;
  weight = real3(0.0);
  pdf = 0.0;
  vec3 wi;
  if (u0 < s.p_spec) {
    wi = reflect(-s.wo, sample_ggx_vndf(s.wo, s.alpha, u1, u2));
  } else {
    // Cosine-weighted (Malley's method): pdf cos / pi.
    float r = sqrt(u1), phi = 2.0 * PI * u2;
    wi = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u1)));
  }
  if (!(wi.z > 0.0)) return false;
  PbrLobes l;
  if (!pbr_lobes(s, wi, l)) return false;
  pdf = l.pdf;
  // In fp32, then to `real`: a factor such as cos / (pi pdf) after an
  // unlikely lobe choice may exceed half's range although its product with
  // the lobe's colour does not (the fp16 variants saw Inf samples from it).
  weight = real3(vec3(l.spec_colour) * (l.spec / l.pdf) + vec3(l.diff_colour) * (wi.z / (PI * l.pdf)));
  dir = wi.x * s.t + wi.y * s.b + wi.z * s.n;
  return true;
}

#endif
