// One render on several Vulkan devices at once (render --device all | 0,2):
// a thread per device, each taking the next batch of sample indices from a
// shared counter (so a fast and a slow device finish together), and the
// devices' accumulation states merged exactly on the host. The samples are
// the same as a one-device render's (the same indices); only the order in
// which they are summed differs, so the image equals it to float rounding.
#pragma once

#include <string>
#include <vector>

#include "render/path_tracer.h"

namespace octrace {

// What one device did.
struct DeviceShare {
  std::string name;
  uint32_t samples = 0;      // samples per pixel it rendered
  double device_ms = 0;      // its passes' device time (timestamp queries)
  double setup_ms = 0;       // octree build, upload, pipeline (wall)
};

// Renders `settings` over `contexts` (at least one). control.progress and
// control.stop work as for render(); checkpoints and resume are not
// supported here (InputError). result.timings.render_wall_ms is the time
// from when every device is set up to when the last finishes its passes;
// render_device_ms the largest device's passes; readback_ms the read-back's
// merge on the host; the set-up timings are device 0's (each device's own
// is in its DeviceShare).
RenderResult render_on_devices(const std::vector<const VulkanContext*>& contexts, const Scene& scene,
                               const RenderSettings& settings, const RenderControl& control,
                               std::vector<DeviceShare>& shares);

// Merges accumulation states of disjoint sample sets of one render: the
// Kahan sums (sum - compensation) add, the counts add, and the squared
// deviations combine by Chan et al.'s parallel update (M2 = sum of M2_i +
// n_i (mean_i - mean)^2); ray segments add. Throws InputError if the sizes differ.
Accumulation merge_accumulations(const std::vector<Accumulation>& parts);
// `count` consecutive pixels of one part: its three buffers from some pixel
// on (a whole Accumulation's, or a slice's that arrived apart).
struct AccumulationPixels {
  const glm::vec4* sum;
  const glm::vec4* comp;
  const glm::vec4* sq;
};
// The same merge for `count` pixels (part k's pixel i at parts[k].sum[i],
// ...), into `sum`, `comp` and `sq`: for a caller that merges a large state
// in slices or threads (the MPI front end merges slices as they arrive). The
// output may be the first part's own pixels (a merge in place: each pixel's
// values are read before they are written); comp.w is left as it is.
void merge_accumulation_pixels(const std::vector<AccumulationPixels>& parts, glm::vec4* sum, glm::vec4* comp,
                               glm::vec4* sq, size_t count);

}  // namespace octrace
