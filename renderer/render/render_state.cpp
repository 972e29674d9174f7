#include "render/render_state.h"

#include <cmath>

#include "core/errors.h"

namespace octrace {

namespace {

std::string mean_path(const std::string& prefix) { return prefix + ".mean.pfm"; }
std::string count_path(const std::string& prefix) { return prefix + ".count.pfm"; }

}  // namespace

void write_state(const RenderState& state, const std::string& prefix) {
  Image count{state.mean.width, state.mean.height, std::vector<float>(state.mean.rgb.size())};
  for (size_t i = 0; i < state.count.size(); ++i)
    for (int c = 0; c < 3; ++c) count.rgb[3 * i + c] = state.count[i];
  write_image(state.mean, mean_path(prefix));
  write_image(count, count_path(prefix));
}

RenderState read_state(const std::string& prefix) {
  RenderState state;
  state.mean = read_image(mean_path(prefix));
  Image count = read_image(count_path(prefix));
  if (count.width != state.mean.width || count.height != state.mean.height)
    throw InputError(count_path(prefix) + ": " + std::to_string(count.width) + "x" + std::to_string(count.height) +
                     ", but the mean is " + std::to_string(state.mean.width) + "x" +
                     std::to_string(state.mean.height));
  state.count.resize(size_t(count.width) * count.height);
  for (size_t i = 0; i < state.count.size(); ++i) {
    float n = count.rgb[3 * i];
    if (!std::isfinite(n) || n < 0.0f)
      throw InputError(count_path(prefix) + ": pixel " + std::to_string(i) + ": count must be a finite number >= 0");
    state.count[i] = n;
  }
  return state;
}

RenderState merge_states(const std::vector<RenderState>& states) {
  if (states.empty()) throw InputError("merge: no states given");
  const Image& first = states.front().mean;
  for (const RenderState& s : states)
    if (s.mean.width != first.width || s.mean.height != first.height)
      throw InputError("merge: state sizes differ: " + std::to_string(first.width) + "x" +
                       std::to_string(first.height) + " vs " + std::to_string(s.mean.width) + "x" +
                       std::to_string(s.mean.height));
  RenderState merged{first, std::vector<float>(states.front().count.size(), 0.0f)};
  for (size_t i = 0; i < merged.count.size(); ++i) {
    double n = 0, sum[3] = {0, 0, 0};
    for (const RenderState& s : states) {
      n += s.count[i];
      for (int c = 0; c < 3; ++c) sum[c] += double(s.count[i]) * double(s.mean.rgb[3 * i + c]);
    }
    merged.count[i] = float(n);
    for (int c = 0; c < 3; ++c) merged.mean.rgb[3 * i + c] = n > 0 ? float(sum[c] / n) : 0.0f;
  }
  return merged;
}

}  // namespace octrace
