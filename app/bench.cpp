#include "bench.h"
#include "octrace_version.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <map>
#include <memory>
#include <optional>

#include "accel/bvh.h"
#include "core/text.h"
#include "io/file.h"
#include "scene/gltf.h"
#include "render/gpu_scene.h"
#include "vk/context.h"

namespace octrace {

namespace {

struct Row {
  uint64_t spheres;
  float radius;
  Accel accel;
  Precision precision;
  bool skipped = false;
  std::string skip_reason;
  double median_ms = 0, min_ms = 0, max_ms = 0;
  double build_ms = 0, bytes_per_sphere = 0, refs_per_sphere = 0;
  std::optional<double> speedup;  // brute median / octree median, same spheres, radius, precision
  std::optional<double> vs_bvh;   // this median / the BVH's, same spheres, radius, precision
};

// The rtiow scene with its materials replaced, one family per effect mix:
// rtiow (all effects), lambertian / metal (fuzz 0) / glass (small spheres
// only; the ground stays lambertian), emissive (every tenth small sphere a
// light, black sky), pinhole (rtiow with aperture 0).
Scene make_family(const std::string& family, uint64_t n, float radius, uint64_t seed) {
  Scene s = make_rtiow_scene({n, radius, seed});
  auto replace_small = [&](auto&& fn) {
    for (size_t i = 1; i < s.materials.size(); ++i) fn(s.materials[i], i);
  };
  if (family == "rtiow") return s;
  if (family == "pinhole") {
    s.camera.aperture = 0;
    return s;
  }
  if (family == "lambertian") {
    replace_small([](Material& m, size_t) { m = {MaterialType::Lambertian, m.type == MaterialType::Dielectric ? glm::vec3(0.8f) : m.albedo}; });
    return s;
  }
  if (family == "metal") {
    replace_small([](Material& m, size_t) { m = {MaterialType::Metal, m.type == MaterialType::Dielectric ? glm::vec3(0.9f) : m.albedo, 0.0f}; });
    return s;
  }
  if (family == "glass") {
    replace_small([](Material& m, size_t) {
      m = Material{};
      m.type = MaterialType::Dielectric;
      m.ior = 1.5f;
    });
    return s;
  }
  if (family == "emissive") {
    s.sky.type = SkyType::None;
    replace_small([](Material& m, size_t i) {
      if (i % 10 == 0) {
        m = Material{};
        m.type = MaterialType::Emissive;
        m.radiance = glm::vec3(4.0f);
      }
    });
    return s;
  }
  throw InputError("--family: expected rtiow, lambertian, metal, glass, emissive or pinhole, got \"" + family + "\"");
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The line above a bench table: device, settings and what the times are.
void print_header(const VulkanContext& ctx, const RenderSettings& settings, const BenchOptions& o, const char* more) {
  // The BVH's settings, where not the defaults.
  std::string bvh =
      settings.octree.bvh_width ? "; BVH width " + std::to_string(settings.octree.bvh_width) : std::string();
  if (settings.octree.bvh_sphere_order != SphereOrder::Auto)
    bvh += std::string("; BVH spheres in the ") + sphere_order_name(settings.octree.bvh_sphere_order) + "'s order";
  if (settings.octree.bvh_spatial_refs != kBvhSpatialRefs)
    bvh += "; BVH spatial splits up to " + float_string(settings.octree.bvh_spatial_refs) + " references per triangle";
  // ContextOptions::robust_buffers: said only where the checks are off.
  const char* robust = ctx.robust_buffers ? "" : "; buffer bounds checks off";
  std::printf("Device: %s (%s, %s); octrace %s. Image %dx%d, %u spp, depth %u%s%s; render = device time of the "
              "passes (timestamp queries), median of %u runs after a warm-up of %gs%s.\n\n",
              ctx.info.name.c_str(), ctx.info.type.c_str(), ctx.info.driver.c_str(), OCTRACE_COMMIT, settings.width,
              settings.height, settings.spp, settings.bounce_limit, bvh.c_str(), robust, o.repeat, o.warmup_s,
              more);
}

// Calls `run` back to back until `seconds` of wall time have passed, at
// least once. A GPU's clock falls to its idle level within seconds of no work
// (345 MHz against 1980 on the H200) and comes back only under sustained
// work: one warm-up run of a few milliseconds after a long build or pipeline
// compile left the timed runs at the idle clock, 4-6x slower (optimisation
// log 55).
template <class Run>
void warm_up(double seconds, Run&& run) {
  const auto start = std::chrono::steady_clock::now();
  do run();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds);
}

// One timed render of s.spp passes from an empty accumulation: its device time.
double timed_render(PathTracer& tracer, const Scene& scene, const RenderSettings& s) {
  tracer.reset();
  return tracer.run_passes(pass_settings(scene, s), 0, s.spp);
}

// One configuration of a bench: its tracer (set up with `accel` and
// `precision`; a warning where a software device's loop limit can cut
// paths) and the device times of `repeat` renders of s.spp passes, after
// warm_up; `what` names the row in the warning that its last render cut
// paths short (RenderCounts::cut_paths: its time is of shorter paths than
// the bounce limit asks for).
struct TimedRuns {
  std::unique_ptr<PathTracer> tracer;
  std::vector<double> times;
  double median_ms = 0, min_ms = 0, max_ms = 0;
};

TimedRuns timed_runs(const VulkanContext& ctx, const Scene& scene, RenderSettings s, Accel accel,
                     Precision precision, uint32_t repeat, double warmup_s, const std::string& what) {
  s.accel = accel;
  s.precision = precision;
  if (std::string w = software_loop_limit_warning(ctx.info, scene, s); !w.empty()) print_warning(w);
  if (std::string w = punctual_without_nee_warning(scene, s); !w.empty()) print_warning(w);
  TimedRuns t;
  t.tracer = std::make_unique<PathTracer>(ctx, scene, s);
  auto run = [&] { return timed_render(*t.tracer, scene, s); };
  warm_up(warmup_s, run);
  for (uint32_t rep = 0; rep < repeat; ++rep) t.times.push_back(run());
  t.median_ms = median(t.times);
  t.min_ms = *std::min_element(t.times.begin(), t.times.end());
  t.max_ms = *std::max_element(t.times.begin(), t.times.end());
  if (const uint64_t cut = t.tracer->counts().cut_paths; cut > 0)
    print_warning(what + ", " + accel_name(accel) + " " + precision_name(precision) + ", its last render: " +
                  cut_paths_note(cut) + ": its time is of shorter paths than --depth " +
                  std::to_string(s.bounce_limit) + " asks for");
  return t;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// The row of `accel` measured (not skipped) for the same scene and precision
// as `r` (`same`), if there is one: what a row is compared with (brute force
// for the speedup; the BVH, the field's standard structure, for the time
// over the BVH's).
template <class R, class Same>
const R* measured_twin(const std::vector<R>& rows, const R& r, Accel accel, Same same) {
  for (const R& b : rows)
    if (b.accel == accel && b.median_ms > 0 && same(r, b)) return &b;
  return nullptr;
}

std::string ratio_cell(const std::optional<double>& x) { return x ? fmt("%.2fx", *x) : ""; }

}  // namespace

// --effects auto against all, per scene family, as ratios measured in one run.
int run_effects_bench(const VulkanContext& ctx, const BenchOptions& o, const RenderSettings& settings) {
  struct EffectsRow {
    std::string family;
    Precision precision;
    std::vector<std::string> features;
    double auto_ms = 0, all_ms = 0, auto_min = 0, auto_max = 0, all_min = 0, all_max = 0;
  };
  std::vector<EffectsRow> rows;
  const uint64_t n = o.spheres.empty() ? 488 : o.spheres.front();
  const float radius = o.radii.empty() ? 0.2f : o.radii.front();
  for (const auto& family : o.families) {
    Scene scene = make_family(family, n, radius, o.seed);
    for (Precision precision : o.precisions) {
      EffectsRow row{family, precision, feature_names(scene_features(scene))};
      RenderSettings s = settings;
      s.accel = o.accels.empty() ? Accel::Octree : o.accels.front();
      s.precision = precision;
      s.all_effects = false;
      PathTracer specialised(ctx, scene, s);
      s.all_effects = true;
      PathTracer general(ctx, scene, s);
      // Alternate the two so that drift of the machine hits both alike.
      std::vector<double> a, g;
      warm_up(o.warmup_s, [&] {
        timed_render(specialised, scene, s);
        timed_render(general, scene, s);
      });
      for (uint32_t rep = 0; rep < o.repeat; ++rep) {
        a.push_back(timed_render(specialised, scene, s));
        g.push_back(timed_render(general, scene, s));
      }
      row.auto_ms = median(a);
      row.all_ms = median(g);
      row.auto_min = *std::min_element(a.begin(), a.end());
      row.auto_max = *std::max_element(a.begin(), a.end());
      row.all_min = *std::min_element(g.begin(), g.end());
      row.all_max = *std::max_element(g.begin(), g.end());
      if (!o.quiet)
        std::fprintf(stderr, "  %-10s %-8s auto %.2f ms, all %.2f ms\n", family.c_str(), precision_name(precision),
                     row.auto_ms, row.all_ms);
      rows.push_back(row);
    }
  }
  std::printf("Device: %s (%s, %s); octrace %s. Image %dx%d, %u spp, depth %u, rtiow %llu spheres r=%g with "
              "materials replaced per family; render = device time, median of %u runs after a warm-up of %gs, "
              "auto and all alternated.\n\n",
              ctx.info.name.c_str(), ctx.info.type.c_str(), ctx.info.driver.c_str(), OCTRACE_COMMIT, settings.width,
              settings.height, settings.spp, settings.bounce_limit, (unsigned long long)n, radius, o.repeat,
              o.warmup_s);
  std::printf("| family | precision | features | auto ms (min-max) | all ms (min-max) | all / auto |\n");
  std::printf("|---|---|---|---:|---:|---:|\n");
  for (const auto& r : rows) {
    std::string features;
    for (const auto& f : r.features) features += (features.empty() ? "" : " ") + f;
    std::printf("| %s | %s | %s | %.2f (%.2f-%.2f) | %.2f (%.2f-%.2f) | %.2fx |\n", r.family.c_str(),
                precision_name(r.precision), features.c_str(), r.auto_ms, r.auto_min, r.auto_max, r.all_ms,
                r.all_min, r.all_max, r.all_ms / r.auto_ms);
  }
  if (!o.csv.empty()) {
    std::ostringstream f;
    f << "device,family,precision,auto_ms,all_ms,ratio\n";
    for (const auto& r : rows)
      f << '"' << ctx.info.name << "\"," << r.family << ',' << precision_name(r.precision) << ',' << r.auto_ms << ','
        << r.all_ms << ',' << r.all_ms / r.auto_ms << '\n';
    const std::string text = f.str();
    write_file_atomically(o.csv, text.data(), text.size());
  }
  return 0;
}

// Given scenes (meshes, JSON scenes) per accel and precision: render time,
// paths and rays per second, the octree's build time and size per primitive.
int run_scene_bench(const VulkanContext& ctx, const BenchOptions& o, const RenderSettings& settings) {
  struct SceneRow {
    std::string name;
    uint64_t spheres = 0, triangles = 0;
    Accel accel;
    Precision precision;
    double median_ms = 0, min_ms = 0, max_ms = 0, build_ms = 0, bytes_per_primitive = 0;
    double paths_per_s = 0, rays_per_s = 0;
    std::optional<double> vs_bvh;  // this median / the BVH's, same scene and precision
    size_t scene_index = 0;        // in o.scenes (two files may share a name)
  };
  std::vector<SceneRow> rows;
  for (size_t index = 0; index < o.scenes.size(); ++index) {
    const auto& [name, scene] = o.scenes[index];
    for (Precision precision : o.precisions) {
      for (Accel accel : o.accels) {
        TimedRuns t = timed_runs(ctx, scene, settings, accel, precision, o.repeat, o.warmup_s, name);
        SceneRow row{name, scene.spheres.size(), instanced_triangle_count(scene), accel, precision};
        row.scene_index = index;
        row.median_ms = t.median_ms;
        row.min_ms = t.min_ms;
        row.max_ms = t.max_ms;
        row.build_ms = t.tracer->setup_timings().accel_build_ms;
        row.bytes_per_primitive = t.tracer->octree_stats().bytes_per_primitive;
        // Every run traces the same samples, so the same paths and rays: the
        // last run's count (the accumulation holds exactly its passes) over
        // the median time.
        const RenderResult last = t.tracer->read_result();
        const double paths = double(settings.width) * settings.height * settings.spp;
        row.paths_per_s = paths / (t.median_ms / 1000.0);
        row.rays_per_s = double(last.rays) / (t.median_ms / 1000.0);
        if (!o.quiet)
          std::fprintf(stderr, "  %-24s %-6s %-8s %.2f ms, %.3g rays/s\n", name.c_str(), accel_name(accel),
                       precision_name(precision), row.median_ms, row.rays_per_s);
        rows.push_back(row);
      }
    }
  }
  for (SceneRow& r : rows) {
    const SceneRow* b = measured_twin(rows, r, Accel::Bvh, [](const SceneRow& r, const SceneRow& b) {
      return b.scene_index == r.scene_index && b.precision == r.precision;
    });
    if (b) r.vs_bvh = r.median_ms / b->median_ms;
  }
  print_header(ctx, settings, o, "; paths/s and rays/s (every segment: camera rays and bounces) at the median time");
  std::printf("| scene | spheres | triangles | accel | precision | render ms (median) | min | max | paths/s | rays/s | "
              "time / BVH's | build ms | bytes/primitive |\n");
  std::printf("|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const SceneRow& r : rows)
    std::printf("| %s | %llu | %llu | %s | %s | %.2f | %.2f | %.2f | %.3g | %.3g | %s | %s | %s |\n", r.name.c_str(),
                (unsigned long long)r.spheres, (unsigned long long)r.triangles, accel_name(r.accel),
                precision_name(r.precision), r.median_ms, r.min_ms, r.max_ms, r.paths_per_s, r.rays_per_s,
                ratio_cell(r.vs_bvh).c_str(), r.accel != Accel::Brute ? fmt("%.1f", r.build_ms).c_str() : "",
                r.accel != Accel::Brute ? fmt("%.1f", r.bytes_per_primitive).c_str() : "");
  if (!o.csv.empty()) {
    std::ostringstream f;
    f << "device,software,width,height,spp,depth,repeat,scene,spheres,triangles,accel,precision,median_ms,min_ms,"
         "max_ms,paths_per_s,rays_per_s,build_ms,bytes_per_primitive,vs_bvh\n";
    for (const SceneRow& r : rows) {
      f << '"' << ctx.info.name << "\"," << (ctx.info.software ? 1 : 0) << ',' << settings.width << ','
        << settings.height << ',' << settings.spp << ',' << settings.bounce_limit << ',' << o.repeat << ",\""
        << r.name << "\"," << r.spheres << ',' << r.triangles << ',' << accel_name(r.accel) << ','
        << precision_name(r.precision) << ',' << r.median_ms << ',' << r.min_ms << ',' << r.max_ms << ','
        << r.paths_per_s << ',' << r.rays_per_s << ',' << r.build_ms << ',' << r.bytes_per_primitive << ',';
      if (r.vs_bvh) f << *r.vs_bvh;
      f << '\n';
    }
    const std::string text = f.str();
    write_file_atomically(o.csv, text.data(), text.size());
  }
  return 0;
}

int run_bench(const BenchOptions& o) {
  {
    // Every setting before the device is made; the size, where not given,
    // is the device's default below.
    RenderSettings given = o.settings;
    if (!o.size_given) given.width = given.height = 1;
    validate_settings(given);
  }
  VulkanContext ctx;
  bool need_fp16 = false;
  for (Precision p : o.precisions) need_fp16 |= p != Precision::FP32;
  ContextOptions context_options{o.device, need_fp16, o.validation};
  context_options.robust_buffers = o.robust_buffers;
  create_context(ctx, context_options);
  RenderSettings settings = o.settings;
  if (!o.size_given) {
    settings.width = ctx.info.software ? 400 : 1200;
    settings.height = ctx.info.software ? 225 : 800;
  }
  validate_settings(settings);

  if (!o.families.empty()) return run_effects_bench(ctx, o, settings);
  if (!o.scenes.empty()) return run_scene_bench(ctx, o, settings);
  if (!o.quiet)
    std::fprintf(stderr, "bench on %s (%s): %dx%d, %u spp, depth %u, %u repeats after a warm-up of %gs\n",
                 ctx.info.name.c_str(), ctx.info.type.c_str(), settings.width, settings.height, settings.spp,
                 settings.bounce_limit, o.repeat, o.warmup_s);

  std::vector<Row> rows;
  // Last measured median per (accel, radius, precision) and its sphere count:
  // brute force grows linearly with N, so the next size's time is predicted
  // from it and skipped when the prediction exceeds the budget.
  std::map<std::tuple<int, float, Precision>, std::pair<uint64_t, double>> last;
  for (float radius : o.radii) {
    for (uint64_t n : o.spheres) {
      Scene scene = make_rtiow_scene({n, radius, o.seed});
      for (Precision precision : o.precisions) {
        for (Accel accel : o.accels) {
          Row row{n, radius, accel, precision};
          auto key = std::make_tuple(int(accel), radius, precision);
          if (accel == Accel::Brute && last.count(key)) {
            auto [prev_n, prev_ms] = last[key];
            // The timed runs and the warm-up (warm_up: at least one run).
            const double run_s = prev_ms * double(n + 4) / double(prev_n + 4) / 1000.0;
            const double predicted_s = run_s * o.repeat + std::max(run_s, o.warmup_s);
            if (predicted_s > o.budget_s) {
              row.skipped = true;
              row.skip_reason = "predicted " + fmt("%.0f", predicted_s) + " s > budget " +
                                fmt("%.0f", o.budget_s) + " s (--budget)";
              rows.push_back(row);
              if (!o.quiet)
                std::fprintf(stderr, "  %8llu spheres r=%g %-6s %s: skipped, %s\n", (unsigned long long)n, radius,
                             accel_name(accel), precision_name(precision), row.skip_reason.c_str());
              continue;
            }
          }
          const TimedRuns t = timed_runs(ctx, scene, settings, accel, precision, o.repeat, o.warmup_s,
                                         std::to_string(n) + " spheres r=" + fmt("%g", radius));
          row.median_ms = t.median_ms;
          row.min_ms = t.min_ms;
          row.max_ms = t.max_ms;
          row.build_ms = t.tracer->setup_timings().accel_build_ms;
          row.bytes_per_sphere = t.tracer->octree_stats().bytes_per_primitive;
          row.refs_per_sphere = t.tracer->octree_stats().refs_per_primitive;
          last[key] = {n, row.median_ms};
          if (!o.quiet)
            std::fprintf(stderr, "  %8llu spheres r=%g %-6s %s: %.2f ms (min %.2f, max %.2f)\n",
                         (unsigned long long)n, radius, accel_name(accel), precision_name(precision), row.median_ms,
                         row.min_ms, row.max_ms);
          rows.push_back(row);
        }
      }
    }
  }
  const auto same = [](const Row& r, const Row& b) {
    return b.spheres == r.spheres && b.radius == r.radius && b.precision == r.precision;
  };
  for (Row& r : rows) {
    if (r.skipped) continue;
    if (const Row* b = measured_twin(rows, r, Accel::Brute, same); b && r.accel != Accel::Brute)
      r.speedup = b->median_ms / r.median_ms;
    if (const Row* b = measured_twin(rows, r, Accel::Bvh, same)) r.vs_bvh = r.median_ms / b->median_ms;
  }

  print_header(ctx, settings, o, "");
  std::printf("| spheres | radius | accel | precision | render ms (median) | min | max | speedup vs brute | "
              "time / BVH's | build ms | bytes/sphere |\n");
  std::printf("|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    std::printf("| %llu | %g | %s | %s | ", (unsigned long long)r.spheres, r.radius, accel_name(r.accel),
                precision_name(r.precision));
    if (r.skipped) {
      std::printf("skipped: %s | | | | | | |\n", r.skip_reason.c_str());
      continue;
    }
    std::printf("%.2f | %.2f | %.2f | %s | %s | %s | %s |\n", r.median_ms, r.min_ms, r.max_ms,
                r.speedup ? fmt("%.1fx", *r.speedup).c_str() : "", ratio_cell(r.vs_bvh).c_str(),
                r.accel != Accel::Brute ? fmt("%.1f", r.build_ms).c_str() : "",
                r.accel != Accel::Brute ? fmt("%.1f", r.bytes_per_sphere).c_str() : "");
  }

  if (!o.csv.empty()) {
    std::ostringstream f;
    f << "device,software,width,height,spp,depth,repeat,spheres,radius,accel,precision,skipped,median_ms,min_ms,"
           "max_ms,speedup,build_ms,bytes_per_sphere,refs_per_sphere,vs_bvh\n";
    for (const Row& r : rows) {
      f << '"' << ctx.info.name << "\"," << (ctx.info.software ? 1 : 0) << ',' << settings.width << ','
        << settings.height << ',' << settings.spp << ',' << settings.bounce_limit << ',' << o.repeat << ','
        << r.spheres << ',' << r.radius << ',' << accel_name(r.accel) << ',' << precision_name(r.precision) << ','
        << (r.skipped ? 1 : 0) << ',';
      if (r.skipped) {
        f << ",,,,,,,\n";
        continue;
      }
      f << r.median_ms << ',' << r.min_ms << ',' << r.max_ms << ',' << (r.speedup ? *r.speedup : 0.0) << ','
        << r.build_ms << ',' << r.bytes_per_sphere << ',' << r.refs_per_sphere << ',';
      if (r.vs_bvh) f << *r.vs_bvh;
      f << '\n';
    }
    const std::string text = f.str();
    write_file_atomically(o.csv, text.data(), text.size());
  }
  return 0;
}

}  // namespace octrace
