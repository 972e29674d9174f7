// Many processes, one render (docs/multi_gpu.md): `mpirun -np N octrace
// render` equals a one-process render of the same samples; a rank that fails
// fails the whole job in one line, with no output file; an interrupted job
// leaves no partial file; --checkpoint writes merged states that resume;
// paths cut short on every rank are counted at rank 0. And the path without MPI: a job array of
// `render --first-sample K --state PART_K` runs merged by `octrace merge`.
//
// The MPI tests run two and three ranks on this machine's lavapipe with one
// lavapipe thread each (LP_NUM_THREADS=1: the ranks share 2 cores); in a
// build without MPI they are skipped, and a launched rank must refuse.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "io/image.h"
#include "scene/scene.h"
#include "test_util.h"

namespace octrace {
namespace {

namespace fs = std::filesystem;
using test::json_of;
using test::run_octrace;
using test::RunResult;

std::string tmp(const std::string& name) { return std::string(OCTRACE_TEST_TMP) + "/mpi_" + name; }

#ifdef OCTRACE_MPIRUN
// OpenMPI refuses root (CI may run as root) unless told; -q: no banners
// beside octrace's own line; --oversubscribe: more ranks than cores.
const std::string kMpiEnv =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 LP_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1";

std::string mpirun_prefix() { return kMpiEnv + " " + OCTRACE_MPIRUN + " -q --oversubscribe "; }

RunResult run_shell(const std::string& cmd) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  RunResult r{-1, ""};
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// `mpirun -np N octrace ARGS`.
RunResult mpirun(int ranks, const std::string& args) {
  return run_shell(mpirun_prefix() + "-np " + std::to_string(ranks) + " " + OCTRACE_BIN + " " + args);
}
#endif

// Equal to float rounding: 1e-5 relative per value, the bound of the
// multi-device and merge tests (tests/app/cli_test.cpp). The samples are the
// same (the same sample indices); only the order of the sums differs: a
// one-process render keeps one Kahan-compensated fp32 sum per pixel, the
// merge adds the ranks' compensated sums in double; both are within a few
// fp32 ulps (~1e-7 relative) of the exact sum of the same samples.
void expect_same_render(const std::string& test, const std::string& reference) {
  const Image a = read_image(reference), b = read_image(test);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  for (size_t i = 0; i < a.rgb.size(); ++i)
    ASSERT_NEAR(b.rgb[i], a.rgb[i], 1e-5 * std::max(1.0f, std::abs(a.rgb[i]))) << test << " value " << i;
}

const std::string kArgs = "render --size 40x24 --spheres 60 --spp 12 ";

#ifdef OCTRACE_MPIRUN

// 2 and 3 ranks (12 samples: uneven shares with 3 ranks' batches) against one
// process; the summary names each rank. The 2 ranks ask for batches of 1
// microsecond (--batch-ms): every batch is then one sample (a pass takes
// longer), so each rank renders as many batches as samples. Both ranks open
// the one lavapipe (the same device UUID on the same host) and are told to
// take turns (--device-turns on; the default, auto, takes turns on GPUs
// only): no two of their batches overlap in time (each rank's batch spans,
// on the host's monotonic clock; without the turns the two ranks render at
// once and their spans overlap), and the ranks waited for each other. The
// 3 ranks render with the default: on lavapipe no rank waits for a turn,
// and the image is the same. The 2 ranks' states
// reach rank 0 through a shared-memory window (one host), the 3 ranks' as
// messages (OCTRACE_MPI_REDUCE=messages, as from ranks of other hosts). (A merged state resumed under
// another number of ranks: CheckpointsOfTheMergedStateResume.)
TEST(Mpi, TwoAndThreeRanksRenderTheSamplesOfOneProcess) {
  const std::string one = tmp("one.pfm");
  ASSERT_EQ(run_octrace(kArgs + "--quiet --device 0 --out " + one).code, 0);
  for (int ranks : {2, 3}) {
    const std::string out = tmp("ranks" + std::to_string(ranks) + ".pfm");
    fs::remove(out);
    const std::string env = ranks == 3 ? "OCTRACE_MPI_REDUCE=messages " : "";
    RunResult r = run_shell(env + mpirun_prefix() + "-np " + std::to_string(ranks) + " " + OCTRACE_BIN + " " + kArgs +
                            (ranks == 2 ? "--batch-ms 0.001 --device-turns on " : "") + "--json --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json j = json_of(r.output);
    ASSERT_TRUE(j.contains("ranks")) << r.output;
    ASSERT_EQ(j["ranks"].size(), size_t(ranks)) << r.output;
    uint32_t samples = 0;
    for (int k = 0; k < ranks; ++k) {
      const nlohmann::json& rank = j["ranks"][k];
      EXPECT_EQ(rank.at("rank").get<int>(), k);
      EXPECT_FALSE(rank.at("host").get<std::string>().empty());
      EXPECT_NE(rank.at("device").get<std::string>().find("llvmpipe"), std::string::npos) << rank;
      // Every rank gets a first batch of one sample when all have started.
      EXPECT_GT(rank.at("samples").get<uint32_t>(), 0u) << rank;
      samples += rank.at("samples").get<uint32_t>();
      // Where its time went: its batches lie within its rendering time.
      EXPECT_GE(rank.at("batches").get<uint32_t>(), 1u) << rank;
      EXPECT_LE(rank.at("passes_wall_ms").get<double>() + rank.at("batch_wait_ms").get<double>(),
                rank.at("render_wall_ms").get<double>() + 0.1) << rank;
      EXPECT_GT(rank.at("setup").at("pipeline").get<double>(), 0.0) << rank;
      if (ranks == 2) {
        EXPECT_EQ(rank.at("batches").get<uint32_t>(), rank.at("samples").get<uint32_t>()) << rank;
      }
    }
    EXPECT_EQ(samples, 12u);
    EXPECT_EQ(j["samples"].get<uint32_t>(), 12u);
    EXPECT_EQ(j.at("device_turns").get<std::string>(), ranks == 2 ? "on" : "auto");
    EXPECT_EQ(j.at("reduce_shared").get<bool>(), ranks == 2);
    std::vector<std::pair<double, double>> spans;
    uint32_t turns = 0;
    for (const nlohmann::json& rank : j["ranks"]) {
      EXPECT_EQ(rank.at("device_uuid"), j["ranks"][0].at("device_uuid")) << "one lavapipe";
      turns += rank.at("turns_waited").get<uint32_t>();
      for (const auto& span : rank.at("batch_spans_ms")) spans.push_back({span[0].get<double>(), span[1].get<double>()});
    }
    if (ranks == 2) {
      ASSERT_EQ(spans.size(), 12u);
      std::sort(spans.begin(), spans.end());
      for (size_t i = 1; i < spans.size(); ++i)
        EXPECT_LE(spans[i - 1].second, spans[i].first) << "batches " << i - 1 << " and " << i << " overlap";
      EXPECT_GT(turns, 0u);
    } else {
      EXPECT_EQ(turns, 0u);
    }
    expect_same_render(out, one);
  }
}

// A state of several slices through the window: 1300x1300 is 1.69 Mpixels,
// 7 slices of 2^18 (the last one partial) in a ring of 3 slots, so the
// sender reuses the slots that rank 0 has merged. Each of the 2 ranks renders
// one of the 2 samples (every rank's first batch is one sample); the merge
// equals one process's render to float rounding.
TEST(Mpi, AStateOfManySlicesReducesThroughTheWindow) {
  const std::string args = "render --size 1300x1300 --spheres 60 --spp 2 --depth 4 ";
  const std::string one = tmp("slices_one.pfm"), two = tmp("slices_two.pfm");
  ASSERT_EQ(run_octrace(args + "--quiet --device 0 --out " + one).code, 0);
  RunResult r = run_shell(mpirun_prefix() + "-np 2 " + OCTRACE_BIN + " " + args + "--json --out " + two);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json j = json_of(r.output);
  EXPECT_TRUE(j.at("reduce_shared").get<bool>()) << r.output;
  for (const nlohmann::json& rank : j.at("ranks")) EXPECT_EQ(rank.at("samples").get<uint32_t>(), 1u) << rank;
  expect_same_render(two, one);
}

// Ranks that take turns on one device are one worker for the batch sizes:
// only one of them renders at a time, so shrinking the batches near the end
// to balance them would only add hand-overs of the device. With batches as
// large as the ranks ask for (--batch-ms of 1000 s: 1024 samples) the 2
// ranks' 12 samples go as each rank's first batch of one sample and then
// one batch of the 10 left; without turns the 2 ranks are 2 workers and the
// 10 are split in shrinking batches (3, 2, 2, 1, 1, 1).
TEST(Mpi, RanksTakingTurnsAreOneWorkerForTheBatches) {
  for (const std::string turns : {"on", "off"}) {
    const std::string out = tmp("turns_" + turns + ".pfm");
    RunResult r = run_shell(mpirun_prefix() + "-np 2 " + OCTRACE_BIN + " " + kArgs +
                            "--batch-ms 1000000 --device-turns " + turns + " --json --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json j = json_of(r.output);
    ASSERT_TRUE(j.contains("ranks")) << r.output;
    uint32_t batches = 0, samples = 0;
    for (const nlohmann::json& rank : j["ranks"]) {
      batches += rank.at("batches").get<uint32_t>();
      samples += rank.at("samples").get<uint32_t>();
    }
    EXPECT_EQ(samples, 12u);
    EXPECT_EQ(batches, turns == "on" ? 3u : 8u) << r.output;
  }
}

// `mpirun -np 1 octrace A : -np 1 octrace B`: rank 1 gets its own bad
// --device, bad scene, or other settings. The job fails: exit non-zero, one
// line from octrace naming rank 1 and its host, no output file.
TEST(Mpi, ARankThatFailsFailsTheJobWithoutOutput) {
  const std::string bad_scene = tmp("bad_scene.json");
  std::ofstream(bad_scene) << "{\"spheres\": [";
  const std::string good = "render --size 16x8 --spheres 20 --spp 4 --quiet ";
  struct Case {
    const char* name;
    std::string rank1;
    std::string message;
  };
  const Case cases[] = {
      {"device", good + "--device 9", "--device: index 9 out of range"},
      {"scene", "render --size 16x8 --spp 4 --quiet --scene " + bad_scene, "bad_scene.json"},
      {"settings", good + "--sample-seed 7", "renders another scene or other settings than rank 0"},
  };
  for (const Case& c : cases) {
    const std::string out = tmp(std::string("never_") + c.name + ".png");
    fs::remove(out);
    const RunResult r = run_shell(mpirun_prefix() + "-np 1 " + OCTRACE_BIN + " " + good + "--out " + out + " : -np 1 " +
                                  OCTRACE_BIN + " " + c.rank1 + " --out " + out);
    EXPECT_NE(r.code, 0) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find("octrace: error: rank 1 ("), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.name << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.name << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  // Both ranks fail alike: still one line, which counts them.
  const std::string out = tmp("never_both.png");
  const RunResult r = mpirun(2, good + "--spp 0 --out " + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("octrace: error: rank 0 ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(2 of 2 ranks failed)"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // --walk-stats counts one process's walks.
  const RunResult w = mpirun(2, good + "--walk-stats --out " + out);
  EXPECT_EQ(w.code, 2) << w.output;
  EXPECT_NE(w.output.find("--walk-stats counts the walks of one process: run it without MPI"), std::string::npos)
      << w.output;
  EXPECT_EQ(std::count(w.output.begin(), w.output.end(), '\n'), 1) << w.output;
  EXPECT_FALSE(fs::exists(out));
  // --dispatch-times times one process's dispatches.
  const RunResult d = mpirun(2, good + "--dispatch-times --out " + out);
  EXPECT_EQ(d.code, 2) << d.output;
  EXPECT_NE(d.output.find("--dispatch-times times the dispatches of one process: run it without MPI"),
            std::string::npos)
      << d.output;
  EXPECT_FALSE(fs::exists(out));
}

// SIGTERM to mpirun while the ranks render: mpirun passes it on, the ranks
// stop after their batches in flight; whatever is left in the folder is a
// whole image (the outputs go through a temporary file and a rename), and
// no temporary file is left behind.
TEST(Mpi, AnInterruptedJobLeavesNoPartialFile) {
  const fs::path dir = tmp("interrupted");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string log = (dir / "log.txt").string(), out = (dir / "out.pfm").string();
  const std::string cmd = "exec env " + kMpiEnv + " " + OCTRACE_MPIRUN + " -q --oversubscribe -np 2 " + OCTRACE_BIN +
                          " render --size 64x40 --spheres 60 --spp 100000 --out " + out + " > " + log + " 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // The progress line: the ranks are rendering.
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool running = false;
  while (!running && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream f(log);
    std::stringstream ss;
    ss << f.rdbuf();
    running = ss.str().find("render: ") != std::string::npos;
  }
  ASSERT_TRUE(running) << "no progress line";
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "log.txt" || name == "out.pfm") << "left behind: " << name;
  }
  if (fs::exists(out)) {
    const Image image = read_image(out);
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 40);
  }
}

// --checkpoint under MPI: the merged state written during the render (the
// ranks' states when no batch is in flight) is a whole render of the
// samples it counts. mpirun is killed (SIGKILL: no final write) after the
// first checkpoint; 3 ranks resume it to N + 7 samples, which equals one
// process rendering N + 7 (1e-5 relative, as above).
TEST(Mpi, CheckpointsOfTheMergedStateResume) {
  const fs::path dir = tmp("checkpoint");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = "render --size 16x10 --spheres 60 ";
  const std::string state = (dir / "state").string(), log = (dir / "log.txt").string();
  const std::string cmd = "exec env " + kMpiEnv + " " + OCTRACE_MPIRUN + " -q --oversubscribe -np 2 " + OCTRACE_BIN +
                          " " + scene + "--spp 100000 --quiet --checkpoint 0.2 --state " + state + " > " + log + " 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(state + ".accum") && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(fs::exists(state + ".accum")) << "no checkpoint";
  // The ranks outlive mpirun by a moment (they end when they find it gone)
  // and may write another checkpoint: wait until the file stays the same.
  auto stamp = fs::last_write_time(state + ".accum");
  for (int still = 0; still < 8 && std::chrono::steady_clock::now() < end;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const auto now = fs::last_write_time(state + ".accum");
    still = now == stamp ? still + 1 : 0;
    stamp = now;
  }
  // The samples the checkpoint holds, from its header.
  std::ifstream f(state + ".accum", std::ios::binary);
  std::string header(512, '\0');
  f.read(header.data(), std::streamsize(header.size()));
  const auto at = header.find("\"samples\":");
  ASSERT_NE(at, std::string::npos) << header;
  const uint32_t samples = uint32_t(std::stoul(header.substr(at + 10)));
  ASSERT_GT(samples, 0u);
  ASSERT_LT(samples, 100000u);
  const std::string spp = "--spp " + std::to_string(samples + 7) + " ";
  const std::string one = (dir / "one.pfm").string(), resumed = (dir / "resumed.pfm").string();
  ASSERT_EQ(run_octrace(scene + spp + "--quiet --out " + one).code, 0);
  const RunResult r = mpirun(3, scene + spp + "--json --resume " + state + " --out " + resumed);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(json_of(r.output).value("resumed_from", 0u), samples) << r.output;
  expect_same_render(resumed, one);
}

// Paths that llvmpipe's loop limit cut short (RenderResult::cut_paths;
// render_test's PathsCutShortByTheLoopLimitAreCounted) are counted on every
// rank and summed at rank 0, which warns as one process does: the light trap
// with whole paths, its 2 samples one a rank, cuts as many invocations as
// one process rendering both (a sample's pass is the same dispatch on
// either). Fails where a rank's count is lost in the gather.
TEST(Mpi, PathsCutShortOnEveryRankAreCountedAtRankZero) {
  const std::string scene = tmp("light_trap.json");
  save_scene_json(test::light_trap_scene(), scene);
  const std::string args = "render --scene " + scene + " --size 80x60 --spp 2 --depth 300 --tail-depth off --json ";
  const RunResult one = run_octrace(args + "--device 0 --out " + tmp("trap_one.pfm"));
  ASSERT_EQ(one.code, 0) << one.output;
  const uint64_t cut = json_of(one.output).at("cut_paths").get<uint64_t>();
  ASSERT_GT(cut, 0u) << "the whole paths reach llvmpipe's loop limit here";
  const RunResult two = mpirun(2, args + "--out " + tmp("trap_two.pfm"));
  ASSERT_EQ(two.code, 0) << two.output;
  const nlohmann::json j = json_of(two.output);
  for (const nlohmann::json& rank : j.at("ranks")) EXPECT_EQ(rank.at("samples").get<uint32_t>(), 1u) << rank;
  EXPECT_EQ(j.at("cut_paths").get<uint64_t>(), cut) << two.output;
  EXPECT_NE(two.output.find("warning: " + std::to_string(cut) + " invocations"), std::string::npos) << two.output;
}

#else

TEST(Mpi, TwoAndThreeRanksRenderTheSamplesOfOneProcess) { GTEST_SKIP() << "built without MPI (OCTRACE_MPI=OFF)"; }

// A build without MPI started by a launcher would render the whole image in
// every rank, each writing the same files: it refuses.
TEST(Mpi, ABuildWithoutMpiRefusesALaunch) {
  const std::string out = tmp("never_nompi.png");
  const RunResult r = run_octrace(kArgs + "--quiet --out " + out, "OMPI_COMM_WORLD_SIZE=2");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("this build has no MPI"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

#endif

// --batch-ms and --device-turns belong to an MPI job: a one-process render
// refuses them (and a bad value) in one line, exit 2, no output.
TEST(Mpi, OneProcessRefusesBatchMs) {
  const std::string out = tmp("never_batch.png");
  fs::remove(out);
  for (const std::string value : {"100", "-1"}) {
    const RunResult r = run_octrace("render --size 8x8 --spp 1 --quiet --batch-ms " + value + " --out " + out);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("octrace: error: --batch-ms: "), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << value;
  }
  const RunResult r = run_octrace("render --size 8x8 --spp 1 --quiet --device-turns off --out " + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("octrace: error: --device-turns: "), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// The job array of docs/multi_gpu.md ("Job arrays without MPI"), as a Slurm
// array would run it: task K renders --first-sample K*N --spp N --state
// PART_K (here 3 tasks of 4 samples, out of order), `octrace merge` joins the
// parts; the image equals one render of the 12 samples, and the merged
// --state holds them (it merges again to the same image).
TEST(JobArray, ThreePartsMergeIntoOneRender) {
  const std::string one = tmp("array_one.pfm"), merged = tmp("array_merged.pfm"), again = tmp("array_again.pfm");
  ASSERT_EQ(run_octrace(kArgs + "--quiet --out " + one).code, 0);
  std::string parts;
  for (int k : {2, 0, 1}) {
    const std::string part = tmp("array_part_" + std::to_string(k));
    const RunResult r = run_octrace("render --size 40x24 --spheres 60 --quiet --spp 4 --first-sample " +
                                    std::to_string(4 * k) + " --state " + part);
    ASSERT_EQ(r.code, 0) << r.output;
    parts += part + " ";
  }
  RunResult r = run_octrace("merge " + parts + "--out " + merged + " --state " + tmp("array_all"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("merged 3 states: 12 samples per pixel"), std::string::npos) << r.output;
  expect_same_render(merged, one);
  r = run_octrace("merge " + tmp("array_all") + " --out " + again);
  ASSERT_EQ(r.code, 0) << r.output;
  expect_same_render(again, one);
}

}  // namespace
}  // namespace octrace
