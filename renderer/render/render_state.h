// The accumulation state as files: what a render *is* (docs/design.md). A state is
// the per-pixel mean and the per-pixel sample count, written as two PFMs
// (PREFIX.mean.pfm, linear; PREFIX.count.pfm, the count in every channel,
// exact up to 2^24). States of the same scene from independent runs (other
// sample seeds, or disjoint --first-sample ranges, on other devices or
// machines) merge into one image weighted by their counts.
#pragma once

#include <string>
#include <vector>

#include "io/image.h"

namespace octrace {

struct RenderState {
  Image mean;
  std::vector<float> count;  // per pixel
};

// Written atomically, like every image. Throws as write_image does.
void write_state(const RenderState& state, const std::string& prefix);
// Throws InputError naming the file when one is missing, unreadable, of
// another size than its partner, or holds a count that is not a finite
// number >= 0.
RenderState read_state(const std::string& prefix);
// Per pixel: the count-weighted mean (in double) and the summed counts.
// Throws InputError if the sizes differ or the list is empty.
RenderState merge_states(const std::vector<RenderState>& states);

}  // namespace octrace
