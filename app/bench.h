// `octrace bench`: the study's experiment (render time against sphere count
// for each acceleration structure), repeated, with medians and spread.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "render/path_tracer.h"

namespace octrace {

struct BenchOptions {
  std::vector<uint64_t> spheres;
  std::vector<float> radii;
  std::vector<Accel> accels;
  std::vector<Precision> precisions;
  RenderSettings settings;   // size, spp, depth, octree parameters
  bool size_given = false;   // else 1200x800 on a GPU, 400x225 on a CPU device
  uint32_t repeat = 5;
  // Before each configuration's timed runs: back-to-back runs for at least
  // this long (at least one), so that a GPU's clock is up (bench.cpp, warm_up).
  double warmup_s = 0.5;
  double budget_s = 60;      // skip a configuration predicted to take longer (all repeats)
  uint64_t seed = 1;
  std::string device = "auto";
  bool validation = false;
  bool robust_buffers = false;  // ContextOptions::robust_buffers
  std::string csv;
  bool quiet = false;
  // Non-empty: instead of the sphere-count sweep, time --effects auto against
  // all for each scene family (rtiow with its materials replaced, see bench.cpp).
  std::vector<std::string> families;
  // Non-empty: instead of the sphere sweep, time these scenes (a name and the
  // scene, loaded by the caller from --scene files) per accel and precision.
  std::vector<std::pair<std::string, Scene>> scenes;
};

int run_bench(const BenchOptions& options);

}  // namespace octrace
