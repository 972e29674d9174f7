// Nothing lost: a render stopped by SIGINT or SIGTERM writes its outputs with
// the samples reached and exits 128 + signal; its state resumes to the
// same image, bit for bit, as a render that was never stopped; a state of
// another scene or settings is refused in one line; a second Ctrl-C ends
// the process at once and leaves no half-written file.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "scene/gltf_builder.h"
#include "test_util.h"

namespace octrace {
namespace {

namespace fs = std::filesystem;
using test::json_of;
using test::run_octrace;
using test::RunResult;

std::string tmp(const std::string& name) { return std::string(OCTRACE_TEST_TMP) + "/interrupt_" + name; }

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Starts octrace with `args` (stdout and stderr to `log`); returns its pid.
pid_t spawn(const std::string& args, const std::string& log) {
  const std::string cmd = std::string("exec ") + OCTRACE_BIN + " " + args + " > " + log + " 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Waits until `path` exists (the first checkpoint: passes are running).
bool wait_for(const std::string& path, double seconds = 120) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (fs::exists(path)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

const std::string kScene = "--size 40x24 --spheres 200 --seed 4 ";

void remove_state(const std::string& prefix) {
  for (const char* ext : {".accum", ".mean.pfm", ".count.pfm"}) fs::remove(prefix + ext);
}

// Interrupted by `sig` after its first checkpoint: exit 128 + sig, the image
// written, and the samples reached (> 0, < spp) in --json.
uint32_t interrupt_render(int sig, const std::string& name) {
  const std::string state = tmp(name), out = tmp(name + ".pfm"), log = tmp(name + ".log");
  remove_state(state);
  fs::remove(out);
  const pid_t pid = spawn("render " + kScene + "--spp 1000000 --json --checkpoint 0.2 --state " + state + " --out " + out, log);
  EXPECT_TRUE(wait_for(state + ".accum")) << read_all(log);
  kill(pid, sig);
  EXPECT_EQ(wait_exit(pid), 128 + sig) << read_all(log);
  EXPECT_TRUE(fs::exists(out));
  const nlohmann::json j = json_of(read_all(log));
  EXPECT_EQ(j.value("interrupted", false), true) << read_all(log);
  const uint32_t samples = j.value("samples", 0u);
  EXPECT_GT(samples, 0u);
  EXPECT_LT(samples, 1000000u);
  return samples;
}

TEST(Interrupt, SigintKeepsTheWorkAndTheResumedRenderEqualsTheWholeOne) {
  const uint32_t k = interrupt_render(SIGINT, "int");
  ASSERT_GT(k, 0u);
  const std::string spp = std::to_string(k + 3);
  // Resumed from the interrupted state up to k + 3 samples ...
  RunResult r = run_octrace("render " + kScene + "--spp " + spp + " --quiet --resume " + tmp("int") + " --out " +
                            tmp("resumed.pfm"));
  ASSERT_EQ(r.code, 0) << r.output;
  // ... equals k + 3 samples rendered at once, bit for bit.
  r = run_octrace("render " + kScene + "--spp " + spp + " --quiet --out " + tmp("whole.pfm"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(read_all(tmp("resumed.pfm")), read_all(tmp("whole.pfm")));
  // The interrupted image itself is the k-sample render.
  r = run_octrace("render " + kScene + "--spp " + std::to_string(k) + " --quiet --out " + tmp("k.pfm"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(read_all(tmp("int.pfm")), read_all(tmp("k.pfm")));
}

TEST(Interrupt, SigtermExits143WithTheOutputs) { interrupt_render(SIGTERM, "term"); }

TEST(Interrupt, SecondSigintEndsAtOnceWithoutPartialFiles) {
  const std::string state = tmp("twice"), out = tmp("twice.pfm"), log = tmp("twice.log");
  remove_state(state);
  fs::remove(out);
  const pid_t pid = spawn("render " + kScene + "--spp 1000000 --checkpoint 0.05 --state " + state + " --out " + out, log);
  ASSERT_TRUE(wait_for(state + ".accum")) << read_all(log);
  kill(pid, SIGINT);
  kill(pid, SIGINT);
  EXPECT_EQ(wait_exit(pid), 130) << read_all(log);
  for (const auto& entry : fs::directory_iterator(OCTRACE_TEST_TMP))
    EXPECT_EQ(entry.path().filename().string().find("interrupt_twice") != std::string::npos &&
                  entry.path().string().find(".tmp-") != std::string::npos,
              false)
        << "left behind: " << entry.path();
}

// A device lost during a render with checkpoints: one line that names the
// last checkpoint (which resumes), exit 1, and no output image. The hook's
// batch checkpoints before the loss (render/path_tracer.cpp); the interval
// is long so that no timed checkpoint comes first on any device (on the
// H200 the first 10 samples took less than any short one).
TEST(Interrupt, LostDeviceNamesTheLastCheckpoint) {
  const std::string state = tmp("lost"), out = tmp("lost.pfm");
  remove_state(state);
  fs::remove(out);
  RunResult r = run_octrace("render " + kScene + "--spp 40 --quiet --checkpoint 1000 --state " + state + " --out " + out,
                            "OCTRACE_TEST_DEVICE_LOST_AFTER=10");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("Vulkan device lost during vkQueueSubmit"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the last checkpoint is " + state + " (10 spp)"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // It resumes to the whole render.
  r = run_octrace("render " + kScene + "--spp 40 --quiet --resume " + state + " --out " + tmp("lost_resumed.pfm"));
  ASSERT_EQ(r.code, 0) << r.output;
  r = run_octrace("render " + kScene + "--spp 40 --quiet --out " + tmp("lost_whole.pfm"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(read_all(tmp("lost_resumed.pfm")), read_all(tmp("lost_whole.pfm")));
}

// A state is resumed only by the render it belongs to; anything else is one
// line naming the file and what differs, exit 2, and no output.
TEST(Interrupt, StateOfAnotherRenderIsRefused) {
  const std::string state = tmp("mine");
  remove_state(state);
  RunResult r = run_octrace("render " + kScene + "--spp 2 --quiet --state " + state);
  ASSERT_EQ(r.code, 0) << r.output;
  const struct {
    std::string args, message;
  } cases[] = {
      {"--size 40x24 --spheres 201 --seed 4", "mine.accum: cannot resume: another scene: hash"},
      {kScene + "--sample-seed 9", "mine.accum: cannot resume: sample seed 1, this render 9"},
      {"--size 40x20 --spheres 200 --seed 4", "mine.accum: cannot resume: size 40x24, this render 40x20"},
      {kScene + "--precision fp16", "mine.accum: cannot resume: precision fp32, this render fp16"},
      {kScene + "--depth 7", "mine.accum: cannot resume: bounce limit 50, this render 7"},
  };
  for (const auto& c : cases) {
    const std::string out = tmp("refused.png");
    fs::remove(out);
    r = run_octrace("render " + c.args + " --spp 4 --quiet --resume " + state + " --out " + out);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  // A truncated checkpoint.
  std::string bytes = read_all(state + ".accum");
  std::ofstream(tmp("cut.accum"), std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() - 100));
  r = run_octrace("render " + kScene + "--spp 4 --quiet --resume " + tmp("cut") + " --out " + tmp("refused.png"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("cut.accum: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bytes of data, expected"), std::string::npos) << r.output;
  // A --spp below the samples the state holds wrote a state whose header
  // counted fewer samples than its pixels, which no render could load.
  remove_state(tmp("fewer"));
  r = run_octrace("render " + kScene + "--spp 1 --quiet --resume " + state + " --state " + tmp("fewer"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("mine.accum: cannot resume: it holds 2 spp, more than --spp 1"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(tmp("fewer.accum")));
  // The header's fields, each checked and named (a negative count was read
  // as 2^32 - 1 and a fractional width as its whole part; a bad hash said
  // "stoull", a mistyped field gave nlohmann's own message).
  const size_t magic_end = bytes.find('\n') + 1, header_end = bytes.find('\n', magic_end);
  const nlohmann::json header = nlohmann::json::parse(bytes.substr(magic_end, header_end - magic_end));
  const struct {
    const char* field;
    nlohmann::json value;
    std::string message;
  } fields[] = {
      {"samples", -1, "samples: expected a whole number in 0..4294967295, got -1"},
      {"samples", 99999999999, "samples: expected a whole number in 0..4294967295, got 99999999999"},
      {"width", 40.5, "width: expected a whole number in 1..1048576, got 40.5"},
      {"width", "40", "width: expected a whole number in 1..1048576, got \"40\""},
      {"scene_hash", "zz", "scene_hash: expected 1 to 16 hexadecimal digits, got \"zz\""},
      {"accel", 3, "accel: expected a name, got 3"},
  };
  for (const auto& f : fields) {
    nlohmann::json bad = header;
    bad[f.field] = f.value;
    std::ofstream(tmp("bad.accum"), std::ios::binary)
        << bytes.substr(0, magic_end) << bad.dump() << bytes.substr(header_end);
    r = run_octrace("render " + kScene + "--spp 4 --quiet --resume " + tmp("bad") + " --out " + tmp("refused.png"));
    EXPECT_EQ(r.code, 2) << f.message << ": " << r.output;
    EXPECT_NE(r.output.find("bad.accum: bad header: " + f.message), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  // --checkpoint needs somewhere to write.
  r = run_octrace("render " + kScene + "--spp 1 --quiet --checkpoint 1 --out " + tmp("refused.png"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--checkpoint: needs --state PREFIX"), std::string::npos) << r.output;
}

// A scene with a shared mesh holds other triangles on the device with
// --instancing keep than baked (auto bakes one placed twice): a state saved
// one way is refused the other way, and the message says which flag
// resumes it; that flag does.
TEST(Interrupt, StateOfTheOtherInstancingNamesTheFlag) {
  test::GltfBuilder b = test::quad_gltf();
  b.add("nodes", {{"mesh", 0}, {"translation", {2, 0, 0}}});
  b.set_scene({0, 1});
  const std::string scene = "--size 16x12 --scene " + b.write(tmp("two_quads.glb")) + " ";
  const std::string state = tmp("kept");
  remove_state(state);
  RunResult r = run_octrace("render " + scene + "--spp 2 --quiet --instancing keep --state " + state);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string out = tmp("instancing.png");
  fs::remove(out);
  r = run_octrace("render " + scene + "--spp 4 --quiet --resume " + state + " --out " + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("kept.accum: cannot resume: another scene: hash"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("resumes with --instancing keep)"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(out));
  r = run_octrace("render " + scene + "--spp 4 --quiet --instancing keep --resume " + state + " --out " + out);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out));
}

}  // namespace
}  // namespace octrace
