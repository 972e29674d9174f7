// Renders a Scene on a VulkanContext: uploads the scene, runs one compute
// dispatch per sample pass into fp32 accumulation buffers, reads the mean back.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "scene/features.h"
#include "io/image.h"
#include "accel/octree.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace octrace {

struct Buffer;

enum class Accel { Brute, Octree };

// Which quantities the shading code keeps in half (shaders/precision.glsl).
enum class Precision { FP32, FP16, FP16All };
const char* precision_name(Precision p);
// "fp32" | "fp16" | "fp16-all"; throws InputError naming --precision.
Precision parse_precision(const std::string& name);

struct RenderSettings {
  Accel accel = Accel::Octree;
  Precision precision = Precision::FP32;
  // false: the pipeline is specialised to the scene's features (`--effects
  // auto`); true: the general pipeline with every effect (`--effects all`).
  bool all_effects = false;
  // Russian roulette from this bounce on (0: off): a path survives with
  // probability p = min(max throughput, 0.95) and carries 1/p more, so the
  // expectation is unchanged and the noise grows; paths end sooner.
  uint32_t rr_depth = 0;
  OctreeParams octree;
  int width = 1200;
  int height = 800;
  uint32_t spp = 10;
  uint32_t max_depth = 50;
  uint32_t sample_seed = 1;
  // The first sample index of this render: runs with disjoint ranges of
  // sample indices (on other devices or machines) merge into one render.
  uint32_t first_sample = 0;
};

// Checks sizes and counts before anything is allocated; throws InputError
// naming the flag ("--size 0x10: width and height must be >= 1").
void validate_settings(const RenderSettings& settings);

struct RenderTimings {
  double accel_build_ms = 0;   // octree build on the CPU (wall)
  double upload_ms = 0;        // buffer creation and scene upload (wall)
  double pipeline_ms = 0;      // compute pipeline creation (wall)
  double render_device_ms = 0; // path-tracing passes, timestamp queries (device)
  double render_wall_ms = 0;   // the same passes, wall clock incl. submission
  double readback_ms = 0;      // accumulation download and resolve (wall)
};

// The accumulation state: what a render *is*.
struct RenderResult {
  Image mean;              // linear mean radiance per pixel
  Image variance_of_mean;  // per pixel and channel: sample variance / count
  std::vector<float> count;  // per pixel: samples added (NaN/Inf ones are not)
  uint32_t min_samples = 0;       // smallest per-pixel sample count
  uint64_t nonfinite_samples = 0; // NaN/Inf samples rejected (0 for a clean render)
  RenderTimings timings;
  OctreeStats octree;             // zeros for --accel brute
  SceneFeatures features;         // what the pipeline was specialised to
};

// Called after each batch of passes: passes done, total passes.
using ProgressFn = std::function<void(uint32_t done, uint32_t total)>;

// A scene uploaded to a device with its pipeline, ready to run passes; reusable
// for several renders (benchmarks, the preview window).
class PathTracer {
 public:
  PathTracer(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings);
  ~PathTracer();
  PathTracer(const PathTracer&) = delete;
  PathTracer& operator=(const PathTracer&) = delete;

  // Clears the accumulation buffers and the statistics.
  void reset();
  // Adds passes [first_sample, first_sample + count) in one submission and
  // waits; returns their device time in milliseconds.
  double run_passes(uint32_t first_sample, uint32_t count);
  // Records the same passes into `cmd` without submitting, for a caller that
  // adds its own work to the submission (the preview window's resolve pass).
  void record_passes(VkCommandBuffer cmd, uint32_t first_sample, uint32_t count) const;
  // The accumulation buffers a resolve pass reads (layout in shaders/shared.h):
  // Kahan sum with the sample count in .w, and the compensation terms.
  const Buffer& accum_sum() const;
  const Buffer& accum_comp() const;
  const RenderSettings& settings() const;
  RenderResult read_result();
  const RenderTimings& setup_timings() const;
  const OctreeStats& octree_stats() const;
  const SceneFeatures& features() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The whole render: set-up, settings.spp passes in batches sized to about a
// quarter second each (progress after each), read-back.
RenderResult render(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings,
                    const ProgressFn& progress = {});

}  // namespace octrace
