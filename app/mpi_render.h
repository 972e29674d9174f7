// `mpirun -np N octrace render ...`: one render over N processes (ranks), on
// one host or many (docs/multi_gpu.md). Compiled into the octrace executable
// only when OCTRACE_MPI is on; the renderer library never links MPI.
//
// Each rank renders on its node-local device (local rank modulo the node's
// GPUs, or --device); rank 0 hands out batches of sample indices from one
// counter (a thread that answers the other ranks' requests, so a fast and a
// slow rank finish together) and prints the global progress line. At the
// end every rank reports to rank 0 whether it failed (one line names the
// first failed rank and its host; every rank exits with the job's code) and
// that it rendered the same scene with the same settings; the ranks'
// accumulation states are sent to rank 0, which merges them in rank order
// with merge_accumulations (exactly as --device 0,1 does) and alone writes
// every output.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <cstdint>
#include <string>
#include <vector>

#include "render/path_tracer.h"
#include "render/render_state.h"

#ifdef OCTRACE_MPI
#include <nlohmann/json.hpp>
#endif

namespace octrace::mpi {

// True when this process was started by an MPI launcher (OMPI_COMM_WORLD_SIZE,
// PMIX_RANK or PMI_SIZE is set) or `--mpi` is among the arguments.
inline bool launched(int argc, char** argv) {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--mpi") == 0) return true;
  return false;
}
// The job's size as the launcher announces it before MPI is initialised (1
// when no launcher variable is set): a build without MPI refuses N > 1.
inline int launcher_size() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* s = std::getenv(v)) return std::max(1, std::atoi(s));
  return 1;
}

// The job failed and rank 0 has printed the line that says why; this rank
// exits with `code`.
struct JobFailed {
  int code;
};

// What one rank did, and where its time went (wall ms unless said).
struct RankShare {
  int rank = 0;
  std::string host;
  std::string device;
  uint32_t samples = 0;   // samples per pixel it rendered
  double device_ms = 0;   // its passes' device time (timestamp queries)
  double setup_ms = 0;    // context, octree, upload, pipeline: the four below and the rest
  double device_init_ms = 0, accel_build_ms = 0, upload_ms = 0, pipeline_ms = 0;
  double start_wait_ms = 0;  // set up, waiting for the other ranks (the batches start together)
  double wall_ms = 0;        // from the job's first batch to this rank's last batch's end
  double passes_ms = 0;      // of it, in its batches (submission to completion)
  double batch_wait_ms = 0;  // of it, waiting for rank 0's answer to a request
  double max_gap_ms = 0;     // the longest time between one batch's end and the next one's start
  uint32_t batches = 0;      // batches it rendered
  std::string device_uuid;   // its device's VkPhysicalDeviceIDProperties::deviceUUID (hex)
  bool device_software = false;  // a CPU device (lavapipe)
  uint32_t turns_waited = 0; // requests that waited for another rank's batch on its device
  double turn_wait_ms = 0;   // of batch_wait_ms, the time they waited (rank 0's clock)
  // Each batch's start and end on this host's monotonic clock (ms since its
  // epoch: comparable between the ranks of one host only).
  std::vector<std::pair<double, double>> spans;
};

// The reduce's parts (rank 0, wall ms): the parts overlap, so they do not
// add up to the total.
struct ReduceTimes {
  double total_ms = 0;       // from the job's decision to the merged state
  double alloc_ms = 0;       // allocating the buffers the states arrive in
  double receive_ms = 0;     // waiting for data
  double merge_wait_ms = 0;  // waiting for the merging threads (a slice's start and end)
  double merge_ms = 0;       // merging (worker threads, overlapped with receiving)
  double send_ms = 0;        // the slowest other rank's sending of its state (or writing it to the window)
  bool shared = false;       // the ranks of rank 0's host wrote their states to a shared-memory window
};

// What rank 0 has once the ranks have reported.
struct Gathered {
  Accumulation merged;               // the ranks' states merged in rank order
  std::vector<RankShare> shares;     // in rank order
  uint32_t samples = 0;              // sample indices handed out, all rendered
  bool interrupted = false;          // a rank was signalled: fewer than spp
  int signal = 0;                    // which signal (SIGINT, SIGTERM)
  uint64_t nonfinite_samples = 0;
  uint64_t cut_paths = 0;            // RenderResult::cut_paths, summed over the ranks
  ReduceTimes reduce;                // where the reduce's time went
  std::string device_turns;          // --device-turns in force: auto, on, off
};

#ifdef OCTRACE_MPI
// A rank's share as the summary's "ranks" entry holds it, and as one line.
nlohmann::json share_json(const RankShare& s);
RankShare share_of(const nlohmann::json& j);
std::string share_line(const RankShare& s);

// MPI_Init_thread (MPI_THREAD_SERIALIZED), the rank, size and host; rank 0
// starts the thread that hands out batches.
void init(int* argc, char*** argv);
bool active();
int rank();
int size();
const std::string& host();

// The device this rank renders on: `requested` unless it is "auto"; else
// the node-local rank modulo the node's GPUs, or "auto" without a GPU.
// A list (--device all | 0,2) is refused: one device per rank.
std::string device_for_rank(const std::string& requested);

// Rank 0: --device-turns: ranks on one physical device (the same host and
// deviceUUID) render one batch at a time, in turns: on GPUs (Auto, the
// default), on every device (On: lavapipe too), or never (Off).
enum class DeviceTurns { Auto, On, Off };
void set_device_turns(DeviceTurns turns);

// Rank 0: the job's total samples per pixel, the samples a resumed state
// already holds, and the progress function (called with the job's totals).
void set_work(uint32_t spp, uint32_t already, ProgressFn progress);

// Rank 0, before render_share: --checkpoint every `seconds` (0: none) of
// the merged state of width x height pixels, written by `write` (with the
// samples per pixel it holds: indices first_sample .. + samples - 1).
void set_checkpoint(double seconds, int width, int height,
                    std::function<void(const Accumulation&, uint32_t samples)> write);

// Rank 0: forgets the progress and checkpoint functions (before what they
// refer to goes away: the batch server may still run while an error
// unwinds the front end).
void clear_callbacks();

// Renders this rank's batches (first_sample + the handed-out index) until
// the job has none left, this rank is asked to stop (`stop`, a signal: the
// whole job then stops after the batches in flight), or another rank failed.
// Each request asks for the samples that take about `batch_ms` (--batch-ms;
// kBatchMs by default) at this rank's speed so far; rank 0 gives fewer near
// the end, so that the ranks finish together.
constexpr double kBatchMs = 250;
void render_share(PathTracer& tracer, const PassSettings& pass, uint32_t first_sample, double batch_ms,
                  const std::atomic<bool>* stop, const std::atomic<int>* signal, RankShare& share);

// Every rank, after render_share: reports success with its state, its share
// and the settings that must agree across ranks (info.scene_hash set).
// Rank 0 returns true with the ranks' states merged (into its own `acc`, in
// place); the others false.
// Throws JobFailed (rank 0 has printed the line) if a rank failed or renders
// another scene or other settings than rank 0.
bool gather(Accumulation acc, uint64_t nonfinite, uint64_t cut_paths, const RankShare& share,
            const CheckpointInfo& info, Gathered& out);

// From the front end's error handler: this rank failed with `code` and
// `message`; takes part in what is left of the job's protocol and returns
// the exit code (rank 0 prints the line naming the first failed rank).
int fail(int code, const std::string& message);
// The end of a successful rank: rank 0 tells the others its final code (it
// may still fail writing its outputs); returns the exit code. Finalises MPI.
int finish(int code);
#endif

}  // namespace octrace::mpi
