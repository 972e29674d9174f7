// `octrace view` as a user meets it, under a virtual X server (Xvfb) on
// lavapipe: the window shows the same image as `octrace render` of the same
// scene and sample count (within 8-bit rounding), and without a display it
// says so in one line. The ctest environment turns the validation layer on,
// and octrace exits non-zero on any validation message.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "io/image.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;

using octrace::test::RunResult;

RunResult run(const std::string& env, const std::string& args) { return octrace::test::run_octrace(args, env); }

std::string tmp(const std::string& name) { return std::string(OCTRACE_TEST_TMP) + "/view_" + name; }

// An Xvfb of its own on a free display (ctest runs test cases in parallel):
// -displayfd makes the server pick the display and write its number to a pipe
// once it accepts connections.
class Xvfb {
 public:
  Xvfb() {
    int fds[2];
    if (pipe(fds) != 0) return;
    pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      if (!std::freopen("/dev/null", "w", stderr)) _exit(127);
      std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "640x480x24", "-nolisten", "tcp",
             static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    pid_ = pid;
    char c;
    std::string number;
    while (read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    close(fds[0]);
    if (!number.empty()) display_ = ":" + number;
  }
  ~Xvfb() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
  }
  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

// The 8-bit sRGB value a PNG holds, from read_image's linear decoding of it.
int png_byte(float linear) { return int(std::lround(octrace::srgb_encode(linear) * 255.0f)); }

struct ViewCase {
  const char* label;
  std::string scene_flags;  // also --size, --depth, --accel: everything both commands share
  int spp;
};

void PrintTo(const ViewCase& c, std::ostream* os) { *os << c.label; }

class ViewScreenshotTest : public ::testing::TestWithParam<ViewCase> {};

TEST_P(ViewScreenshotTest, WindowShowsWhatRenderWrites) {
  const ViewCase& c = GetParam();
  Xvfb xvfb;
  ASSERT_FALSE(xvfb.display().empty()) << "cannot start Xvfb (Debian: xvfb)";
  std::string shot = tmp(std::string(c.label) + "_window.png");
  std::string reference = tmp(std::string(c.label) + "_render.png");
  fs::remove(shot);
  std::string spp = std::to_string(c.spp);

  RunResult view = run("DISPLAY=" + xvfb.display(), "view --device cpu " + c.scene_flags + " --max-spp " + spp +
                                                        " --screenshot " + shot + " --exit-after-spp");
  ASSERT_EQ(view.code, 0) << view.output;
  EXPECT_EQ(view.output.find("validation"), std::string::npos) << view.output;
  RunResult render = run("", "render --device cpu --quiet " + c.scene_flags + " --spp " + spp + " --out " + reference);
  ASSERT_EQ(render.code, 0) << render.output;

  octrace::Image a = octrace::read_image(shot);
  octrace::Image b = octrace::read_image(reference);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  int worst = 0, differ = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    int d = std::abs(png_byte(a.rgb[i]) - png_byte(b.rgb[i]));
    worst = std::max(worst, d);
    differ += d != 0;
  }
  // The resolve pass computes the mean and the sRGB curve in float on the
  // device, write_image in double and float on the host: a value on a
  // rounding boundary may land one step apart, never more.
  EXPECT_LE(worst, 1) << differ << " of " << a.rgb.size() << " channel values differ";
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, ViewScreenshotTest,
    ::testing::Values(
        // Several passes per frame (small passes), octree.
        ViewCase{"rtiow_octree", "--spheres 40 --size 96x64 --depth 10", 24},
        // A size that is no multiple of the 8x8 workgroup; brute force; other noise.
        ViewCase{"rtiow_brute_odd_size", "--spheres 20 --size 37x23 --accel brute --sample-seed 3", 5},
        // The half-precision variant goes through the same resolve.
        ViewCase{"rtiow_fp16", "--spheres 40 --size 64x48 --depth 10 --precision fp16", 8}),
    [](const auto& info) { return std::string(info.param.label); });

// Brute force on a CPU device past llvmpipe's loop limit (2,000 spheres at
// 50 bounces: 100,000 iterations a path) is said once, as `render` and
// `bench` say it (render/path_tracer.h software_loop_limit_warning); the
// window showed such images in silence. Fails where view drops the
// warning or prints it every frame (2 spp: two frames at least).
TEST(ViewTest, BruteForcePastTheLoopLimitIsSaidOnce) {
  Xvfb xvfb;
  ASSERT_FALSE(xvfb.display().empty()) << "cannot start Xvfb (Debian: xvfb)";
  const std::string shot = tmp("brute_limit.png");
  RunResult view = run("DISPLAY=" + xvfb.display(), "view --device cpu --spheres 2000 --radius 0.1 --size 16x8 "
                                                    "--accel brute --max-spp 2 --screenshot " + shot +
                                                    " --exit-after-spp");
  ASSERT_EQ(view.code, 0) << view.output;
  const std::string said = "octrace view: warning: ";
  const size_t at = view.output.find(said);
  ASSERT_NE(at, std::string::npos) << view.output;
  EXPECT_NE(view.output.find("brute force over", at), std::string::npos) << view.output;
  EXPECT_NE(view.output.find("can cut paths longer than", at), std::string::npos) << view.output;
  EXPECT_EQ(view.output.find(said, at + 1), std::string::npos) << "said twice: " << view.output;
}

TEST(ViewTest, WithoutDisplayOneLineNonZeroExit) {
  std::string shot = tmp("no_display.png");
  fs::remove(shot);
  RunResult r = run("env -u DISPLAY -u WAYLAND_DISPLAY",
                    "view --device cpu --size 16x16 --max-spp 1 --screenshot " + shot + " --exit-after-spp");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(shot));
}

// view accumulates until --max-spp: --spp is refused by name (CLI11 said
// "The following arguments were not expected: 5 --spp").
TEST(ViewTest, SppIsRefusedByName) {
  RunResult r = run("", "view --device cpu --spp 5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("--spp: view accumulates until --max-spp N"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(ViewTest, ScreenshotWithoutTargetIsBadInput) {
  RunResult r = run("", "view --device cpu --screenshot " + tmp("no_target.png"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("--screenshot: needs --max-spp"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

}  // namespace
