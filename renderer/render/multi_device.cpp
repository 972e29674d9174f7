#include "render/multi_device.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "core/clock.h"
#include "core/errors.h"

namespace octrace {

void merge_accumulation_pixels(const std::vector<AccumulationPixels>& parts, glm::vec4* sum, glm::vec4* comp,
                               glm::vec4* sq, size_t count) {
  // In place (sum == parts[0].sum ...): the counts (.w) and every part's
  // channel c are read before the output's channel c is written, and the
  // counts are written last.
  for (size_t i = 0; i < count; ++i) {
    double n = 0, total[3] = {0, 0, 0};
    uint32_t rays = 0;
    for (const AccumulationPixels& p : parts) {
      n += p.sum[i].w;
      rays += std::bit_cast<uint32_t>(p.sq[i].w);
      for (int c = 0; c < 3; ++c) total[c] += double(p.sum[i][c]) - double(p.comp[i][c]);
    }
    for (int c = 0; c < 3; ++c) {
      const double mean = n > 0 ? total[c] / n : 0.0;
      double m2 = 0;
      for (const AccumulationPixels& p : parts) {
        const double ni = p.sum[i].w;
        if (ni == 0) continue;
        const double mean_i = (double(p.sum[i][c]) - double(p.comp[i][c])) / ni;
        m2 += double(p.sq[i][c]) + ni * (mean_i - mean) * (mean_i - mean);
      }
      // The total as a float and what it overshoots (the Kahan form: sum - comp).
      sum[i][c] = float(total[c]);
      comp[i][c] = float(double(sum[i][c]) - total[c]);
      sq[i][c] = float(m2);
    }
    sum[i].w = float(n);
    sq[i].w = std::bit_cast<float>(rays);
  }
}

Accumulation merge_accumulations(const std::vector<Accumulation>& parts) {
  if (parts.empty()) throw InputError("merge: no accumulation states");
  const Accumulation& first = parts.front();
  std::vector<AccumulationPixels> pixels;
  for (const Accumulation& p : parts) {
    if (p.width != first.width || p.height != first.height || p.sum.size() != first.sum.size() ||
        p.comp.size() != p.sum.size() || p.sq.size() != p.sum.size())
      throw InputError("merge: accumulation states of different sizes");
    pixels.push_back({p.sum.data(), p.comp.data(), p.sq.data()});
  }
  Accumulation out{first.width, first.height, std::vector<glm::vec4>(first.sum.size()),
                   std::vector<glm::vec4>(first.sum.size()), std::vector<glm::vec4>(first.sum.size())};
  merge_accumulation_pixels(pixels, out.sum.data(), out.comp.data(), out.sq.data(), first.sum.size());
  return out;
}

RenderResult render_on_devices(const std::vector<const VulkanContext*>& contexts, const Scene& scene,
                               const RenderSettings& settings, const RenderControl& control,
                               std::vector<DeviceShare>& shares) {
  if (contexts.empty()) throw InputError("device: no device given");
  if (control.resume || control.checkpoint)
    throw InputError("--resume and --state/--checkpoint work on one device only, not with a device list");
  const size_t devices = contexts.size();
  shares.assign(devices, {});
  std::vector<Accumulation> parts(devices);
  RenderResult r;  // device 0's set-up timings, octree and features; the merged state
  std::vector<RenderCounts> counts(devices);
  std::vector<std::vector<DispatchTime>> dispatches(devices);
  std::atomic<uint32_t> next{0};  // the next sample offset to hand out
  std::atomic<uint32_t> done{0};
  std::atomic<bool> failed{false};
  std::mutex progress_mutex;
  std::exception_ptr error;
  std::mutex error_mutex;
  const PassSettings pass = pass_settings(scene, settings);
  // The passes' wall time runs from when every device is set up to when the
  // last one finishes its passes: set-up (octree, upload, pipeline) and the
  // read-back and merge are timed apart, as render() does.
  std::atomic<size_t> ready{0};
  std::vector<Clock::time_point> ends(devices);
  Clock::time_point start;
  std::mutex start_mutex;
  std::condition_variable all_ready;

  const auto work = [&](size_t d) {
    try {
      auto setup_start = Clock::now();
      PathTracer tracer(*contexts[d], scene, settings);
      shares[d].name = contexts[d]->info.name;
      shares[d].setup_ms = ms_since(setup_start);
      {
        std::unique_lock<std::mutex> lock(start_mutex);
        if (++ready == devices) {
          start = Clock::now();
          all_ready.notify_all();
        } else {
          all_ready.wait(lock, [&] { return ready.load() >= devices; });
        }
      }
      // Batches grow until one takes about a quarter second, and shrink near
      // the end so that no device is left with much more than the others.
      // The first batch (PathTracer::first_batch) and every later one in whole
      // multiples of the batch granule, as render()'s.
      const uint32_t lanes = tracer.batch_granule();
      uint32_t batch = tracer.first_batch();
      for (;;) {
        if (failed || (control.stop && control.stop->load())) break;
        const uint32_t remaining = settings.spp - std::min(settings.spp, next.load());
        const uint32_t want = std::max(1u, std::min(batch, remaining / uint32_t(2 * devices) + 1));
        const uint32_t first = next.fetch_add(want);
        if (first >= settings.spp) break;
        const uint32_t n = std::min(want, settings.spp - first);
        auto batch_start = Clock::now();
        shares[d].device_ms += tracer.run_passes(pass, settings.first_sample + first, n);
        const double per_pass = ms_since(batch_start) / n;
        shares[d].samples += n;
        batch = next_batch(per_pass, lanes);
        const uint32_t total = done += n;
        if (control.progress) {
          std::lock_guard<std::mutex> lock(progress_mutex);
          control.progress(total, settings.spp);
        }
      }
      ends[d] = Clock::now();
      parts[d] = tracer.read_accumulation();
      counts[d] = tracer.counts();
      dispatches[d] = tracer.dispatch_times();
      if (d == 0) {
        r.timings = tracer.setup_timings();
        r.octree = tracer.octree_stats();
        r.buffer_parts = tracer.buffer_parts();
        r.buffer_part_bytes = tracer.buffer_part_bytes();
        r.features = tracer.features();
      }
    } catch (...) {
      failed = true;
      {
        // A device that failed before the start releases the others.
        std::lock_guard<std::mutex> lock(start_mutex);
        ready = devices;
        all_ready.notify_all();
      }
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  for (size_t d = 1; d < devices; ++d) threads.emplace_back(work, d);
  work(0);
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);

  auto merge_start = Clock::now();
  resolve_accumulation(merge_accumulations(parts), r);
  r.timings.readback_ms = ms_since(merge_start);
  RenderCounts total;
  for (const RenderCounts& c : counts) total += c;
  r.nonfinite_samples = total.nonfinite_samples;
  r.cut_paths = total.cut_paths;
  r.walk = total.walk;
  for (const std::vector<DispatchTime>& d : dispatches) add_dispatch_times(r.dispatches, d);
  const Clock::time_point last = *std::max_element(ends.begin(), ends.end());
  r.timings.render_wall_ms = std::chrono::duration<double, std::milli>(last - start).count();
  r.timings.render_device_ms = 0;
  for (const DeviceShare& s : shares) r.timings.render_device_ms = std::max(r.timings.render_device_ms, s.device_ms);
  r.samples = std::min(done.load(), settings.spp);
  r.interrupted = r.samples < settings.spp;
  return r;
}

}  // namespace octrace
