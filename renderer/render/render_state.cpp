#include "render/render_state.h"

#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "io/file.h"
#include "scene/json_text.h"

namespace octrace {

namespace {

std::string mean_path(const std::string& prefix) { return prefix + ".mean.pfm"; }
std::string count_path(const std::string& prefix) { return prefix + ".count.pfm"; }
std::string accum_path(const std::string& prefix) { return prefix + ".accum"; }

// PREFIX.accum: this line, one line of JSON (the CheckpointInfo), then the
// sum, comp and sq arrays (width * height vec4 each, little-endian float32).
constexpr char kAccumMagic[] = "octrace accumulation 1\n";

// A state's width and height, at most (the header is checked against it).
constexpr uint64_t kMaxStateSide = uint64_t(1) << 20;

std::string hex(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// PREFIX.mean.pfm and PREFIX.count.pfm, encoded, and with `accum` (a
// checkpoint's PREFIX.accum) written as one set (write_files_atomically): a
// failure leaves none of the state's files new.
void write_state_files(const RenderState& state, const std::string& prefix, const std::string* accum) {
  Image count{state.mean.width, state.mean.height, std::vector<float>(state.mean.rgb.size())};
  for (size_t i = 0; i < state.count.size(); ++i)
    for (int c = 0; c < 3; ++c) count.rgb[3 * i + c] = state.count[i];
  const std::vector<unsigned char> mean_bytes = encode_image(state.mean, mean_path(prefix)),
                                   count_bytes = encode_image(count, count_path(prefix));
  std::vector<FileToWrite> files = {{mean_path(prefix), mean_bytes.data(), mean_bytes.size(), "cannot write image"},
                                    {count_path(prefix), count_bytes.data(), count_bytes.size(), "cannot write image"}};
  if (accum) files.push_back({accum_path(prefix), accum->data(), accum->size(), "cannot write checkpoint"});
  write_files_atomically(files);
}

}  // namespace

void write_state(const RenderState& state, const std::string& prefix) { write_state_files(state, prefix, nullptr); }

RenderState read_state(const std::string& prefix) {
  RenderState state;
  state.mean = read_image(mean_path(prefix));
  Image count = read_image(count_path(prefix));
  if (count.width != state.mean.width || count.height != state.mean.height)
    throw InputError(count_path(prefix) + ": " + std::to_string(count.width) + "x" + std::to_string(count.height) +
                     ", but the mean is " + std::to_string(state.mean.width) + "x" +
                     std::to_string(state.mean.height));
  state.count.resize(size_t(count.width) * count.height);
  for (size_t i = 0; i < state.count.size(); ++i) {
    float n = count.rgb[3 * i];
    if (!std::isfinite(n) || n < 0.0f)
      throw InputError(count_path(prefix) + ": pixel " + std::to_string(i) + ": count must be a finite number >= 0");
    state.count[i] = n;
  }
  return state;
}

RenderState merge_states(const std::vector<RenderState>& states) {
  if (states.empty()) throw InputError("merge: no states given");
  const Image& first = states.front().mean;
  for (const RenderState& s : states)
    if (s.mean.width != first.width || s.mean.height != first.height)
      throw InputError("merge: state sizes differ: " + std::to_string(first.width) + "x" +
                       std::to_string(first.height) + " vs " + std::to_string(s.mean.width) + "x" +
                       std::to_string(s.mean.height));
  RenderState merged{first, std::vector<float>(states.front().count.size(), 0.0f)};
  for (size_t i = 0; i < merged.count.size(); ++i) {
    double n = 0, sum[3] = {0, 0, 0};
    for (const RenderState& s : states) {
      n += s.count[i];
      for (int c = 0; c < 3; ++c) sum[c] += double(s.count[i]) * double(s.mean.rgb[3 * i + c]);
    }
    merged.count[i] = float(n);
    for (int c = 0; c < 3; ++c) merged.mean.rgb[3 * i + c] = n > 0 ? float(sum[c] / n) : 0.0f;
  }
  return merged;
}

RenderState state_of(const Accumulation& acc) {
  RenderState st{Image{acc.width, acc.height, std::vector<float>(acc.sum.size() * 3)}, std::vector<float>(acc.sum.size())};
  for (size_t i = 0; i < acc.sum.size(); ++i) {
    const double n = acc.sum[i].w;
    st.count[i] = float(n);
    for (int c = 0; c < 3; ++c) st.mean.rgb[3 * i + c] = pixel_mean(acc.sum[i][c], acc.comp[i][c], n);
  }
  return st;
}

std::string checkpoint_mismatch(const CheckpointInfo& saved, const CheckpointInfo& now) {
  const auto differ = [](const std::string& what, const std::string& a, const std::string& b) {
    return what + " " + a + ", this render " + b;
  };
  if (saved.scene_hash != now.scene_hash)
    return differ("another scene: hash", hex(saved.scene_hash), hex(now.scene_hash));
  if (saved.width != now.width || saved.height != now.height)
    return differ("size", std::to_string(saved.width) + "x" + std::to_string(saved.height),
                  std::to_string(now.width) + "x" + std::to_string(now.height));
  if (saved.sample_seed != now.sample_seed)
    return differ("sample seed", std::to_string(saved.sample_seed), std::to_string(now.sample_seed));
  if (saved.first_sample != now.first_sample)
    return differ("first sample", std::to_string(saved.first_sample), std::to_string(now.first_sample));
  if (saved.bounce_limit != now.bounce_limit)
    return differ("bounce limit", std::to_string(saved.bounce_limit), std::to_string(now.bounce_limit));
  if (saved.rr_depth != now.rr_depth)
    return differ("roulette depth", std::to_string(saved.rr_depth), std::to_string(now.rr_depth));
  if (saved.precision != now.precision) return differ("precision", saved.precision, now.precision);
  if (saved.accel != now.accel) return differ("accel", saved.accel, now.accel);
  return {};
}

nlohmann::json checkpoint_info_json(const CheckpointInfo& info) {
  return {{"scene_hash", hex(info.scene_hash)}, {"width", info.width},
          {"height", info.height},              {"sample_seed", info.sample_seed},
          {"first_sample", info.first_sample},  {"bounce_limit", info.bounce_limit},
          {"rr_depth", info.rr_depth},          {"precision", info.precision},
          {"accel", info.accel},                {"samples", info.samples}};
}

CheckpointInfo checkpoint_info_of(const nlohmann::json& j) {
  if (!j.is_object()) throw InputError("expected a JSON object, got " + describe_json(j));
  const auto field = [&](const char* name) -> const nlohmann::json& {
    const auto it = j.find(name);
    if (it == j.end()) throw InputError(std::string(name) + ": missing");
    return *it;
  };
  const auto whole = [&](const char* name, uint64_t lo, uint64_t hi) {
    const nlohmann::json& v = field(name);
    if (!v.is_number_unsigned() || v.get<uint64_t>() < lo || v.get<uint64_t>() > hi)
      throw InputError(std::string(name) + ": expected a whole number in " + std::to_string(lo) + ".." +
                       std::to_string(hi) + ", got " + describe_json(v));
    return v.get<uint64_t>();
  };
  const auto text = [&](const char* name) {
    const nlohmann::json& v = field(name);
    if (!v.is_string() || v.get_ref<const std::string&>().empty())
      throw InputError(std::string(name) + ": expected a name, got " + describe_json(v));
    return v.get<std::string>();
  };
  CheckpointInfo info;
  const nlohmann::json& hash = field("scene_hash");
  const std::string* digits = hash.is_string() ? &hash.get_ref<const std::string&>() : nullptr;
  if (!digits || digits->empty() || digits->size() > 16 ||
      digits->find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
    throw InputError("scene_hash: expected 1 to 16 hexadecimal digits, got " + describe_json(hash));
  info.scene_hash = std::stoull(*digits, nullptr, 16);
  info.width = int(whole("width", 1, kMaxStateSide));
  info.height = int(whole("height", 1, kMaxStateSide));
  info.sample_seed = uint32_t(whole("sample_seed", 0, UINT32_MAX));
  info.first_sample = uint32_t(whole("first_sample", 0, UINT32_MAX));
  info.bounce_limit = uint32_t(whole("bounce_limit", 0, UINT32_MAX));
  info.rr_depth = uint32_t(whole("rr_depth", 0, UINT32_MAX));
  info.precision = text("precision");
  info.accel = text("accel");
  info.samples = uint32_t(whole("samples", 0, UINT32_MAX));
  return info;
}

void write_checkpoint(const std::string& prefix, const Accumulation& acc, const CheckpointInfo& info,
                      const RenderState& state) {
  std::string bytes = kAccumMagic + checkpoint_info_json(info).dump() + "\n";
  const size_t header = bytes.size(), plane = acc.sum.size() * sizeof(glm::vec4);
  bytes.resize(header + 3 * plane);
  std::memcpy(bytes.data() + header, acc.sum.data(), plane);
  std::memcpy(bytes.data() + header + plane, acc.comp.data(), plane);
  std::memcpy(bytes.data() + header + 2 * plane, acc.sq.data(), plane);
  write_state_files(state, prefix, &bytes);
}

std::vector<std::string> state_paths(const std::string& prefix, bool checkpoint) {
  std::vector<std::string> paths = {mean_path(prefix), count_path(prefix)};
  if (checkpoint) paths.push_back(accum_path(prefix));
  return paths;
}

Accumulation read_checkpoint(const std::string& prefix, CheckpointInfo& info) {
  const std::string path = accum_path(prefix);
  const std::string bytes = read_file(path);
  const size_t magic = sizeof kAccumMagic - 1;
  if (bytes.compare(0, magic, kAccumMagic) != 0) throw InputError(path + ": not an octrace checkpoint");
  const size_t eol = bytes.find('\n', magic);
  if (eol == std::string::npos) throw InputError(path + ": truncated header");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(bytes.substr(magic, eol - magic), json_depth_limit<nlohmann::json>(""));
    info = checkpoint_info_of(j);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path + ": bad header: " + invalid_json_message(e.what()));
  } catch (const InputError& e) {
    throw InputError(path + ": bad header: " + e.what());
  }
  Accumulation acc;
  acc.width = info.width;
  acc.height = info.height;
  const size_t pixels = size_t(info.width) * size_t(info.height), plane = pixels * sizeof(glm::vec4);
  if (bytes.size() - (eol + 1) != 3 * plane)
    throw InputError(path + ": " + std::to_string(bytes.size() - (eol + 1)) + " bytes of data, expected " +
                     std::to_string(3 * plane) + " for " + std::to_string(info.width) + "x" +
                     std::to_string(info.height));
  acc.sum.resize(pixels);
  acc.comp.resize(pixels);
  acc.sq.resize(pixels);
  const char* data = bytes.data() + eol + 1;
  std::memcpy(acc.sum.data(), data, plane);
  std::memcpy(acc.comp.data(), data + plane, plane);
  std::memcpy(acc.sq.data(), data + 2 * plane, plane);
  for (size_t i = 0; i < pixels; ++i)
    if (acc.sum[i].w != float(info.samples) && !(acc.sum[i].w < float(info.samples)))
      throw InputError(path + ": pixel " + std::to_string(i) + " holds more samples than the header's " +
                       std::to_string(info.samples));
  return acc;
}

}  // namespace octrace
