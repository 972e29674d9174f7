// One path-tracing pass: one sample per pixel, added to the accumulation
// buffers. Materials follow "Ray Tracing in One Weekend" v4, and glTF 2.0's
// metallic-roughness material (shading/pbr.glsl; docs/design.md).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require

#include "shared/shared.h"
#include "shading/precision.glsl"

// 64 invocations per workgroup; PassParams.sample_lanes of them share a
// pixel (main() says how).
layout(local_size_x = WORKGROUP_SIZE * WORKGROUP_SIZE) in;

layout(std430, binding = BINDING_SCENE) readonly buffer SceneBuf { SceneParams scene; };
#include "shared/scene_buffers.glsl"
layout(std430, binding = BINDING_ACCUM_SUM) buffer AccumSumBuf { vec4 accum_sum[]; };
layout(std430, binding = BINDING_ACCUM_COMP) buffer AccumCompBuf { vec4 accum_comp[]; };
layout(std430, binding = BINDING_ACCUM_SQ) buffer AccumSqBuf { vec4 accum_sq[]; };
layout(std430, binding = BINDING_STATS) buffer StatsBuf { RenderStats stats; };
layout(std430, binding = BINDING_INSTANCES) readonly buffer InstanceBuf { GpuInstance instances[]; };
layout(std430, binding = BINDING_MESHES) readonly buffer MeshBuf { GpuMesh meshes[]; };
layout(std430, binding = BINDING_TEXTURES) readonly buffer TextureBuf { GpuTexture textures[]; };
layout(std430, binding = BINDING_TEXELS) readonly buffer TexelBuf { uint texels[]; };
layout(std430, binding = BINDING_TEXTURE_TRANSFORMS) readonly buffer TextureTransformBuf { GpuUvTransform texture_transforms[]; };
layout(std430, binding = BINDING_TRANSMISSION) readonly buffer TransmissionBuf { GpuTransmission material_transmission[]; };
layout(std430, binding = BINDING_ENVMAP_TEXELS) readonly buffer EnvmapTexelBuf { float envmap_texels[]; };
layout(std430, binding = BINDING_ENVMAP_MARGINAL) readonly buffer EnvmapMarginalBuf { float envmap_marginal[]; };
layout(std430, binding = BINDING_ENVMAP_CONDITIONAL) readonly buffer EnvmapConditionalBuf { float envmap_conditional[]; };
layout(std430, binding = BINDING_LIGHTS) readonly buffer LightBuf { GpuLight lights[]; };
layout(std430, binding = BINDING_SPHERE_LIGHTS) readonly buffer SphereLightBuf { uint sphere_lights[]; };
layout(std430, binding = BINDING_TRIANGLE_LIGHTS) readonly buffer TriangleLightBuf { uint triangle_lights[]; };

layout(push_constant) uniform Push { PassParams pass; };

// The scene's features (renderer/scene/features.h), as specialization
// constants: the driver compiles out the code of effects the scene lacks.
// Defaults are the general pipeline (`--effects all`). Every effect draws its
// random numbers from its own bounce's stream, so leaving one out changes no
// other number: the image is the same.
layout(constant_id = SPEC_LAMBERTIAN) const bool HAS_LAMBERTIAN = true;
layout(constant_id = SPEC_METAL) const bool HAS_METAL = true;
layout(constant_id = SPEC_FUZZ) const bool HAS_FUZZ = true;
layout(constant_id = SPEC_DIELECTRIC) const bool HAS_DIELECTRIC = true;
layout(constant_id = SPEC_EMISSIVE) const bool HAS_EMISSIVE = true;
layout(constant_id = SPEC_PBR) const bool HAS_PBR = true;
layout(constant_id = SPEC_DEFOCUS) const bool HAS_DEFOCUS = true;
layout(constant_id = SPEC_SKY) const uint SKY = SKY_RUNTIME;
layout(constant_id = SPEC_ANY_LIGHT) const bool ANY_LIGHT = true;
layout(constant_id = SPEC_SPHERES) const bool HAS_SPHERES = true;
layout(constant_id = SPEC_TRIANGLES) const bool HAS_TRIANGLES = true;
layout(constant_id = SPEC_VERTEX_NORMALS) const bool HAS_VERTEX_NORMALS = true;
layout(constant_id = SPEC_TEXTURES) const bool HAS_TEXTURES = true;
layout(constant_id = SPEC_SURFACE_EMISSION) const bool HAS_SURFACE_EMISSION = true;
layout(constant_id = SPEC_NORMAL_MAPS) const bool HAS_NORMAL_MAPS = true;
layout(constant_id = SPEC_ALPHA) const bool HAS_ALPHA = true;
layout(constant_id = SPEC_SINGLE_SIDED) const bool HAS_SINGLE_SIDED = true;
layout(constant_id = SPEC_TRANSMISSION) const bool HAS_TRANSMISSION = true;
layout(constant_id = SPEC_ABSORPTION) const bool HAS_ABSORPTION = true;
layout(constant_id = SPEC_SAMPLE_LANES) const bool SAMPLE_LANES = true;
layout(constant_id = SPEC_NEE) const bool NEE = true;
layout(constant_id = SPEC_PUNCTUAL) const bool HAS_PUNCTUAL = true;
layout(constant_id = SPEC_SKY_LIGHT) const bool SKY_LIGHT = true;
layout(constant_id = SPEC_TRIANGLE_LIGHTS) const bool TRIANGLE_LIGHTS = true;
// A sphere light needs spheres and an emitting material (emissive, or a
// lambertian or pbr emission): a scene lit only by its sky or by punctual
// lights compiles no sphere-light sampling.
#define HAS_SPHERE_LIGHTS (HAS_SPHERES && (HAS_EMISSIVE || HAS_SURFACE_EMISSION))
// Emissive triangles as lights need triangles too.
#define HAS_TRIANGLE_LIGHTS (TRIANGLE_LIGHTS && HAS_TRIANGLES && (HAS_EMISSIVE || HAS_SURFACE_EMISSION))

// Which part of a dispatch of samples this pipeline runs (STAGE_*, below).
layout(constant_id = SPEC_STAGE) const uint STAGE = STAGE_WHOLE;
// The subgroup stage (tail_subgroup_pass): every lane of a subgroup traces
// the same path, and the octree walks split each leaf's tests and each
// node step's child box tests among them.
#define SPLIT_LEAVES (STAGE == STAGE_TAIL_SUBGROUP)

#include "shared/rng.h"
#include "sampling/warp.glsl"
#include "geometry/camera.glsl"
#include "accel/closest_hit.glsl"
#include "shading/materials.glsl"
#include "shading/pbr.glsl"
#include "shading/sky.glsl"
#include "shading/lights.glsl"

// The camera's tiles (RenderSettings::camera_tiles; shared.h
// BINDING_CAMERA_TILES): camera rays all leave the eye, so the spheres a
// camera ray through a tile of 8 x 8 pixels can meet are those that reach
// into the tile's pyramid from the eye, a few in a sparse field where the
// walk would take a dozen node steps to find them. camera_tiles.comp lists
// them for each tile before the passes; the whole paths and the head then
// test a camera ray against its tile's list, or walk the tree where more
// spheres reach the tile than a list holds. The list holds every sphere
// the ray could meet and the tie rule (closest_hit.glsl) does not depend on
// the order of the tests: the same hit as the walk's, bit for bit
// (render_test). For scenes of spheres alone with a tree
// (render/path_tracer.cpp camera_tiles()).
layout(constant_id = SPEC_CAMERA_TILES) const bool CAMERA_TILES = false;
#define CAMERA_LISTS (CAMERA_TILES && (STAGE == STAGE_WHOLE || STAGE == STAGE_HEAD))
#include "shared/camera_tiles.glsl"

// The tile of the pixel whose camera ray this invocation traces (whole_pass
// and head_pass set it).
uint camera_tile = 0u;

// A camera ray's nearest hit from its tile's list, as closest_hit would
// find it (true), or false where the tile has more spheres than its list.
bool camera_list_hit(Ray ray, out Hit hit) {
  const uint count = camera_tiles[camera_tile];
  if (count == CAMERA_TILE_OVERFLOW) return false;
  start_query(INF, hit);
  if (WALK_STATS) ++walk_leaves;
  const uint list = camera_tile_total() + camera_tile * CAMERA_TILE_REFS;
  for (uint k = 0u; k < count; ++k) test_sphere(ray, camera_tiles[list + k], NO_PRIM, false, hit);
  return true;
}

// Next-event estimation at a lambertian or pbr vertex (shading/lights.glsl).
// The shadow ray is a segment of the path: a vertex at bounce b samples a
// light only if b + 1 < the bounce limit, so that with NEE on and off the
// same paths (of at most bounce_limit segments) carry light.
// what a light sample adds, f cos L / pdf times its MIS weight, in fp32 (a
// point light close to a surface may exceed half's range before the
// throughput scales it down). `pbr`: which BSDF; albedo (lambertian) or s
// (pbr) describe it. Draws from the bounce's NEE stream only.
vec3 next_event(Surface surf, Hit hit, vec3 g, vec3 n, bool pbr, real3 albedo, PbrSurface s, uint pixel_index,
                uint sample_index, uint bounce) {
  Rng rng = rng_init(pass.sample_seed, pixel_index, sample_index, bounce | NEE_STREAM);
  LightSample ls;
  if (!sample_light(surf.p, rng, ls)) return vec3(0.0);
  // A light below the geometric surface is not seen from it (no leak
  // through a thin wall whose shading normal leans toward the light).
  if (!(dot(ls.dir, g) > 0.0)) return vec3(0.0);
  vec3 f_cos;
  float bsdf_pdf;
  if (pbr) {
    if (!pbr_eval(s, ls.dir, f_cos, bsdf_pdf)) return vec3(0.0);
  } else {
    float c = dot(n, ls.dir);
    if (!(c > 0.0)) return vec3(0.0);
    f_cos = vec3(albedo) * (c / PI);
    bsdf_pdf = c / PI;
  }
  if (HAS_ALPHA) alpha_key = pcg4d(uvec4(pixel_index, sample_index, bounce | NEE_STREAM | ALPHA_STREAM, pass.sample_seed)).x;
  if (!light_visible(surf.p, surf.ng, hit.t, hit.prim, ls)) return vec3(0.0);
  float w = ls.pdf > 0.0 ? power_heuristic(ls.pdf, bsdf_pdf) : 1.0;
  return f_cos * ls.value * w;
}

// A path between two of its segments: everything trace_path carries from
// one bounce to the next, so that a path stopped after some bounce (the
// tail queue, PassParams.tail_depth) goes on in another dispatch with the
// same arithmetic in the same order: the same value, bit for bit.
struct PathState {
  Ray ray;          // the next segment's ray
  real3 radiance;   // light picked up so far (throughput x emission)
  real3 throughput;
  vec3 direct;      // next-event estimation: what light samples added (fp32)
  vec3 prev_p;      // NEE: the last vertex, and the pdf of the direction it chose
  float prev_pdf;
  uint from_prim;   // the primitive the ray leaves (NO_PRIM for a camera ray)
  bool into_from;   // whether it enters it
  bool prev_nee;    // whether the last vertex sampled a light (MIS)
  uint bounce;      // the next segment's bounce index
  uint segments;    // rays traced so far
};

PathState path_start(Ray ray) {
  PathState p;
  p.ray = ray;
  p.radiance = real3(0.0);
  p.throughput = real3(1.0);
  p.direct = vec3(0.0);
  p.prev_p = vec3(0.0);
  p.prev_pdf = 0.0;
  p.from_prim = NO_PRIM;
  p.into_from = false;
  p.prev_nee = false;
  p.bounce = 0u;
  p.segments = 0u;
  return p;
}

// What a finished path adds to its pixel.
vec3 path_value(PathState p) {
  if (NEE) return vec3(p.radiance) + p.direct;
  return vec3(p.radiance);
}

// Traces path `p` on from its next segment until it ends (true) or its next
// bounce is `bounce_end` (false: it goes on later). A path that reaches the
// bounce limit has ended.
bool trace_path(inout PathState p, uint pixel_index, uint sample_index, uint bounce_end) {
  // The loop's state in locals, as the one loop of the whole path had it.
  Ray ray = p.ray;
  real3 radiance = p.radiance;
  real3 throughput = p.throughput;
  uint from_prim = p.from_prim;
  bool into_from = p.into_from;
  vec3 direct = p.direct;
  bool prev_nee = p.prev_nee;
  vec3 prev_p = p.prev_p;
  float prev_pdf = p.prev_pdf;
  uint segments = p.segments;
  uint bounce = p.bounce;
  bool ended = true;
  for (;; ++bounce) {
    if (bounce >= bounce_end) {
      ended = bounce >= pass.bounce_limit;
      break;
    }
    Hit hit;
    ++segments;
    // BLEND's cut-out key for this ray (accel/closest_hit.glsl: alpha_cut).
    if (HAS_ALPHA) alpha_key = pcg4d(uvec4(pixel_index, sample_index, bounce | ALPHA_STREAM, pass.sample_seed)).x;
    // A camera ray: its tile's list where there is one (CAMERA_LISTS).
    bool met;
    if (CAMERA_LISTS && bounce == 0u && camera_list_hit(ray, hit)) met = hit.prim != NO_PRIM;
    else met = closest_hit(ray, from_prim, into_from, hit);
    if (!met) {
      // The sky as a light: light sampling at the last vertex could have
      // found this direction too (MIS, as emit_w below; the same form, so
      // that a weight of 1 contracts alike).
      float sky_w = 1.0;
      if (NEE && SKY_LIGHT && prev_nee) sky_w = sky_weight(prev_pdf, ray.dir);
      if (SKY != SKY_NONE) radiance += throughput * (sky_radiance(ray.dir) * real(sky_w));
      break;
    }
    Surface surf = surface_at(ray, hit);
    Material m = load_material(surf.material);
    bool mapped = HAS_NORMAL_MAPS && m.normal_texture != NO_TEXTURE;
    if (mapped) surf.ns = mapped_normal(m, surf.ns, surf.uv, surf.dpdu, surf.dpdv);
    // Sides are decided by the geometric normal; scattering uses the shading
    // normal turned to the side the ray came from.
    bool front_face = dot(ray.dir, surf.ng) < 0.0;
    // A segment that ends on a back face travelled inside what it bounds.
    if (HAS_ABSORPTION && !front_face) throughput *= transmittance(m, hit.t);
    vec3 g = front_face ? surf.ng : -surf.ng;
    vec3 n = front_face ? surf.ns : -surf.ns;
    // An interpolated shading normal can face away from the ray near a
    // silhouette, and a normal map can bend it below the horizon anywhere;
    // reflecting about it would send the path below the surface (a mirror
    // would lose it): use the geometric normal there.
    if (((HAS_VERTEX_NORMALS && scene.vertex_normals != 0u) || mapped) && dot(ray.dir, n) >= 0.0) n = g;

    // Light sampling at the last vertex could have found what this hit
    // emits: its MIS weight (1 for a camera ray, after glass or metal, or
    // for an emitter that is no light of the list).
    // emit_w multiplies the emission before the throughput does: an emission
    // times 1 is the emission, so the pipelines with and without light
    // sampling contract throughput * emission + radiance alike (auto == all
    // on drivers that fuse multiply-adds, as NVIDIA's does).
    float emit_w = 1.0;
    if (NEE && prev_nee) emit_w = emission_weight(prev_p, prev_pdf, ray, hit, surf);
    if (HAS_EMISSIVE && m.type == MAT_EMISSIVE) {
      radiance += throughput * (m.color * real(emit_w));
      break;
    }
    prev_nee = false;

    Rng rng = rng_init(pass.sample_seed, pixel_index, sample_index, bounce);
    // Directions are worked out in dreal and re-normalised in fp32 for the
    // next intersection test.
    dreal3 dn = dreal3(n);
    dreal3 d_in = dreal3(ray.dir);
    vec3 dir;
    bool refracted = false;
    if (HAS_LAMBERTIAN && m.type == MAT_LAMBERTIAN) {
      // A glTF surface emits and reflects: its emission is added here and
      // the path goes on.
      if (HAS_SURFACE_EMISSION) radiance += throughput * (surface_emission(m, surf.uv) * real(emit_w));
      real3 albedo = base_color(m, surf.uv);
      if (NEE && scene.light_count > 0u && bounce + 1u < pass.bounce_limit) {
        PbrSurface none;
        direct += vec3(throughput) * next_event(surf, hit, g, n, false, albedo, none, pixel_index, sample_index, bounce);
        prev_nee = true;
      }
      // Cosine-weighted: normal + uniform unit vector (book v4); the rare sum
      // that cancels to zero falls back to the normal.
      dir = safe_normalize(vec3(dn + dreal3(random_unit_vector(rng))), n);
      throughput *= albedo;
    } else if (HAS_METAL && m.type == MAT_METAL) {
      dreal3 d = reflect(d_in, dn);
      if (HAS_FUZZ) d += dreal(m.fuzz) * dreal3(random_unit_vector(rng));
      // A fuzzed direction below the surface is absorbed (book v4).
      if (dot(d, dn) <= dreal(0.0)) break;
      dir = safe_normalize(vec3(d), n);
      throughput *= m.color;
    } else if (HAS_DIELECTRIC && m.type == MAT_DIELECTRIC) {
      dreal eta = front_face ? dreal(1.0) / dreal(m.ior) : dreal(m.ior);
      dreal cos_theta = min(dot(-d_in, dn), dreal(1.0));
      dreal sin_theta = sqrt(max(dreal(0.0), dreal(1.0) - cos_theta * cos_theta));
      dreal u = dreal(rng_next(rng));
      // Past the critical angle refraction is impossible: reflect (TIR).
      dreal3 d;
      if (eta * sin_theta > dreal(1.0) || schlick(cos_theta, eta) > u) {
        d = reflect(d_in, dn);
      } else {
        d = refract(d_in, dn, eta);
        refracted = true;
      }
      dir = safe_normalize(vec3(d), reflect(ray.dir, n));
    } else if (HAS_PBR && m.type == MAT_PBR) {
      if (HAS_SURFACE_EMISSION) radiance += throughput * (surface_emission(m, surf.uv) * real(emit_w));
      real3 weight;
      PbrSurface s;
      // No direction: the view is exactly grazing or below the shading normal.
      if (!pbr_surface(m, surf.uv, n, -ray.dir, front_face, s)) break;
      if (NEE && scene.light_count > 0u && bounce + 1u < pass.bounce_limit) {
        direct += vec3(throughput) * next_event(surf, hit, g, n, true, real3(0.0), s, pixel_index, sample_index, bounce);
        prev_nee = true;
      }
      // Transmission's choice to reflect or pass through has a stream of its own.
      Rng layer = rng_init(pass.sample_seed, pixel_index, sample_index, bounce | TRANSMISSION_STREAM);
      // No direction: the sample went to a side where the BSDF is 0. A
      // transmitted one leaves on the far side, where light sampling finds
      // nothing (pbr_eval): an emitter it hits takes MIS weight 1.
      if (!sample_pbr(s, rng, layer, dir, weight, prev_pdf, refracted)) break;
      if (refracted) prev_nee = false;
      throughput *= weight;
    } else {
      break;  // not reached: the pipeline is specialised to the scene's materials
    }
    // A path that carries nothing any more cannot add light: stop it.
    if (all(equal(throughput, real3(0.0)))) break;
    // Russian roulette (--rr-depth): unbiased, since a surviving path is
    // weighted by 1/p.
    if (bounce + 1u >= pass.rr_depth) {
      Rng rr = rng_init(pass.sample_seed, pixel_index, sample_index, bounce | RR_STREAM);
      float p = min(float(max(max(throughput.r, throughput.g), throughput.b)), 0.95);
      if (rng_next(rr) >= p) break;
      throughput /= real(p);
    }
    // A reflection leaves on the ray's side of the geometric surface, a
    // refraction on the other. A direction on the wrong side (worked out in
    // half, a rounding error of ~1e-3 does it at grazing angles; or scattered
    // about a shading normal that leans away from the geometric one) would
    // enter an opaque surface and leak light from inside it: mirror it back
    // across the geometric tangent plane.
    if ((dot(dir, g) < 0.0) != refracted) dir = reflect(dir, g);
    // The new ray leaves into the side its direction points to.
    bool inward = dot(dir, surf.ng) < 0.0;
    ray = Ray(offset_ray_origin(surf.p, inward ? -surf.ng : surf.ng, hit.t), dir);
    from_prim = hit.prim;
    into_from = inward;
    if (NEE && prev_nee) {
      prev_p = surf.p;
      // The lambertian's cosine-weighted pdf; pbr's came from sample_pbr.
      if (m.type == MAT_LAMBERTIAN) prev_pdf = max(dot(n, dir), 0.0) / PI;
    }
  }
  p.ray = ray;
  p.radiance = radiance;
  p.throughput = throughput;
  p.from_prim = from_prim;
  p.into_from = into_from;
  p.direct = direct;
  p.prev_nee = prev_nee;
  p.prev_p = prev_p;
  p.prev_pdf = prev_pdf;
  p.segments = segments;
  p.bounce = bounce;
  return ended;
}

#include "shared/accumulate.glsl"

// Samples that lanes traced, for their pixel's first lane to add in order:
// entry gl_LocalInvocationIndex of each invocation. The array's size is the
// host's (render/path_tracer.h lane_sample_slots): the workgroup memory a
// pipeline declares sets the registers NVIDIA's compiler gives it.
layout(constant_id = SPEC_LANE_SAMPLE_SLOTS) const uint LANE_SAMPLE_SLOTS = WORKGROUP_SIZE * WORKGROUP_SIZE;
shared vec4 lane_sample[LANE_SAMPLE_SLOTS];

// --walk-stats: adds n to 64-bit count k of RenderStats.walk (shared.h), kept
// as two words: the low word's atomic add returns what it held before, so
// the one add that wraps it knows, and carries one into the high word.
void add_walk_count(uint k, uint n) {
  if (n == 0u) return;
  uint before = atomicAdd(stats.walk[2u * k], n);
  if (before + n < before) atomicAdd(stats.walk[2u * k + 1u], 1u);
}

// Adds this invocation's walk counts (accel/closest_hit.glsl) to the stats
// buffer and starts them again from 0.
void flush_walk_counts() {
  add_walk_count(WALK_QUERIES, walk_queries);
  add_walk_count(WALK_NODES, walk_nodes);
  add_walk_count(WALK_LEAVES, walk_leaves);
  add_walk_count(WALK_BOXES, walk_boxes);
  add_walk_count(WALK_PRIMITIVES, walk_primitives);
  add_walk_count(WALK_INSTANCES, walk_instances);
  add_walk_count(WALK_QUERY_SLOTS, walk_query_slots);
  add_walk_count(WALK_NODE_SLOTS, walk_node_slots);
  add_walk_count(WALK_PRIMITIVE_SLOTS, walk_primitive_slots);
  walk_queries = walk_nodes = walk_leaves = walk_boxes = walk_primitives = walk_instances = 0u;
  walk_query_slots = walk_node_slots = walk_primitive_slots = 0u;
}

// The pixel of this invocation: `lanes` invocations share a pixel (lane =
// gl_LocalInvocationIndex % lanes) and a workgroup covers an 8 x (8 / lanes)
// tile. With shifts, lanes being 1, 2, 4 or 8: divisions by a push
// constant were emulated in some 45 instructions (optimisation log 65).
uvec2 lane_pixel(uint lanes) {
  const uint shift = uint(findLSB(lanes));
  const uint local_pixel = gl_LocalInvocationIndex >> shift;
  return uvec2(gl_WorkGroupID.x * WORKGROUP_SIZE + local_pixel % WORKGROUP_SIZE,
               gl_WorkGroupID.y * (WORKGROUP_SIZE >> shift) + local_pixel / WORKGROUP_SIZE);
}

// A dispatch adds samples sample_index .. + sample_count - 1 to every pixel.
// Each pixel's state is read once, takes the samples in sample-index order
// and is written once: the same arithmetic in the same order however the
// samples are split into dispatches, so the image does not depend on it.
// `sample_lanes` invocations share a pixel: lane l traces samples l, l +
// lanes, ... and the pixel's first lane adds each round of them in order.
// One pixel whose paths are long (light trapped inside a closed mesh runs to
// the bounce limit) then costs the dispatch a path per round, not a path per
// sample.
void whole_pass() {
  const uint lanes = SAMPLE_LANES ? pass.sample_lanes : 1u;
  const uint lane = gl_LocalInvocationIndex & (lanes - 1u);
  const uvec2 pixel = lane_pixel(lanes);
  const bool in_image = pixel.x < pass.width && pixel.y < pass.height;
  const uint index = pixel.y * pass.width + pixel.x;
  if (CAMERA_LISTS) camera_tile = camera_tile_of(pixel);

  vec4 acc = vec4(0.0), sq = vec4(0.0);
  vec3 comp = vec3(0.0);
  if (in_image && lane == 0u) {
    acc = accum_sum[index];
    comp = accum_comp[index].rgb;
    sq = accum_sq[index];
  }
  for (uint first = 0u; first < pass.sample_count; first += lanes) {
    const uint s = first + lane;
    vec3 value = vec3(0.0);
    uint segments = 0u;
    // A scene with no emitter under a black sky is black: nothing to trace.
    if (in_image && s < pass.sample_count && ANY_LIGHT) {
      const uint sample_index = pass.sample_index + s;
      PathState p = path_start(camera_ray(pixel, index, sample_index));
      trace_path(p, index, sample_index, pass.bounce_limit);
      value = path_value(p);
      segments = p.segments;
      // Each count stays below 2^32 in the invocation's own word: added to
      // the buffer once one passes 2^31 (a path adds fewer than 2^31 to
      // each), which is when bit 31 of their OR is set.
      if (WALK_STATS && (walk_queries | walk_nodes | walk_leaves | walk_boxes | walk_primitives | walk_instances |
                         walk_query_slots | walk_node_slots | walk_primitive_slots) >= 0x80000000u)
        flush_walk_counts();
    }
    if (!SAMPLE_LANES || lanes == 1u) {
      if (in_image) add_sample(value, segments, acc, comp, sq);
      continue;
    }
    lane_sample[gl_LocalInvocationIndex] = vec4(value, uintBitsToFloat(segments));
    barrier();
    if (in_image && lane == 0u) {
      for (uint l = 0u; l < lanes && first + l < pass.sample_count; ++l) {
        vec4 v = lane_sample[gl_LocalInvocationIndex + l];
        add_sample(v.rgb, floatBitsToUint(v.w), acc, comp, sq);
      }
    }
    barrier();
  }
  if (WALK_STATS) flush_walk_counts();
  if (in_image && lane == 0u) {
    accum_comp[index].rgb = comp;
    accum_sum[index] = acc;
    accum_sq[index] = sq;
  }
}

// The tail queue (PassParams.tail_depth > 0; docs/design.md): a dispatch
// of samples runs as three. STAGE_HEAD traces every sample's path up to
// bounce tail_depth; a path still going on there is put in the queue (while
// it has room; past that the head finishes it itself), and every other
// sample's value goes to tail_values[s][pixel]. STAGE_TAIL takes the queue,
// one path per invocation, dense: the few long paths (light trapped in a
// closed mesh, glass and metal between close spheres) no longer hold a warp
// of short ones. accumulate.comp then adds each pixel's values in sample
// order. The arithmetic and its order are those of whole_pass: the same bits.
// A level of fewer paths than TAIL_SUBGROUP runs in STAGE_TAIL_SUBGROUP
// instead (tail_subgroup_pass).
layout(constant_id = SPEC_TAIL_SUBGROUP) const uint TAIL_SUBGROUP = 0u;
layout(std430, binding = BINDING_TAIL_VALUES) buffer TailValueBuf { vec4 tail_values[]; };
layout(std430, binding = BINDING_TAIL_QUEUE) buffer TailQueueBuf { GpuTailPath tail_queue[]; };
layout(std430, binding = BINDING_TAIL_CONTROL) buffer TailControlBuf { TailControl tail_control[]; };

const uint TAIL_INTO_FROM = 0x40000000u, TAIL_PREV_NEE = 0x80000000u;

void tail_store(uint slot, PathState p, uint index, uint s) {
  GpuTailPath q;
  q.origin = p.ray.origin;
  q.pixel = index;
  q.dir = p.ray.dir;
  q.sample_offset = s;
  q.throughput = vec3(p.throughput);
  q.bounce_flags = p.bounce | (p.into_from ? TAIL_INTO_FROM : 0u) | (p.prev_nee ? TAIL_PREV_NEE : 0u);
  q.radiance = vec3(p.radiance);
  q.segments = p.segments;
  q.direct = p.direct;
  q.from_prim = p.from_prim;
  q.prev_p = p.prev_p;
  q.prev_pdf = p.prev_pdf;
  tail_queue[slot] = q;
}

PathState tail_load(GpuTailPath q) {
  PathState p;
  p.ray = Ray(q.origin, q.dir);
  p.radiance = real3(q.radiance);
  p.throughput = real3(q.throughput);
  p.direct = q.direct;
  p.prev_p = q.prev_p;
  p.prev_pdf = q.prev_pdf;
  p.from_prim = q.from_prim;
  p.into_from = (q.bounce_flags & TAIL_INTO_FROM) != 0u;
  p.prev_nee = (q.bounce_flags & TAIL_PREV_NEE) != 0u;
  p.bounce = q.bounce_flags & ~(TAIL_INTO_FROM | TAIL_PREV_NEE);
  p.segments = q.segments;
  return p;
}

// llvmpipe (Mesa's CPU Vulkan driver) ends every loop of a shader once
// 65,535 iterations of all its loops together have run for an 8-lane
// vector of invocations (gallivm's loop limiter: one count a vector, never
// reset), so a long path over many walk steps (light trapped in a closed
// scene at a high bounce limit) is cut short there, silently: fewer
// segments, a wrong nearest hit. After that every loop runs its body once
// and leaves, so a loop that must run twice and runs once says it
// happened (in the form `while (k < bound) ++k`: a do-while's first test
// is not at its back edge there, and it ran twice anyway); its bound is 2,
// read from the stats buffer (the host writes it), so that no compiler can
// unroll the loop. On CPU devices only
// (SPEC_LOOP_LIMIT_CHECK); RenderStats.cut_paths counts the invocations.
layout(constant_id = SPEC_LOOP_LIMIT_CHECK) const bool LOOP_LIMIT_CHECK = false;
void check_loop_limit() {
  if (!LOOP_LIMIT_CHECK) return;
  uint k = 0u;
  while (k < stats.loop_bound) ++k;
  if (k < 2u) atomicAdd(stats.cut_paths, 1u);
}

// A finished path's value for accumulate.comp: sample s of the dispatch, pixel `index`.
void store_value(uint s, uint index, PathState p) {
  tail_values[s * (pass.width * pass.height) + index] = vec4(path_value(p), uintBitsToFloat(p.segments));
}

// Sizes level `level`'s dispatches for a path queued in `slot`: the tail
// stage's one workgroup per 64 slots, the subgroup stage's one per
// workgroup's subgroups among the first TAIL_SUBGROUP slots, at most 65535
// workgroups (every device's dispatch limit; the stage's loop takes the
// paths past them, and those of subgroups that come out larger).
void count_queued(uint level, uint slot) {
  if (slot % (WORKGROUP_SIZE * WORKGROUP_SIZE) == 0u) atomicAdd(tail_control[level].groups_x, 1u);
  const uint paths_per_group = max(WORKGROUP_SIZE * WORKGROUP_SIZE / gl_SubgroupSize, 1u);
  if (slot < min(TAIL_SUBGROUP, 65535u * paths_per_group) && slot % paths_per_group == 0u)
    atomicAdd(tail_control[level].subgroup_groups_x, 1u);
}

// One invocation per sample: workgroup z is the round of lanes (sample s =
// z * lanes + lane), the pixel as whole_pass maps it.
void head_pass() {
  const uint lanes = SAMPLE_LANES ? pass.sample_lanes : 1u;
  const uint lane = gl_LocalInvocationIndex & (lanes - 1u);
  const uvec2 pixel = lane_pixel(lanes);
  const uint s = gl_WorkGroupID.z * lanes + lane;
  if (pixel.x >= pass.width || pixel.y >= pass.height || s >= pass.sample_count) return;
  const uint index = pixel.y * pass.width + pixel.x;
  const uint sample_index = pass.sample_index + s;
  if (CAMERA_LISTS) camera_tile = camera_tile_of(pixel);
  PathState p = path_start(camera_ray(pixel, index, sample_index));
  // A scene with no emitter under a black sky is black: nothing to trace.
  if (ANY_LIGHT && !trace_path(p, index, sample_index, min(pass.tail_depth, pass.bounce_limit))) {
    uint slot = atomicAdd(tail_control[0].count, 1u);
    if (slot < pass.tail_capacity) {
      tail_store(slot, p, index, s);
      count_queued(0u, slot);
      if (WALK_STATS) flush_walk_counts();
      return;
    }
    trace_path(p, index, sample_index, pass.bounce_limit);  // the queue is full
  }
  if (WALK_STATS) flush_walk_counts();
  store_value(s, index, p);
}

// Tail level l (PassParams.tail_level) takes the paths queued for it, one
// per invocation, and traces each up to bounce tail_end; those still going
// on there are queued again, dense, for level l + 1, so that a warp of the
// tail holds its paths for a few bounces, not until the longest of them
// ends. The last level (tail_end >= bounce_limit) finishes them, and so
// does a level that takes fewer than tail_fill paths: packed into fewer
// warps than the GPU holds, its survivors would run each bounce at the
// pace of the slowest of 32 where, left in place, most run alone. A level
// queues at most the paths it took, so the next one never overflows.
// With TAIL_FETCH (RenderSettings::tail_fetch) an invocation takes paths
// from the level's counter instead (tail_fetch_paths).
layout(constant_id = SPEC_TAIL_FETCH) const bool TAIL_FETCH = false;

// Where a tail level's path goes once it ended (its value) or reached the
// level's last bounce `end` still going (the next level's queue).
void tail_path_done(uint level, PathState p, GpuTailPath q, bool ended) {
  if (ended) {
    store_value(q.sample_offset, q.pixel, p);
    return;
  }
  uint next = atomicAdd(tail_control[level + 1u].count, 1u);
  tail_store(((level + 1u) & 1u) * pass.tail_capacity + next, p, q.pixel, q.sample_offset);
  count_queued(level + 1u, next);
}

// The tail stage's paths taken from the level's counter (TailControl.
// fetched), a bounce at a time: an invocation whose path ended, or
// reached the level's last bounce, takes the next path at once, instead of
// idling until the longest of its warp's paths is done. The levels whose
// paths outnumber the invocations the GPU holds at once run in waves of
// warps, each warp as long as its longest path: on the H100 the engine's
// levels 1-3 0.80-0.94x and its passes 0.945x, the image the same bit for
// bit (optimisation log 152). Each round the subgroup's invocations that
// need a path take them with one atomic, and none leaves the loop before
// its subgroup's last, so that its subgroup operations see them all. Not on
// a CPU device: llvmpipe 22.3 ends a loop after 65,535 iterations counted
// over the whole invocation (optimisation log 16), which an invocation
// that takes many paths reaches, and its paths are lost.
void tail_fetch_paths(uint level, uint taken, uint end, bool first) {
  bool want = first, more = false;
  GpuTailPath q;
  PathState p;
  while (true) {
    // The round's paths for the invocations that want one: one atomic for
    // the subgroup, broadcast with every invocation active (the first that
    // wants a path need not be the subgroup's first lane).
    const uvec4 wanting = subgroupBallot(want);
    const uint n = subgroupBallotBitCount(wanting);
    if (n > 0u) {
      uint base = 0u;
      if (subgroupElect()) base = atomicAdd(tail_control[level].fetched, n);
      base = subgroupBroadcastFirst(base);
      if (want) {
        const uint slot = base + subgroupBallotExclusiveBitCount(wanting);
        more = slot < taken;
        if (more) {
          q = tail_queue[(level & 1u) * pass.tail_capacity + slot];
          p = tail_load(q);
        }
      }
    }
    if (subgroupBallotBitCount(subgroupBallot(more)) == 0u) break;
    // One bounce: trace_path stops at bounce p.bounce + 1, where a path
    // that has not ended is still going (p.bounce then is its next).
    bool ended = false;
    if (more) ended = trace_path(p, q.pixel, pass.sample_index + q.sample_offset, p.bounce + 1u);
    want = more && (ended || p.bounce >= end);
    if (want) tail_path_done(level, p, q, ended);
  }
}

void tail_pass() {
  const uint level = pass.tail_level;
  const uint slot = gl_WorkGroupID.x * (WORKGROUP_SIZE * WORKGROUP_SIZE) + gl_LocalInvocationIndex;
  const uint taken = min(tail_control[level].count, pass.tail_capacity);
  // Fewer than TAIL_SUBGROUP: the subgroup stage takes the level. More:
  // this stage does, and the subgroup stage's dispatch after it, which the
  // heads or the level before sized for the first TAIL_SUBGROUP paths,
  // launches no workgroup (the barrier between makes this write its size).
  if (TAIL_SUBGROUP > 0u && slot == 0u && taken >= TAIL_SUBGROUP) tail_control[level].subgroup_groups_x = 0u;
  if (taken < TAIL_SUBGROUP) return;
  const uint end = taken < pass.tail_fill ? pass.bounce_limit : min(pass.tail_end, pass.bounce_limit);
  if (TAIL_FETCH) {
    // Every invocation of the dispatch (one a path, in whole workgroups)
    // enters; those past the paths take none.
    tail_fetch_paths(level, taken, end, slot < taken);
  } else {
    if (slot >= taken) return;
    GpuTailPath q = tail_queue[(level & 1u) * pass.tail_capacity + slot];
    PathState p = tail_load(q);
    const bool ended = trace_path(p, q.pixel, pass.sample_index + q.sample_offset, end);
    tail_path_done(level, p, q, ended);
  }
  if (WALK_STATS) flush_walk_counts();
}

// A tail level of fewer paths than TAIL_SUBGROUP (RenderSettings::
// tail_subgroup: auto, 4 paths for each subgroup the GPU holds at once),
// which tail_pass leaves alone: each path takes a whole subgroup and is
// finished there. Every lane traces the same path with the
// same numbers, and the octree walks (accel/octree_walk.glsl, SPLIT_LEAVES)
// share each leaf's tests among the lanes, whose nearest hits a subgroup
// minimum then agrees on: the order-independent tie rule (closest_hit.glsl)
// makes that the hit one lane alone would find, so the image is the same;
// and each node step's child box tests, a child a lane, whose results a
// ballot and shuffles give every lane (accel/octree_descend.glsl).
// With fewer paths than the GPU holds, a path's bounces run one after the
// other at the pace of its walks' memory reads (optimisation log 140): a
// leaf's tests then take one round of reads instead of one per reference,
// a node's children one instead of one a child (log 142).
// The loop takes whatever paths the dispatch's subgroups did not cover.
void tail_subgroup_pass() {
  const uint level = pass.tail_level;
  const uint taken = min(tail_control[level].count, pass.tail_capacity);
  if (taken >= TAIL_SUBGROUP) return;
  for (uint slot = gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID; slot < taken;
       slot += gl_NumWorkGroups.x * gl_NumSubgroups) {
    GpuTailPath q = tail_queue[(level & 1u) * pass.tail_capacity + slot];
    PathState p = tail_load(q);
    trace_path(p, q.pixel, pass.sample_index + q.sample_offset, pass.bounce_limit);
    if (subgroupElect()) store_value(q.sample_offset, q.pixel, p);
  }
}

void main() {
  if (STAGE == STAGE_HEAD) head_pass();
  else if (STAGE == STAGE_TAIL) tail_pass();
  else if (STAGE == STAGE_TAIL_SUBGROUP) tail_subgroup_pass();
  else whole_pass();
  check_loop_limit();
}
