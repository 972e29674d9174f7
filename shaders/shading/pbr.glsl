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
// Transmission (KHR_materials_transmission, factor t): the dielectric
// layer's unreflected light is split, t through the surface, 1 - t diffused:
//   dielectric_brdf  = mix(mix(base / pi, specular_btdf * base, t),
//                          specular_brdf, Fr)
// specular_btdf is rough refraction through the same GGX microfacets: Walter
// et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
// (EGSR), eq. 21, with the generalized half vector (eq. 16), the
// refraction Jacobian (eq. 17) and the height-correlated G2 = 1 / (1 +
// Lambda(wo) + Lambda(wi)) of the cosines' magnitudes. A surface is either the boundary of a closed
// solid of index ior (rays refract in and out; inside, eta = ior and past
// the critical angle the layer reflects everything: Fr = 1, and past it at
// the macro normal no light reaches the diffuse base either) or thin-walled
// (glTF without KHR_materials_volume: a microfacet reflection mirrored
// through the macro surface, so a smooth surface passes light straight on and
// a rough one blurs it; no bending, no total internal reflection).
// Fr is Schlick's, at the microfacet normal, with F0 from ior: the one the
// `dielectric` material uses at the macro normal, so that transmission 1,
// roughness 0 renders as `dielectric` of the same ior. Radiance's (n1 / n2)^2
// factor across a refraction (Veach 1997, sec. 5.2) is left out, as
// `dielectric` leaves it out: it cancels on every path that leaves the solid
// again, which is every path that reaches a light outside it.
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
// unbiased whichever lobe produced wi. With transmission, the specular lobe's
// microfacet normal h is sampled first, then reflection or transmission is
// chosen with probability proportional to its weight at h (Fr against (1 -
// Fr) t lum(base)); the chosen probability multiplies that direction's pdf.
// Only transmission reaches the far side, so a transmitted direction's weight
// is its colour times G2 / G1 over the probabilities of the two choices: D,
// Walter's Jacobian and the BTDF's denominators cancel against the VNDF's
// pdf (Heitz 2018 eq. 3).
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

// The dielectric layer's reflectance at a microfacet seen at cos c = wo.h:
// Schlick's with F0, and 1 past the critical angle of a solid (eta: index on
// the viewer's side over the far side's; TIR as `dielectric` tests it).
float layer_fresnel(float c, float f0, float eta, bool thin) {
  if (!thin && eta * eta * (1.0 - c * c) > 1.0) return 1.0;
  return f0 + (1.0 - f0) * pow5(1.0 - clamp(c, 0.0, 1.0));
}

// A pbr surface at a hit, as sampling and evaluation need it: its
// parameters after the textures, its local frame (t, b, n) with n the
// shading normal on the viewer's side, the view wo in that frame, the
// probability p_spec of sampling the specular lobe, and its transmission.
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
  float lum_base;      // luminance of base
  float transmission;  // KHR_materials_transmission's factor (0: none)
  bool thin;           // thin-walled (else the boundary of a solid)
  float eta;           // index on the viewer's side over the far side's
};

// What is left of light that travelled a distance t inside the solid that
// material m bounds: Beer-Lambert's exp(-sigma t) per channel, sigma from
// KHR_materials_volume's attenuation (shared.h's GpuTransmission; 0 for a
// clear solid). Exactly 1 for any material that bounds no solid (the
// transmission buffer, a placeholder in scenes without transmission, is
// read only for a transmissive solid: transmission t > 0 in `fuzz`).
// fp32, rounded once into the variant's precision: sigma may be far above
// half's range (a short attenuation distance) and +Inf (a colour channel
// of 0), where exp gives 0 for any t > 0. A ray inside one solid that
// meets another solid's front face is attenuated by neither on that
// segment: nested media are not supported (docs/design.md).
real3 transmittance(Material m, float t) {
  if (m.type != MAT_PBR || !(float(m.fuzz) > 0.0)) return real3(1.0);
  return real3(exp(-material_transmission[m.index].absorption * t));
}

// Whether s transmits (the transmission code compiles out without
// SPEC_TRANSMISSION).
bool pbr_transmits(PbrSurface s) { return HAS_TRANSMISSION && s.transmission > 0.0; }

// front_face: the viewer is outside the surface (for a solid, outside the
// solid). False when the view is exactly grazing or below the shading normal
// (no reflection is defined there).
bool pbr_surface(Material m, vec2 uv, vec3 n, vec3 to_viewer, bool front_face, out PbrSurface s) {
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
  s.lum_base = 0.0;
  float ior = float(m.ior);
  // Transmission t in the fuzz slot, negated when thin-walled (shared.h).
  s.transmission = HAS_TRANSMISSION ? abs(float(m.fuzz)) : 0.0;
  // KHR_materials_transmission's transmissionTexture: its red channel, linear.
  if (HAS_TRANSMISSION && HAS_TEXTURES && s.transmission > 0.0) {
    uint texture = material_transmission[m.index].transmission_texture;
    if (texture != NO_TEXTURE)
      s.transmission *= sample_material_texture(m, TEXTURE_SLOT_TRANSMISSION, texture, uv, false).r;
  }
  s.thin = pbr_transmits(s) && float(m.fuzz) < 0.0;
  s.eta = s.thin ? 1.0 : front_face ? 1.0 / ior : ior;
  if (!(s.wo.z > 0.0)) return false;
  float f0 = (ior - 1.0) / (ior + 1.0);
  s.f0 = f0 * f0;

  // Lobe choice: each lobe's weight estimated with Fresnel at the macro
  // normal (n.wo in place of h.wo), in luminance. The metal's Schlick colour
  // is linear in the base colour, so its luminance is lum(base) + (1 -
  // lum(base)) w. A diffuse estimate of 0 means no diffuse reflection at all
  // (metallic 1 or a black base): then p_spec = 1. Transmission belongs to
  // the specular lobe (it is sampled through the same microfacet normal) and
  // takes the share t of the diffuse one; inside a solid past the critical
  // angle the layer reflects everything. (Estimating Schlick's few percent
  // there instead chose the specular lobe with p_spec ~ 0.25 while its
  // weight was ~1: each reflection of a path held by TIR multiplied it by
  // 1 / p_spec, and the fp16 variants saw Inf samples.) A diffuse estimate
  // of 0 still leaves no direction unsampled: the VNDF covers the hemisphere.
  float w_view = pow5(1.0 - s.wo.z);
  float lum_base = dot(vec3(s.base), PBR_LUMINANCE);
  s.lum_base = lum_base;
  float fr_view = s.f0 + (1.0 - s.f0) * w_view;
  float spec_est = (1.0 - metallic) * fr_view + metallic * (lum_base + (1.0 - lum_base) * w_view);
  float diff_est = (1.0 - metallic) * (1.0 - fr_view) * lum_base;
  if (pbr_transmits(s)) {
    float fr_layer = layer_fresnel(s.wo.z, s.f0, s.eta, s.thin);
    spec_est = (1.0 - metallic) * (fr_layer + (1.0 - fr_layer) * s.transmission * lum_base) +
               metallic * (lum_base + (1.0 - lum_base) * w_view);
    diff_est = (1.0 - metallic) * (1.0 - fr_layer) * (1.0 - s.transmission) * lum_base;
  }
  s.p_spec = diff_est > 0.0 ? spec_est / (spec_est + diff_est) : 1.0;
  return true;
}

// The two lobes for a direction wi on the viewer's side (local frame, wi.z >
// 0): f cos = spec_colour * spec + diff_colour * wi.z / pi, and pdf, the
// density of wi under the lobe mixture that sample_pbr draws from (with
// transmission: times the probability of reflecting at wi's microfacet
// normal). False where pdf is 0.
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
  float w = pow5(1.0 - clamp(dot(s.wo, h), 0.0, 1.0));
  float fr = s.f0 + (1.0 - s.f0) * w;
  float p_spec_here = s.p_spec;
  float diff_share = 1.0;
  if (pbr_transmits(s)) {
    // Reflection was chosen at h with probability 1 - p_trans; past the
    // critical angle the layer reflects everything (Fr = 1).
    fr = layer_fresnel(dot(s.wo, h), s.f0, s.eta, s.thin);
    float refl = (1.0 - s.metallic) * fr + s.metallic * (s.lum_base + (1.0 - s.lum_base) * w);
    float trans = (1.0 - s.metallic) * (1.0 - fr) * s.transmission * s.lum_base;
    if (trans > 0.0) p_spec_here *= refl / (refl + trans);
    // Inside a solid past the critical angle at the macro normal nothing
    // reaches the diffuse base either (diff_est is 0 there, so it is never
    // sampled). glTF's mix weighs the diffuse term by 1 - Fr at the pair's
    // own half vector, which for a diffuse direction lies far from the
    // normal, below the critical angle: it would add (1 - t) base to a
    // reflection that already returns everything, so that a path held by
    // TIR gained energy at every bounce, and the diffuse term, reached only
    // through the specular lobe's pdf, weighed 1 / pdf_vndf (unbounded).
    diff_share = layer_fresnel(s.wo.z, s.f0, s.eta, s.thin) == 1.0 ? 0.0 : 1.0 - s.transmission;
  }
  // pdf of wi by the VNDF: D_wo(h) / (4 wo.h) with D_wo(h) = G1(wo) (wo.h)
  // D(h) / zo (Heitz 2018 eq. 3 and the reflection Jacobian) = D / (2 (zo + so)).
  l.pdf = p_spec_here * d / (2.0 * (s.wo.z + so)) + (1.0 - s.p_spec) * wi.z / PI;
  l.spec_colour = real((1.0 - s.metallic) * fr) + real(s.metallic) * (s.base + (real(1.0) - s.base) * real(w));
  l.diff_colour = real((1.0 - s.metallic) * (1.0 - fr)) * s.base;
  if (pbr_transmits(s)) l.diff_colour *= real(diff_share);
  return l.pdf > 0.0;
}

// f(wo, wi) cos and the sampling pdf of world direction `dir` off the
// surface, for light sampling's MIS (Veach 1997 ch. 9); fp32. False where
// the BSDF is 0 or the pdf is, and for a direction on the far side: light
// sampling does not evaluate transmission (a transmitted path that hits an
// emitter keeps MIS weight 1; path_trace.comp).
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
// f cos / pdf and its pdf (0 for a transmitted direction, which light
// sampling never produces). `transmitted`: dir passes to the far side. False
// when there is none: the sample went to a side where f = 0 (below a
// reflection, above a transmission: the path ends, as the integral says).
// Draws three numbers from `rng` whatever happens, and one from `layer` when
// the material transmits and the specular lobe is chosen (TRANSMISSION_STREAM).
bool sample_pbr(PbrSurface s, inout Rng rng, inout Rng layer, out vec3 dir, out real3 weight, out float pdf,
                out bool transmitted) {
  float u0 = rng_next(rng), u1 = rng_next(rng), u2 = rng_next(rng);
  dir = s.n;
  weight = real3(0.0);
  pdf = 0.0;
  transmitted = false;
  vec3 wi;
  if (u0 < s.p_spec) {
    vec3 h = sample_ggx_vndf(s.wo, s.alpha, u1, u2);
    wi = reflect(-s.wo, h);
    if (pbr_transmits(s)) {
      // Reflect or transmit at h, in proportion to the two weights there.
      float c = dot(s.wo, h);
      float fr = layer_fresnel(c, s.f0, s.eta, s.thin);
      float w = pow5(1.0 - clamp(c, 0.0, 1.0));
      float refl = (1.0 - s.metallic) * fr + s.metallic * (s.lum_base + (1.0 - s.lum_base) * w);
      float trans = (1.0 - s.metallic) * (1.0 - fr) * s.transmission * s.lum_base;
      float p_trans = trans > 0.0 ? trans / (refl + trans) : 0.0;
      if (rng_next(layer) < p_trans) {
        // The far side: a solid refracts about h (Walter eq. 40; no TIR
        // here, where trans > 0 needs fr < 1); a thin wall mirrors the
        // microfacet reflection through the macro surface.
        wi = s.thin ? vec3(wi.xy, -wi.z) : refract(-s.wo, h, s.eta);
        float zi = -wi.z;
        if (!(zi > 0.0)) return false;
        // f cos / pdf = (1 - metallic) (1 - Fr) t base G2 / G1 / (p_spec
        // p_trans), G2 / G1 = zi (zo + so) / (so zi + si zo) (smith_s), and
        // (1 - metallic) (1 - Fr) t / p_trans = (refl + trans) / lum(base).
        float so = smith_s(s.wo.z, s.alpha), si = smith_s(zi, s.alpha);
        float g2_g1 = zi * (s.wo.z + so) / (so * zi + si * s.wo.z);
        weight = real3(vec3(s.base) * ((refl + trans) / s.lum_base * g2_g1 / s.p_spec));
        dir = wi.x * s.t + wi.y * s.b + wi.z * s.n;
        transmitted = true;
        return true;
      }
    }
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
