// `octrace view`: the preview window. The flags and the key list are here so
// that a build without window support (-DOCTRACE_WINDOW=OFF) still parses and
// documents them; view.cpp, the window itself, is built only with it.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "render/path_tracer.h"
#include "scene/scene.h"

namespace octrace {

inline constexpr const char* kViewKeys =
    "Mouse: left drag orbits around the look-at point, right (or middle) drag pans,\n"
    "       the wheel zooms; any camera move restarts the accumulation.\n"
    "Keys:  P          next precision (fp32 / fp16 / fp16-all)\n"
    "       B          next acceleration structure (octree / bvh / brute)\n"
    "       E          toggle the effects: specialised pipeline (auto) / general (all)\n"
    "       Up / Down  bounce limit +1 / -1 (PageUp / PageDown: x2 / /2)\n"
    "       R          restart the accumulation\n"
    "       C          camera back to the scene's\n"
    "       S          save the image: PNG + PFM next to the scene file\n"
    "       H          print this list\n"
    "       Esc / Q    quit\n";

struct ViewOptions {
  std::string scene_file;  // where `S` saves (its folder and name); empty: rtiow-*.png here
  std::string device = "auto";
  bool validation = false;
  uint32_t max_spp = 0;     // stop accumulating here; 0: never
  std::string screenshot;   // written when max_spp is reached: the window's pixels
  bool exit_after_spp = false;
  uint32_t orbit_test = 0;  // scripted camera moves, for timing; 0: none
  // Set (by Ctrl-C or SIGTERM): the window closes as if asked to; nothing is
  // saved that was not asked for.
  const std::atomic<bool>* stop = nullptr;
  // Called once the window is open (the flags checked, the device made):
  // where `view --dump-scene` writes its file.
  std::function<void()> on_open;

  void add_to(CLI::App& cmd) {
    cmd.add_option("--max-spp", max_spp, "Stop accumulating at this many samples per pixel (0: never)")
        ->capture_default_str();
    cmd.add_option("--screenshot", screenshot, "When --max-spp is reached, write the window's pixels here (.png)");
    cmd.add_flag("--exit-after-spp", exit_after_spp, "Quit when --max-spp is reached (after --screenshot)");
    cmd.add_option("--orbit-test", orbit_test,
                   "Timing: orbit the camera by 1 degree after each frame that showed the last move, N times, "
                   "then quit and print the time from a move to its first pass");
    cmd.footer(std::string("\n") + kViewKeys);
  }
};

// Opens the window and runs until it is closed. Throws RuntimeError without a
// display, InputError for inconsistent flags.
int run_view(const Scene& scene, const RenderSettings& settings, const ViewOptions& options);

}  // namespace octrace
