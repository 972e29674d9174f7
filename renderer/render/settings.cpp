#include "render/settings.h"

#include "core/errors.h"
#include "core/text.h"
#include "shared/shared.h"

namespace octrace {

const char* accel_name(Accel a) {
  switch (a) {
    case Accel::Octree: return "octree";
    case Accel::Bvh: return "bvh";
    case Accel::Brute: break;
  }
  return "brute";
}

Accel parse_accel(const std::string& name) {
  for (Accel a : {Accel::Octree, Accel::Bvh, Accel::Brute})
    if (name == accel_name(a)) return a;
  throw SettingError("accel", ": expected octree, bvh or brute, got \"" + name + "\"");
}

const char* sphere_order_name(SphereOrder o) {
  switch (o) {
    case SphereOrder::Tree: return "tree";
    case SphereOrder::Scene: return "scene";
    case SphereOrder::Auto: break;
  }
  return "auto";
}

SphereOrder parse_sphere_order(const std::string& name) {
  for (SphereOrder o : {SphereOrder::Auto, SphereOrder::Tree, SphereOrder::Scene})
    if (name == sphere_order_name(o)) return o;
  throw SettingError("octree.bvh_sphere_order", ": expected auto, tree or scene, got \"" + name + "\"");
}

const char* instancing_name(Instancing i) {
  switch (i) {
    case Instancing::Keep: return "keep";
    case Instancing::Bake: return "bake";
    case Instancing::Auto: break;
  }
  return "auto";
}

Instancing parse_instancing(const std::string& name) {
  for (Instancing i : {Instancing::Auto, Instancing::Keep, Instancing::Bake})
    if (name == instancing_name(i)) return i;
  throw SettingError("octree.instancing", ": expected auto, keep or bake, got \"" + name + "\"");
}

const char* hidden_parts_name(HiddenParts h) { return h == HiddenParts::Keep ? "keep" : "cull"; }

const char* surface_cells_name(SurfaceCells c) {
  switch (c) {
    case SurfaceCells::On: return "on";
    case SurfaceCells::Off: return "off";
    case SurfaceCells::Auto: break;
  }
  return "auto";
}

SurfaceCells parse_surface_cells(const std::string& name) {
  return parse_auto_on_off<SurfaceCells>(name, "octree.surface_cells");
}

bool bakes_every_instance(Instancing instancing, uint64_t stored, uint64_t placed) {
  if (instancing != Instancing::Auto) return instancing == Instancing::Bake;
  const uint64_t extra = placed > stored ? placed - stored : 0;
  return extra <= stored && extra <= kAutoBakeExtraTriangles;
}

const char* precision_name(Precision p) {
  switch (p) {
    case Precision::FP16: return "fp16";
    case Precision::FP16All: return "fp16-all";
    default: return "fp32";
  }
}

Precision parse_precision(const std::string& name) {
  for (Precision p : {Precision::FP32, Precision::FP16, Precision::FP16All})
    if (name == precision_name(p)) return p;
  throw SettingError("precision", ": expected fp32, fp16 or fp16-all, got \"" + name + "\"");
}

void validate_settings(const RenderSettings& s) {
  const std::string size = " " + std::to_string(s.width) + "x" + std::to_string(s.height);
  if (s.width < 1 || s.height < 1) throw SettingError("size", size + ": width and height must be >= 1");
  // The dispatch grid is at most 65535 workgroups of 8 per dimension on every
  // device we know; far above any sensible image.
  const int max_side = 65535 * int(gpu::WORKGROUP_SIZE);
  if (s.width > max_side || s.height > max_side)
    throw SettingError("size", size + ": each side must be <= " + std::to_string(max_side));
  if (s.spp < 1) throw SettingError("spp", ": must be >= 1");
  if (uint64_t(s.first_sample) + s.spp > (uint64_t(1) << 32))
    throw SettingError("first_sample", ": first sample + spp must be <= 2^32");
  if (s.spp > (1u << 24))
    throw SettingError("spp", ": must be <= 16777216 (sample counts are exact fp32 integers)");
  if (s.bounce_limit < 1) throw SettingError("bounce_limit", ": must be >= 1");
  if (s.sample_lanes > gpu::MAX_SAMPLE_LANES || (s.sample_lanes & (s.sample_lanes - 1)) != 0)
    throw SettingError("sample_lanes", ": must be 0 (auto), 1, 2, 4 or 8, got " + std::to_string(s.sample_lanes));
  if (s.octree.bvh_width != 0 && s.octree.bvh_width != 2 && s.octree.bvh_width != 4)
    throw SettingError("octree.bvh_width", ": must be 0 (auto), 2 or 4, got " + std::to_string(s.octree.bvh_width));
  if (!(s.octree.bvh_spatial_refs >= 1.0 && s.octree.bvh_spatial_refs <= 4.0))
    throw SettingError("octree.bvh_spatial_refs", ": must be between 1 (no spatial splits) and 4, got " +
                                                      float_string(s.octree.bvh_spatial_refs));
  // The subgroup stage splits the octree's leaves; over another structure
  // its lanes would only trace each path 32 times, and the walk counts
  // would take one walk for many.
  if (s.tail_subgroup != RenderSettings::kTailAuto && s.tail_subgroup != 0) {
    if (s.accel != Accel::Octree)
      throw SettingError("tail_subgroup", ": the subgroup stage splits the octree's leaves; with --accel " +
                                              std::string(accel_name(s.accel)) + " use auto or off");
    if (s.walk_stats)
      throw SettingError("tail_subgroup", ": the walk counts take one walk a path; with --walk-stats use auto or off");
  }
  check_octree_params(s.octree);
}

}  // namespace octrace
