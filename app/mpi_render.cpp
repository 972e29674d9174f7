#include "mpi_render.h"

#include <algorithm>
#include <barrier>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <functional>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <set>
#include <mutex>
#include <optional>
#include <thread>

#include <mpi.h>

#include <nlohmann/json.hpp>

#include "core/clock.h"
#include "core/errors.h"
#include "core/parallel.h"
#include "render/multi_device.h"
#include "vk/context.h"

namespace octrace::mpi {

namespace {

using json = nlohmann::json;

constexpr int kTagRequest = 11, kTagReply = 12, kTagDevice = 13, kTagState = 20, kTagCheckpoint = 21,
              kTagShared = 22;
// A reply {kCheckpoint, 0}: send your state (a checkpoint), then ask again.
constexpr uint32_t kCheckpoint = UINT32_MAX;
// The states travel in slices of kSlice pixels (3 messages of 16 bytes per
// pixel each: 1 MiB): small enough that rank 0's reused receive buffers
// cost little to allocate and that the merge of the last slice, which
// nothing overlaps, is short.
constexpr size_t kSlice = size_t(1) << 16;
// A request's kinds: a batch (after `completed` samples of the last one), a
// batch and stop the job (a signal reached the rank), the rank failed.
constexpr int64_t kWant = 0, kStop = 1, kFailed = 2;

// Waits for a non-blocking operation without spinning a core: OpenMPI's
// blocking calls poll, which would take a lavapipe rank's CPU.
void wait_gently(MPI_Request& request) {
  for (;;) {
    int flag = 0;
    MPI_Test(&request, &flag, MPI_STATUS_IGNORE);
    if (flag) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

enum class Phase { Render, Final, Done };

// A time on this host's monotonic clock (steady_clock: CLOCK_MONOTONIC on
// Linux, one for every process of the host), in ms.
double ms_since_epoch(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(t.time_since_epoch()).count();
}

// Every slice's messages are posted at once: OpenMPI announces each to rank
// 0, which copies it out of this process's memory (the single-copy
// mechanism, CMA, on one host) when it has a buffer for it, without waiting
// for this rank to be scheduled between messages.
void send_state(const Accumulation& acc, int tag) {
  const size_t pixels = acc.sum.size();
  std::vector<MPI_Request> requests;
  for (size_t begin = 0; begin < pixels; begin += kSlice) {
    const int count = int(std::min(kSlice, pixels - begin) * 4);
    for (const std::vector<glm::vec4>* v : {&acc.sum, &acc.comp, &acc.sq}) {
      requests.emplace_back();
      MPI_Isend(v->data() + begin, count, MPI_FLOAT, 0, tag, MPI_COMM_WORLD, &requests.back());
    }
  }
  for (MPI_Request& request : requests) wait_gently(request);
}

void receive_state(int source, int tag, Accumulation& acc) {
  const size_t pixels = size_t(acc.width) * size_t(acc.height);
  for (std::vector<glm::vec4>* v : {&acc.sum, &acc.comp, &acc.sq}) v->resize(pixels);
  for (size_t begin = 0; begin < pixels; begin += kSlice) {
    const int count = int(std::min(kSlice, pixels - begin) * 4);
    for (std::vector<glm::vec4>* v : {&acc.sum, &acc.comp, &acc.sq})
      MPI_Recv(v->data() + begin, count, MPI_FLOAT, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
}

// `text` with its first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  if (const size_t at = text.find(from); at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Waits for a request, checking every 0.1 ms: shorter than wait_gently's
// naps (the reduce waits for many slices), still without spinning a core.
void wait_briefly(MPI_Request& request) {
  for (;;) {
    int flag = 0;
    MPI_Test(&request, &flag, MPI_STATUS_IGNORE);
    if (flag) return;
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
}

// The reduce on one host without the MPI transport (docs/multi_gpu.md,
// "Reduce"): the ranks of rank 0's host allocate one MPI shared-memory window
// (MPI_Win_allocate_shared) with a ring of kSharedRing slices (sum, comp,
// sq) per rank but rank 0. A rank copies slice s of its state into ring slot
// s % kSharedRing once rank 0 has merged slice s - kSharedRing, then tells
// rank 0 (a message of the slices written, after MPI_Win_sync: the unified
// memory model's pattern, MPI 4.0 sec. 12.7); rank 0 merges the slice from
// the window in place and tells the rank how many slices it has merged. The
// ring, not a window of the whole state: fresh pages of a shared-memory file
// cost a fault and a zeroed page each (4 KiB; tmpfs gives no huge pages by
// default), which for a 398 MB window took ~0.5 s on the 2-core VM, while
// the ring stays mapped (its pages are touched while the ranks render:
// Job::prefault). When every rank is on rank 0's host, a slice is
// kSharedGroup message slices (2^18 pixels): each slice costs a hand-over
// (two barriers on each side and two messages), and the 4K reduce's 127
// small slices of 2^16 took 60 ms where 32 of 2^18 took 47 ms on the H100
// host (optimisation log 28).
// OCTRACE_MPI_REDUCE (rank 0's environment): "shared" this, "messages"
// every state through OpenMPI's transport, as ranks on other hosts always
// do.
constexpr size_t kSharedRing = 3;
constexpr size_t kSharedGroup = 4;
constexpr size_t kSharedSlotPixels = 3 * kSlice * kSharedGroup;  // sum, comp, sq of the largest slice

struct SharedWindow {
  MPI_Win win = MPI_WIN_NULL;
  bool ok = false;  // every rank of the host has its segment
  std::vector<const glm::vec4*> base;  // rank 0: by world rank, the segment (null: not in the window)
};

// Collective over the host's ranks (rank 0's host): `bytes` for this rank's
// segment. Falls back (ok = false, on every rank of the host) when any
// rank's allocation fails.
SharedWindow allocate_shared(MPI_Comm node, const std::vector<int>& node_ranks, size_t bytes, int world_size) {
  SharedWindow w;
  MPI_Comm_set_errhandler(node, MPI_ERRORS_RETURN);
  void* mine = nullptr;
  int ok = MPI_Win_allocate_shared(MPI_Aint(bytes), int(sizeof(glm::vec4)), MPI_INFO_NULL, node, &mine, &w.win) ==
           MPI_SUCCESS;
  int all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, node);
  MPI_Comm_set_errhandler(node, MPI_ERRORS_ARE_FATAL);
  if (!all) {
    if (w.win != MPI_WIN_NULL) MPI_Win_free(&w.win);
    return w;
  }
  w.ok = true;
  w.base.assign(size_t(world_size), nullptr);
  for (size_t k = 1; k < node_ranks.size(); ++k) {
    MPI_Aint segment = 0;
    int unit = 0;
    void* at = nullptr;
    MPI_Win_shared_query(w.win, int(k), &segment, &unit, &at);
    w.base[size_t(node_ranks[k])] = static_cast<const glm::vec4*>(at);
  }
  MPI_Win_lock_all(MPI_MODE_NOCHECK, w.win);
  return w;
}

// At the end of the job: every rank of the host leaves the window.
void free_shared(SharedWindow& w) {
  if (!w.ok) return;
  MPI_Win_unlock_all(w.win);
  MPI_Win_free(&w.win);
  w.ok = false;
}

// One slice's work shared by the calling thread and one worker per further
// core, workers that stay for the whole loop: each round runs between two
// barriers, `start` (the workers take slice s) and `finish` (every share of
// it is done); the caller does share 0 in between (`share_here`). The destructor ends the
// workers. Used by the sender's copy into the window and rank 0's merge.
class SliceWorkers {
 public:
  // share(t, s): thread t's part (0 = the caller) of slice s, for `threads` threads.
  SliceWorkers(size_t threads, std::function<void(size_t, size_t)> share)
      : threads_(std::max<size_t>(1, threads)), share_(std::move(share)),
        start_(ptrdiff_t(threads_)), done_(ptrdiff_t(threads_)) {
    for (size_t t = 1; t < threads_; ++t)
      pool_.emplace_back([this, t] {
        for (;;) {
          start_.arrive_and_wait();
          if (slice_ == kNone) return;
          share_(t, slice_);
          done_.arrive_and_wait();
        }
      });
  }
  ~SliceWorkers() {
    slice_ = kNone;
    start_.arrive_and_wait();
    for (std::thread& t : pool_) t.join();
  }
  SliceWorkers(const SliceWorkers&) = delete;
  SliceWorkers& operator=(const SliceWorkers&) = delete;

  size_t threads() const { return threads_; }
  void start(size_t slice) {
    slice_ = slice;
    start_.arrive_and_wait();
  }
  void share_here() { share_(0, slice_); }  // the caller's share of the slice started
  void finish() { done_.arrive_and_wait(); }

 private:
  static constexpr size_t kNone = SIZE_MAX;
  size_t threads_;
  std::function<void(size_t, size_t)> share_;
  std::barrier<> start_, done_;
  size_t slice_ = kNone;
  std::vector<std::thread> pool_;
};

// A rank of rank 0's host: its state through its ring in the window, in
// slices of `slice` pixels. The copy of a slice is shared by this thread and
// `threads` - 1 workers that stay for the whole reduce (as rank 0's merge),
// between two barriers: one thread copies 398 MB at ~10 GB/s, longer than
// rank 0's merge of it on 16 cores.
void write_shared(const Accumulation& acc, const SharedWindow& w, void* segment, size_t slice, size_t threads) {
  const size_t pixels = acc.sum.size(), slices = (pixels + slice - 1) / slice;
  glm::vec4* ring = static_cast<glm::vec4*>(segment);
  int64_t merged = 0;  // slices rank 0 has merged, as its messages say
  const auto wait_merged = [&](int64_t n) {
    while (merged < n) {
      MPI_Request request;
      MPI_Irecv(&merged, 1, MPI_INT64_T, 0, kTagShared, MPI_COMM_WORLD, &request);
      wait_briefly(request);
    }
  };
  SliceWorkers workers(threads, [&](size_t t, size_t s) {
    const size_t begin = s * slice, count = std::min(slice, pixels - begin);
    const size_t at = count * t / threads, n = count * (t + 1) / threads - at;
    glm::vec4* slot = ring + (s % kSharedRing) * kSharedSlotPixels;
    int array = 0;
    for (const std::vector<glm::vec4>* v : {&acc.sum, &acc.comp, &acc.sq})
      std::memcpy(slot + size_t(array++) * slice + at, v->data() + begin + at, n * sizeof(glm::vec4));
  });
  for (size_t s = 0; s < slices; ++s) {
    if (s >= kSharedRing) wait_merged(int64_t(s - kSharedRing + 1));  // slot s % kSharedRing is free
    workers.start(s);
    workers.share_here();
    workers.finish();
    MPI_Win_sync(w.win);
    const int64_t written = int64_t(s + 1);
    MPI_Send(&written, 1, MPI_INT64_T, 0, kTagShared, MPI_COMM_WORLD);
  }
  wait_merged(int64_t(slices));  // every message of rank 0's received
}

struct Job {
  bool active = false;
  int rank = 0, size = 1, local_rank = 0;
  // The ranks of this host (MPI_COMM_TYPE_SHARED, ordered by world rank) and
  // their world ranks: those on rank 0's host reduce through shared memory.
  MPI_Comm node = MPI_COMM_NULL;
  std::vector<int> node_ranks;
  SharedWindow window;  // the reduce's rings, on rank 0's host (allocate_shared)
  std::thread prefault;  // a rank of the window touching its ring's pages while it renders
  std::string host;
  Phase phase = Phase::Render;
  bool released = false;  // rank > 0: the server answered "no more" (or was told of a failure)

  // Rank 0: the counter of sample indices and what the ranks reported.
  std::mutex mutex;
  bool configured = false, failed = false, stop = false;
  // The batches start once every rank is set up (has asked for its first
  // batch) or one failed: a rank that is slow to set up does not leave the
  // others' first batches unevenly large, and every rank starts together.
  bool rank0_ready = false, started = false;
  int signal = 0;
  uint32_t work = 0;     // samples to hand out (spp - already)
  uint32_t already = 0;  // samples a resumed state holds
  uint32_t next = 0;     // next index to hand out, from `already`
  uint32_t done = 0;     // samples reported rendered
  ProgressFn progress;
  std::thread server;
  // --checkpoint: every `checkpoint_seconds` the ranks are asked, as they
  // finish their batches, for their states (no new batch meanwhile, so the
  // states hold exactly the indices handed out); the last one to deliver
  // merges them and writes the checkpoint, and the batches go on.
  double checkpoint_seconds = 0;
  int width = 0, height = 0;
  std::function<void(const Accumulation&, uint32_t samples)> write_checkpoint;
  Clock::time_point last_checkpoint;
  bool draining = false;
  int drained = 0;
  std::vector<Accumulation> drained_parts;  // by rank
  std::vector<bool> delivered;              // by rank, in this checkpoint
  std::condition_variable drain_done;
  std::string checkpoint_error;  // a checkpoint that could not be written fails rank 0

  // Under `mutex`: rank `r`'s state for the checkpoint; the last one merges
  // and writes.
  void deliver_locked(int r, Accumulation&& acc) {
    if (!draining) return;  // called off: a rank failed
    drained_parts[size_t(r)] = std::move(acc);
    delivered[size_t(r)] = true;
    if (++drained < size) return;
    try {
      if (write_checkpoint) write_checkpoint(merge_accumulations(drained_parts), already + next);
    } catch (const std::exception& e) {
      checkpoint_error = e.what();
      failed = true;
    }
    drained_parts.clear();
    draining = false;
    last_checkpoint = Clock::now();
    drain_done.notify_all();
  }
  void call_off_checkpoint_locked() {
    if (!draining) return;
    draining = false;
    drained_parts.clear();
    drain_done.notify_all();
  }

  // Under `mutex`: a rank reports `completed` samples (and a signal).
  void report_locked(uint32_t completed, bool stop_request, int sig) {
    done += completed;
    if (completed && progress) progress(already + done, already + work);
    if (stop_request && !stop) {
      stop = true;
      signal = sig;
    }
  }

  // Under `mutex`: the next batch for a rank that wants `want` samples
  // ({first, 0} when there is none; {kCheckpoint, 0}: send your state).
  std::pair<uint32_t, uint32_t> give_locked(uint32_t want) {
    if (failed || stop || next >= work) {
      call_off_checkpoint_locked();
      return {0, 0};
    }
    if (draining || (checkpoint_seconds > 0 && ms_since(last_checkpoint) >= 1000.0 * checkpoint_seconds)) {
      if (!draining) {
        draining = true;
        drained = 0;
        drained_parts.assign(size_t(size), Accumulation{});
        delivered.assign(size_t(size), false);
      }
      return {kCheckpoint, 0};
    }
    // As the multi-device render: batches shrink near the end so that no
    // worker is left with much more than the others. One worker alone
    // needs no shrinking, and each shrunk batch of ranks taking turns is a
    // hand-over of the device (~2.5 ms on the H100: optimisation log 27).
    const uint32_t remaining = work - next;
    const uint32_t workers = workers_locked();
    const uint32_t share = workers > 1 ? remaining / (2 * workers) + 1 : remaining;
    const uint32_t n = std::clamp(std::min(want, share), 1u, remaining);
    const uint32_t first = already + next;
    next += n;
    return {first, n};
  }

  // Turns on a shared device (docs/multi_gpu.md, "Ranks that share a
  // device"). Processes that share one GPU get time slices of it from the
  // driver, which switches between their contexts at a cost (on the H100 at
  // 67ee20c each of 2 or 4 ranks' device time grew 1.7x); so rank 0 lets at
  // most one rank per physical device (host + VkPhysicalDeviceIDProperties::
  // deviceUUID) hold a batch. A rank that asks while another rank of its
  // device holds one waits in the device's queue (first come, first served)
  // and is answered when that batch comes back (the holder's next request).
  DeviceTurns turns = DeviceTurns::Auto;   // --device-turns (rank 0's)
  std::vector<std::string> device_of;      // by rank: "host/uuid"; empty: unknown, no turns
  std::map<std::string, int> holder;       // device -> the rank that holds a batch of it
  std::map<std::string, std::deque<int>> queue;  // device -> ranks waiting for it, in order
  std::vector<uint32_t> wants;             // by rank: the samples a queued rank asked for
  std::vector<Clock::time_point> queued_at;
  std::vector<uint32_t> turns_waited;      // by rank: requests that waited for the device
  std::vector<double> turn_wait_ms;        // by rank: the time they waited
  // Answers decided on a thread that may not call MPI (rank 0's render
  // thread): the batch server sends them. Rank 0's own answer goes to
  // rank0_reply.
  std::vector<std::pair<int, std::pair<uint32_t, uint32_t>>> due;
  std::optional<std::pair<uint32_t, uint32_t>> rank0_reply;
  std::condition_variable rank0_answered;

  // Whether the ranks of device `key` ("gpu HOST/UUID" or "cpu HOST/UUID")
  // take turns: a software device (lavapipe) renders on each process's own
  // CPU threads, with no context to switch, so only with --device-turns on.
  bool takes_turns(const std::string& key) const {
    if (key.empty() || turns == DeviceTurns::Off) return false;
    return turns == DeviceTurns::On || key.rfind("gpu ", 0) == 0;
  }
  void init_turns_locked() {
    if (!device_of.empty()) return;
    device_of.assign(size_t(size), std::string());
    wants.assign(size_t(size), 0);
    queued_at.assign(size_t(size), Clock::time_point{});
    turns_waited.assign(size_t(size), 0);
    turn_wait_ms.assign(size_t(size), 0.0);
  }
  // Under `mutex`: how many render at once, which the batch sizes balance:
  // one per device whose ranks take turns (only one of them renders at a
  // time; how the device's work splits among them does not matter), one
  // per other rank.
  uint32_t workers_locked() {
    init_turns_locked();
    std::set<std::string> shared;
    uint32_t others = 0;
    for (const std::string& key : device_of) {
      if (takes_turns(key)) shared.insert(key);
      else ++others;
    }
    return std::max(1u, uint32_t(shared.size()) + others);
  }
  const std::string& device_key_locked(int r) {
    init_turns_locked();
    return device_of[size_t(r)];
  }
  void deliver_answer_locked(int r, std::pair<uint32_t, uint32_t> got) {
    if (r == 0) {
      rank0_reply = got;
      rank0_answered.notify_all();
    } else {
      due.push_back({r, got});
    }
  }
  // Rank r's batch came back (or r failed): the device goes to the first
  // rank in its queue that gets a batch (the others are answered too: with
  // "no more", or a checkpoint request).
  void release_locked(int r) {
    const std::string& key = device_key_locked(r);
    if (key.empty()) return;
    auto h = holder.find(key);
    if (h == holder.end() || h->second != r) return;
    holder.erase(h);
    std::deque<int>& q = queue[key];
    while (!q.empty() && !holder.count(key)) {
      const int next_rank = q.front();
      q.pop_front();
      turn_wait_ms[size_t(next_rank)] += ms_since(queued_at[size_t(next_rank)]);
      const auto got = give_locked(wants[size_t(next_rank)]);
      if (got.second > 0) holder[key] = next_rank;
      deliver_answer_locked(next_rank, got);
    }
  }
  // Rank r asks for `want` samples after it rendered `completed`: answered
  // now, or queued behind the rank that holds its device.
  void request_locked(int r, uint32_t completed, uint32_t want, bool stop_request, int sig) {
    report_locked(completed, stop_request, sig);
    release_locked(r);
    const std::string& key = device_key_locked(r);
    const bool take_turns = takes_turns(key);
    if (take_turns && holder.count(key)) {
      wants[size_t(r)] = want;
      queued_at[size_t(r)] = Clock::now();
      ++turns_waited[size_t(r)];
      queue[key].push_back(r);
      return;
    }
    const auto got = give_locked(want);
    if (take_turns && got.second > 0) holder[key] = r;
    deliver_answer_locked(r, got);
  }

  // Rank 0's render thread: its next batch (after `completed`), waiting for
  // its turn on a device it shares.
  std::pair<uint32_t, uint32_t> take(uint32_t completed, uint32_t want, bool stop_request, int sig) {
    std::unique_lock<std::mutex> lock(mutex);
    rank0_reply.reset();
    request_locked(0, completed, want, stop_request, sig);
    rank0_answered.wait(lock, [&] { return rank0_reply.has_value(); });
    return *rank0_reply;
  }

  // Rank 0's thread: answers the other ranks' requests until each has been
  // told there is no more work or has reported a failure.
  void serve() {
    int active_ranks = size - 1, waiting = 0;
    struct Pending {
      int source;
      int64_t msg[4];
    };
    std::vector<Pending> pending;  // first requests, held until the start
    std::vector<Pending> held;     // requests of ranks that delivered, held until the checkpoint is written
    // Sends the answers decided (here or on rank 0's render thread).
    const auto flush = [&] {
      std::vector<std::pair<int, std::pair<uint32_t, uint32_t>>> answers;
      {
        std::lock_guard<std::mutex> lock(mutex);
        answers.swap(due);
      }
      for (const auto& [source, got] : answers) {
        uint32_t reply[2] = {got.first, got.second};
        MPI_Send(reply, 2, MPI_UINT32_T, source, kTagReply, MPI_COMM_WORLD);
        if (got.second == 0 && got.first != kCheckpoint) --active_ranks;
      }
    };
    const auto answer = [&](int source, const int64_t* msg) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        request_locked(source, uint32_t(msg[1]), uint32_t(msg[2]), msg[0] == kStop, int(msg[3]));
      }
      flush();
    };
    while (active_ranks > 0) {
      flush();
      bool go = false;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (!started && (failed || (rank0_ready && waiting == active_ranks))) {
          started = go = true;
          last_checkpoint = Clock::now();
        }
      }
      if (go) {
        for (const Pending& p : pending) answer(p.source, p.msg);
        pending.clear();
        continue;
      }
      bool drain_over;
      {
        std::lock_guard<std::mutex> lock(mutex);
        drain_over = !draining;
      }
      if (drain_over && !held.empty()) {
        for (const Pending& p : held) answer(p.source, p.msg);
        held.clear();
        continue;
      }
      bool ready;
      {
        std::lock_guard<std::mutex> lock(mutex);
        ready = configured || failed;
      }
      if (!ready) {
        // Rank 0 is still reading its settings.
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      int flag = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
      if (!flag) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      if (status.MPI_TAG == kTagDevice) {
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string key(size_t(length), '\0');
        MPI_Recv(key.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagDevice, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        std::lock_guard<std::mutex> lock(mutex);
        device_key_locked(status.MPI_SOURCE);
        device_of[size_t(status.MPI_SOURCE)] = key;
        continue;
      }
      if (status.MPI_TAG == kTagCheckpoint) {
        Accumulation acc{width, height, {}, {}, {}};
        receive_state(status.MPI_SOURCE, kTagCheckpoint, acc);
        std::lock_guard<std::mutex> lock(mutex);
        deliver_locked(status.MPI_SOURCE, std::move(acc));
        continue;
      }
      int64_t msg[4];
      MPI_Recv(msg, 4, MPI_INT64_T, status.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (msg[0] == kFailed) {
        {
          std::lock_guard<std::mutex> lock(mutex);
          failed = true;
          call_off_checkpoint_locked();
          release_locked(status.MPI_SOURCE);
        }
        --active_ranks;
        continue;
      }
      bool wait, hold;
      {
        std::lock_guard<std::mutex> lock(mutex);
        wait = !started;
        // A rank that has given its state for the checkpoint under way
        // gets its next batch once the checkpoint is written.
        hold = draining && delivered[size_t(status.MPI_SOURCE)];
      }
      if (hold) {
        held.push_back({status.MPI_SOURCE, {msg[0], msg[1], msg[2], msg[3]}});
        continue;
      }
      if (wait) {
        pending.push_back({status.MPI_SOURCE, {msg[0], msg[1], msg[2], msg[3]}});
        ++waiting;
        continue;
      }
      answer(status.MPI_SOURCE, msg);
    }
    std::lock_guard<std::mutex> lock(mutex);
    started = true;
  }

  void join_server() {
    if (server.joinable()) server.join();
  }

  // The job's one decision after the render: every rank sends its code and
  // report; rank 0 decides (the first failed rank, else a rank whose scene
  // or settings differ from its own) and prints the line; all get the code.
  int decide(int code, const std::string& message, json report, std::vector<json>* reports) {
    report["code"] = code;
    report["message"] = message;
    report["host"] = host;
    // A message may hold bytes that are not UTF-8 (a file name): replaced.
    const std::string text = report.dump(-1, ' ', false, json::error_handler_t::replace);
    int length = int(text.size());
    std::vector<int> lengths(size);
    MPI_Request request;
    MPI_Igather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
    wait_gently(request);
    std::vector<int> offsets(size, 0);
    for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    std::string all(rank == 0 ? size_t(offsets[size - 1] + lengths[size - 1]) : 0, '\0');
    MPI_Igatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
                 MPI_COMM_WORLD, &request);
    wait_gently(request);
    int decision = 0;
    if (rank == 0) {
      std::vector<json> all_reports;
      for (int r = 0; r < size; ++r) all_reports.push_back(json::parse(all.substr(offsets[r], lengths[r])));
      std::string line;
      int failed_ranks = 0;
      for (int r = 0; r < size; ++r) {
        const json& j = all_reports[r];
        const int c = j.at("code").get<int>();
        if (c == 0) continue;
        decision = std::max(decision, c);
        if (failed_ranks++ == 0)
          line = "rank " + std::to_string(r) + " (" + j.at("host").get<std::string>() +
                 "): " + j.at("message").get<std::string>();
      }
      if (failed_ranks > 1) line += " (" + std::to_string(failed_ranks) + " of " + std::to_string(size) + " ranks failed)";
      if (decision == 0) {
        // Every rank must have rendered the samples of rank 0's render.
        const CheckpointInfo first = info_of(all_reports[0].at("info"));
        for (int r = 1; r < size && decision == 0; ++r) {
          const std::string why = checkpoint_mismatch(first, info_of(all_reports[r].at("info")));
          if (!why.empty()) {
            decision = 2;
            line = "rank " + std::to_string(r) + " (" + all_reports[r].at("host").get<std::string>() +
                   "): renders another scene or other settings than rank 0: " +
                   replaced(why, ", this render ", ", rank " + std::to_string(r) + " ");
          }
        }
      }
      if (decision != 0) std::fprintf(stderr, "octrace: error: %s\n", line.c_str());
      if (reports) *reports = std::move(all_reports);
    }
    MPI_Ibcast(&decision, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
    wait_gently(request);
    return decision;
  }

  // A rank reports its info as a checkpoint's header holds it (null: none).
  static CheckpointInfo info_of(const json& j) { return j.is_null() ? CheckpointInfo{} : checkpoint_info_of(j); }
};

Job g_job;

}  // namespace

void init(int* argc, char*** argv) {
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  Job& job = g_job;
  job.active = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &job.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &job.size);
  char name[MPI_MAX_PROCESSOR_NAME];
  int length = 0;
  MPI_Get_processor_name(name, &length);
  job.host.assign(name, size_t(length));
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, job.rank, MPI_INFO_NULL, &job.node);
  MPI_Comm_rank(job.node, &job.local_rank);
  int node_size = 1;
  MPI_Comm_size(job.node, &node_size);
  job.node_ranks.resize(size_t(node_size));
  MPI_Allgather(&job.rank, 1, MPI_INT, job.node_ranks.data(), 1, MPI_INT, job.node);
  // The window of the reduce's rings, once for the job (its size does not
  // depend on the image; allocating it takes tens of ms in a rank that has
  // set up Vulkan, which the reduce would otherwise wait for).
  if (job.node_ranks.front() == 0 && node_size > 1)
    job.window = allocate_shared(job.node, job.node_ranks,
                                 job.rank == 0 ? 0 : kSharedRing * kSharedSlotPixels * sizeof(glm::vec4), job.size);
  // The ring's fresh pages each cost a fault and a zeroed page on first
  // touch (36 MiB: 9,216 of them); they are touched beside the render, not
  // in the reduce.
  if (job.window.ok && job.rank != 0) {
    MPI_Aint bytes = 0;
    int unit = 0;
    void* mine = nullptr;
    MPI_Win_shared_query(job.window.win, job.local_rank, &bytes, &unit, &mine);
    job.prefault = std::thread([mine, bytes] { std::memset(mine, 0, size_t(bytes)); });
  }
  if (provided < MPI_THREAD_SERIALIZED) {
    // Rank 0's batch server is a second thread that calls MPI.
    if (job.rank == 0) std::fprintf(stderr, "octrace: error: this MPI library offers no MPI_THREAD_SERIALIZED\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  if (job.rank == 0 && job.size > 1) job.server = std::thread([] { g_job.serve(); });
}

bool active() { return g_job.active; }
int rank() { return g_job.rank; }
int size() { return g_job.size; }
const std::string& host() { return g_job.host; }

std::string device_for_rank(const std::string& requested) {
  if (requested == "all" || requested.find(',') != std::string::npos)
    throw InputError("--device " + requested + ": under MPI each rank renders on one device (give each rank its own "
                     "--device, or let it take its node-local rank's GPU)");
  if (requested != "auto") return requested;
  std::vector<uint32_t> gpus;
  for (const DeviceInfo& d : list_devices())
    if (!d.software) gpus.push_back(d.index);
  if (gpus.empty()) return "auto";
  return std::to_string(gpus[size_t(g_job.local_rank) % gpus.size()]);
}

void set_device_turns(DeviceTurns turns) {
  if (g_job.rank != 0) return;
  std::lock_guard<std::mutex> lock(g_job.mutex);
  g_job.turns = turns;
}

void set_work(uint32_t spp, uint32_t already, ProgressFn progress) {
  if (g_job.rank != 0) return;
  std::lock_guard<std::mutex> lock(g_job.mutex);
  g_job.already = std::min(already, spp);
  g_job.work = spp - g_job.already;
  g_job.progress = std::move(progress);
  g_job.configured = true;
}

void set_checkpoint(double seconds, int width, int height,
                    std::function<void(const Accumulation&, uint32_t samples)> write) {
  if (g_job.rank != 0) return;
  std::lock_guard<std::mutex> lock(g_job.mutex);
  g_job.checkpoint_seconds = seconds;
  g_job.width = width;
  g_job.height = height;
  g_job.write_checkpoint = std::move(write);
}

void clear_callbacks() {
  if (g_job.rank != 0) return;
  std::lock_guard<std::mutex> lock(g_job.mutex);
  g_job.progress = nullptr;
  g_job.write_checkpoint = nullptr;
  g_job.call_off_checkpoint_locked();
}

void render_share(PathTracer& tracer, const PassSettings& pass, uint32_t first_sample, double batch_ms,
                  const std::atomic<bool>* stop, const std::atomic<int>* signal, RankShare& share) {
  Job& job = g_job;
  share.rank = job.rank;
  share.host = job.host;
  // The first batch (PathTracer::first_batch) and every later one in whole
  // multiples of the batch granule, as render()'s.
  const uint32_t lanes = tracer.batch_granule();
  uint32_t completed = 0, batch = tracer.first_batch();
  const auto ready = Clock::now();
  // The device this rank renders on, for turns (empty: no UUID, no turns).
  const std::string device_key =
      share.device_uuid.empty() ? std::string()
                                : (share.device_software ? "cpu " : "gpu ") + job.host + "/" + share.device_uuid;
  if (job.rank != 0) {
    MPI_Send(device_key.data(), int(device_key.size()), MPI_CHAR, 0, kTagDevice, MPI_COMM_WORLD);
  } else {
    {
      std::lock_guard<std::mutex> lock(job.mutex);
      job.device_key_locked(0);
      job.device_of[0] = device_key;
      job.rank0_ready = true;
      if (job.size == 1) {
        job.started = true;
        job.last_checkpoint = Clock::now();
      }
    }
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(job.mutex);
        if (job.started) break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  // The job starts with each rank's first answer (rank 0: when it is given).
  std::optional<Clock::time_point> start, last_batch_end;
  for (;;) {
    const bool stopping = stop && stop->load();
    const int sig = signal ? signal->load() : 0;
    const auto request_start = Clock::now();
    std::pair<uint32_t, uint32_t> got;
    if (job.rank == 0) {
      got = job.take(completed, batch, stopping, sig);
    } else {
      int64_t msg[4] = {stopping ? kStop : kWant, completed, batch, sig};
      MPI_Send(msg, 4, MPI_INT64_T, 0, kTagRequest, MPI_COMM_WORLD);
      uint32_t reply[2];
      MPI_Recv(reply, 2, MPI_UINT32_T, 0, kTagReply, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      got = {reply[0], reply[1]};
    }
    if (!start) {
      start = Clock::now();
      share.start_wait_ms = ms_since(ready);
    } else {
      share.batch_wait_ms += ms_since(request_start);
    }
    completed = 0;
    if (got.first == kCheckpoint && got.second == 0) {
      // Everything handed out so far is in this state.
      Accumulation acc = tracer.read_accumulation();
      if (job.rank != 0) {
        send_state(acc, kTagCheckpoint);
      } else {
        std::unique_lock<std::mutex> lock(job.mutex);
        job.deliver_locked(0, std::move(acc));
        job.drain_done.wait(lock, [&] { return !job.draining; });
      }
      continue;
    }
    if (got.second == 0) {
      job.released = true;
      break;
    }
    const auto batch_start = Clock::now();
    if (last_batch_end)
      share.max_gap_ms = std::max(share.max_gap_ms, ms_between(*last_batch_end, batch_start));
    share.device_ms += tracer.run_passes(pass, first_sample + got.first, got.second);
    last_batch_end = Clock::now();
    share.spans.push_back({ms_since_epoch(batch_start), ms_since_epoch(*last_batch_end)});
    const double passes_ms = ms_between(batch_start, *last_batch_end);
    share.passes_ms += passes_ms;
    ++share.batches;
    const double per_pass = passes_ms / got.second;
    // As render(): batches of about a quarter second (or --batch-ms), at
    // most 1024 samples, in whole rounds of lanes (next_batch).
    batch = next_batch(per_pass, lanes, batch_ms > 0 ? batch_ms : kBatchMs);
    share.samples += got.second;
    completed = got.second;
  }
  share.wall_ms = ms_since(*start);
  if (job.rank == 0) {
    std::lock_guard<std::mutex> lock(job.mutex);
    if (!job.checkpoint_error.empty()) throw RuntimeError(job.checkpoint_error);
  }
}

json share_json(const RankShare& s) {
  return {{"rank", s.rank},
          {"host", s.host},
          {"device", s.device},
          {"samples", s.samples},
          {"render_ms", s.device_ms},
          {"setup_ms", s.setup_ms},
          {"setup", {{"device_init", s.device_init_ms}, {"accel_build", s.accel_build_ms},
                     {"upload", s.upload_ms}, {"pipeline", s.pipeline_ms}}},
          {"start_wait_ms", s.start_wait_ms},
          {"render_wall_ms", s.wall_ms},
          {"passes_wall_ms", s.passes_ms},
          {"batch_wait_ms", s.batch_wait_ms},
          {"max_gap_ms", s.max_gap_ms},
          {"batches", s.batches},
          {"device_uuid", s.device_uuid},
          {"turns_waited", s.turns_waited},
          {"turn_wait_ms", s.turn_wait_ms},
          {"batch_spans_ms", s.spans}};
}

RankShare share_of(const json& j) {
  RankShare s;
  s.rank = j.at("rank");
  s.host = j.at("host");
  s.device = j.at("device");
  s.samples = j.at("samples");
  s.device_ms = j.at("render_ms");
  s.setup_ms = j.at("setup_ms");
  const json& setup = j.at("setup");
  s.device_init_ms = setup.at("device_init");
  s.accel_build_ms = setup.at("accel_build");
  s.upload_ms = setup.at("upload");
  s.pipeline_ms = setup.at("pipeline");
  s.start_wait_ms = j.at("start_wait_ms");
  s.wall_ms = j.at("render_wall_ms");
  s.passes_ms = j.at("passes_wall_ms");
  s.batch_wait_ms = j.at("batch_wait_ms");
  s.max_gap_ms = j.at("max_gap_ms");
  s.batches = j.at("batches");
  s.device_uuid = j.at("device_uuid");
  s.turns_waited = j.at("turns_waited");
  s.turn_wait_ms = j.at("turn_wait_ms");
  s.spans = j.at("batch_spans_ms").get<std::vector<std::pair<double, double>>>();
  return s;
}

std::string share_line(const RankShare& s) {
  char line[640];
  std::snprintf(line, sizeof line,
                "rank %d    %s, %s: %u spp in %u batches, %.1f ms of passes (device); set-up %.1f ms (device %.1f, "
                "accel build %.1f, upload %.1f, pipeline %.1f), then %.1f ms waiting for the other ranks; of %.1f ms "
                "rendering: %.1f in batches, %.1f waiting for rank 0's answers (of it %.1f in %u turns for the "
                "device), the rest between (longest gap %.1f)",
                s.rank, s.host.c_str(), s.device.c_str(), s.samples, s.batches, s.device_ms, s.setup_ms,
                s.device_init_ms, s.accel_build_ms, s.upload_ms, s.pipeline_ms, s.start_wait_ms, s.wall_ms,
                s.passes_ms, s.batch_wait_ms, s.turn_wait_ms, s.turns_waited, s.max_gap_ms);
  return line;
}

bool gather(Accumulation acc, uint64_t nonfinite, uint64_t cut_paths, const RankShare& share,
            const CheckpointInfo& info, Gathered& out) {
  Job& job = g_job;
  if (job.rank == 0) job.join_server();
  json report = {{"share", share_json(share)}, {"info", checkpoint_info_json(info)}, {"nonfinite", nonfinite},
                {"cut_paths", cut_paths}};
  std::vector<json> reports;
  const int decision = job.decide(0, "", report, &reports);
  job.phase = Phase::Final;
  if (decision != 0) throw JobFailed{decision};
  // The states travel in slices; rank 0 merges each slice into its own
  // state (in place: no second state of the image's size is allocated or
  // zero-filled) on worker threads while the next slices arrive, so the
  // reduce costs about the transfer, not transfer + merge. Per pixel the
  // merge is merge_accumulations' (rank order). The ranks of rank 0's host
  // hand their states over in a shared-memory window (allocate_shared),
  // the others as messages.
  const auto reduce_start = Clock::now();
  const size_t pixels = acc.sum.size();
  int shared_mode = 1;
  if (job.rank == 0) {
    const char* mode = std::getenv("OCTRACE_MPI_REDUCE");
    shared_mode = !(mode && std::string(mode) == "messages");
  }
  MPI_Request mode_request;
  MPI_Ibcast(&shared_mode, 1, MPI_INT, 0, MPI_COMM_WORLD, &mode_request);
  wait_gently(mode_request);
  const SharedWindow& window = job.window;
  const bool shared = shared_mode && window.ok;
  // Every rank copies or merges on all of the host's cores: sharing them out
  // among the host's ranks made the merge 2x slower and the reduce no
  // faster (optimisation log 28).
  const size_t threads = host_threads();
  // Large slices when every state comes through the window (see kSharedGroup).
  const size_t slice = shared && job.node_ranks.size() == size_t(job.size) ? kSlice * kSharedGroup : kSlice;
  if (job.prefault.joinable()) job.prefault.join();
  if (job.rank != 0) {
    const auto send_start = Clock::now();
    if (shared) {
      MPI_Aint segment = 0;
      int unit = 0;
      void* mine = nullptr;
      MPI_Win_shared_query(window.win, job.local_rank, &segment, &unit, &mine);
      write_shared(acc, window, mine, slice, threads);
    } else {
      send_state(acc, kTagState);
    }
    const double send_ms = ms_since(send_start);
    MPI_Send(&send_ms, 1, MPI_DOUBLE, 0, kTagState, MPI_COMM_WORLD);
    return false;
  }
  ReduceTimes& times = out.reduce;
  out.merged = std::move(acc);
  Accumulation& merged = out.merged;
  const int others = job.size - 1;
  const size_t slices = (pixels + slice - 1) / slice;
  const auto in_window = [&](int r) { return shared && window.base[size_t(r)] != nullptr; };
  // How far each rank of the window has written (pixels), as its messages say.
  std::vector<int64_t> written(size_t(job.size), 0);
  const auto wait_for_window = [&](int r, size_t slices_written) {
    while (written[size_t(r)] < int64_t(slices_written)) {
      MPI_Request request;
      MPI_Irecv(&written[size_t(r)], 1, MPI_INT64_T, r, kTagShared, MPI_COMM_WORLD, &request);
      wait_briefly(request);
    }
    MPI_Win_sync(window.win);
  };
  // kRing slots of one slice per other rank, reused: slice s arrives in slot
  // s % kRing while the workers merge slice s - 1 and slice s + 1 is on its
  // way (its receives are posted).
  constexpr size_t kRing = 3;
  const size_t slot_pixels = std::min(slice, pixels);
  std::vector<std::vector<glm::vec4>> slots(kRing * size_t(others) * 3);
  for (size_t k = 0; k < slots.size(); ++k)
    if (!in_window(int(k / 3 % size_t(others)) + 1)) slots[k].resize(slot_pixels);
  // Where slice s of rank r's `array` (0 sum, 1 comp, 2 sq) is.
  const auto slot = [&](size_t s, int r, int array) -> const glm::vec4* {
    if (in_window(r)) return window.base[size_t(r)] + (s % kSharedRing) * kSharedSlotPixels + size_t(array) * slice;
    return slots[((s % kRing) * size_t(others) + size_t(r - 1)) * 3 + size_t(array)].data();
  };
  std::vector<std::vector<MPI_Request>> requests(kRing);
  const auto post = [&](size_t s) {
    const size_t begin = s * slice, count = std::min(slice, pixels - begin);
    std::vector<MPI_Request>& slice_requests = requests[s % kRing];
    slice_requests.assign(size_t(others) * 3, MPI_REQUEST_NULL);
    for (int r = 1; r < job.size; ++r)
      for (int array = 0; array < 3 && !in_window(r); ++array)
        MPI_Irecv(const_cast<glm::vec4*>(slot(s, r, array)), int(count * 4), MPI_FLOAT, r, kTagState,
                  MPI_COMM_WORLD, &slice_requests[size_t(r - 1) * 3 + size_t(array)]);
  };
  // The merge of a slice is shared by this thread and workers that stay for
  // the whole reduce (`threads` in all), between two barriers (start,
  // done). This thread merges its share, then waits for the next slice's
  // data (OpenMPI copies it in that wait) while the workers finish theirs.
  std::vector<double> merge_ms(threads, 0.0);
  SliceWorkers workers(threads, [&](size_t w, size_t s) {
    const auto merge_start = Clock::now();
    const size_t begin = s * slice, count = std::min(slice, pixels - begin);
    const size_t at = begin + count * w / threads, n = begin + count * (w + 1) / threads - at;
    const size_t in_slot = at - begin;
    std::vector<AccumulationPixels> parts = {{merged.sum.data() + at, merged.comp.data() + at, merged.sq.data() + at}};
    for (int r = 1; r < job.size; ++r)
      parts.push_back({slot(s, r, 0) + in_slot, slot(s, r, 1) + in_slot, slot(s, r, 2) + in_slot});
    merge_accumulation_pixels(parts, merged.sum.data() + at, merged.comp.data() + at, merged.sq.data() + at, n);
    merge_ms[w] += ms_since(merge_start);
  });
  times.alloc_ms = ms_since(reduce_start);
  // The ranks of the window may reuse the slots of the slices merged.
  const auto tell_merged = [&](int64_t n) {
    for (int r = 1; r < job.size; ++r)
      if (in_window(r)) MPI_Send(&n, 1, MPI_INT64_T, r, kTagShared, MPI_COMM_WORLD);
  };
  const auto wait_for_merge = [&] {
    const auto wait_start = Clock::now();
    workers.finish();
    times.merge_wait_ms += ms_since(wait_start);
  };
  for (size_t s = 0; s < std::min(slices, kRing - 1); ++s) post(s);
  for (size_t s = 0; s < slices; ++s) {
    const auto receive_start = Clock::now();
    MPI_Waitall(int(requests[s % kRing].size()), requests[s % kRing].data(), MPI_STATUSES_IGNORE);
    for (int r = 1; r < job.size; ++r)
      if (in_window(r)) wait_for_window(r, s + 1);
    times.receive_ms += ms_since(receive_start);
    if (s > 0) {
      wait_for_merge();  // slice s - 1: its slot is free again
      tell_merged(int64_t(s));
    }
    if (s + kRing - 1 < slices) post(s + kRing - 1);
    const auto start_wait = Clock::now();
    workers.start(s);
    times.merge_wait_ms += ms_since(start_wait);
    workers.share_here();
  }
  if (slices > 0) wait_for_merge();
  tell_merged(int64_t(slices));
  times.merge_ms = *std::max_element(merge_ms.begin(), merge_ms.end());
  times.shared = shared;
  times.total_ms = ms_since(reduce_start);
  for (int r = 1; r < job.size; ++r) {
    double send_ms = 0;
    MPI_Recv(&send_ms, 1, MPI_DOUBLE, r, kTagState, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    times.send_ms = std::max(times.send_ms, send_ms);
  }
  out.nonfinite_samples = 0;
  out.cut_paths = 0;
  for (const json& j : reports) {
    out.shares.push_back(share_of(j.at("share")));
    // The turns are counted where they are decided.
    RankShare& r = out.shares.back();
    if (job.size > 1 && size_t(r.rank) < job.turns_waited.size()) {
      r.turns_waited = job.turns_waited[size_t(r.rank)];
      r.turn_wait_ms = job.turn_wait_ms[size_t(r.rank)];
    }
    out.nonfinite_samples += j.at("nonfinite").get<uint64_t>();
    out.cut_paths += j.at("cut_paths").get<uint64_t>();
  }
  out.device_turns = job.turns == DeviceTurns::On ? "on" : job.turns == DeviceTurns::Off ? "off" : "auto";
  out.samples = job.already + job.next;
  out.interrupted = job.next < job.work;
  out.signal = job.signal;
  return true;
}

namespace {

// Rank 0 tells the others its final code; every rank finalises.
int final_code(int code) {
  Job& job = g_job;
  MPI_Request request;
  MPI_Ibcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait_gently(request);
  job.phase = Phase::Done;
  if (job.prefault.joinable()) job.prefault.join();
  free_shared(job.window);
  MPI_Finalize();
  return code;
}

}  // namespace

int fail(int code, const std::string& message) {
  Job& job = g_job;
  if (job.phase == Phase::Render) {
    if (job.rank == 0) {
      {
        std::lock_guard<std::mutex> lock(job.mutex);
        job.failed = true;
        job.call_off_checkpoint_locked();
        job.release_locked(0);  // a rank waiting for rank 0's device is answered
      }
      job.join_server();
    } else if (!job.released) {
      int64_t msg[4] = {kFailed, 0, 0, 0};
      MPI_Send(msg, 4, MPI_INT64_T, 0, kTagRequest, MPI_COMM_WORLD);
      job.released = true;
    }
    const int decision = job.decide(code, message, json{{"info", nullptr}}, nullptr);
    job.phase = Phase::Final;
    return final_code(decision);
  }
  if (job.phase == Phase::Final) {
    // After the decision only rank 0 works (the merge and the outputs).
    std::fprintf(stderr, "octrace: error: rank %d (%s): %s\n", job.rank, job.host.c_str(), message.c_str());
    return final_code(code);
  }
  std::fprintf(stderr, "octrace: error: %s\n", message.c_str());
  return code;
}

int finish(int code) {
  if (g_job.phase == Phase::Done) return code;
  if (g_job.phase == Phase::Render) {
    // A rank that ended without rendering (nothing to render: --dump-scene
    // alone) still takes part in the decision.
    return fail(code ? code : 1, "ended before rendering");
  }
  return final_code(code);
}

}  // namespace octrace::mpi
