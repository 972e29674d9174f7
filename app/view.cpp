// `octrace view`: a GLFW window that shows the image converge. Each frame
// runs some passes into the accumulation buffers, then a resolve pass writes
// the mean as 8-bit sRGB into a buffer that is copied into the swapchain
// image: the image never leaves the device (the study's preview went through
// the CPU and an OpenGL texture every pass).
#include "view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "io/image.h"
#include "resolve.h"
#include "shared/shared.h"
#include "vk/resources.h"
#include "vk/swapchain.h"

namespace octrace {

namespace {

using Clock = std::chrono::steady_clock;

// Device time of the passes in one frame: about 30 frames per second where a
// pass is short enough, one pass per frame where it is not.
constexpr double kPassBudgetMs = 25.0;
constexpr uint32_t kMaxPassesPerFrame = 256;
constexpr uint32_t kMaxDepth = 1u << 16;
constexpr uint32_t kSampleLimit = 1u << 24;

std::string g_glfw_error = "unknown error";
void on_glfw_error(int, const char* text) { g_glfw_error = text; }

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Rotates v about the unit axis k by angle a (Rodrigues' formula).
glm::vec3 rotate(glm::vec3 v, glm::vec3 k, float a) {
  return v * std::cos(a) + glm::cross(k, v) * std::sin(a) + k * glm::dot(k, v) * (1.0f - std::cos(a));
}

// Orbit about lookat: yaw about vup, pitch about the camera's right axis,
// stopping short of the poles where the view direction would align with vup.
void orbit(Camera& c, float yaw, float pitch) {
  glm::vec3 up = glm::normalize(c.vup);
  glm::vec3 offset = rotate(c.lookfrom - c.lookat, up, yaw);
  glm::vec3 right = glm::normalize(glm::cross(up, offset));
  float angle = std::acos(std::clamp(glm::dot(glm::normalize(offset), up), -1.0f, 1.0f));
  const float margin = 0.01f;
  pitch = std::clamp(pitch, margin - angle, glm::pi<float>() - margin - angle);
  c.lookfrom = c.lookat + rotate(offset, right, pitch);
}

// Moves lookfrom and lookat together in the view plane; `dx`, `dy` are in
// pixels of an image `height` tall, scaled so the look-at point follows the cursor.
void pan(Camera& c, float dx, float dy, int height) {
  glm::vec3 w = c.lookfrom - c.lookat;
  float per_pixel = 2.0f * std::tan(glm::radians(c.vfov) / 2.0f) * glm::length(w) / float(height);
  glm::vec3 u = glm::normalize(glm::cross(c.vup, w));
  glm::vec3 v = glm::normalize(glm::cross(w, u));
  glm::vec3 delta = (-dx * u + dy * v) * per_pixel;
  c.lookfrom += delta;
  c.lookat += delta;
}

// Scales the distance to lookat, and the focus distance with it so that what
// was in focus stays in focus.
void zoom(Camera& c, float steps) {
  float f = std::pow(0.9f, steps);
  c.lookfrom = c.lookat + (c.lookfrom - c.lookat) * f;
  c.focus_dist *= f;
}

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

// The surface must go before the instance (the context) and after the swapchain.
struct Surface {
  VkInstance instance = VK_NULL_HANDLE;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  ~Surface() {
    if (surface) vkDestroySurfaceKHR(instance, surface, nullptr);
  }
};

class Viewer {
 public:
  Viewer(const Scene& scene, const RenderSettings& settings, const ViewOptions& options)
      : scene_(scene), original_camera_(scene.camera), settings_(settings), options_(options) {}
  ~Viewer();

  void open();
  void run();

 private:
  void recreate_swapchain(int width, int height);
  void rebuild_tracer();
  void frame();
  void wait_for_frame();
  void update_title();
  void save();
  void write_screenshot();

  // Where accumulation stops: --max-spp, else where the sample count stops
  // being an exact float (as --spp of render).
  uint32_t target_spp() const { return options_.max_spp ? options_.max_spp : kSampleLimit; }

  void on_key(int key, int action);
  void on_button(int button, int action);
  void on_cursor(double x, double y);

  // Member order is destruction order reversed: everything on the device
  // goes before the context, the surface before the instance and the window.
  GlfwSession glfw_;
  std::unique_ptr<GLFWwindow, WindowDeleter> window_;
  VulkanContext ctx_;
  Surface surface_;
  Swapchain swapchain_;
  std::unique_ptr<ComputePipeline> resolve_;
  bool resolve_bgra_ = false;
  Buffer pixels_;  // width * height packed 8-bit pixels in the swapchain's byte order
  std::unique_ptr<PathTracer> tracer_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;

  Scene scene_;
  Camera original_camera_;
  RenderSettings settings_;
  std::optional<RenderSettings> good_settings_;  // of the last tracer that could be built
  ViewOptions options_;

  uint32_t spp_ = 0;          // passes accumulated since the last restart
  double pass_ms_ = 0;        // device time per pass, last frame; 0 before the first
  bool tracer_dirty_ = true;  // camera, size, accel or depth changed
  bool swapchain_dirty_ = true;
  bool restart_ = false;
  bool save_requested_ = false;
  bool target_reached_ = false;
  bool quit_ = false;
  int drag_button_ = -1;
  double drag_x_ = 0, drag_y_ = 0;

  // For the title and the summary line.
  uint64_t frames_ = 0, total_passes_ = 0;
  double total_pass_ms_ = 0;
  Clock::time_point fps_start_ = Clock::now();
  uint64_t fps_frames_ = 0;
  double fps_ = 0;
  std::string title_;
};

Viewer::~Viewer() {
  if (!ctx_.device) return;
  // Errors are ignored here: after a lost device the handles are destroyed all the same.
  vkDeviceWaitIdle(ctx_.device);
  if (fence_) vkDestroyFence(ctx_.device, fence_, nullptr);
  if (acquired_) vkDestroySemaphore(ctx_.device, acquired_, nullptr);
  if (queries_) vkDestroyQueryPool(ctx_.device, queries_, nullptr);
  if (cmd_) vkFreeCommandBuffers(ctx_.device, ctx_.command_pool, 1, &cmd_);
}

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
  if (ctx_.info.software)
    std::fprintf(stderr, "octrace: rendering on %s, a CPU (software) Vulkan device: its timings are not a GPU's\n",
                 ctx_.info.name.c_str());

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_.reset(glfwCreateWindow(settings_.width, settings_.height, "octrace", nullptr, nullptr));
  if (!window_) throw RuntimeError("cannot open a window: " + g_glfw_error);
  surface_.instance = ctx_.instance;
  VK_CHECK(glfwCreateWindowSurface(ctx_.instance, window_.get(), nullptr, &surface_.surface));

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
    v->tracer_dirty_ = true;
  });
  glfwSetFramebufferSizeCallback(window_.get(), [](GLFWwindow* w, int, int) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->swapchain_dirty_ = true;
  });

  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = ctx_.command_pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx_.device, &alloc, &cmd_));
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(ctx_.device, &fence_info, nullptr, &fence_));
  VkSemaphoreCreateInfo sem_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VK_CHECK(vkCreateSemaphore(ctx_.device, &sem_info, nullptr, &acquired_));
  VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  query_info.queryCount = 2;
  VK_CHECK(vkCreateQueryPool(ctx_.device, &query_info, nullptr, &queries_));
}

void Viewer::run() {
  std::printf("octrace view: H lists the keys\n");
  std::fflush(stdout);
  while (!quit_ && !glfwWindowShouldClose(window_.get())) {
    const bool idle = spp_ >= target_spp() && !tracer_dirty_ && !restart_;
    // Nothing to add: re-present now and then (an uncovered window needs
    // its pixels again) rather than spin.
    if (idle) glfwWaitEventsTimeout(0.1);
    else glfwPollEvents();
    if (quit_ || glfwWindowShouldClose(window_.get())) break;

    int width = 0, height = 0;
    glfwGetFramebufferSize(window_.get(), &width, &height);
    // Minimised (a zero-size framebuffer on some systems, iconified on
    // others): nothing to show, and nothing to acquire, until restored.
    if (width == 0 || height == 0 || glfwGetWindowAttrib(window_.get(), GLFW_ICONIFIED)) {
      glfwWaitEvents();
      continue;
    }
    if (swapchain_dirty_ || uint32_t(width) != swapchain_.extent.width ||
        uint32_t(height) != swapchain_.extent.height) {
      recreate_swapchain(width, height);
      continue;
    }
    if (tracer_dirty_) rebuild_tracer();
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
}

void Viewer::recreate_swapchain(int width, int height) {
  VK_CHECK(vkDeviceWaitIdle(ctx_.device));
  swapchain_dirty_ = false;
  if (!create_swapchain(swapchain_, ctx_, surface_.surface, {uint32_t(width), uint32_t(height)})) return;
  // The resolve writes bytes in the swapchain's order (a specialization constant).
  if (!resolve_ || resolve_bgra_ != swapchain_.bgra) {
    resolve_ = std::make_unique<ComputePipeline>();
    resolve_bgra_ = swapchain_.bgra;
    create_compute_pipeline(*resolve_, ctx_, resolve_spv, sizeof(resolve_spv), 3, 2 * sizeof(uint32_t),
                            {{0, resolve_bgra_ ? 1u : 0u}});
    tracer_dirty_ = true;
  }
  if (int(swapchain_.extent.width) != settings_.width || int(swapchain_.extent.height) != settings_.height) {
    settings_.width = int(swapchain_.extent.width);
    settings_.height = int(swapchain_.extent.height);
    tracer_dirty_ = true;
  }
}

// Camera, size, accel and depth are all set-up-time inputs of the tracer, so
// any change builds a new one (scene upload, octree and pipeline: about 10 ms
// for the default scene on lavapipe) and the accumulation restarts.
void Viewer::rebuild_tracer() {
  VK_CHECK(vkDeviceWaitIdle(ctx_.device));
  tracer_.reset();
  try {
    tracer_ = std::make_unique<PathTracer>(ctx_, scene_, settings_);
  } catch (const InputError& e) {
    // A key asked for what this scene or device does not allow (fp16 with
    // radiance beyond half's range, say): say so, keep the settings that worked.
    if (!good_settings_) throw;
    std::fprintf(stderr, "octrace view: %s\n", e.what());
    RenderSettings good = *good_settings_;
    good.width = settings_.width;
    good.height = settings_.height;
    settings_ = good;
    tracer_ = std::make_unique<PathTracer>(ctx_, scene_, settings_);
  }
  good_settings_ = settings_;
  create_buffer(pixels_, ctx_, uint64_t(settings_.width) * uint64_t(settings_.height) * 4, false, "window pixel buffer");
  bind_buffers(*resolve_, {&tracer_->accum_sum(), &tracer_->accum_comp(), &pixels_});
  tracer_dirty_ = false;
  restart_ = false;
  spp_ = 0;
  pass_ms_ = 0;
  target_reached_ = false;
}

void Viewer::frame() {
  uint32_t index = 0;
  if (!acquire_image(swapchain_, acquired_, &index)) {
    swapchain_dirty_ = true;
    return;
  }
  uint32_t passes = 0;
  if (spp_ < target_spp()) {
    passes = pass_ms_ > 0 ? uint32_t(std::clamp(kPassBudgetMs / pass_ms_, 1.0, double(kMaxPassesPerFrame))) : 1;
    passes = std::min(passes, target_spp() - spp_);
  }
  const uint32_t size[2] = {uint32_t(settings_.width), uint32_t(settings_.height)};
  VkImage image = swapchain_.images[index];

  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
  vkCmdResetQueryPool(cmd_, queries_, 0, 2);
  // Earlier submissions (a restart's clear, the last frame) touched the accumulation.
  compute_barrier(cmd_);
  if (passes) {
    vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    tracer_->record_passes(cmd_, spp_, passes);
    vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
    compute_barrier(cmd_);
  }
  vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, resolve_->pipeline);
  vkCmdBindDescriptorSets(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, resolve_->layout, 0, 1, &resolve_->set, 0, nullptr);
  vkCmdPushConstants(cmd_, resolve_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(size), size);
  vkCmdDispatch(cmd_, (size[0] + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE,
                (size[1] + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE, 1);
  compute_barrier(cmd_);  // the resolve's writes before the copy reads them

  // The image's old contents are not needed. Its transition waits at the
  // transfer stage, the stage the submission waits on the acquire semaphore.
  VkImageMemoryBarrier to_dst{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  to_dst.srcAccessMask = 0;
  to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_dst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_dst.srcQueueFamilyIndex = to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.image = image;
  to_dst.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &to_dst);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {size[0], size[1], 1};
  vkCmdCopyBufferToImage(cmd_, pixels_.buffer, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  VkImageMemoryBarrier to_present = to_dst;
  to_present.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_present.dstAccessMask = 0;
  to_present.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_present.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr,
                       0, nullptr, 1, &to_present);
  VK_CHECK(vkEndCommandBuffer(cmd_));

  VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &acquired_;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &swapchain_.written[index];
  VK_CHECK(vkQueueSubmit(ctx_.queue, 1, &submit, fence_));
  if (!present_image(swapchain_, index)) swapchain_dirty_ = true;
  wait_for_frame();

  if (passes) {
    uint64_t stamps[2] = {0, 0};
    VK_CHECK(vkGetQueryPoolResults(ctx_.device, queries_, 0, 2, sizeof(stamps), stamps, sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    double ms = double(stamps[1] - stamps[0]) * double(ctx_.limits.timestampPeriod) * 1e-6;
    pass_ms_ = ms / passes;
    total_pass_ms_ += ms;
    total_passes_ += passes;
    spp_ += passes;
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
}

// Waits for the frame's submission, handling window events meanwhile so that
// a long pass never makes the window unresponsive (moves apply next frame).
void Viewer::wait_for_frame() {
  const uint64_t poll_ns = 10'000'000;
  VkResult r;
  while ((r = vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, poll_ns)) == VK_TIMEOUT) glfwPollEvents();
  VK_CHECK(r);
  VK_CHECK(vkResetFences(ctx_.device, 1, &fence_));
}

void Viewer::update_title() {
  double paths_per_s = pass_ms_ > 0 ? double(settings_.width) * settings_.height / (pass_ms_ / 1000.0) : 0.0;
  char title[256];
  std::snprintf(title, sizeof title,
                "octrace  |  %u spp%s  |  %.1f ms/pass  |  %.3g paths/s  |  %s  |  %s  |  effects %s  |  depth %u  |  %dx%d  |  %.0f fps",
                spp_, target_reached_ ? " (done)" : "", pass_ms_, paths_per_s, precision_name(settings_.precision),
                settings_.accel == Accel::Octree ? "octree" : "brute", settings_.all_effects ? "all" : "auto",
                settings_.max_depth, settings_.width,
                settings_.height, fps_);
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

// The bytes the window shows, as written by the resolve pass, back to
// linear so that write_image encodes them to the same bytes again.
void Viewer::write_screenshot() {
  const size_t count = size_t(settings_.width) * size_t(settings_.height);
  std::vector<uint32_t> packed(count);
  download_buffer(ctx_, pixels_, packed.data(), count * 4);
  Image image;
  image.width = settings_.width;
  image.height = settings_.height;
  image.rgb.resize(count * 3);
  for (size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 3; ++c) {
      int shift = 8 * (swapchain_.bgra ? 2 - c : c);
      image.rgb[3 * i + c] = srgb_decode(float((packed[i] >> shift) & 0xff) / 255.0f);
    }
  }
  write_image(image, options_.screenshot);
  std::printf("octrace view: wrote %s (%u spp)\n", options_.screenshot.c_str(), spp_);
  std::fflush(stdout);
}

void Viewer::on_key(int key, int action) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: quit_ = true; break;
    case GLFW_KEY_H:
      std::printf("%s", kViewKeys);
      std::fflush(stdout);
      break;
    case GLFW_KEY_P:
      settings_.precision = Precision((int(settings_.precision) + 1) % 3);
      tracer_dirty_ = true;
      break;
    case GLFW_KEY_B:
      settings_.accel = settings_.accel == Accel::Octree ? Accel::Brute : Accel::Octree;
      tracer_dirty_ = true;
      break;
    case GLFW_KEY_E:
      settings_.all_effects = !settings_.all_effects;
      tracer_dirty_ = true;
      break;
    case GLFW_KEY_UP: settings_.max_depth = std::min(settings_.max_depth + 1, kMaxDepth); tracer_dirty_ = true; break;
    case GLFW_KEY_DOWN: settings_.max_depth = std::max(settings_.max_depth - 1, 1u); tracer_dirty_ = true; break;
    case GLFW_KEY_PAGE_UP: settings_.max_depth = std::min(settings_.max_depth * 2, kMaxDepth); tracer_dirty_ = true; break;
    case GLFW_KEY_PAGE_DOWN: settings_.max_depth = std::max(settings_.max_depth / 2, 1u); tracer_dirty_ = true; break;
    case GLFW_KEY_R: restart_ = true; break;
    case GLFW_KEY_C: scene_.camera = original_camera_; tracer_dirty_ = true; break;
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
  tracer_dirty_ = true;
}

}  // namespace

int run_view(const Scene& scene, const RenderSettings& settings, const ViewOptions& options) {
  if (options.max_spp > kSampleLimit)
    throw InputError("--max-spp: must be <= 16777216 (sample counts are exact fp32 integers)");
  if (options.exit_after_spp && !options.max_spp) throw InputError("--exit-after-spp: needs --max-spp N");
  if (!options.screenshot.empty()) {
    if (!options.max_spp) throw InputError("--screenshot: needs --max-spp N (it is taken when N is reached)");
    check_image_path(options.screenshot);
  }
  Viewer viewer(scene, settings, options);
  viewer.open();
  viewer.run();
  return 0;
}

}  // namespace octrace
