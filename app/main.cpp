// octrace: command-line front end. Parses arguments, calls the renderer
// library, prints results. Errors from the library arrive as exceptions and
// leave as one line: exit 2 for bad input, 1 for a runtime failure.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <stdlib.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench.h"
#include "mpi_render.h"
#include "octrace_version.h"
#include "io/image.h"
#include "io/file.h"
#include "core/clock.h"
#include "core/text.h"
#include "render/gpu_scene.h"
#include "render/multi_device.h"
#include "render/path_tracer.h"
#include "render/render_state.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "view.h"
#include "vk/context.h"

using namespace octrace;
using json = nlohmann::json;

namespace {


// Whether `text` is one or more decimal digits and nothing else.
bool all_digits(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}

// What every option's value must look like before CLI11 converts it, by the
// type CLI11 reads it into; added to every option of every command at once
// (check_option_values), so no flag is left out. CLI11 reads integers with
// strtoull / strtoll in base 0: "-5" as 2^64 - 5, "0x10" as 16, "010" as 8,
// and a value too large as the largest; and it takes "" as 0 or as "not
// given". So: an empty value is refused everywhere; an integer is decimal
// digits only (a minus sign first where the type is signed), its leading
// zeros dropped, and within 64 bits; a narrower type's own limit is
// CLI11's "Could not convert" check (both say "out of range").
std::string check_option_value(std::string& value, const std::string& type) {
  if (value.empty()) return "expected a value, got an empty string";
  if (type == "FLOAT") {
    char* end = nullptr;
    if (std::isspace(static_cast<unsigned char>(value[0])) || (std::strtod(value.c_str(), &end), *end != '\0'))
      return "expected a number, got \"" + value + "\"";
    return "";
  }
  const bool is_uint = type == "UINT", is_int = type == "INT";
  if (!is_uint && !is_int) return "";
  const bool negative = is_int && value[0] == '-';
  std::string digits = value.substr(negative ? 1 : 0);
  if (!all_digits(digits))
    return std::string("expected a whole number") + (is_uint ? " >= 0" : "") + ", got \"" + value + "\"";
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
  const std::string max = is_uint ? "18446744073709551615" : negative ? "9223372036854775808" : "9223372036854775807";
  if (digits.size() > max.size() || (digits.size() == max.size() && digits > max))
    return "\"" + value + "\" is out of range";  // as CLI11's check says of a narrower type's
  value = (negative ? "-" : "") + digits;
  return "";
}

void check_option_values(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    if (opt->get_type_size() <= 0) continue;  // a flag
    const std::string full = opt->get_type_name();
    const std::string type = full.substr(0, full.find(':'));
    opt->transform(CLI::Validator([type](std::string& value) { return check_option_value(value, type); }, ""));
  }
  for (CLI::App* sub : app.get_subcommands({})) check_option_values(*sub);
}

// The images (and a --dump-scene file) written as one set
// (write_files_atomically): a failed write leaves none of them new.
void write_outputs(const Image& image, const std::vector<std::string>& outputs, const Scene* scene,
                   const std::string& dump_path) {
  std::vector<std::vector<unsigned char>> images;
  for (const auto& o : outputs) images.push_back(encode_image(image, o));
  std::vector<FileToWrite> files;
  for (size_t k = 0; k < outputs.size(); ++k)
    files.push_back({outputs[k], images[k].data(), images[k].size(), "cannot write image"});
  const std::string text = scene ? scene_to_json(*scene) : std::string();
  if (scene) files.push_back({dump_path, text.data(), text.size()});
  if (!files.empty()) write_files_atomically(files);
}

// Every file a command will write, checked before any work: each image's
// format and folder, the state's files (state_paths), the --dump-scene
// file (check_output_folder), and that no two share a path: the later would
// overwrite the earlier (`-o a.png --dump-scene a.png` left the scene's JSON
// in a.png). Paths compare as absolute, normalised paths.
void check_outputs(const std::vector<std::string>& images, const std::string& state, bool checkpoint,
                   const std::string& dump) {
  std::vector<std::pair<std::string, const char*>> named;  // (path, the flag that names it)
  for (const auto& o : images) {
    check_image_path(o);
    named.emplace_back(o, "--out");
  }
  if (!state.empty())
    for (const auto& path : state_paths(state, checkpoint)) {
      check_output_folder(path);
      named.emplace_back(path, "--state");
    }
  if (!dump.empty()) {
    check_output_folder(dump);
    named.emplace_back(dump, "--dump-scene");
  }
  std::map<std::string, const char*> seen;  // normalised path -> its flag
  for (const auto& [path, flag] : named) {
    const auto [at, fresh] = seen.emplace(std::filesystem::absolute(path).lexically_normal().string(), flag);
    if (!fresh)
      throw InputError(path + ": named twice as an output (" + at->second + " and " + flag +
                       "): the second would overwrite the first");
  }
}

// Flags that choose and describe the scene, shared by every command that renders.
struct SceneOptions {
  std::string scene_file;
  uint64_t spheres = RtiowParams{}.spheres;
  float radius = RtiowParams{}.radius;
  uint64_t seed = RtiowParams{}.seed;
  GltfOptions gltf;
  std::string dump_scene;

  void add_to(CLI::App& cmd) {
    auto* file = cmd.add_option("--scene", scene_file,
                                "Scene file: JSON (.json) or glTF (.gltf, .glb) (default: the built-in rtiow scene)");
    cmd.add_option("--spheres", spheres, "rtiow: number of small spheres")
        ->capture_default_str()
        ->excludes(file);
    cmd.add_option("--radius", radius, "rtiow: radius of the small spheres")->capture_default_str()->excludes(file);
    cmd.add_option("--seed", seed, "rtiow: scene generator seed")
        ->capture_default_str()
        ->excludes(file);
    cmd.add_option("--gltf-scene", gltf.scene, "glTF: which of the file's scenes (default: its default scene)")
        ->needs(file);
    cmd.add_option("--camera", gltf.camera,
                   "glTF: which of the file's cameras (default: its first perspective camera, else one that frames "
                   "the scene)")
        ->needs(file);
    cmd.add_option("--dump-scene", dump_scene, "Write the scene as JSON to this file");
  }

  std::string describe() const {
    if (!scene_file.empty()) return scene_file;
    char buf[128];
    std::snprintf(buf, sizeof buf, "rtiow, %llu spheres of radius %g, seed %llu", (unsigned long long)spheres,
                  radius, (unsigned long long)seed);
    return buf;
  }

  Scene load() const {
    Scene scene;
    if (scene_file.empty()) {
      scene = make_rtiow_scene({spheres, radius, seed});
    } else {
      // By extension, in any case: a .GLB from Windows tools is a .glb.
      std::string ext = std::filesystem::path(scene_file).extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (ext == ".json") {
        const char* flag = gltf.scene ? "--gltf-scene" : gltf.camera ? "--camera" : nullptr;
        if (flag) throw InputError(std::string(flag) + ": only for glTF scenes (.gltf, .glb), not " + scene_file);
        scene = load_scene_json(scene_file);
      } else if (ext == ".gltf" || ext == ".glb") {
        scene = load_gltf_scene(scene_file, gltf);
      } else {
        throw InputError(scene_file + ": unknown scene format (expected .json, .gltf or .glb)");
      }
    }
    return scene;
  }

  // --dump-scene alone, or in view: render writes it with its images (write_outputs).
  void write_dump(const Scene& scene) const {
    if (!dump_scene.empty()) save_scene_json(scene, dump_scene);
  }
};

// "488 spheres, 3 meshes, 5 instances, 1200 triangles (800 unique), 4 materials, 2 textures";
// the mesh part only when there are meshes, the textures only when there are some.
std::string scene_summary(const Scene& scene) {
  std::string out = std::to_string(scene.spheres.size()) + " spheres, ";
  if (!scene.meshes.empty())
    out += std::to_string(scene.meshes.size()) + " meshes, " + std::to_string(scene.instances.size()) +
           " instances, " + std::to_string(instanced_triangle_count(scene)) + " triangles (" +
           std::to_string(unique_triangle_count(scene)) + " unique), ";
  out += std::to_string(scene.materials.size()) + " materials";
  if (!scene.textures.empty()) out += ", " + std::to_string(scene.textures.size()) + " textures";
  return out;
}

// Whether some mesh is placed more than once (--instancing decides what the device stores of it).
bool shares_meshes(const Scene& scene) { return instanced_triangle_count(scene) > unique_triangle_count(scene); }

// What --instancing comes to for this scene: bake (every instance in world
// space) or keep (shared meshes stored once), as the upload decides it.
Instancing resolved_instancing(const Scene& scene, const RenderSettings& settings) {
  return bakes_every_instance(scene, settings.octree.instancing) ? Instancing::Bake : Instancing::Keep;
}

// Parses "WxH": two decimal integers; values beyond int range are reported
// as too large rather than wrapped.
void parse_size(const std::string& text, RenderSettings& s) {
  auto x = text.find('x');
  auto digits = [](const std::string& t) { return t.size() <= 9 && all_digits(t); };
  if (x == std::string::npos || !digits(text.substr(0, x)) || !digits(text.substr(x + 1)))
    throw InputError("--size: expected WIDTHxHEIGHT with each side at most 9 digits (e.g. 1200x800), got \"" +
                     text + "\"");
  s.width = std::stoi(text.substr(0, x));
  s.height = std::stoi(text.substr(x + 1));
}

struct RenderOptions {
  std::string size = "1200x800";
  std::string accel = "octree";
  std::string precision = "fp32";
  std::string effects = "auto";
  std::string nee = "on";
  std::string octant_culling = "auto";
  std::string camera_tiles = "auto";
  std::string bvh_walk = "auto";
  std::string tail_depth = "auto";
  std::string tail_step = "auto";
  std::string tail_fill = "auto";
  std::string tail_subgroup = "auto";
  std::string tail_fetch = "auto";
  std::string bvh_sphere_order = "auto";
  std::string instancing = "auto";
  std::string hidden_parts = "auto";
  std::string surface_cells = "auto";
  RenderSettings settings;
  std::string device = "auto";
  bool validation = false;
  bool pipeline_stats = false;
  bool robust_buffers = false;

  void add_to(CLI::App& cmd) {
    cmd.add_option("--accel", accel, "Acceleration structure: octree | bvh | brute")->capture_default_str();
    cmd.add_option("--precision", precision, "Shading precision: fp32 | fp16 | fp16-all (see README)")
        ->capture_default_str();
    cmd.add_option("--effects", effects,
                   "auto: a pipeline specialised to the scene's effects; all: the general pipeline")
        ->capture_default_str();
    cmd.add_option("--octree-leaf", settings.octree.leaf_size,
                   "Octree: split cells holding more primitives than this (0: auto, 10; 16 where the octant culling's "
                   "auto is off: scenes without triangles on lavapipe from Mesa 25; 24 for scenes without triangles "
                   "on a GPU); same image, other speed")
        ->capture_default_str();
    cmd.add_option("--octree-depth", settings.octree.max_depth, "Octree: maximum depth")->capture_default_str();
    cmd.add_option("--octree-refs", settings.octree.max_refs,
                   "Octree: references per primitive, at most (1..64; 0: auto, 8, but for scenes with triangles on "
                   "a GPU 12 with copy leaves: cells of at most 20 that a long triangle spans stay leaves, and a "
                   "tree over 48 bytes per primitive is built again at 8): more lets clipped meshes split "
                   "further, fewer triangle tests for more memory (against the auto's tree on the H100, 16: the "
                   "engine's passes 5.5% faster at 82 instead of 46 bytes per triangle, 24: 6.8% at 95); same "
                   "image")
        ->capture_default_str();
    cmd.add_option("--bvh-width", settings.octree.bvh_width,
                   "BVH (--accel bvh): children per node, 2 or 4 (0: auto, four-wide over meshes on a GPU, "
                   "binary over spheres and on a CPU device); same image, other speed")
        ->capture_default_str();
    cmd.add_option("--bvh-spatial-refs", settings.octree.bvh_spatial_refs,
                   "BVH (--accel bvh) over a mesh: references per triangle, at most, that spatial splits may make "
                   "(1..4; 1: none, the plain binned SAH): more memory and build time for fewer box and triangle "
                   "tests; same image, other speed")
        ->capture_default_str();
    cmd.add_option("--bvh-sphere-order", bvh_sphere_order,
                   "BVH (--accel bvh) over spheres alone: the device holds the spheres in the tree's order (a leaf "
                   "tests its spheres without reading its references) or the scene's; auto: the tree's on a GPU, "
                   "the scene's on a CPU device; same image, other speed")
        ->capture_default_str();
    cmd.add_option("--instancing", instancing,
                   "Meshes placed several times: keep (stored once, walked in object space), bake (a world-space "
                   "copy per placement: more memory; the octree faster, a GPU's four-wide BVH a little slower), "
                   "auto (bake where that at most doubles the stored triangles and adds at most 2^20)")
        ->capture_default_str();
    cmd.add_option("--hidden-parts", hidden_parts,
                   "Spheres that overlap opaque ones: cull (the trees hold only the parts no opaque sphere "
                   "covers: a dense field tests a few spheres a ray instead of a hundred), keep (whole spheres), "
                   "auto (cull where the camera stays: render and bench; keep in view, whose camera moves, and "
                   "which refuses cull); "
                   "other speed, and in dense overlapping fields a few values in millions differ (keep: the "
                   "image of whole spheres, bit for bit)")
        ->capture_default_str();
    cmd.add_option("--octree-surfaces", surface_cells,
                   "Octree, where --hidden-parts left parts out: on (cells follow the spheres' surfaces, which "
                   "parts a dense field's top caps from its bottom ones: the 1M field's passes 0.77x on an H100, "
                   "for 4.7 references a sphere instead of 1.6 and a longer build), off, or auto (on for a GPU "
                   "where the render has at least 576M samples, 600 spp at 1200x800, from which the faster passes "
                   "pay for the build on an H100; off for a CPU device, where the passes gain nothing at 1M); the "
                   "same image but for a few values in millions "
                   "(paths that enter glass where it meets an opaque sphere, log 125)")
        ->capture_default_str();
    cmd.add_option("--size", size, "Image size WIDTHxHEIGHT")->capture_default_str();
    cmd.add_option("--spp", settings.spp, "Samples (passes) per pixel")->capture_default_str();
    cmd.add_option("--depth", settings.bounce_limit, "Bounce limit; a path that reaches it contributes 0")
        ->capture_default_str();
    cmd.add_option("--sample-seed", settings.sample_seed, "Seed of the sampler (independent noise)")
        ->capture_default_str();
    cmd.add_option("--first-sample", settings.first_sample,
                   "First sample index: runs over disjoint ranges merge into one render (octrace merge)")
        ->capture_default_str();
    cmd.add_option("--rr-depth", settings.rr_depth,
                   "Russian roulette from this bounce on (0: off; changes the noise, not the expectation)")
        ->capture_default_str();
    cmd.add_option("--nee", nee,
                   "Next-event estimation with MIS: on | off (off: light is found only by hitting it, and point, "
                   "spot and directional lights add nothing)")
        ->capture_default_str();
    cmd.add_option("--samples-per-dispatch", settings.samples_per_dispatch,
                   "Samples each GPU dispatch adds per pixel (0: a whole batch in one); same image, other speed")
        ->capture_default_str();
    cmd.add_option("--sample-lanes", settings.sample_lanes,
                   "Invocations sharing a pixel's samples in a dispatch: 1, 2, 4, 8 (0: auto: 4, 8 for "
                   "triangles without the tail queue, 2 or 1 where a dispatch's samples would leave 4 lanes "
                   "idle, 1 on a CPU device); same image")
        ->capture_default_str();
    cmd.add_option("--octant-culling", octant_culling,
                   "Octree walk: skip children in octants the ray cannot reach: auto | on | off (auto: on, but "
                   "off for scenes without triangles on lavapipe from Mesa 25); same image, other speed")
        ->capture_default_str();
    cmd.add_option("--camera-tiles", camera_tiles,
                   "Camera rays tested against the spheres their 8x8-pixel tile can see, listed on the device "
                   "for each batch's camera, instead of walking the tree: auto | on | off (auto: on for scenes "
                   "of spheres alone with the octree or the BVH, up to 1,024 spheres on a CPU device, on a GPU "
                   "8,192 with the octree and 4,096 with the BVH); same image, other speed")
        ->capture_default_str();
    cmd.add_option("--bvh-walk", bvh_walk,
                   "BVH (--accel bvh): the top level's binary walk: auto | one-loop | while-while (auto: "
                   "while-while on a GPU where its leaves hold 4 or more references on average, as in dense "
                   "sphere fields; one loop otherwise); same image, other speed")
        ->capture_default_str();
    cmd.add_option("--tail-depth", tail_depth,
                   "Tail queue: paths still going at this bounce finish in a dispatch of their own: auto | off | "
                   "BOUNCE (auto: " + std::to_string(kTailDepthDefault) +
                       " on a GPU; on a CPU device " + std::to_string(kTailDepthDefault) + " above --depth " +
                       std::to_string(kCpuWholePathBounces) +
                       ", else no queue, one sample per invocation); same image")
        ->capture_default_str();
    cmd.add_option("--tail-step", tail_step,
                   "Tail levels: the first tail dispatch traces its paths this many bounces on, each next twice "
                   "as many, and each queues those still going, dense, for the next (at most " +
                       std::to_string(kMaxTailLevels) + " levels): auto | off | BOUNCES (auto: " +
                       std::to_string(kTailStepDefault) +
                       ", with triangles on a GPU only where a fill applies (--tail-fill); off: one tail finishes every "
                       "path); "
                       "same image")
        ->capture_default_str();
    cmd.add_option("--tail-fill", tail_fill,
                   "Tail levels: a level that takes fewer paths than this finishes them rather than queuing "
                   "those still going for the next: auto | off | PATHS (auto: --tail-subgroup's where there is one, "
                   "else the threads the GPU holds at once, where its driver says; off: every level but the last "
                   "queues them); same image")
        ->capture_default_str();
    cmd.add_option("--tail-subgroup", tail_subgroup,
                   "Tail levels: a level that takes fewer paths than this gives each path a whole subgroup, whose "
                   "lanes share the octree's leaf and child box tests: auto | off | PATHS (auto: with tail levels and the "
                   "octree, "
                   "for scenes with triangles, on a GPU whose driver says how many threads it holds at once, " +
                       std::to_string(kTailSubgroupPaths) +
                       " paths for each subgroup it holds, where a subgroup has 8 to 64 lanes; off with "
                       "--walk-stats; a count needs the octree, no --walk-stats and subgroups of 8 to 64 lanes); "
                       "same image")
        ->capture_default_str();
    cmd.add_option("--tail-fetch", tail_fetch,
                   "Tail queue: the tail stage's invocations take their level's paths from a counter, a bounce at "
                   "a time, so that one whose path ended takes the next at once: auto | on | off (auto: on a GPU "
                   "for scenes with triangles, or of at least " + std::to_string(kTailFetchSpheresOctree) +
                       " spheres with the octree, " + std::to_string(kTailFetchSpheresBvh) +
                       " with the BVH; on is refused on a CPU device, whose llvmpipe ends a loop after "
                   "65,535 iterations over the whole invocation); same image, other speed")
        ->capture_default_str();
    cmd.add_option("--device", device, "auto | cpu | gpu | INDEX (see `octrace devices`)")->capture_default_str();
    cmd.add_flag("--validation", validation, "Enable the Khronos validation layer (also OCTRACE_VALIDATION=1)");
    cmd.add_flag("--pipeline-stats", pipeline_stats,
                 "Print the driver's statistics of the compiled path-tracing pipeline (registers, spills, ...; "
                 "VK_KHR_pipeline_executable_properties)");
    cmd.add_flag("--robust-buffers", robust_buffers,
                 "Keep the driver's bounds checks on buffer accesses (by default pipelines are created without "
                 "them where the device has VK_EXT_pipeline_robustness; same image)");
  }

  // --tail-depth, --tail-step, --tail-fill and --tail-subgroup: auto
  // (RenderSettings::kTailAuto), off (0) or a count from 1 to `max`;
  // `what` names the count in the message.
  static uint32_t parse_tail_count(const std::string& text, const std::string& setting, const std::string& what,
                                   unsigned long max = 100000) {
    if (text == "auto") return RenderSettings::kTailAuto;
    if (text == "off") return 0;
    char* end = nullptr;
    const unsigned long v = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || text[0] == '-' || v < 1 || v > max)
      throw SettingError(setting, ": expected auto, off or " + what + " from 1 to " + std::to_string(max) +
                                      ", got \"" + text + "\"");
    return uint32_t(v);
  }

  // `moving_camera`: for view, whose camera moves: auto keeps whole
  // spheres there, and cull is refused.
  RenderSettings parsed(bool moving_camera = false) const {
    RenderSettings s = settings;
    if (hidden_parts != "auto" && hidden_parts != "cull" && hidden_parts != "keep")
      throw SettingError("octree.hidden_parts", ": expected auto, cull or keep, got \"" + hidden_parts + "\"");
    s.octree.hidden_parts = hidden_parts == "keep" || (hidden_parts == "auto" && moving_camera) ? HiddenParts::Keep
                                                                                             : HiddenParts::Cull;
    if (moving_camera && s.octree.hidden_parts == HiddenParts::Cull)
      throw SettingError("octree.hidden_parts", ": cull needs a camera that stays where it is; view's moves "
                                                "(use auto or keep)");
    s.accel = parse_accel(accel);
    s.precision = parse_precision(precision);
    if (effects != "auto" && effects != "all")
      throw SettingError("effects", ": expected auto or all, got \"" + effects + "\"");
    s.all_effects = effects == "all";
    s.octree.bvh_sphere_order = parse_sphere_order(bvh_sphere_order);
    s.octree.instancing = parse_instancing(instancing);
    s.octree.surface_cells = parse_surface_cells(surface_cells);
    if (nee != "on" && nee != "off") throw SettingError("nee", ": expected on or off, got \"" + nee + "\"");
    s.nee = nee == "on";
    s.camera_tiles = parse_auto_on_off<CameraTiles>(camera_tiles, "camera_tiles");
    s.octant_culling = parse_auto_on_off<OctantCulling>(octant_culling, "octant_culling");
    if (bvh_walk != "auto" && bvh_walk != "one-loop" && bvh_walk != "while-while")
      throw SettingError("bvh_walk", ": expected auto, one-loop or while-while, got \"" + bvh_walk + "\"");
    s.bvh_walk = bvh_walk == "auto" ? BvhWalk::Auto : bvh_walk == "one-loop" ? BvhWalk::OneLoop : BvhWalk::WhileWhile;
    s.tail_depth = parse_tail_count(tail_depth, "tail_depth", "a bounce");
    s.tail_step = parse_tail_count(tail_step, "tail_step", "a bounce count");
    s.tail_fill = parse_tail_count(tail_fill, "tail_fill", "a path count", 1000000000);
    s.tail_subgroup = parse_tail_count(tail_subgroup, "tail_subgroup", "a path count", 1000000000);
    s.tail_fetch = parse_auto_on_off<TailFetch>(tail_fetch, "tail_fetch");
    parse_size(size, s);
    validate_settings(s);
    return s;
  }
};

// The library names a setting as its API does ("octree.leaf_size"); the user
// typed a flag, so its message names the flag. A setting without one is
// printed as the library named it.
std::string message_for_cli(const SettingError& e) {
  static const std::map<std::string, std::string> flags = {
      {"size", "--size"},
      {"spp", "--spp"},
      {"bounce_limit", "--depth"},
      {"first_sample", "--first-sample"},
      {"rr_depth", "--rr-depth"},
      {"sample_lanes", "--sample-lanes"},
      {"sample_seed", "--sample-seed"},
      {"octree.leaf_size", "--octree-leaf"},
      {"octree.max_depth", "--octree-depth"},
      {"octree.max_refs", "--octree-refs"},
      {"octree.bvh_width", "--bvh-width"},
      {"octree.bvh_spatial_refs", "--bvh-spatial-refs"},
      {"octree.bvh_sphere_order", "--bvh-sphere-order"},
      {"octree.instancing", "--instancing"},
      {"octree.hidden_parts", "--hidden-parts"},
      {"octree.surface_cells", "--octree-surfaces"},
      {"precision", "--precision"},
      {"accel", "--accel"},
      {"effects", "--effects"},
      {"nee", "--nee"},
      {"octant_culling", "--octant-culling"},
      {"camera_tiles", "--camera-tiles"},
      {"bvh_walk", "--bvh-walk"},
      {"tail_depth", "--tail-depth"},
      {"tail_step", "--tail-step"},
      {"tail_fill", "--tail-fill"},
      {"tail_subgroup", "--tail-subgroup"},
      {"tail_fetch", "--tail-fetch"},
      {"device", "--device"},
      {"rtiow.radius", "--radius"},
      {"rtiow.spheres", "--spheres"},
      {"gltf.scene", "--gltf-scene"},
      {"gltf.camera", "--camera"},
  };
  std::string message = e.what();
  if (auto it = flags.find(e.setting); it != flags.end()) message.replace(0, e.setting.size(), it->second);
  if (e.setting == "device") message += " (see `octrace devices`)";
  return message;
}

constexpr Precision kPrecisions[] = {Precision::FP32, Precision::FP16, Precision::FP16All};

DeviceRequirements requirements_of(Precision p) { return {p != Precision::FP32, false}; }

// What the device is, and which precision variants it runs (with every
// requirement it fails for those it does not).
json device_json(const DeviceInfo& d) {
  json j = {{"index", d.index},           {"name", d.name},
            {"type", d.type},             {"driver", d.driver},
            {"api_version", d.api_version}, {"software", d.software},
            {"shader_float16", d.shader_float16}, {"storage_buffer_16bit_access", d.storage_16bit},
            {"fp16_variant", d.supports_fp16()}, {"pipeline_robustness", d.pipeline_robustness},
            {"resident_threads", d.resident_threads}, {"subgroup_size", d.subgroup_size},
            {"subgroup_operations", missing_subgroup_operations(d).empty()},
            {"cpu_threads", d.cpu_threads}};
  for (Precision p : kPrecisions) {
    auto unmet = unmet_requirements(d, requirements_of(p));
    j["variants"][precision_name(p)] = unmet.empty();
    j["unmet"][precision_name(p)] = unmet;
  }
  return j;
}

// A progress line on stderr, rewritten in place on a terminal and printed at
// most every few seconds otherwise; silent for renders under about a second.
// Ctrl-C (SIGINT) and SIGTERM during a render or the preview: the first
// asks the work to stop after the batch in flight (the outputs are written
// with the samples reached); a second ends the process at once, removing a
// file half written, with the exit code of the signal.
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};

extern "C" void on_stop_signal(int sig) {
  if (g_stop.load()) {
    remove_file_being_written();
    _exit(128 + sig);
  }
  g_signal = sig;
  g_stop = true;
}

// Installs on_stop_signal for SIGINT and SIGTERM while it lives.
class SignalGuard {
 public:
  SignalGuard() {
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~SignalGuard() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

class Progress {
 public:
  explicit Progress(bool enabled) : enabled_(enabled), tty_(isatty(STDERR_FILENO)) {}

  void update(uint32_t done, uint32_t total) {
    if (!enabled_) return;
    double elapsed = ms_since(start_) / 1000.0;
    double eta = done ? elapsed * (total - done) / done : 0.0;
    // Show only renders that take, or will take, more than about a second.
    if (elapsed + eta < 1.0 && !shown_) return;
    if (!tty_ && done < total && elapsed - last_ < 5.0 && shown_) return;
    last_ = elapsed;
    shown_ = true;
    std::fprintf(stderr, "%srender: %u/%u passes  %.1f s elapsed  ETA %.1f s%s", tty_ ? "\r" : "", done, total,
                 elapsed, eta, tty_ ? "\033[K" : "\n");
    if (tty_ && done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
  }

 private:
  bool enabled_, tty_;
  bool shown_ = false;
  double last_ = 0;
  Clock::time_point start_ = Clock::now();
};

// --device: "all" is every GPU (every device where there is none); a
// comma-separated list names devices by index (one may repeat: two logical
// devices on one physical device); anything else is one selection.
std::vector<std::string> device_selections(const std::string& device) {
  std::vector<std::string> out;
  if (device == "all") {
    const std::vector<DeviceInfo> infos = list_devices();
    for (const DeviceInfo& d : infos)
      if (!d.software) out.push_back(std::to_string(d.index));
    if (out.empty())
      for (const DeviceInfo& d : infos) out.push_back(std::to_string(d.index));
    if (out.empty()) out.push_back("auto");
    return out;
  }
  if (device.find(',') == std::string::npos) return {device};
  size_t at = 0;
  for (;;) {
    const size_t comma = device.find(',', at);
    const std::string item = device.substr(at, comma - at);
    if (!all_digits(item))
      throw InputError("--device: expected a list of device indices like 0,2, got \"" + device + "\"");
    out.push_back(item);
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return out;
}

// The MPI front end's rank and device choice; a build without MPI is rank 0
// of one.
int mpi_rank() {
#ifdef OCTRACE_MPI
  if (mpi::active()) return mpi::rank();
#endif
  return 0;
}

std::string mpi_device(const std::string& requested) {
#ifdef OCTRACE_MPI
  return mpi::device_for_rank(requested);
#else
  return requested;
#endif
}

// The settings a checkpoint must match (render_state.h); the scene's hash
// is known once it is on the device.
CheckpointInfo checkpoint_info(const RenderSettings& s) {
  CheckpointInfo info;
  info.width = s.width;
  info.height = s.height;
  info.sample_seed = s.sample_seed;
  info.first_sample = s.first_sample;
  info.bounce_limit = s.bounce_limit;
  info.rr_depth = s.rr_depth;
  info.precision = precision_name(s.precision);
  info.accel = accel_name(s.accel);
  return info;
}

int cmd_render(SceneOptions scene_opts, const RenderOptions& render_opts, std::vector<std::string> outputs,
               std::string state, double checkpoint_seconds, std::string resume_prefix, double batch_ms, bool as_json,
               bool quiet) {
  // Everything the user typed is checked before the (possibly long) render.
  RenderSettings settings = render_opts.parsed();
#ifdef OCTRACE_MPI
  // Under mpirun only rank 0 reports and writes; the others render their share.
  const bool under_mpi = mpi::active();
  if (under_mpi) {
    if (settings.walk_stats) throw InputError("--walk-stats counts the walks of one process: run it without MPI");
    if (settings.dispatch_times)
      throw InputError("--dispatch-times times the dispatches of one process: run it without MPI");
    if (outputs.empty() && state.empty() && !scene_opts.dump_scene.empty())
      throw InputError("--dump-scene: under MPI give --out or --state too (there is nothing to render)");
    if (mpi::rank() != 0) {
      quiet = true;
      as_json = false;
      outputs.clear();  // only rank 0 writes
      state.clear();
      checkpoint_seconds = 0;  // rank 0 writes the merged checkpoints
      scene_opts.dump_scene.clear();
      resume_prefix.clear();  // rank 0 continues the state
    }
  }
#else
  const bool under_mpi = false;
#endif
  if (batch_ms < 0 || std::isnan(batch_ms) || std::isinf(batch_ms))
    throw InputError("--batch-ms: must be a number of milliseconds > 0");
  if (batch_ms > 0 && !under_mpi)
    throw InputError("--batch-ms: sizes the batches of an MPI job's ranks only (mpirun -np N octrace render ...)");
  const bool writes = !under_mpi || mpi_rank() == 0;
  if (writes && outputs.empty() && scene_opts.dump_scene.empty() && state.empty()) outputs.push_back("out.png");
  check_outputs(outputs, state, true, scene_opts.dump_scene);
  if (checkpoint_seconds < 0 || std::isnan(checkpoint_seconds))
    throw InputError("--checkpoint: must be a number of seconds >= 0");
  if (checkpoint_seconds > 0 && state.empty())
    throw InputError("--checkpoint: needs --state PREFIX (where the checkpoints go)");
  // A state to resume is read and checked against the settings now; against
  // the scene once it is on the device.
  CheckpointInfo resumed;
  Accumulation resumed_acc;
  if (!resume_prefix.empty()) {
    resumed_acc = read_checkpoint(resume_prefix, resumed);
    CheckpointInfo current = checkpoint_info(settings);
    current.scene_hash = resumed.scene_hash;  // compared after the upload
    if (std::string why = checkpoint_mismatch(resumed, current); !why.empty())
      throw InputError(resume_prefix + ".accum: cannot resume: " + why);
    // Fewer would write a state whose header counts fewer samples than its pixels hold.
    if (resumed.samples > settings.spp)
      throw InputError(resume_prefix + ".accum: cannot resume: it holds " + std::to_string(resumed.samples) +
                       " spp, more than --spp " + std::to_string(settings.spp));
  }

  auto start = Clock::now();
  Scene scene = scene_opts.load();
  double scene_ms = ms_since(start);
  if (!under_mpi && outputs.empty() && state.empty()) {  // only --dump-scene
    scene_opts.write_dump(scene);
    return 0;
  }

  start = Clock::now();
  // --device all | 0,2: one context per device, the first one the main one.
  // Under MPI: this rank's one device.
  const std::vector<std::string> device_list =
      under_mpi ? std::vector<std::string>{mpi_device(render_opts.device)} : device_selections(render_opts.device);
  if (device_list.size() > 1 && (!state.empty() || !resume_prefix.empty()))
    throw InputError("--device " + render_opts.device +
                     ": --state, --checkpoint and --resume work with one device only (use octrace merge)");
  VulkanContext ctx;
  ContextOptions context_opts{device_list[0], settings.precision != Precision::FP32, render_opts.validation};
  context_opts.pipeline_statistics = render_opts.pipeline_stats;
  context_opts.robust_buffers = render_opts.robust_buffers;
  create_context(ctx, context_opts);
  std::vector<std::unique_ptr<VulkanContext>> more_contexts;
  for (size_t k = 1; k < device_list.size(); ++k) {
    ContextOptions o = context_opts;
    o.device = device_list[k];
    more_contexts.push_back(std::make_unique<VulkanContext>());
    create_context(*more_contexts.back(), o);
  }
  if (render_opts.pipeline_stats && !ctx.pipeline_statistics)
    print_warning(ctx.info.name + " has no VK_KHR_pipeline_executable_properties: no pipeline statistics");
  double device_ms = ms_since(start);
  if (ctx.info.software && !quiet && !as_json) std::fprintf(stderr, "octrace: %s\n", software_device_note(ctx.info).c_str());
  if (std::string w = software_loop_limit_warning(ctx.info, scene, settings); !w.empty()) print_warning(w);
  if (std::string w = punctual_without_nee_warning(scene, settings); !w.empty()) print_warning(w);

  Progress progress(!quiet);
  RenderControl control;
  control.progress = [&](uint32_t d, uint32_t t) { progress.update(d, t); };
  control.stop = &g_stop;
  const CheckpointInfo now = checkpoint_info(settings);
  Accumulation resume;
  if (!resume_prefix.empty()) {
    control.resume = &resume;
    control.resume_samples = resumed.samples;
    control.check_resume = [&](uint64_t hash) {
      CheckpointInfo current = now;
      current.scene_hash = hash;
      std::string why = checkpoint_mismatch(resumed, current);
      if (why.empty()) return;
      // The device's triangles of a scene with shared meshes depend on
      // --instancing: a state saved the other way has another scene's hash.
      if (resumed.scene_hash != hash && shares_meshes(scene))
        why += resolved_instancing(scene, settings) == Instancing::Bake
                   ? " (its shared meshes are baked into world space now: a state saved with them stored once, "
                     "or before --instancing existed, resumes with --instancing keep)"
                   : " (its shared meshes are stored once now: a state saved with them baked resumes with "
                     "--instancing bake)";
      throw InputError(resume_prefix + ".accum: cannot resume: " + why);
    };
    resume = std::move(resumed_acc);
  }
  std::string last_checkpoint;  // named in the message if the device fails later
  if (!state.empty()) {
    control.checkpoint_seconds = checkpoint_seconds > 0 ? checkpoint_seconds : HUGE_VAL;
    control.checkpoint = [&](const Accumulation& acc, uint32_t samples, uint64_t hash) {
      CheckpointInfo info = now;
      info.scene_hash = hash;
      info.samples = samples;
      write_checkpoint(state, acc, info, state_of(acc));
      last_checkpoint = state + " (" + std::to_string(samples) + " spp)";
    };
  }
  SignalGuard signals;
  RenderResult result;
  std::vector<DeviceShare> shares;
  mpi::Gathered gathered;  // under MPI: what each rank did
  try {
    if (under_mpi) {
#ifdef OCTRACE_MPI
      // This rank's share of the job's batches; rank 0 merges the states.
      struct ForgetCallbacks {
        ~ForgetCallbacks() { mpi::clear_callbacks(); }
      } forget;  // they refer to this function's locals
      mpi::set_work(settings.spp, control.resume_samples, control.progress);
      auto setup_start = Clock::now();
      PathTracer tracer(ctx, scene, settings);
      if (control.resume) {
        control.check_resume(tracer.scene_hash());
        tracer.write_accumulation(*control.resume);
      }
      if (!state.empty() && checkpoint_seconds > 0)
        mpi::set_checkpoint(checkpoint_seconds, settings.width, settings.height,
                            [&, hash = tracer.scene_hash()](const Accumulation& acc, uint32_t samples) {
                              control.checkpoint(acc, samples, hash);
                            });
      mpi::RankShare share;
      share.device = ctx.info.name;
      share.device_uuid = ctx.info.uuid;
      share.device_software = ctx.info.software;
      share.setup_ms = device_ms + ms_since(setup_start);
      share.device_init_ms = device_ms;
      share.accel_build_ms = tracer.setup_timings().accel_build_ms;
      share.upload_ms = tracer.setup_timings().upload_ms;
      share.pipeline_ms = tracer.setup_timings().pipeline_ms;
      mpi::render_share(tracer, pass_settings(scene, settings), settings.first_sample, batch_ms, &g_stop, &g_signal,
                        share);
      CheckpointInfo info = now;
      info.scene_hash = tracer.scene_hash();
      // After the job's decision this rank's failure could no longer fail it.
      if (uint32_t n = validation_message_count())
        throw RuntimeError("the Vulkan validation layer reported " + std::to_string(n) + " message(s)");
      const RenderCounts counts = tracer.counts();
      if (!mpi::gather(tracer.read_accumulation(), counts.nonfinite_samples, counts.cut_paths, share, info, gathered))
        return 0;
      const Accumulation& merged = gathered.merged;
      result.timings = tracer.setup_timings();
      result.octree = tracer.octree_stats();
      result.features = tracer.features();
      resolve_accumulation(merged, result);
      result.nonfinite_samples = gathered.nonfinite_samples;
      result.cut_paths = gathered.cut_paths;
      result.samples = gathered.samples;
      result.interrupted = gathered.interrupted;
      if (result.interrupted) g_signal = gathered.signal;
      result.timings.readback_ms = gathered.reduce.total_ms;
      for (const mpi::RankShare& r : gathered.shares) {
        result.timings.render_device_ms = std::max(result.timings.render_device_ms, r.device_ms);
        result.timings.render_wall_ms = std::max(result.timings.render_wall_ms, r.wall_ms);
      }
      if (!state.empty()) {
        info.samples = result.samples;
        write_checkpoint(state, merged, info, state_of(merged));
      }
#endif
    } else if (!more_contexts.empty()) {
      std::vector<const VulkanContext*> contexts = {&ctx};
      for (const auto& c : more_contexts) contexts.push_back(c.get());
      result = render_on_devices(contexts, scene, settings, control, shares);
    } else {
      result = render(ctx, scene, settings, control);
    }
  } catch (const SceneSizeError& e) {
    if (scene_opts.scene_file.empty()) throw;
    throw SceneSizeError(scene_opts.scene_file + ": " + e.what());
  } catch (const RuntimeError& e) {
    if (last_checkpoint.empty()) throw;
    throw RuntimeError(std::string(e.what()) + "; the last checkpoint is " + last_checkpoint + ": resume with --resume " +
                       state);
  }

  // A CPU device that cut paths short (RenderResult::cut_paths) rendered an
  // image that is wrong where they were: said even with -q, as brute
  // force's caveat is.
  if (result.cut_paths)
    print_warning(cut_paths_note(result.cut_paths) +
                  " (the image is wrong there); render with --tail-depth 2 --tail-step 1 (fewer bounces a "
                  "dispatch), a lower --depth, or on a GPU");
  start = Clock::now();
  write_outputs(result.mean, outputs, scene_opts.dump_scene.empty() ? nullptr : &scene, scene_opts.dump_scene);
  double write_ms = ms_since(start);
  const int exit_code = result.interrupted ? 128 + g_signal.load() : 0;
  if (result.interrupted && !as_json)
    std::fprintf(stderr, "octrace: interrupted (%s) at %u of %u spp; the outputs hold the samples reached%s\n",
                 g_signal.load() == SIGTERM ? "SIGTERM" : "SIGINT", result.samples, settings.spp,
                 state.empty() ? "" : (", and the state " + state + " resumes it (--resume)").c_str());

  const RenderTimings& t = result.timings;
  double paths = double(settings.width) * settings.height * (result.samples - std::min(result.samples, control.resume_samples));
  double paths_per_s = t.render_device_ms > 0 ? paths / (t.render_device_ms / 1000.0) : 0.0;
  double rays_per_s = t.render_device_ms > 0 ? double(result.rays) / (t.render_device_ms / 1000.0) : 0.0;
  if (as_json) {
    json j = {{"octrace", OCTRACE_COMMIT},
              {"device", device_json(ctx.info)},
              {"robust_buffers", ctx.robust_buffers},
              {"scene", {{"source", scene_opts.describe()},
                         {"spheres", scene.spheres.size()},
                         {"meshes", scene.meshes.size()},
                         {"instances", scene.instances.size()},
                         {"triangles_unique", unique_triangle_count(scene)},
                         {"triangles_instanced", instanced_triangle_count(scene)},
                         {"instancing", instancing_name(resolved_instancing(scene, settings))},
                         {"materials", scene.materials.size()},
                         {"textures", scene.textures.size()}}},
              {"width", settings.width},
              {"height", settings.height},
              {"spp", settings.spp},
              {"samples", result.samples},
              {"interrupted", result.interrupted},
              {"resumed_from", control.resume_samples},
              {"depth", settings.bounce_limit},
              {"sample_seed", settings.sample_seed},
              {"accel", accel_name(settings.accel)},
              {"precision", precision_name(settings.precision)},
              {"effects", settings.all_effects ? "all" : "auto"},
              {"rr_depth", settings.rr_depth},
              {"nee", settings.nee ? "on" : "off"},
              {"samples_per_dispatch", settings.samples_per_dispatch},
              {"sample_lanes", settings.sample_lanes},
              {"octant_culling", result.octant_culling ? "on" : "off"},
              {"camera_tiles", result.camera_tiles ? "on" : "off"},
              {"tail_depth", result.tail_depth},
              {"tail_step", result.tail_step},
              {"tail_fill", result.tail_fill},
              {"tail_subgroup", result.tail_subgroup},
              {"tail_fetch", result.tail_fetch ? "on" : "off"},
              {"features", feature_names(result.features)},
              {"times_ms", {{"scene", scene_ms},
                            {"device_init", device_ms},
                            {"accel_build", t.accel_build_ms},
                            {"upload", t.upload_ms},
                            {"pipeline", t.pipeline_ms},
                            {"render", t.render_device_ms},
                            {"render_wall", t.render_wall_ms},
                            {"readback", t.readback_ms},
                            {"write", write_ms}}},
              {"paths_per_second", paths_per_s},
              {"rays", result.rays},
              {"rays_per_second", rays_per_s},
              {"nonfinite_samples", result.nonfinite_samples},
              {"cut_paths", result.cut_paths},
              {"buffer_parts", result.buffer_parts},
              {"buffer_part_bytes", result.buffer_part_bytes},
              {"outputs", outputs}};
    if (!shares.empty()) {
      json per_device = json::array();
      for (const DeviceShare& d : shares)
        per_device.push_back({{"name", d.name}, {"samples", d.samples}, {"render_ms", d.device_ms}, {"setup_ms", d.setup_ms}});
      j["devices"] = per_device;
    }
#ifdef OCTRACE_MPI
    if (!gathered.shares.empty()) {
      json per_rank = json::array();
      for (const mpi::RankShare& r : gathered.shares) per_rank.push_back(mpi::share_json(r));
      j["ranks"] = per_rank;
      j["batch_ms"] = batch_ms > 0 ? batch_ms : mpi::kBatchMs;
      j["device_turns"] = gathered.device_turns;
      const mpi::ReduceTimes& red = gathered.reduce;
      j["times_ms"]["reduce"] = red.total_ms;
      j["times_ms"]["reduce_alloc"] = red.alloc_ms;
      j["times_ms"]["reduce_receive"] = red.receive_ms;
      j["times_ms"]["reduce_merge"] = red.merge_ms;
      j["times_ms"]["reduce_merge_wait"] = red.merge_wait_ms;
      j["times_ms"]["reduce_send"] = red.send_ms;
      j["reduce_shared"] = red.shared;
    }
#endif
    if (settings.accel == Accel::Bvh) {
      const OctreeStats& o = result.octree;
      j["bvh"] = {{"build_ms", o.build_ms}, {"nodes", o.nodes},           {"leaves", o.leaves},
                  {"depth_reached", o.max_depth_reached},                  {"refs", o.refs},
                  {"bytes", o.bytes},       {"refs_per_primitive", o.refs_per_primitive},
                  {"bytes_per_primitive", o.bytes_per_primitive},
                  {"width", {{"top", o.bvh_top_width}, {"meshes", o.bvh_mesh_width}}},
                  {"spatial_refs", settings.octree.bvh_spatial_refs},
                  {"sphere_order", sphere_order_name(o.bvh_sphere_order ? SphereOrder::Tree : SphereOrder::Scene)},
                  {"top_refs_per_leaf", o.top_refs_per_leaf()},
                  {"top_walk", result.bvh_top_while ? "while-while" : "one-loop"}};
    }
    if (settings.accel == Accel::Octree) {
      const OctreeStats& o = result.octree;
      j["octree"] = {{"leaf_size", o.leaf_size}, {"max_depth", settings.octree.max_depth},
                     {"max_refs", o.max_refs},
                     {"build_ms", o.build_ms},         {"nodes", o.nodes},
                     {"leaves", o.leaves},             {"depth_reached", o.max_depth_reached},
                     {"refs", o.refs},                 {"big_spheres", o.big_primitives},
                     {"refs_per_sphere", o.refs_per_primitive}, {"bytes", o.bytes},
                     {"bytes_per_sphere", o.bytes_per_primitive},
                     {"refs_per_primitive", o.refs_per_primitive}, {"bytes_per_primitive", o.bytes_per_primitive},
                     {"copy_leaf", o.copy_leaf},
                     {"first_build_bytes_per_primitive", o.first_bytes_per_primitive}};
    }
    if (settings.accel != Accel::Brute) {
      const OctreeStats& o = result.octree;
      j["hidden_parts"] = {{"mode", hidden_parts_name(settings.octree.hidden_parts)},
                           {"spheres_clipped", o.spheres_clipped},
                           {"spheres_hidden", o.spheres_hidden},
                           {"ms", o.hidden_parts_ms},
                           {"surface_cells", o.surface_cells}};
    }
    if (render_opts.pipeline_stats) {
      json stats = json::object();
      for (const auto& [name, value] : result.pipeline_statistics) stats[name] = value;
      j["pipeline_statistics"] = stats;
    }
    if (result.walk.counted) {
      const WalkStats& w = result.walk;
      j["walk"] = {{"queries", w.queries},         {"nodes", w.nodes},
                   {"leaves", w.leaves},           {"boxes", w.boxes},
                   {"primitives", w.primitives},   {"instances", w.instances},
                   {"query_slots", w.query_slots}, {"node_slots", w.node_slots},
                   {"primitive_slots", w.primitive_slots}};
    }
    if (settings.dispatch_times) {
      json list = json::array();
      for (const DispatchTime& d : result.dispatches)
        list.push_back({{"stage", d.stage}, {"level", d.level}, {"runs", d.runs}, {"ms", d.ms}, {"paths", d.paths}});
      j["dispatches"] = list;
    }
    std::cout << j.dump(2) << "\n";
  } else if (!quiet) {
    std::printf("device    %s (%s)\n", ctx.info.name.c_str(), ctx.info.type.c_str());
    std::printf("scene     %s: %s%s\n", scene_opts.describe().c_str(), scene_summary(scene).c_str(),
                shares_meshes(scene) ? (resolved_instancing(scene, settings) == Instancing::Bake
                                            ? "; every instance baked into world space (--instancing)"
                                            : "; shared meshes stored once (--instancing)")
                                     : "");
    std::printf("image     %dx%d, %u spp, depth %u, sample seed %u, %s\n", settings.width, settings.height,
                settings.spp, settings.bounce_limit, settings.sample_seed, precision_name(settings.precision));
    if (settings.accel == Accel::Octree) {
      const OctreeStats& o = result.octree;
      char copy[48] = "";
      if (o.copy_leaf) std::snprintf(copy, sizeof copy, ", copy leaves up to %u", o.copy_leaf);
      std::printf("octree    %u nodes, %u leaves (leaf size %u%s, at most %u refs/primitive), depth %u, %.2f "
                  "refs/primitive, %.1f bytes/primitive, %u big primitives\n",
                  o.nodes, o.leaves, o.leaf_size, copy, o.max_refs, o.max_depth_reached, o.refs_per_primitive,
                  o.bytes_per_primitive, o.big_primitives);
      if (o.first_bytes_per_primitive > 0)
        std::printf("          built again at %u refs/primitive without copy leaves: %.1f bytes/primitive at the "
                    "first settings, over %.0f\n",
                    o.max_refs, o.first_bytes_per_primitive, kOctreeBytesBound);
    }
    if (result.buffer_parts)
      std::printf("buffers   the scene's arrays split over %u buffers of at most %s (larger than one storage buffer)\n",
                  result.buffer_parts, mib_string(result.buffer_part_bytes).c_str());
    if (settings.accel == Accel::Bvh)
      std::printf("bvh       %u nodes, %u leaves, depth %u, %.1f bytes/primitive, %u-wide top level, %u-wide meshes%s%s\n",
                  result.octree.nodes, result.octree.leaves, result.octree.max_depth_reached,
                  result.octree.bytes_per_primitive, result.octree.bvh_top_width, result.octree.bvh_mesh_width,
                  result.octree.bvh_sphere_order ? ", spheres in its order" : "",
                  result.bvh_top_while ? ", while-while top walk" : "");
    if (settings.accel != Accel::Brute && (result.octree.spheres_clipped > 0 || result.octree.spheres_hidden > 0))
      std::printf("hidden    %llu spheres' boxes shrunk to the parts no opaque sphere covers, %llu wholly covered "
                  "(--hidden-parts; %.1f ms of the build)%s\n",
                  (unsigned long long)result.octree.spheres_clipped, (unsigned long long)result.octree.spheres_hidden,
                  result.octree.hidden_parts_ms,
                  result.octree.surface_cells ? "; the octree's cells follow their surfaces (--octree-surfaces)" : "");
    std::printf("times     scene %.1f ms, %s build %.1f ms, upload %.1f ms, pipeline %.1f ms, render %.1f ms (device)\n",
                scene_ms, accel_name(settings.accel), t.accel_build_ms, t.upload_ms, t.pipeline_ms,
                t.render_device_ms);
    std::printf("speed     %.3g paths/s, %.3g rays/s (%.2f segments per path)\n", paths_per_s, rays_per_s,
                paths > 0 ? double(result.rays) / paths : 0.0);
    for (size_t d = 0; d < shares.size(); ++d)
      std::printf("device %zu  %s: %u spp, %.1f ms of passes, %.1f ms set-up\n", d, shares[d].name.c_str(),
                  shares[d].samples, shares[d].device_ms, shares[d].setup_ms);
#ifdef OCTRACE_MPI
    for (const mpi::RankShare& r : gathered.shares) std::printf("%s\n", mpi::share_line(r).c_str());
#endif
    if (!gathered.shares.empty())
      std::printf("reduce    %.1f ms receiving and merging the ranks' states: %.1f ms allocating, %.1f ms waiting "
                  "for data, %.1f ms waiting for the merging threads (%.1f ms merging, overlapped); sending %.1f ms\n",
                  gathered.reduce.total_ms, gathered.reduce.alloc_ms, gathered.reduce.receive_ms,
                  gathered.reduce.merge_wait_ms, gathered.reduce.merge_ms, gathered.reduce.send_ms);
    for (const auto& [name, value] : result.pipeline_statistics)
      std::printf("pipeline  %s: %s\n", name.c_str(), value.c_str());
    if (result.walk.counted) {
      const WalkStats& w = result.walk;
      const double q = w.queries ? double(w.queries) : 1.0;
      std::printf("walk      %llu queries; per query %.2f nodes, %.2f leaves, %.2f box tests, %.2f primitive "
                  "tests, %.2f mesh instances (--walk-stats: the passes' times include the counting)\n",
                  (unsigned long long)w.queries, double(w.nodes) / q, double(w.leaves) / q, double(w.boxes) / q,
                  double(w.primitives) / q, double(w.instances) / q);
      const auto busy = [](uint64_t n, uint64_t slots) { return slots ? 100.0 * double(n) / double(slots) : 0.0; };
      std::printf("lanes     busy in their subgroup: %.0f%% where queries start, %.0f%% at node expansions, %.0f%% at "
                  "primitive tests\n",
                  busy(w.queries, w.query_slots), busy(w.nodes, w.node_slots), busy(w.primitives, w.primitive_slots));
    }
    // The devices' passes in all (the dispatches are summed over them).
    double passes_ms = 0;
    for (const DeviceShare& d : shares) passes_ms += d.device_ms;
    if (shares.empty()) passes_ms = t.render_device_ms;
    for (const DispatchTime& d : result.dispatches) {
      const std::string level = d.tail() ? " " + std::to_string(d.level) : "";
      const std::string paths = d.tail() ? ", " + std::to_string(d.paths) + " paths" : "";
      std::printf("dispatch  %-16s %9.3f ms in %llu run%s (%.1f%% of the passes)%s\n", (d.stage + level).c_str(),
                  d.ms, (unsigned long long)d.runs, d.runs == 1 ? "" : "s",
                  passes_ms > 0 ? 100.0 * d.ms / passes_ms : 0.0, paths.c_str());
    }
    if (result.nonfinite_samples)
      std::printf("warning   %llu NaN/Inf samples were rejected\n", (unsigned long long)result.nonfinite_samples);
    for (const auto& o : outputs) std::printf("wrote     %s\n", o.c_str());
    if (!state.empty()) std::printf("state     %s (.accum, .mean.pfm, .count.pfm)\n", state.c_str());
  }
  return exit_code;
}

// Merges accumulation states (render --state) weighted by their sample counts.
int cmd_merge(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs,
              const std::string& state, bool quiet) {
  if (outputs.empty() && state.empty()) throw InputError("merge: give --out and/or --state");
  check_outputs(outputs, state, false, "");
  std::vector<RenderState> states;
  for (const auto& in : inputs) states.push_back(read_state(in));
  RenderState merged = merge_states(states);
  // The images first, as one set; then the state (one set of its own).
  write_outputs(merged.mean, outputs, nullptr, "");
  if (!state.empty()) write_state(merged, state);
  if (!quiet) {
    double total = 0;
    for (float n : merged.count) total += n;
    std::printf("merged %zu states: %.0f samples per pixel on average\n", states.size(),
                merged.count.empty() ? 0.0 : total / double(merged.count.size()));
  }
  return 0;
}

int cmd_devices(bool as_json) {
  auto devices = list_devices();
  // Per device, the variants that a headless `--device auto` runs on it.
  std::vector<std::vector<std::string>> auto_picks(devices.size());
  for (Precision p : kPrecisions) {
    try {
      auto_picks[select_device(devices, "auto", requirements_of(p))].push_back(precision_name(p));
    } catch (const std::runtime_error&) {
      // No device runs this variant; each device's unmet list says why.
    }
  }
  if (as_json) {
    json j = json::array();
    for (const auto& d : devices) {
      j.push_back(device_json(d));
      j.back()["auto_picks"] = auto_picks[d.index];
    }
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  if (devices.empty()) {
    std::printf("no Vulkan devices (install mesa-vulkan-drivers for the CPU device)\n");
    return 1;
  }
  for (const auto& d : devices) {
    std::printf("%u  %s\n", d.index, d.name.c_str());
    std::printf("   type      %s%s\n", d.type.c_str(), d.software ? " (software: timings are not a GPU's)" : "");
    std::printf("   driver    %s, Vulkan %s\n", d.driver.c_str(), d.api_version.c_str());
    std::printf("   features  shaderFloat16 %s, storageBuffer16BitAccess %s\n", d.shader_float16 ? "yes" : "no",
                d.storage_16bit ? "yes" : "no");
    if (d.subgroup_size > 0) std::printf("   subgroup  %u lanes\n", d.subgroup_size);
    if (d.cpu_threads > 0)
      std::printf("   threads   %u (llvmpipe's: LP_NUM_THREADS, else the CPUs; batches take whole multiples)\n",
                  d.cpu_threads);
    if (const uint32_t subgroup = default_tail_subgroup(d, true); subgroup > 0)
      std::printf("   resident  %llu threads at once (--tail-subgroup's auto: %u paths, and --tail-fill's, for the "
                  "octree over triangles; elsewhere the fill)\n",
                  (unsigned long long)d.resident_threads, subgroup);
    else if (d.resident_threads > 0)
      std::printf("   resident  %llu threads at once (--tail-fill's auto)\n", (unsigned long long)d.resident_threads);
    else
      std::printf("   resident  threads at once unknown (--tail-fill's and --tail-subgroup's auto: off)\n");
    const auto& picks = auto_picks[d.index];
    for (Precision p : kPrecisions) {
      auto unmet = unmet_requirements(d, requirements_of(p));
      std::string runs = unmet.empty() ? "yes" : "no: ";
      for (size_t k = 0; k < unmet.size(); ++k) runs += (k ? ", " : "") + unmet[k];
      if (std::find(picks.begin(), picks.end(), precision_name(p)) != picks.end()) runs += ", picked by --device auto";
      std::printf("   %-9s %s\n", precision_name(p), runs.c_str());
    }
  }
  return 0;
}

int cmd_compare(const std::string& a, const std::string& b, bool as_json) {
  Image test = read_image(a);
  Image reference = read_image(b);
  if (test.width != reference.width || test.height != reference.height)
    throw InputError(a + " is " + std::to_string(test.width) + "x" + std::to_string(test.height) + ", " + b +
                     " is " + std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                     ": compare needs images of one size");
  // A NaN or an infinity would make every metric NaN.
  for (const auto& [image, path] : {std::pair{&test, &a}, std::pair{&reference, &b}}) {
    const auto bad = std::find_if(image->rgb.begin(), image->rgb.end(), [](float v) { return !std::isfinite(v); });
    if (bad != image->rgb.end()) {
      const size_t pixel = size_t(bad - image->rgb.begin()) / 3;
      throw InputError(*path + ": pixel (" + std::to_string(pixel % size_t(image->width)) + ", " +
                       std::to_string(pixel / size_t(image->width)) + ") is " + (std::isnan(*bad) ? "NaN" : "infinite") +
                       ": compare needs finite values");
    }
  }
  ErrorMetrics m = compare_images(test, reference);
  if (as_json) {
    // JSON has no infinity: identical images report psnr null.
    json j = {{"rmse", m.rmse}, {"rel_mse", m.rel_mse}, {"ssim", m.ssim}};
    j["psnr"] = std::isfinite(m.psnr) ? json(m.psnr) : json(nullptr);
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("rmse     %.6g\nrel_mse  %.6g\npsnr     %.2f dB\nssim     %.6f\n", m.rmse, m.rel_mse, m.psnr,
                m.ssim);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Mesa's lavapipe warns on every start when XDG_RUNTIME_DIR is unset (as
  // in containers and CI); it needs only a writable folder.
  setenv("XDG_RUNTIME_DIR", "/tmp", 0);
  // `mpirun -np N octrace render ...` (or render --mpi): one rank of a job
  // (app/mpi_render.h). Every way out of main below then goes through the
  // job's protocol, so that every rank ends with the job's exit code.
  const bool mpi_launch = argc > 1 && std::strcmp(argv[1], "render") == 0 && mpi::launched(argc, argv);
#ifdef OCTRACE_MPI
  if (mpi_launch) mpi::init(&argc, &argv);
  const auto end = [](int code) { return mpi::active() ? mpi::finish(code) : code; };
  const auto fail = [](int code, const std::string& message) {
    if (mpi::active()) return mpi::fail(code, message);
    std::fprintf(stderr, "octrace: error: %s\n", message.c_str());
    return code;
  };
#else
  if (mpi_launch) {
    std::fprintf(stderr, "octrace: error: started by an MPI launcher (or --mpi), but this build has no MPI "
                         "(configure with -DOCTRACE_MPI=ON and libopenmpi-dev)\n");
    return 2;
  }
  const auto end = [](int code) { return code; };
  const auto fail = [](int code, const std::string& message) {
    std::fprintf(stderr, "octrace: error: %s\n", message.c_str());
    return code;
  };
#endif
  CLI::App app{"octrace: a Vulkan compute path tracer (spheres, glTF meshes, JSON scenes)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("octrace ") + OCTRACE_COMMIT,
                       "The commit this binary was built from (git describe; -dirty: with uncommitted changes)");
  // A flag given twice takes its last value, as scripts that append flags expect.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);

  SceneOptions scene_opts;
  RenderOptions render_opts;
  std::vector<std::string> outputs;
  bool as_json = false, quiet = false;

  auto* render_cmd = app.add_subcommand("render", "Render headless to PNG (sRGB), PFM or EXR (linear)");
  scene_opts.add_to(*render_cmd);
  render_opts.add_to(*render_cmd);
  // render alone renders on several devices at once (view and bench on one).
  render_cmd->get_option("--device")->description(
      "auto | cpu | gpu | INDEX (see `octrace devices`), or several devices: all (every GPU) | a list of indices "
      "like 0,2 (docs/multi_gpu.md)");
  // One file a flag (--out a.png --out b.pfm): a list after one flag would
  // take the words after it, as `merge -o m.png s1 s2` takes the states.
  render_cmd->add_option("--out,-o", outputs, "Output image(s), format by extension: .png .pfm .exr (default out.png)")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  render_cmd->add_flag("--json", as_json, "Print a machine-readable summary on stdout");
  std::string state_out;
  render_cmd->add_option("--state", state_out,
                         "Also save the accumulation state as PREFIX.accum (--resume) + PREFIX.mean.pfm + "
                         "PREFIX.count.pfm (octrace merge)");
  double checkpoint_seconds = 0;
  render_cmd->add_option("--checkpoint", checkpoint_seconds,
                         "Write the --state files at most every SECONDS during the render (0: only at the end)")
      ->capture_default_str();
  std::string resume_prefix;
  render_cmd->add_option("--resume", resume_prefix,
                         "Continue the render saved as PREFIX (--state) up to --spp, with the same sample indices");
  render_cmd->add_flag("--quiet,-q", quiet, "No progress or summary");
  render_cmd->add_flag("--walk-stats", render_opts.settings.walk_stats,
                       "Count what the walks do: queries, nodes expanded, leaves, box and primitive tests, and "
                       "how many of a subgroup's lanes were busy at those steps (the summary's \"walk\" and "
                       "\"lanes\" lines, or \"walk\" in --json); the same image, slower passes");
  render_cmd->add_flag("--dispatch-times", render_opts.settings.dispatch_times,
                       "Time every dispatch of the passes on the device (the camera's tiles, the whole paths or "
                       "the head, each tail level and its subgroup stage, the sum), each from the end of the one "
                       "before: the summary's \"dispatch\" lines, or \"dispatches\" in --json; the same image");
  double batch_ms = 0;
  render_cmd->add_option("--batch-ms", batch_ms,
                         "Under MPI: each rank asks rank 0 for the samples that take about MS milliseconds at its "
                         "speed so far (at most 1024; fewer near the end, so that the ranks finish together). "
                         "Default 250");
  std::string device_turns = "auto";
  render_cmd
      ->add_option("--device-turns", device_turns,
                   "Under MPI: ranks that share one physical device (same host and device UUID) render one batch at "
                   "a time, in turns: on GPUs (auto), on every device, lavapipe too (on), or never (off: the "
                   "driver time-slices their contexts)")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  bool mpi_flag = false;  // read before parsing (mpi::launched)
  render_cmd->add_flag("--mpi", mpi_flag,
                       "Run as one rank of an MPI job; implied when started by mpirun (OMPI_COMM_WORLD_SIZE, "
                       "PMIX_RANK or PMI_SIZE set). `mpirun -np N octrace render ...`: each rank renders on its "
                       "node-local GPU (local rank modulo the node's GPUs; or its own --device), takes batches of "
                       "samples from rank 0, and rank 0 merges the states and alone writes the outputs, --state and "
                       "the summary (\"ranks\"). A failed rank fails the job: one line names it and its host, every "
                       "rank exits non-zero, no output is written. --checkpoint writes the merged state; device lists "
                       "are refused under MPI (docs/multi_gpu.md)");

  ViewOptions view_opts;
  auto* view_cmd = app.add_subcommand("view", "Open a window that shows the image converge, pass by pass");
  scene_opts.add_to(*view_cmd);
  render_opts.add_to(*view_cmd);
  // The window accumulates until --max-spp; --spp stays a flag so that
  // `view --spp 5` says so (CLI11 said "not expected: 5 --spp"; a hidden
  // option has no name in CLI11's messages).
  view_cmd->get_option("--spp")
      ->description("Not for view (refused): it accumulates until --max-spp")
      ->default_str("")
      ->check(CLI::Validator(
          [](std::string&) { return std::string("view accumulates until --max-spp N (or until its window closes)"); },
          ""));
  view_opts.add_to(*view_cmd);

  auto* devices_cmd = app.add_subcommand("devices", "List Vulkan devices and the precision variants each can run");
  devices_cmd->add_flag("--json", as_json, "Machine-readable output");

  std::string compare_a, compare_b;
  auto* compare_cmd = app.add_subcommand("compare", "Image error between a test image and a reference");
  compare_cmd->add_option("test", compare_a, "Test image (.png .pfm .exr .hdr)")->required();
  compare_cmd->add_option("reference", compare_b, "Reference image")->required();
  compare_cmd->add_flag("--json", as_json, "Machine-readable output");

  std::vector<std::string> merge_inputs, merge_outputs;
  std::string merge_state;
  auto* merge_cmd = app.add_subcommand("merge", "Merge accumulation states (render --state) weighted by their counts");
  merge_cmd->add_option("states", merge_inputs, "State prefixes (PREFIX.mean.pfm + PREFIX.count.pfm)")->required();
  merge_cmd->add_option("--out,-o", merge_outputs, "Output image(s): .png .pfm .exr (give --out, --state or both)")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  merge_cmd->add_option("--state", merge_state, "Also save the merged state under this prefix");
  merge_cmd->add_flag("--quiet,-q", quiet, "No summary");

  BenchOptions bench;
  std::vector<uint64_t> bench_spheres{488, 1000, 2000, 4000, 8000, 32000, 128000, 1000000};
  std::vector<float> bench_radii{0.1f};
  std::vector<std::string> bench_accels{"octree", "brute"}, bench_precisions{"fp32"};
  std::string bench_size;
  auto* bench_cmd = app.add_subcommand("bench", "Render time per accel against sphere count (the study's experiment), of scene files "
                                                "(--scene), or of specialised against general pipelines (--family)");
  bench_cmd->add_option("--spheres", bench_spheres, "Sphere counts (comma-separated)")->delimiter(',')
      ->capture_default_str();
  bench_cmd->add_option("--radius", bench_radii, "Radii of the small spheres (comma-separated)")->delimiter(',')
      ->capture_default_str();
  bench_cmd->add_option("--accel", bench_accels, "Acceleration structures (comma-separated): octree, bvh, brute")->delimiter(',')->capture_default_str();
  bench_cmd->add_option("--precision", bench_precisions, "Precisions (comma-separated)")->delimiter(',')
      ->capture_default_str();
  bench_cmd->add_option("--size", bench_size, "Image size (default 1200x800 on a GPU, 400x225 on a CPU device)");
  bench_cmd->add_option("--spp", bench.settings.spp, "Samples per pixel")->capture_default_str();
  bench_cmd->add_option("--depth", bench.settings.bounce_limit, "Bounce limit")->capture_default_str();
  bench_cmd->add_option("--octree-leaf", bench.settings.octree.leaf_size, "Octree leaf size (0: auto, as in render)")
      ->capture_default_str();
  bench_cmd->add_option("--octree-depth", bench.settings.octree.max_depth, "Octree maximum depth")
      ->capture_default_str();
  bench_cmd->add_option("--octree-refs", bench.settings.octree.max_refs,
                        "Octree references per primitive, at most (1..64; 0: auto, as in render)")
      ->capture_default_str();
  bench_cmd->add_option("--bvh-width", bench.settings.octree.bvh_width, "BVH children per node: 2, 4 or 0 (auto)")
      ->capture_default_str();
  bench_cmd->add_option("--bvh-spatial-refs", bench.settings.octree.bvh_spatial_refs,
                        "BVH over a mesh: references per triangle spatial splits may make, at most (1..4; 1: none)")
      ->capture_default_str();
  std::string bench_sphere_order = "auto";
  bench_cmd->add_option("--bvh-sphere-order", bench_sphere_order,
                        "BVH over spheres alone: the spheres in the tree's order or the scene's: auto | tree | scene")
      ->capture_default_str();
  std::string bench_instancing = "auto";
  bench_cmd->add_option("--instancing", bench_instancing,
                        "Meshes placed several times: keep | bake | auto (bake where that at most doubles the "
                        "stored triangles)")
      ->capture_default_str();
  std::string bench_surface_cells = "auto";
  bench_cmd->add_option("--octree-surfaces", bench_surface_cells,
                        "Octree over dense overlapping spheres: cells follow their surfaces: auto (as render's: on a "
                        "GPU from 576M samples a render, 600 spp at 1200x800) | on | off")
      ->capture_default_str();
  bench_cmd->add_option("--repeat", bench.repeat, "Timed runs per configuration, after the warm-up")
      ->capture_default_str();
  bench_cmd->add_option("--warmup", bench.warmup_s,
                        "Warm-up per configuration: untimed runs back to back for at least SECONDS (at least one), "
                        "so that a GPU has left its idle clock before the timed runs")
      ->capture_default_str();
  bench_cmd->add_option("--budget", bench.budget_s, "Skip brute force predicted to take longer (seconds)")
      ->capture_default_str();
  bench_cmd->add_option("--seed", bench.seed, "Scene generator seed")->capture_default_str();
  bench_cmd->add_option("--device", bench.device, "auto | cpu | gpu | INDEX")->capture_default_str();
  bench_cmd->add_option("--csv", bench.csv, "Also write the results as CSV");
  std::vector<std::string> bench_scenes;
  auto* bench_scene_opt =
      bench_cmd
          ->add_option("--scene", bench_scenes,
                       "Instead of the sphere sweep: time these scene files (.json, .gltf, .glb; comma-separated) "
                       "per accel and precision, with rays/s")
          ->delimiter(',');
  bench_cmd
      ->add_option("--family", bench.families,
                   "Instead of the sphere sweep: time --effects auto against all for these scene families "
                   "(rtiow, lambertian, metal, glass, emissive, pinhole; comma-separated), with the first of "
                   "--spheres (default 488), --radius (default 0.1) and --accel (default octree)")
      ->delimiter(',')
      ->excludes(bench_scene_opt);
  for (const char* generator : {"--spheres", "--radius", "--seed"})
    bench_cmd->get_option(generator)->excludes(bench_scene_opt);
  bench_cmd->add_flag("--validation", bench.validation, "Enable the Khronos validation layer");
  bench_cmd->add_flag("--robust-buffers", bench.robust_buffers,
                      "Keep the driver's bounds checks on buffer accesses (see render --robust-buffers)");
  bench_cmd->add_flag("--quiet,-q", bench.quiet, "No progress on stderr");

  check_option_values(app);
  // CLI11 says "A subcommand is required" of `octrace frobnicate` and of
  // `octrace --frobnicate`; name the word instead.
  if (argc > 1 && std::strcmp(argv[1], "-h") != 0 && std::strcmp(argv[1], "--help") != 0 &&
      std::strcmp(argv[1], "--version") != 0) {
    std::string commands;
    bool known = false;
    for (CLI::App* sub : app.get_subcommands({})) {
      commands += (commands.empty() ? "" : ", ") + sub->get_name();
      known = known || sub->check_name(argv[1]);
    }
    if (!known)
      return fail(2, std::string(argv[1][0] == '-' ? "unknown option \"" : "unknown command \"") + argv[1] +
                       "\" (a command comes first: " + commands + "; see --help)");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return end(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return end(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return end(app.exit(e));
  } catch (const CLI::ConversionError& e) {
    // "Could not convert: --spp = 99999999999": after check_option_values
    // only a value beyond a narrower integer type's range gets here. A flag
    // given twice shows both values ("--spp = 1,99999999999"); the last is
    // the one read.
    const std::string what = e.what(), head = "Could not convert: ";
    const size_t eq = what.find(" = ");
    if (what.rfind(head, 0) != 0 || eq == std::string::npos) return fail(2, what + " (see --help)");
    const std::string values = what.substr(eq + 3);
    return fail(2, what.substr(head.size(), eq - head.size()) + ": \"" + values.substr(values.rfind(',') + 1) +
                       "\" is out of range (see --help)");
  } catch (const CLI::ParseError& e) {
    return fail(2, std::string(e.what()) + " (see --help)");
  }

  int code = 0;
  try {
    if (*render_cmd && render_cmd->count("--device-turns") > 0) {
#ifdef OCTRACE_MPI
      if (!mpi::active())
#endif
        throw InputError("--device-turns: applies to the ranks of an MPI job only (mpirun -np N octrace render ...)");
#ifdef OCTRACE_MPI
      mpi::set_device_turns(device_turns == "on"    ? mpi::DeviceTurns::On
                            : device_turns == "off" ? mpi::DeviceTurns::Off
                                                    : mpi::DeviceTurns::Auto);
#endif
    }
    if (*render_cmd)
      code = cmd_render(scene_opts, render_opts, outputs, state_out, checkpoint_seconds, resume_prefix, batch_ms, as_json,
                        quiet);
    else if (*merge_cmd) code = cmd_merge(merge_inputs, merge_outputs, merge_state, quiet);
    else if (*view_cmd) {
#ifdef OCTRACE_WINDOW
      view_opts.scene_file = scene_opts.scene_file;
      view_opts.device = render_opts.device;
      view_opts.validation = render_opts.validation;
      RenderSettings settings = render_opts.parsed(true);
      view_opts.stop = &g_stop;
      check_outputs({}, "", false, scene_opts.dump_scene);
      const Scene scene = scene_opts.load();
      view_opts.on_open = [&] { scene_opts.write_dump(scene); };
      SignalGuard signals;
      code = run_view(scene, settings, view_opts);
#else
      throw RuntimeError("this build has no window support (configure with -DOCTRACE_WINDOW=ON and libglfw3-dev)");
#endif
    } else if (*devices_cmd) code = cmd_devices(as_json);
    else if (*compare_cmd) code = cmd_compare(compare_a, compare_b, as_json);
    else if (*bench_cmd) {
      bench.spheres = bench_spheres;
      bench.radii = bench_radii;
      for (const auto& a : bench_accels) bench.accels.push_back(parse_accel(a));
      for (const auto& p : bench_precisions) bench.precisions.push_back(parse_precision(p));
      bench.settings.octree.bvh_sphere_order = parse_sphere_order(bench_sphere_order);
      bench.settings.octree.instancing = parse_instancing(bench_instancing);
      bench.settings.octree.surface_cells = parse_surface_cells(bench_surface_cells);
      if (!bench_size.empty()) {
        parse_size(bench_size, bench.settings);
        bench.size_given = true;
      }
      if (bench.repeat < 1) throw InputError("--repeat: must be >= 1");
      if (!(bench.warmup_s >= 0) || !std::isfinite(bench.warmup_s))
        throw InputError("--warmup: must be a finite number of seconds >= 0");
      if (!(bench.budget_s >= 0)) throw InputError("--budget: must be a number of seconds >= 0 (inf: no limit)");
      for (float r : bench.radii)  // every scene's parameters (radius, count), before the first render
        for (uint64_t n : bench.spheres) check_rtiow_params({n, r, bench.seed});
      if (!bench.csv.empty()) check_output_folder(bench.csv);
      // The family bench renders one scene a family with one structure.
      if (!bench.families.empty())
        for (const auto& [flag, values] : {std::pair{"--spheres", bench_spheres.size()},
                                           std::pair{"--radius", bench_radii.size()},
                                           std::pair{"--accel", bench_accels.size()}})
          if (bench_cmd->count(flag) && values > 1)
            throw InputError(std::string(flag) + ": --family takes one value, got " + std::to_string(values));
      for (const auto& file : bench_scenes) {
        SceneOptions one;
        one.scene_file = file;
        bench.scenes.emplace_back(file.substr(file.find_last_of('/') + 1), one.load());
      }
      code = run_bench(bench);
    }
  } catch (const mpi::JobFailed& e) {
    return end(e.code);  // rank 0 has said why
  } catch (const SettingError& e) {
    return fail(2, message_for_cli(e));
  } catch (const InputError& e) {
    return fail(2, e.what());
  } catch (const RuntimeError& e) {
    return fail(1, e.what());
  } catch (const std::bad_alloc&) {
    return fail(1, "out of host memory");
  }
  if (uint32_t n = validation_message_count())
    return fail(1, "the Vulkan validation layer reported " + std::to_string(n) + " message(s)");
  return end(code);
}
