// `octrace view`: a GLFW window that shows the image converge. Each frame
// runs some passes into the accumulation buffers, then a resolve pass writes
// the mean as 8-bit sRGB into a buffer that is copied into the swapchain
// image: the image never leaves the device (the study's preview went through
// the CPU and an OpenGL texture every pass).
#include "view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include "core/clock.h"
#include "io/image.h"
#include "render/camera.h"
#include "render/preview.h"

namespace octrace {

namespace {

// Device time of the passes in one frame: about 30 frames per second where a
// pass is short enough, one pass per frame where it is not.
constexpr double kPassBudgetMs = 25.0;
constexpr uint32_t kMaxPassesPerFrame = 256;
constexpr uint32_t kMaxDepth = 1u << 16;
constexpr uint32_t kSampleLimit = 1u << 24;

std::string g_glfw_error = "unknown error";
void on_glfw_error(int, const char* text) { g_glfw_error = text; }

// PNG/PFM base name for `S`: next to the scene file, or here for rtiow.
std::string save_base(const std::string& scene_file, uint32_t spp) {
  std::string base = "rtiow";
  if (!scene_file.empty()) {
    base = scene_file;
    size_t slash = base.find_last_of('/');
    size_t dot = base.find_last_of('.');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) base.resize(dot);
  }
  return base + "-" + std::to_string(spp) + "spp";
}

struct GlfwSession {
  bool open = false;
  ~GlfwSession() {
    if (open) glfwTerminate();
  }
};

struct WindowDeleter {
  void operator()(GLFWwindow* w) const { glfwDestroyWindow(w); }
};

class Viewer {
 public:
  Viewer(const Scene& scene, const RenderSettings& settings, const ViewOptions& options)
      : scene_(scene), original_camera_(scene.camera), settings_(settings), options_(options) {}

  void open();
  void run();

 private:
  void recreate_swapchain(int width, int height);
  void apply_configuration();
  void warn_loop_limit();
  void frame();
  void after_frame(uint32_t passes);
  void update_title();
  void save();
  void write_screenshot();
  void camera_moved();

  // Where accumulation stops: --max-spp, else where the sample count stops
  // being an exact float (as --spp of render).
  uint32_t target_spp() const { return options_.max_spp ? options_.max_spp : kSampleLimit; }
  PassSettings pass() const { return pass_settings(scene_, settings_); }

  void on_key(int key, int action);
  void on_button(int button, int action);
  void on_cursor(double x, double y);

  // Member order is destruction order reversed: everything on the device
  // goes before the context, the context after the window.
  GlfwSession glfw_;
  std::unique_ptr<GLFWwindow, WindowDeleter> window_;
  VulkanContext ctx_;
  std::unique_ptr<PathTracer> tracer_;
  Preview preview_;

  Scene scene_;
  Camera original_camera_;
  RenderSettings settings_;  // what the keys ask for; the tracer's are what runs
  ViewOptions options_;

  uint32_t spp_ = 0;           // passes accumulated since the last restart
  double pass_ms_ = 0;         // device time per pass, last frame; 0 before the first
  bool reconfigure_ = false;   // precision, accel or effects changed
  // The loop-limit warning last printed and the accel and depth it was
  // worked out for (software_loop_limit_warning: on a CPU device it depends
  // on those alone of what the keys change), so that it is worked out
  // again only when they change, and printed only when it changes.
  std::string loop_limit_warning_;
  std::optional<std::pair<Accel, uint32_t>> loop_limit_for_;
  bool swapchain_dirty_ = true;
  bool restart_ = false;       // camera or bounce limit changed, or R
  bool save_requested_ = false;
  bool target_reached_ = false;
  bool quit_ = false;
  int drag_button_ = -1;
  double drag_x_ = 0, drag_y_ = 0;

  // Camera move to the first pass that shows it (--orbit-test reports these).
  std::optional<Clock::time_point> move_started_;
  std::vector<double> move_latency_ms_;
  uint32_t orbits_done_ = 0;

  // For the title and the summary line.
  uint64_t frames_ = 0, total_passes_ = 0;
  double total_pass_ms_ = 0;
  Clock::time_point fps_start_ = Clock::now();
  uint64_t fps_frames_ = 0;
  double fps_ = 0;
  std::string title_;
};

void Viewer::open() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!x11 || !*x11) && (!wayland || !*wayland))
    throw RuntimeError("no display (DISPLAY and WAYLAND_DISPLAY are unset): `octrace view` needs a desktop or an "
                       "X server such as Xvfb (xvfb-run octrace view ...); `octrace render` needs neither");
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) throw RuntimeError("cannot open the display: " + g_glfw_error);
  glfw_.open = true;
  if (!glfwVulkanSupported()) throw RuntimeError("GLFW found no Vulkan loader with surface support");

  ContextOptions context_options{options_.device, settings_.precision != Precision::FP32, options_.validation};
  uint32_t count = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&count);
  if (!extensions) throw RuntimeError("this display cannot show Vulkan images: " + g_glfw_error);
  context_options.instance_extensions.assign(extensions, extensions + count);
  context_options.can_present = [](VkInstance instance, VkPhysicalDevice physical, uint32_t family) {
    return glfwGetPhysicalDevicePresentationSupport(instance, physical, family) == GLFW_TRUE;
  };
  create_context(ctx_, context_options);
  if (ctx_.info.software) std::fprintf(stderr, "octrace: %s\n", software_device_note(ctx_.info).c_str());

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_.reset(glfwCreateWindow(settings_.width, settings_.height, "octrace", nullptr, nullptr));
  if (!window_) throw RuntimeError("cannot open a window: " + g_glfw_error);
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VK_CHECK(glfwCreateWindowSurface(ctx_.instance, window_.get(), nullptr, &surface));
  create_preview(preview_, ctx_, surface);

  glfwSetWindowUserPointer(window_.get(), this);
  glfwSetKeyCallback(window_.get(), [](GLFWwindow* w, int key, int, int action, int) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->on_key(key, action);
  });
  glfwSetMouseButtonCallback(window_.get(), [](GLFWwindow* w, int button, int action, int) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->on_button(button, action);
  });
  glfwSetCursorPosCallback(window_.get(), [](GLFWwindow* w, double x, double y) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->on_cursor(x, y);
  });
  glfwSetScrollCallback(window_.get(), [](GLFWwindow* w, double, double dy) {
    Viewer* v = static_cast<Viewer*>(glfwGetWindowUserPointer(w));
    zoom(v->scene_.camera, float(dy));
    v->camera_moved();
  });
  glfwSetFramebufferSizeCallback(window_.get(), [](GLFWwindow* w, int, int) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->swapchain_dirty_ = true;
  });
}

void Viewer::run() {
  std::printf("octrace view: H lists the keys\n");
  std::fflush(stdout);
  const auto stopped = [&] { return options_.stop && options_.stop->load(); };
  while (!quit_ && !stopped() && !glfwWindowShouldClose(window_.get())) {
    const bool idle = spp_ >= target_spp() && !restart_ && !reconfigure_;
    // Nothing to add: re-present now and then (an uncovered window needs
    // its pixels again) rather than spin.
    if (idle) glfwWaitEventsTimeout(0.1);
    else glfwPollEvents();
    if (quit_ || stopped() || glfwWindowShouldClose(window_.get())) break;

    int width = 0, height = 0;
    glfwGetFramebufferSize(window_.get(), &width, &height);
    // Minimised (a zero-size framebuffer on some systems, iconified on
    // others): nothing to show, and nothing to acquire, until restored.
    if (width == 0 || height == 0 || glfwGetWindowAttrib(window_.get(), GLFW_ICONIFIED)) {
      glfwWaitEventsTimeout(0.1);  // not forever: a Ctrl-C must be seen
      continue;
    }
    if (swapchain_dirty_ || uint32_t(width) != preview_.swapchain.extent.width ||
        uint32_t(height) != preview_.swapchain.extent.height) {
      recreate_swapchain(width, height);
      continue;
    }
    if (reconfigure_) apply_configuration();
    warn_loop_limit();
    if (restart_) {
      tracer_->reset();
      spp_ = 0;
      target_reached_ = false;
      restart_ = false;
    }
    frame();
    if (save_requested_) save();
  }
  double mean_ms = total_passes_ ? total_pass_ms_ / double(total_passes_) : 0.0;
  std::printf("octrace view: %u spp at %dx%d, %llu frames, %.1f ms per pass (device), %.1f frames/s at the end\n",
              spp_, settings_.width, settings_.height, (unsigned long long)frames_, mean_ms, fps_);
  if (!move_latency_ms_.empty()) {
    std::vector<double> t = move_latency_ms_;
    std::sort(t.begin(), t.end());
    std::printf("octrace view: %zu camera moves, from a move to its first pass: median %.2f ms (min %.2f, max %.2f)\n",
                t.size(), t[t.size() / 2], t.front(), t.back());
  }
}

// A new swapchain size is a new image size: the tracer keeps its scene and
// pipeline and gets a new accumulation state.
void Viewer::recreate_swapchain(int width, int height) {
  swapchain_dirty_ = false;
  if (!resize_preview(preview_, {uint32_t(width), uint32_t(height)})) return;
  settings_.width = int(preview_.swapchain.extent.width);
  settings_.height = int(preview_.swapchain.extent.height);
  if (!tracer_) {
    // The depth keys change the bounce limit pass by pass, but the tracer
    // decides its tail queue once: a CPU device's auto (whole paths up to
    // kCpuWholePathBounces, the tail levels above) is decided for the
    // deepest paths the keys can ask for.
    RenderSettings made = settings_;
    made.bounce_limit = kMaxDepth;
    tracer_ = std::make_unique<PathTracer>(ctx_, scene_, made);
  } else if (tracer_->settings().width != settings_.width || tracer_->settings().height != settings_.height) {
    tracer_->resize(settings_.width, settings_.height);
  } else if (preview_.width == uint32_t(settings_.width) && preview_.height == uint32_t(settings_.height)) {
    return;  // same size, same resolve pipeline: the accumulation goes on
  }
  attach_tracer(preview_, *tracer_);
  spp_ = 0;
  pass_ms_ = 0;
  target_reached_ = false;
}

// On a CPU device, brute force at the accel and depth in force can reach
// llvmpipe's loop limit, which cuts paths short (render/path_tracer.h,
// software_loop_limit_warning): said once when the B or depth keys (or the
// flags) bring a render there, and again only when the warning changes.
void Viewer::warn_loop_limit() {
  const std::pair<Accel, uint32_t> now{settings_.accel, settings_.bounce_limit};
  if (loop_limit_for_ == now) return;
  loop_limit_for_ = now;
  std::string w = software_loop_limit_warning(ctx_.info, scene_, settings_);
  if (w == loop_limit_warning_) return;
  loop_limit_warning_ = w;
  if (!w.empty()) std::fprintf(stderr, "octrace view: warning: %s\n", w.c_str());
}

// P, B and E: another pipeline (or acceleration structure) over the same
// scene on the device. What the scene or device does not allow (fp16 with
// radiance beyond half's range, say) is reported and the window goes on
// with what it had.
void Viewer::apply_configuration() {
  reconfigure_ = false;
  try {
    tracer_->reconfigure(scene_, settings_.accel, settings_.precision, settings_.all_effects);
  } catch (const InputError& e) {
    std::fprintf(stderr, "octrace view: %s\n", e.what());
    settings_.accel = tracer_->settings().accel;
    settings_.precision = tracer_->settings().precision;
    settings_.all_effects = tracer_->settings().all_effects;
  }
  spp_ = 0;
  pass_ms_ = 0;
  target_reached_ = false;
  restart_ = false;
}

void Viewer::camera_moved() {
  restart_ = true;
  if (!move_started_) move_started_ = Clock::now();
}

void Viewer::frame() {
  uint32_t passes = 0;
  if (spp_ < target_spp()) {
    // The first frame after a restart shows one pass at once (a camera move
    // is seen after one pass, not after a frame's budget of them).
    passes = pass_ms_ > 0 && spp_ > 0
                 ? uint32_t(std::clamp(kPassBudgetMs / pass_ms_, 1.0, double(kMaxPassesPerFrame)))
                 : 1;
    passes = std::min(passes, target_spp() - spp_);
  }
  const FrameStatus status = submit_frame(preview_, *tracer_, pass(), spp_, passes);
  if (status == FrameStatus::Skipped) {
    swapchain_dirty_ = true;
    return;
  }
  if (status == FrameStatus::SubmittedStale) swapchain_dirty_ = true;
  // Window events are handled while the frame runs, so that a long pass
  // never makes the window unresponsive (moves apply next frame).
  while (!wait_frame(preview_, 10'000'000)) glfwPollEvents();
  after_frame(passes);
}

void Viewer::after_frame(uint32_t passes) {
  if (passes) {
    const double ms = frame_pass_ms(preview_);
    pass_ms_ = ms / passes;
    total_pass_ms_ += ms;
    total_passes_ += passes;
    spp_ += passes;
    // The first frame with passes after a move (and no newer move) shows it.
    if (move_started_ && !restart_) {
      move_latency_ms_.push_back(ms_since(*move_started_));
      move_started_.reset();
    }
  }
  ++frames_;
  ++fps_frames_;
  double elapsed = ms_since(fps_start_);
  if (elapsed > 500.0) {
    fps_ = 1000.0 * double(fps_frames_) / elapsed;
    fps_frames_ = 0;
    fps_start_ = Clock::now();
  }
  update_title();

  if (spp_ >= target_spp() && !target_reached_) {
    target_reached_ = true;
    if (!options_.screenshot.empty()) write_screenshot();
    if (options_.exit_after_spp) quit_ = true;
  }
  // --orbit-test N: a scripted camera move after each frame that showed the
  // last one, N times, then quit.
  if (options_.orbit_test && passes && !move_started_ && !restart_) {
    if (orbits_done_ == options_.orbit_test) {
      quit_ = true;
    } else {
      ++orbits_done_;
      orbit(scene_.camera, glm::radians(1.0f), 0.0f);
      camera_moved();
    }
  }
}

void Viewer::update_title() {
  double paths_per_s = pass_ms_ > 0 ? double(settings_.width) * settings_.height / (pass_ms_ / 1000.0) : 0.0;
  char title[256];
  std::snprintf(title, sizeof title,
                "octrace  |  %u spp%s  |  %.1f ms/pass  |  %.3g paths/s  |  %s  |  %s  |  effects %s  |  depth %u  |  %dx%d  |  %.0f fps",
                spp_, target_reached_ ? " (done)" : "", pass_ms_, paths_per_s, precision_name(settings_.precision),
                accel_name(settings_.accel), settings_.all_effects ? "all" : "auto", settings_.bounce_limit,
                settings_.width, settings_.height, fps_);
  // Only on change: setting it sends the window an event, which would wake
  // an idle loop at once.
  if (title_ != title) {
    title_ = title;
    glfwSetWindowTitle(window_.get(), title);
  }
}

// `S`: the accumulation as it stands, PNG and PFM, each written atomically.
// A failed save is reported and the window stays open.
void Viewer::save() {
  save_requested_ = false;
  std::string base = save_base(options_.scene_file, spp_);
  try {
    RenderResult result = tracer_->read_result();
    write_image(result.mean, base + ".png");
    write_image(result.mean, base + ".pfm");
    std::printf("octrace view: saved %s.png and %s.pfm (%u spp)\n", base.c_str(), base.c_str(), spp_);
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "octrace view: cannot save: %s\n", e.what());
  }
  std::fflush(stdout);
}

void Viewer::write_screenshot() {
  write_image(read_preview_pixels(preview_), options_.screenshot);
  std::printf("octrace view: wrote %s (%u spp)\n", options_.screenshot.c_str(), spp_);
  std::fflush(stdout);
}

void Viewer::on_key(int key, int action) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  uint32_t& depth = settings_.bounce_limit;
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: quit_ = true; break;
    case GLFW_KEY_H:
      std::printf("%s", kViewKeys);
      std::fflush(stdout);
      break;
    case GLFW_KEY_P:
      settings_.precision = Precision((int(settings_.precision) + 1) % 3);
      reconfigure_ = true;
      break;
    case GLFW_KEY_B:
      settings_.accel = settings_.accel == Accel::Octree ? Accel::Bvh
                        : settings_.accel == Accel::Bvh  ? Accel::Brute
                                                         : Accel::Octree;
      reconfigure_ = true;
      break;
    case GLFW_KEY_E:
      settings_.all_effects = !settings_.all_effects;
      reconfigure_ = true;
      break;
    case GLFW_KEY_UP: depth = std::min(depth + 1, kMaxDepth); restart_ = true; break;
    case GLFW_KEY_DOWN: depth = std::max(depth - 1, 1u); restart_ = true; break;
    case GLFW_KEY_PAGE_UP: depth = std::min(depth * 2, kMaxDepth); restart_ = true; break;
    case GLFW_KEY_PAGE_DOWN: depth = std::max(depth / 2, 1u); restart_ = true; break;
    case GLFW_KEY_R: restart_ = true; break;
    case GLFW_KEY_C: scene_.camera = original_camera_; camera_moved(); break;
    case GLFW_KEY_S: save_requested_ = true; break;
    default: break;
  }
}

void Viewer::on_button(int button, int action) {
  if (action == GLFW_RELEASE) {
    if (button == drag_button_) drag_button_ = -1;
    return;
  }
  if (button == GLFW_MOUSE_BUTTON_LEFT || button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE) {
    drag_button_ = button;
    glfwGetCursorPos(window_.get(), &drag_x_, &drag_y_);
  }
}

// Left drag orbits (a full window width turns half way round), right or
// middle drag pans.
void Viewer::on_cursor(double x, double y) {
  if (drag_button_ < 0) return;
  float dx = float(x - drag_x_), dy = float(y - drag_y_);
  drag_x_ = x;
  drag_y_ = y;
  if (dx == 0 && dy == 0) return;
  int window_w = 1, window_h = 1;
  glfwGetWindowSize(window_.get(), &window_w, &window_h);
  if (drag_button_ == GLFW_MOUSE_BUTTON_LEFT) {
    float per_pixel = glm::pi<float>() / float(std::max(window_w, 1));
    orbit(scene_.camera, -dx * per_pixel, -dy * per_pixel);
  } else {
    pan(scene_.camera, dx, dy, std::max(window_h, 1));
  }
  camera_moved();
}

}  // namespace

int run_view(const Scene& scene, const RenderSettings& settings, const ViewOptions& options) {
  if (options.max_spp > kSampleLimit)
    throw InputError("--max-spp: must be <= 16777216 (sample counts are exact fp32 integers)");
  if (options.exit_after_spp && !options.max_spp) throw InputError("--exit-after-spp: needs --max-spp N");
  if (options.orbit_test && options.max_spp)
    throw InputError("--orbit-test: cannot be combined with --max-spp (each move restarts the accumulation)");
  if (!options.screenshot.empty()) {
    if (!options.max_spp) throw InputError("--screenshot: needs --max-spp N (it is taken when N is reached)");
    check_image_path(options.screenshot);
  }
  Viewer viewer(scene, settings, options);
  viewer.open();
  if (options.on_open) options.on_open();
  viewer.run();
  return 0;
}

}  // namespace octrace
