#include "accel/hidden_parts.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "accel/clip.h"
#include "core/parallel.h"

namespace octrace {
namespace {

// The occluders' centres in a uniform grid of about two a cell; those whose
// radius exceeds kLargeRadii times the median occluder's in a list of their
// own (the rtiow ground, radius 1000, whose centre lies far from the balls
// it touches).
constexpr double kLargeRadii = 16.0;

struct OccluderGrid {
  glm::dvec3 lo{0.0};
  double cell = 1.0;
  glm::ivec3 dims{1};
  std::vector<uint32_t> start;  // per cell, into items; start[cells] = items.size()
  // The occluders by cell, copied so that a cell's are read in one run,
  // each with its radius less the margin (reach, below).
  struct Item {
    glm::vec3 center;
    float reach;
    uint32_t index;
  };
  std::vector<Item> items;
  std::vector<uint32_t> large;

  glm::ivec3 cell_of(const glm::dvec3& p) const {
    const glm::dvec3 c = glm::floor((p - lo) / cell);
    return glm::clamp(glm::ivec3(glm::clamp(c, glm::dvec3(-1.0), glm::dvec3(dims))), glm::ivec3(0), dims - 1);
  }
  size_t index(const glm::ivec3& c) const { return (size_t(c.z) * dims.y + c.y) * dims.x + c.x; }
};

// The edge for about `per_cell` centres a cell over extents `ext` (an axis
// shorter than the edge counts as one cell).
double grid_cell(const glm::dvec3& ext, double count, double per_cell) {
  const double target = std::max(1.0, count / per_cell);
  double cell = 0.0;
  for (int it = 0; it < 8; ++it) {
    double product = 1.0;
    int axes = 0;
    for (int a = 0; a < 3; ++a)
      if (ext[a] > cell) {
        product *= ext[a];
        ++axes;
      }
    if (axes == 0) break;
    const double next = std::pow(product / target, 1.0 / axes);
    if (next == cell) break;
    cell = next;
  }
  return cell > 0.0 && std::isfinite(cell) ? cell : 1.0;
}

// The margin by which a point must lie inside occluder b to count as hidden.
double margin(const Ball& b) {
  const glm::dvec3 c = glm::abs(glm::dvec3(b.center));
  return 1e-4 * b.radius + 32.0 * double(std::numeric_limits<float>::epsilon()) * (std::max({c.x, c.y, c.z}) + b.radius);
}

// The float at or below / above x.
float float_down(double x) {
  const float f = float(x);
  return double(f) > x ? next_float_down(f) : f;
}
float float_up(double x) {
  const float f = float(x);
  return double(f) < x ? next_float_up(f) : f;
}

// An occluder's radius less the margin: how far from its centre a point
// counts as hidden; rounded down to a float for the grid's copy (a smaller
// reach hides less: never wrong).
double reach(const Ball& b) { return double(b.radius) - margin(b); }
float reach_down(const Ball& b) { return float_down(reach(b)); }

// The q-quantile (0..1) of v, which it reorders.
double quantile(std::vector<double>& v, double q) {
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

OccluderGrid make_grid(std::span<const Ball> balls, std::span<const uint8_t> occludes) {
  OccluderGrid g;
  std::vector<uint32_t> occ;
  for (uint32_t j = 0; j < balls.size(); ++j)
    if (occludes[j] && balls[j].radius > 0.0f) occ.push_back(j);
  if (occ.empty()) {
    g.start.assign(2, 0);
    return g;
  }
  // The grid spans the centres' 1st to 99th percentiles per axis, so that a
  // few far ones (the rtiow ground's centre lies 1000 below the field) do
  // not make its cells huge; centres outside fall into the border cells.
  // Percentiles (and the median radius, below) of every step-th occluder:
  // a grid is only a way to find neighbours, and any grid finds them.
  const size_t step = std::max<size_t>(1, occ.size() / 65536);
  std::vector<double> coord;
  coord.reserve(occ.size() / step + 1);
  glm::dvec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    coord.clear();
    for (size_t q = 0; q < occ.size(); q += step) coord.push_back(balls[occ[q]].center[a]);
    lo[a] = quantile(coord, 0.01);
    hi[a] = quantile(coord, 0.99);
  }
  g.lo = lo;
  g.cell = grid_cell(hi - lo, double(occ.size()), 2.0);
  // At most about 4 cells an occluder, whatever the extents.
  for (;;) {
    const glm::dvec3 d = glm::floor((hi - lo) / g.cell) + 1.0;
    if (d.x * d.y * d.z <= 4.0 * double(occ.size()) + 8.0) {
      g.dims = glm::ivec3(d);
      break;
    }
    g.cell *= 1.25;
  }
  // The large ones, largest first, at most kMaxLargeOccluders (the rest occlude nothing: boxes only grow).
  coord.clear();
  for (size_t q = 0; q < occ.size(); q += step) coord.push_back(balls[occ[q]].radius);
  const double large = kLargeRadii * quantile(coord, 0.5);
  std::vector<uint32_t> small;
  for (uint32_t j : occ) (double(balls[j].radius) > large ? g.large : small).push_back(j);
  std::stable_sort(g.large.begin(), g.large.end(), [&](uint32_t a, uint32_t b) { return balls[a].radius > balls[b].radius; });
  if (g.large.size() > kMaxLargeOccluders) g.large.resize(kMaxLargeOccluders);
  const size_t cells = size_t(g.dims.x) * g.dims.y * g.dims.z;
  g.start.assign(cells + 1, 0);
  std::vector<uint32_t> cell_of(small.size());
  parallel_ranges(small.size(), parallel_range_count(small.size(), 65536), [&](size_t, size_t begin, size_t end) {
    for (size_t q = begin; q < end; ++q) cell_of[q] = uint32_t(g.index(g.cell_of(glm::dvec3(balls[small[q]].center))));
  });
  for (uint32_t c : cell_of) ++g.start[c + 1];
  for (size_t c = 0; c < cells; ++c) g.start[c + 1] += g.start[c];
  g.items.resize(small.size());
  std::vector<uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (size_t q = 0; q < small.size(); ++q) {
    const Ball& b = balls[small[q]];
    g.items[fill[cell_of[q]]++] = {b.center, reach_down(b), small[q]};
  }
  return g;
}

// A half-space e . q <= h in the ball's frame (q = p - centre).
struct Cut {
  glm::dvec3 e;
  double h;
};

// The box of `box` and the half-space, in place; false when nothing is left.
// `cut` is set when the half-space cut the box.
bool clip_box(glm::dvec3& lo, glm::dvec3& hi, const Cut& c, bool& cut) {
  glm::dvec3 lo_t, hi_t;
  for (int k = 0; k < 3; ++k) {
    lo_t[k] = std::min(c.e[k] * lo[k], c.e[k] * hi[k]);
    hi_t[k] = std::max(c.e[k] * lo[k], c.e[k] * hi[k]);
  }
  const double min_sum = lo_t.x + lo_t.y + lo_t.z, max_sum = hi_t.x + hi_t.y + hi_t.z;
  cut = false;
  if (max_sum <= c.h) return true;
  if (min_sum > c.h) return false;
  cut = true;
  for (int k = 0; k < 3; ++k) {
    if (c.e[k] == 0.0) continue;
    const double bound = (c.h - (min_sum - lo_t[k])) / c.e[k];
    if (c.e[k] > 0.0)
      hi[k] = std::min(hi[k], bound);
    else
      lo[k] = std::max(lo[k], bound);
  }
  return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z;
}

}  // namespace

std::vector<Aabb> visible_sphere_boxes(std::span<const Ball> balls, std::span<const uint8_t> occludes,
                                       HiddenPartsStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Aabb> boxes(balls.size());
  const OccluderGrid grid = make_grid(balls, occludes);
  const size_t ranges = parallel_range_count(balls.size(), 4096);
  std::vector<HiddenPartsStats> per_range(clamp_ranges(balls.size(), ranges));
  parallel_ranges(balls.size(), ranges, [&](size_t k, size_t begin, size_t end) {
    std::vector<Cut> cuts;
    for (size_t i = begin; i < end; ++i) {
      const Ball& s = balls[i];
      boxes[i] = {s.center - s.radius, s.center + s.radius};
      const glm::dvec3 c(s.center);
      const double r = s.radius;
      glm::dvec3 lo(-r), hi(r);
      bool alive = true, any_cut = false;
      cuts.clear();
      const auto consider = [&](uint32_t j, const glm::vec3& center, double big_r) {
        if (j == i || !alive || big_r <= 0.0) return;
        const glm::dvec3 e = glm::dvec3(center) - c;
        const double d2 = glm::dot(e, e);
        if (d2 >= (r + big_r) * (r + big_r)) return;  // no point of the surface inside by the margin
        const Cut cut{e, 0.5 * (d2 + r * r - big_r * big_r)};
        if (d2 == 0.0) {  // concentric: all inside, or nothing
          if (cut.h < 0.0) alive = false;
          return;
        }
        bool did = false;
        alive = clip_box(lo, hi, cut, did);
        if (did) {
          cuts.push_back(cut);
          any_cut = true;
        }
      };
      if (!grid.items.empty()) {
        const glm::ivec3 home = grid.cell_of(c);
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const glm::ivec3 cell = home + glm::ivec3(dx, dy, dz);
              if (glm::any(glm::lessThan(cell, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(cell, grid.dims)))
                continue;
              const size_t at = grid.index(cell);
              for (uint32_t q = grid.start[at]; q < grid.start[at + 1]; ++q) {
                const OccluderGrid::Item& it = grid.items[q];
                consider(it.index, it.center, it.reach);
              }
            }
      }
      for (uint32_t j : grid.large) consider(j, balls[j].center, reach(balls[j]));
      // A second pass over the cuts: each was applied to the box as it was then.
      for (size_t q = 0; alive && q < cuts.size(); ++q) {
        bool did = false;
        alive = clip_box(lo, hi, cuts[q], did);
      }
      if (!alive) {
        boxes[i] = {s.center, s.center};
        ++per_range[k].hidden;
      } else if (any_cut) {
        const Aabb whole = boxes[i];
        Aabb part;
        for (int a = 0; a < 3; ++a) {
          part.lo[a] = std::max(whole.lo[a], float_down(c[a] + lo[a]));
          part.hi[a] = std::min(whole.hi[a], float_up(c[a] + hi[a]));
        }
        if (part.lo != whole.lo || part.hi != whole.hi) ++per_range[k].clipped;
        boxes[i] = part;
      }
    }
  });
  if (stats) {
    *stats = {};
    for (const HiddenPartsStats& p : per_range) {
      stats->clipped += p.clipped;
      stats->hidden += p.hidden;
    }
    stats->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  return boxes;
}

}  // namespace octrace
