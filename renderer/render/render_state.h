// The accumulation state as files: what a render *is* (docs/design.md). A state is
// the per-pixel mean and the per-pixel sample count, written as two PFMs
// (PREFIX.mean.pfm, linear; PREFIX.count.pfm, the count in every channel,
// exact up to 2^24). States of the same scene from independent runs (other
// sample seeds, or disjoint --first-sample ranges, on other devices or
// machines) merge into one image weighted by their counts.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>
#include <vector>

#include <glm/vec4.hpp>

#include "io/image.h"

namespace octrace {

struct RenderState {
  Image mean;
  std::vector<float> count;  // per pixel
};

// PREFIX.mean.pfm and PREFIX.count.pfm, written as one set: each flushed to
// a temporary before either is renamed (write_files_atomically), so a failed
// write leaves neither new. Throws as write_image does.
void write_state(const RenderState& state, const std::string& prefix);
// Throws InputError naming the file when one is missing, unreadable, of
// another size than its partner, or holds a count that is not a finite
// number >= 0.
RenderState read_state(const std::string& prefix);
// Per pixel: the count-weighted mean (in double) and the summed counts.
// Throws InputError if the sizes differ or the list is empty.
RenderState merge_states(const std::vector<RenderState>& states);

// The raw accumulation buffers of a render (shaders/shared/shared.h: Kahan
// sum with the sample count in .w, compensation, M2 with the ray segments in
// .w), as the device holds them: what a checkpoint keeps, so that a resumed
// render continues bit for bit.
struct Accumulation {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> sum, comp, sq;
};

// What a checkpoint must match to be resumed: the scene as uploaded (a hash
// of its device arrays and camera), and every setting that changes a sample.
struct CheckpointInfo {
  uint64_t scene_hash = 0;
  int width = 0;
  int height = 0;
  uint32_t sample_seed = 0;
  uint32_t first_sample = 0;
  uint32_t bounce_limit = 0;
  uint32_t rr_depth = 0;
  std::string precision;
  std::string accel;
  uint32_t samples = 0;  // samples per pixel the state holds (not compared)
};

// A CheckpointInfo as the JSON object of a checkpoint's header (scene_hash
// as a hex string), and back; the reader throws InputError naming a
// missing, mistyped or out-of-range field ("samples: expected a whole number
// in 0..4294967295, got -1"). Also what MPI ranks exchange (app/mpi_render).
nlohmann::json checkpoint_info_json(const CheckpointInfo& info);
CheckpointInfo checkpoint_info_of(const nlohmann::json& j);

// The mean and count of an accumulation, as PathTracer::read_result has them.
RenderState state_of(const Accumulation& acc);

// One channel of a pixel's mean: its Kahan sum (sum - comp: comp holds what
// the float sum overshot) over its n samples, in double.
inline float pixel_mean(float sum, float comp, double n) {
  return float(n > 0 ? (double(sum) - double(comp)) / n : 0.0);
}
// One channel of the variance of a pixel's mean: its sum of squared
// deviations (Welford's M2) over n - 1, over n.
inline float pixel_variance_of_mean(float m2, double n) {
  const double var = n > 1 ? double(m2) / (n - 1) : 0.0;
  return n > 0 ? float(var / n) : 0.0f;
}

// The first difference between a saved checkpoint and a render that would
// resume it, in words ("sample seed 3, this render 1"); empty if none.
std::string checkpoint_mismatch(const CheckpointInfo& saved, const CheckpointInfo& now);

// PREFIX.accum: the raw buffers and the info (one file, so the two always
// agree), and PREFIX.mean.pfm + PREFIX.count.pfm as write_state writes them
// (for octrace merge); the three written as one set.
void write_checkpoint(const std::string& prefix, const Accumulation& acc, const CheckpointInfo& info,
                      const RenderState& state);
// The files a state is written to: PREFIX.mean.pfm, PREFIX.count.pfm and,
// with `checkpoint`, PREFIX.accum (for the checks before any long work).
std::vector<std::string> state_paths(const std::string& prefix, bool checkpoint);

// Reads PREFIX.accum. Throws InputError naming the file when it is missing,
// not a checkpoint, truncated or inconsistent.
Accumulation read_checkpoint(const std::string& prefix, CheckpointInfo& info);

}  // namespace octrace
