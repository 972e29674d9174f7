#include "io/image.h"

#include <stb_image.h>
#include <tinyexr.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "core/parallel.h"
#include "io/deflate.h"

// PNG files are written by stb_image_write compiled here, with zlib's deflate
// at its fastest level in place of stb's own (STBIW_ZLIB_COMPRESS, the
// library's documented hook): writing a 1200x800 PNG went from 168 to 70 ms
// on the development machine, and the files are 10% smaller
// (docs/performance.md, "Writing the image"; log 92). The same pixels
// either way; only the compressed bytes differ. Static, so Debian's libstb
// (linked for stb_image) keeps its own copy of the writer unused.
// The deflate runs in pieces on the host's threads (io/deflate.h, log 98).
namespace {
constexpr size_t kDeflatePiece = 512 * 1024;  // the least data a piece gets

unsigned char* png_deflate(unsigned char* data, int data_len, int* out_len, int /*stb's level*/) {
  const size_t n = size_t(std::max(data_len, 0));
  const std::vector<unsigned char> z = octrace::zlib_deflate(data, n, octrace::parallel_range_count(n, kDeflatePiece));
  auto* out = z.empty() ? nullptr : static_cast<unsigned char*>(std::malloc(z.size()));
  if (!out) return nullptr;  // stb's encoder then fails, and encode_png says so
  std::copy(z.begin(), z.end(), out);
  *out_len = int(z.size());
  return out;
}
}  // namespace
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBIW_ZLIB_COMPRESS png_deflate
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>

#include "io/file.h"
#include "core/errors.h"

namespace octrace {

namespace {

enum class ImageFormat { png, pfm, exr, hdr };

// .hdr (Radiance) is read, never written.
ImageFormat image_format(const std::string& path, bool reading = false) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::string lower = ext;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (lower == ".png") return ImageFormat::png;
  if (lower == ".pfm") return ImageFormat::pfm;
  if (lower == ".exr") return ImageFormat::exr;
  if (lower == ".hdr" && reading) return ImageFormat::hdr;
  const char* expected = reading ? ".png, .pfm, .exr or .hdr" : ".png, .pfm or .exr";
  throw InputError(path + ": unknown image format \"" + ext + "\" (expected " + expected + ")");
}

// --- Encoding to bytes. Each format is encoded in memory first so that one
// function does the atomic file write for all of them.

using Bytes = std::vector<unsigned char>;

[[noreturn]] void write_failed(const std::string& path, const std::string& reason) {
  throw RuntimeError(path + ": cannot write image: " + reason);
}

// The sRGB value a display shows for a linear value: clamped to [0,1], with
// NaN shown as black.
float displayed(float linear) {
  return srgb_encode(!(linear > 0.0f) ? 0.0f : std::min(linear, 1.0f));
}

Bytes encode_png(const Image& image, const std::string& path) {
  std::vector<std::uint8_t> pixels(image.rgb.size());
  // On the host's threads (log 98): a powf per value.
  parallel_ranges(pixels.size(), parallel_range_count(pixels.size(), 64 * 1024), [&](size_t, size_t begin, size_t end) {
    std::transform(image.rgb.begin() + std::ptrdiff_t(begin), image.rgb.begin() + std::ptrdiff_t(end),
                   pixels.begin() + std::ptrdiff_t(begin),
                   [](float v) { return std::uint8_t(displayed(v) * 255.0f + 0.5f); });
  });
  Bytes bytes;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<Bytes*>(context);
    auto* begin = static_cast<unsigned char*>(data);
    out->insert(out->end(), begin, begin + size);
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 3,
                              pixels.data(), 3 * image.width))
    write_failed(path, "PNG encoder failed");
  return bytes;
}

// PFM stores floats in the byte order given by the sign of the scale; we always
// write little-endian (scale -1), independent of the host.
Bytes encode_pfm(const Image& image) {
  std::string header =
      "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  Bytes bytes(header.size() + 4 * image.rgb.size());
  std::copy(header.begin(), header.end(), bytes.begin());
  // PFM rows run bottom to top (Netpbm PFM specification); a row's values
  // are copied whole where the host's byte order is the file's (log 100).
  const size_t row = 3 * size_t(image.width);
  unsigned char* out = bytes.data() + header.size();
  for (int y = image.height - 1; y >= 0; --y, out += 4 * row) {
    const float* values = image.pixel(0, y);
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(out, values, 4 * row);
    } else {
      for (size_t i = 0; i < row; ++i) {
        const auto bits = std::bit_cast<std::uint32_t>(values[i]);
        for (int b = 0; b < 4; ++b) out[4 * i + b] = std::uint8_t(bits >> (8 * b));
      }
    }
  }
  return bytes;
}

std::string take_exr_error(const char* err) {
  std::string message = err ? err : "unknown tinyexr error";
  if (err) FreeEXRErrorMessage(err);
  // Some of tinyexr's messages end in a newline; an octrace error is one line.
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  return message;
}

Bytes encode_exr(const Image& image, const std::string& path) {
  // Planar channels in the order B, G, R: OpenEXR readers expect channel names
  // sorted alphabetically.
  size_t count = size_t(image.width) * image.height;
  std::array<std::vector<float>, 3> planes;
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(count);
    for (size_t i = 0; i < count; ++i) planes[c][i] = image.rgb[3 * i + (2 - c)];
  }
  std::array<float*, 3> plane_ptrs = {planes[0].data(), planes[1].data(), planes[2].data()};

  EXRImage exr_image;
  InitEXRImage(&exr_image);
  exr_image.num_channels = 3;
  exr_image.images = reinterpret_cast<unsigned char**>(plane_ptrs.data());
  exr_image.width = image.width;
  exr_image.height = image.height;

  std::array<EXRChannelInfo, 3> channels{};
  std::strcpy(channels[0].name, "B");
  std::strcpy(channels[1].name, "G");
  std::strcpy(channels[2].name, "R");
  std::array<int, 3> float_types = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT,
                                    TINYEXR_PIXELTYPE_FLOAT};
  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = 3;
  header.channels = channels.data();
  header.pixel_types = float_types.data();
  header.requested_pixel_types = float_types.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

  unsigned char* memory = nullptr;
  const char* err = nullptr;
  size_t size = SaveEXRImageToMemory(&exr_image, &header, &memory, &err);
  if (size == 0) write_failed(path, "EXR encoder failed: " + take_exr_error(err));
  Bytes bytes(memory, memory + size);
  std::free(memory);
  return bytes;
}

// --- Decoding from bytes. Every length is checked against the file size, so
// a truncated or corrupt file gives an error, not a crash.

Image decode_png(const std::string& path, const Bytes& bytes) {
  // 16-bit decoding reads 8- and 16-bit PNGs alike without losing precision
  // (stb widens 8-bit values v to v * 257, so v / 255 == v * 257 / 65535).
  // stb_image reads other formats too; a .png must be a PNG (a PGM header
  // claiming millions of pixels took seconds to decode: found by
  // tests/fuzz/fuzz_image.cpp). PNG specification, 5.2: the signature.
  constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin()))
    throw InputError(path + ": not a valid PNG file: no PNG signature");
  if (std::string why = png_chunk_error(bytes.data(), bytes.size()); !why.empty())
    throw InputError(path + ": not a valid PNG file: " + why);
  int width = 0, height = 0, channels = 0;
  std::uint16_t* data = stbi_load_16_from_memory(bytes.data(), int(bytes.size()), &width,
                                                 &height, &channels, 3);
  if (!data) throw InputError(path + ": not a valid PNG file: " + stb_failure_reason());
  Image image{width, height, std::vector<float>(size_t(width) * height * 3)};
  for (size_t i = 0; i < image.rgb.size(); ++i)
    image.rgb[i] = srgb_decode(float(data[i]) / 65535.0f);
  stbi_image_free(data);
  return image;
}

// Portable Float Map, as defined by Netpbm: "PF" (RGB) or "Pf" (grey), width,
// height and a scale separated by whitespace, then one whitespace character
// and the raw floats, rows bottom to top. A negative scale means little-endian
// data, a positive one big-endian; like pbrt-v4 we multiply the data by
// |scale| (writers, ours included, use 1).
Image decode_pfm(const std::string& path, const Bytes& bytes) {
  auto invalid = [&](const std::string& why) {
    return InputError(path + ": not a valid PFM file: " + why);
  };
  const char* begin = reinterpret_cast<const char*>(bytes.data());
  const char* end = begin + bytes.size();
  const char* p = begin;
  auto skip_space = [&] {
    while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
  };
  auto parse = [&](auto& value, const char* what) {
    skip_space();
    auto [next, ec] = std::from_chars(p, end, value);
    if (ec != std::errc() || next == end || !std::isspace(static_cast<unsigned char>(*next)))
      throw invalid("bad " + std::string(what) + " in header");
    p = next;
  };

  if (bytes.size() < 2 || begin[0] != 'P' || (begin[1] != 'F' && begin[1] != 'f'))
    throw invalid("does not start with \"PF\" or \"Pf\"");
  int channels = begin[1] == 'F' ? 3 : 1;
  p += 2;
  int width = 0, height = 0;
  double scale = 0;
  parse(width, "width");
  parse(height, "height");
  parse(scale, "scale");
  ++p;  // the single whitespace character that ends the header
  if (width <= 0 || height <= 0)
    throw invalid("bad size " + std::to_string(width) + "x" + std::to_string(height));
  if (scale == 0 || !std::isfinite(scale)) throw invalid("bad scale in header");

  std::uint64_t expected = std::uint64_t(width) * std::uint64_t(height) * channels * 4;
  std::uint64_t found = std::uint64_t(end - p);
  if (found < expected)
    throw invalid("truncated pixel data (expected " + std::to_string(expected) +
                  " bytes, found " + std::to_string(found) + ")");

  bool little_endian = scale < 0;
  float factor = float(std::abs(scale));
  auto read_float = [&](std::uint64_t index) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(p) + 4 * index;
    std::uint32_t bits = little_endian
                             ? std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                                   std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24
                             : std::uint32_t(b[3]) | std::uint32_t(b[2]) << 8 |
                                   std::uint32_t(b[1]) << 16 | std::uint32_t(b[0]) << 24;
    return std::bit_cast<float>(bits) * factor;
  };

  Image image{width, height, std::vector<float>(size_t(width) * height * 3)};
  for (int y = 0; y < height; ++y) {
    std::uint64_t row = std::uint64_t(height - 1 - y) * width;
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        image.pixel(x, y)[c] = read_float((row + x) * channels + (channels == 3 ? c : 0));
  }
  return image;
}

// The attributes of an EXR file's (first) header, read as tinyexr's
// ParseEXRHeader reads them (OpenEXR file layout: after the 8 bytes of magic
// number and version, each attribute is its name and its type, each ending
// in a zero byte, a little-endian 4-byte size and the value; an empty name
// ends the list; a string of size 0 is one zero byte), up to where tinyexr
// would stop reading: `visit(name, type, value)` for each, until it returns
// false.
template <typename Visit>
void for_each_exr_attribute(const Bytes& bytes, Visit&& visit) {
  constexpr size_t kVersionSize = 8;
  if (bytes.size() <= kVersionSize) return;
  std::string_view rest(reinterpret_cast<const char*>(bytes.data()) + kVersionSize, bytes.size() - kVersionSize);
  for (int n = 0; n < TINYEXR_MAX_HEADER_ATTRIBUTES && !rest.empty() && rest[0] != '\0'; ++n) {
    const size_t name_end = rest.find('\0');
    if (name_end == std::string_view::npos) return;
    const std::string_view name = rest.substr(0, name_end);
    const size_t type_end = rest.find('\0', name_end + 1);
    if (type_end == std::string_view::npos || rest.size() - (type_end + 1) < 4) return;
    const std::string_view type = rest.substr(name_end + 1, type_end - name_end - 1);
    std::uint32_t length = 0;
    std::memcpy(&length, rest.data() + type_end + 1, 4);
    rest.remove_prefix(type_end + 5);
    std::string_view value;
    if (length == 0) {
      if (type != "string") return;
      value = std::string_view("\0", 1);  // tinyexr's empty string
    } else {
      if (rest.size() < length) return;
      value = rest.substr(0, length);
      rest.remove_prefix(length);
    }
    if (!visit(name, type, value)) return;
  }
}

// Debian's tinyexr 1.0.1 keeps its asserts, and two malformed attributes end
// the process in one instead of an error (found by tests/fuzz/fuzz_image.cpp
// in a CI run): a "tiles" attribute of other than 9 bytes in a file whose
// version says tiled, multipart or non-image, and a "type" attribute other
// than scanlineimage, tiledimage, deepscanline or deeptile, or one that
// contradicts whether the header has tiles. tinyexr converts the header it
// has read so far even when reading it fails, so those two are checked
// first, on the attributes it would have read (for_each_exr_attribute);
// anything else malformed is left to tinyexr's own errors.
template <typename Invalid>
void check_exr_asserts(const Bytes& bytes, const EXRVersion& version, const Invalid& invalid) {
  const auto printable = [](std::string_view text) {
    std::string out;
    for (char c : text.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return out + (text.size() > 40 ? "..." : "");
  };
  bool tiled = false;
  std::string type;
  for_each_exr_attribute(bytes, [&](std::string_view name, std::string_view, std::string_view value) {
    if ((version.tiled || version.multipart || version.non_image) && name == "tiles") {
      if (value.size() != 9)
        throw invalid("its \"tiles\" attribute has " + std::to_string(value.size()) + " bytes, not 9");
      std::int32_t size_x = 0, size_y = 0;
      std::memcpy(&size_x, value.data(), 4);
      std::memcpy(&size_y, value.data() + 4, 4);
      if (size_x < 0 || size_y < 0) return false;  // tinyexr stops here with an error of its own
      tiled = true;
    } else if (name == "type" && value[0] != '\0') {
      type = std::string(value.substr(0, value.find('\0')));
    }
    return true;
  });
  if (type.empty()) return;
  const bool known = type == "scanlineimage" || type == "tiledimage" || type == "deepscanline" || type == "deeptile";
  if (!known)
    throw invalid("its \"type\" attribute is \"" + printable(type) +
                  "\", not scanlineimage, tiledimage, deepscanline or deeptile");
  const bool wants_tiles = type == "tiledimage" || type == "deeptile";
  if (wants_tiles != tiled)
    throw invalid("its \"type\" attribute is " + type + (tiled ? ", but the header has tiles" : ", but the header has no tiles"));
}

// tinyexr 1.0.1 sizes its offset table from the header before it checks the
// header against the file: a tiled header of a few bytes asked for 2^61
// entries (found by tests/fuzz/fuzz_image.cpp). So the data window, the tiles
// and the chunk count are checked first: every chunk (a block of scanlines
// or a tile) has an 8-byte entry in the file's offset table (OpenEXR file
// layout, "Offset Tables"), so there cannot be more chunks than size / 8.
template <typename Invalid>
void check_exr_tables(const EXRHeader& header, size_t size, const Invalid& invalid) {
  const EXRBox2i& window = header.data_window;
  const std::int64_t width = std::int64_t(window.max_x) - window.min_x + 1;
  const std::int64_t height = std::int64_t(window.max_y) - window.min_y + 1;
  constexpr std::int64_t kMaxSide = std::int64_t(1) << 24;
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide)
    throw invalid("bad data window " + std::to_string(width) + "x" + std::to_string(height));
  const std::int64_t max_chunks = std::int64_t(size / 8);
  std::int64_t chunks = (height + 31) / 32;  // at most 32 scanlines per chunk (PIZ, PXR24, B44)
  if (header.tiled) {
    if (header.tile_size_x < 1 || header.tile_size_y < 1)
      throw invalid("bad tile size " + std::to_string(header.tile_size_x) + "x" + std::to_string(header.tile_size_y));
    chunks = (width + header.tile_size_x - 1) / header.tile_size_x * ((height + header.tile_size_y - 1) / header.tile_size_y);
  }
  if (header.chunk_count > 0) chunks = std::max<std::int64_t>(chunks, header.chunk_count);
  if (chunks > max_chunks)
    throw invalid(std::to_string(chunks) + " chunks cannot fit in " + std::to_string(size) + " bytes");
  // Nor can the pixels take more bytes than the file's data decompresses to:
  // tinyexr 1.0.1 accepts a chunk that decompresses short, and a header of
  // 3.7 million pixels in 400 bytes took seconds (found the same way). The
  // ratios bound each method: raw 1, RLE 64 (2 bytes give at most 128),
  // zlib (ZIP, ZIPS, PXR24) about 1032, PIZ and B44 far less; 2048 for all but
  // the first two.
  std::int64_t pixel_bytes = 0;
  for (int c = 0; c < header.num_channels; ++c) pixel_bytes += header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF ? 2 : 4;
  const std::int64_t ratio = header.compression_type == TINYEXR_COMPRESSIONTYPE_NONE  ? 1
                             : header.compression_type == TINYEXR_COMPRESSIONTYPE_RLE ? 64
                                                                                      : 2048;
  if (pixel_bytes * width * height > std::int64_t(size) * ratio)
    throw invalid(std::to_string(width) + "x" + std::to_string(height) + " pixels cannot be stored in " +
                  std::to_string(size) + " bytes");
}

// The name of the compression an EXR header declares (OpenEXR file layout:
// attribute "compression", type "compression", one byte: 0 none ... 9 DWAB),
// or "" if it declares none that tinyexr would read. For the message when
// tinyexr refuses a method (Blender's HDRIs are DWAB).
std::string exr_compression_name(const Bytes& bytes) {
  static constexpr const char* kNames[] = {"none", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};
  std::string name;
  for_each_exr_attribute(bytes, [&](std::string_view attribute, std::string_view type, std::string_view value) {
    if (attribute != "compression" || type != "compression" || value.size() != 1) return true;
    const unsigned method = static_cast<unsigned char>(value[0]);
    name = method < std::size(kNames) ? kNames[method] : "number " + std::to_string(method);
    return false;
  });
  return name;
}

// Read in tinyexr's steps (version, header, image) rather than with its
// LoadEXRFromMemory, which does the same but does not free the header when a
// step fails (tinyexr 1.0.1: a leak found by tests/fuzz/fuzz_image.cpp): here
// both are freed whatever happens. Like LoadEXRFromMemory, a file of one
// channel is grey and one of more needs R, G and B (A is not read); half
// channels are read as float.
Image decode_exr(const std::string& path, const Bytes& bytes) {
  auto invalid = [&](const std::string& why) { return InputError(path + ": not a valid EXR file: " + why); };
  struct Exr {
    EXRHeader header;
    EXRImage image;
    Exr() {
      InitEXRHeader(&header);
      InitEXRImage(&image);
    }
    ~Exr() {
      FreeEXRImage(&image);
      FreeEXRHeader(&header);
    }
  } exr;
  EXRVersion version;
  if (int ret = ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()); ret != TINYEXR_SUCCESS)
    throw invalid("Failed to parse EXR version. code(" + std::to_string(ret) + ")");
  check_exr_asserts(bytes, version, invalid);
  const char* err = nullptr;
  if (ParseEXRHeaderFromMemory(&exr.header, &version, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS) {
    const std::string why = take_exr_error(err);
    if (const std::string method = exr_compression_name(bytes); !method.empty() && why.find("compression") != std::string::npos)
      throw invalid("compression " + method + " is not supported (tinyexr reads none, RLE, ZIPS, ZIP and PIZ): re-save it "
                    "with ZIP or PIZ, e.g. exrmaketiled -z zip IN.exr OUT.exr (Debian: openexr)");
    throw invalid(why);
  }
  check_exr_tables(exr.header, bytes.size(), invalid);
  for (int c = 0; c < exr.header.num_channels; ++c)
    if (exr.header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF)
      exr.header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
  // tinyexr 1.0.1's PIZ decoder reads a chunk's bitmap range and the length
  // word after it (at most 4 + 8192 + 4 bytes) before it checks them against
  // the chunk's size, so a chunk at the end of the file was read past the
  // file's bytes (found by tests/fuzz/fuzz_image.cpp:
  // regression_exr_piz_bitmap_past_end.exr). A PIZ file's bytes go to it
  // followed by that many zeros: those reads stay in octrace's buffer, and
  // the check after them rejects the chunk.
  constexpr size_t kPizReadsPast = 4 + 8192 + 4;
  Bytes padded;
  if (exr.header.compression_type == TINYEXR_COMPRESSIONTYPE_PIZ) {
    padded.assign(bytes.size() + kPizReadsPast, 0);
    std::copy(bytes.begin(), bytes.end(), padded.begin());
  }
  const unsigned char* data = padded.empty() ? bytes.data() : padded.data();
  if (LoadEXRImageFromMemory(&exr.image, &exr.header, data, bytes.size(), &err) != TINYEXR_SUCCESS) {
    // tinyexr has freed the image and left its pointers (a second free was
    // found by tests/fuzz/fuzz_image.cpp); it leaks the channel buffers
    // (tools/lsan.supp).
    InitEXRImage(&exr.image);
    throw invalid(take_exr_error(err));
  }

  // Which channel gives R, G and B.
  std::array<int, 3> source{0, 0, 0};
  if (exr.header.num_channels != 1) {
    for (int k = 0; k < 3; ++k) {
      const char* name = k == 0 ? "R" : k == 1 ? "G" : "B";
      source[k] = -1;
      for (int c = 0; c < exr.header.num_channels; ++c)
        if (std::strcmp(exr.header.channels[c].name, name) == 0) source[k] = c;
      if (source[k] < 0) throw invalid(std::string(name) + " channel not found");
    }
  }
  const int width = exr.image.width, height = exr.image.height;
  Image image{width, height, std::vector<float>(size_t(width) * height * 3)};
  // Copies a block of `w` x `h` pixels (a tile, or the whole image) to (x0, y0).
  auto copy = [&](unsigned char** planes, int x0, int y0, int w, int h) {
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const int x = x0 + i, y = y0 + j;
        if (x < 0 || y < 0 || x >= width || y >= height) continue;
        for (int k = 0; k < 3; ++k)
          image.pixel(x, y)[k] = reinterpret_cast<const float*>(planes[source[k]])[size_t(j) * w + i];
      }
  };
  if (exr.header.tiled) {
    const int tw = exr.header.tile_size_x, th = exr.header.tile_size_y;
    for (int t = 0; t < exr.image.num_tiles; ++t) {
      const EXRTile& tile = exr.image.tiles[t];
      copy(tile.images, tile.offset_x * tw, tile.offset_y * th, tw, th);
    }
  } else {
    copy(exr.image.images, 0, 0, width, height);
  }
  return image;
}

// Radiance RGBE (.hdr; Greg Ward, "Real Pixels", Graphics Gems II, 1991, and
// the Radiance file format notes): a text header ("#?RADIANCE" or "#?RGBE",
// lines up to an empty one, FORMAT=32-bit_rle_rgbe), the resolution line
// "-Y height +X width" (rows top to bottom), then scanlines of 4-byte RGBE
// pixels, flat or in the "new" run-length encoding (2, 2, width as two bytes,
// then each of the four components in runs). stb_image decodes it, but it
// reads zeros past the end of the data and trusts the header's size, so the
// structure is walked here first: every scanline must be complete.
std::string hdr_structure_error(const Bytes& bytes, int& width, int& height) {
  const auto* begin = reinterpret_cast<const char*>(bytes.data());
  const std::string_view text(begin, bytes.size());
  size_t pos = 0;
  auto line = [&](std::string_view& out) {
    const size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) return false;
    out = text.substr(pos, end - pos);
    pos = end + 1;
    return true;
  };
  std::string_view l;
  if (!line(l) || (l != "#?RADIANCE" && l != "#?RGBE")) return "does not start with \"#?RADIANCE\" or \"#?RGBE\"";
  bool rgbe = false;
  for (;;) {
    if (!line(l)) return "header does not end";
    if (l.empty()) break;
    rgbe |= l == "FORMAT=32-bit_rle_rgbe";
  }
  if (!rgbe) return "no FORMAT=32-bit_rle_rgbe in header";
  if (!line(l) || l.substr(0, 3) != "-Y ") return "resolution line is not \"-Y height +X width\"";
  const char* p = l.data() + 3;
  const char* end = l.data() + l.size();
  auto [after_h, ec_h] = std::from_chars(p, end, height);
  if (ec_h != std::errc() || std::string_view(after_h, end - after_h).substr(0, 4) != " +X ")
    return "resolution line is not \"-Y height +X width\"";
  auto [after_w, ec_w] = std::from_chars(after_h + 4, end, width);
  if (ec_w != std::errc() || after_w != end) return "resolution line is not \"-Y height +X width\"";
  constexpr int kMaxSide = 1 << 24;  // stb_image's STBI_MAX_DIMENSIONS
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide)
    return "bad size " + std::to_string(width) + "x" + std::to_string(height);
  const uint64_t flat = 4 * uint64_t(width) * uint64_t(height);
  // Flat pixels: stb_image reads scanlines of these widths flat.
  if (width < 8 || width >= 32768)
    return bytes.size() - pos >= flat ? "" : "truncated pixel data (expected " + std::to_string(flat) + " bytes)";
  const unsigned char* d = bytes.data();
  const size_t size = bytes.size();
  for (int y = 0; y < height; ++y) {
    const std::string at = " at scanline " + std::to_string(y);
    if (size - pos < 4) return "truncated" + at;
    if (d[pos] != 2 || d[pos + 1] != 2 || (d[pos + 2] & 0x80)) {
      if (y == 0 && size - pos >= flat) return "";  // a flat file
      return y == 0 ? "truncated pixel data (expected " + std::to_string(flat) + " bytes)"
                    : "flat scanline among run-length encoded ones" + at;
    }
    if ((d[pos + 2] << 8 | d[pos + 3]) != width) return "scanline length is not the width" + at;
    pos += 4;
    for (int c = 0; c < 4; ++c)
      for (int x = 0; x < width;) {
        if (pos >= size) return "truncated" + at;
        const int count = d[pos++];
        const int n = count > 128 ? count - 128 : count;
        if (n == 0 || n > width - x) return "bad run length" + at;
        const size_t data = count > 128 ? 1 : size_t(n);
        if (size - pos < data) return "truncated" + at;
        pos += data;
        x += n;
      }
  }
  return "";
}

Image decode_hdr(const std::string& path, const Bytes& bytes) {
  int width = 0, height = 0;
  if (std::string why = hdr_structure_error(bytes, width, height); !why.empty())
    throw InputError(path + ": not a valid Radiance HDR file: " + why);
  int w = 0, h = 0, channels = 0;
  float* data = stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 3);
  if (!data) throw InputError(path + ": not a valid Radiance HDR file: " + stb_failure_reason());
  Image image{w, h, std::vector<float>(data, data + size_t(w) * h * 3)};
  stbi_image_free(data);
  return image;
}

// Structural similarity of one window from its (weighted) moments: equation
// (13) of Wang et al. 2004 with C1 = (K1 L)^2, C2 = (K2 L)^2.
double ssim_from_moments(double mu_x, double mu_y, double xx, double yy, double xy) {
  constexpr double c1 = (0.01 * 1.0) * (0.01 * 1.0);
  constexpr double c2 = (0.03 * 1.0) * (0.03 * 1.0);
  double var_x = xx - mu_x * mu_x;
  double var_y = yy - mu_y * mu_y;
  double cov = xy - mu_x * mu_y;
  return (2 * mu_x * mu_y + c1) * (2 * cov + c2) /
         ((mu_x * mu_x + mu_y * mu_y + c1) * (var_x + var_y + c2));
}

// SSIM as defined by Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli,
// "Image quality assessment: from error visibility to structural similarity",
// IEEE Trans. Image Processing 13(4), 2004, and their reference code
// ssim_index.m:
// - It is computed on one channel, the luma Y = 0.2126 R' + 0.7152 G' + 0.0722 B'
//   (Rec. 709 weights) of the sRGB-encoded channels clamped to [0,1], i.e. of
//   what a viewer sees on screen rather than of linear radiance; L = 1.
// - Each window is an 11x11 circular-symmetric Gaussian with sigma 1.5,
//   normalised to sum 1; K1 = 0.01, K2 = 0.03. Variances and the covariance
//   are the weighted population moments (no N/(N-1) correction), as in the paper.
// - The result is the mean SSIM over every window position that lies fully
//   inside the image ("valid" filtering), with no downsampling.
// - For an image smaller than 11 pixels in either dimension, the whole image is
//   one window with uniform weights.
// The Gaussian is separable, so the five moment maps (x, y, x^2, y^2, xy) are
// filtered along rows and then along columns.
double ssim(const Image& test, const Image& reference) {
  auto luma = [](const Image& image) {
    std::vector<double> y(size_t(image.width) * image.height);
    for (size_t i = 0; i < y.size(); ++i) {
      const float* p = &image.rgb[3 * i];
      y[i] = 0.2126 * displayed(p[0]) + 0.7152 * displayed(p[1]) + 0.0722 * displayed(p[2]);
    }
    return y;
  };
  std::vector<double> a = luma(test), b = luma(reference);
  int w = test.width, h = test.height;

  constexpr int radius = 5, size = 2 * radius + 1;
  if (w < size || h < size) {
    double n = double(a.size()), mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      mx += a[i];
      my += b[i];
      xx += a[i] * a[i];
      yy += b[i] * b[i];
      xy += a[i] * b[i];
    }
    return ssim_from_moments(mx / n, my / n, xx / n, yy / n, xy / n);
  }

  std::array<double, size> weights;
  double total = 0;
  for (int i = 0; i < size; ++i)
    total += weights[i] = std::exp(-(i - radius) * (i - radius) / (2 * 1.5 * 1.5));
  for (double& weight : weights) weight /= total;

  // Horizontal pass: five maps of (w - 10) x h.
  int ow = w - 2 * radius, oh = h - 2 * radius;
  std::array<std::vector<double>, 5> rows;
  for (auto& map : rows) map.resize(size_t(ow) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      std::array<double, 5> sum{};
      for (int k = 0; k < size; ++k) {
        size_t i = size_t(y) * w + x + k;
        double wk = weights[k], va = a[i], vb = b[i];
        sum[0] += wk * va;
        sum[1] += wk * vb;
        sum[2] += wk * va * va;
        sum[3] += wk * vb * vb;
        sum[4] += wk * va * vb;
      }
      for (int m = 0; m < 5; ++m) rows[m][size_t(y) * ow + x] = sum[m];
    }

  // Vertical pass, folded into the mean of the SSIM map.
  double ssim_sum = 0;
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      std::array<double, 5> sum{};
      for (int k = 0; k < size; ++k)
        for (int m = 0; m < 5; ++m) sum[m] += weights[k] * rows[m][size_t(y + k) * ow + x];
      ssim_sum += ssim_from_moments(sum[0], sum[1], sum[2], sum[3], sum[4]);
    }
  return ssim_sum / (double(ow) * oh);
}

}  // namespace

void check_image_path(const std::string& path) {
  image_format(path);
  check_output_folder(path);
}

std::vector<unsigned char> encode_image(const Image& image, const std::string& path) {
  ImageFormat format = image_format(path);
  return format == ImageFormat::png   ? encode_png(image, path)
         : format == ImageFormat::pfm ? encode_pfm(image)
                                      : encode_exr(image, path);
}

void write_image(const Image& image, const std::string& path) {
  const Bytes bytes = encode_image(image, path);
  write_file_atomically(path, bytes.data(), bytes.size(), "cannot write image");
}

Image read_image(const std::string& path) {
  image_format(path, true);  // an unknown extension is named before the file is read
  return decode_image(read_file(path), path);
}

Image decode_image(const std::string& file_bytes, const std::string& path) {
  ImageFormat format = image_format(path, true);
  const Bytes bytes(file_bytes.begin(), file_bytes.end());
  return format == ImageFormat::png   ? decode_png(path, bytes)
         : format == ImageFormat::pfm ? decode_pfm(path, bytes)
         : format == ImageFormat::hdr ? decode_hdr(path, bytes)
                                      : decode_exr(path, bytes);
}

// IEC 61966-2-1 (sRGB) transfer functions, exact piecewise form.
float srgb_encode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear
                              : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f
                             : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

ErrorMetrics compare_images(const Image& test, const Image& reference) {
  if (test.width != reference.width || test.height != reference.height)
    throw InputError("image sizes differ: " + std::to_string(test.width) + "x" +
                     std::to_string(test.height) + " vs " + std::to_string(reference.width) +
                     "x" + std::to_string(reference.height));
  if (test.rgb.empty()) throw InputError("cannot compare empty images");

  double squared = 0, relative = 0;
  for (size_t i = 0; i < test.rgb.size(); ++i) {
    double a = test.rgb[i], b = reference.rgb[i];
    squared += (a - b) * (a - b);
    // relMSE as in Rousselle, Knaus, Zwicker, "Adaptive sampling and
    // reconstruction using greedy error minimization", SIGGRAPH Asia 2011;
    // the 1e-2 keeps dark reference pixels from dominating.
    relative += (a - b) * (a - b) / (b * b + 1e-2);
  }
  double n = double(test.rgb.size());
  double mse = squared / n;
  ErrorMetrics metrics;
  metrics.rmse = std::sqrt(mse);
  metrics.rel_mse = relative / n;
  metrics.psnr = mse == 0 ? std::numeric_limits<double>::infinity() : 10 * std::log10(1 / mse);
  metrics.ssim = ssim(test, reference);
  return metrics;
}

std::string stb_failure_reason() {
  const char* reason = stbi_failure_reason();
  std::string text = reason ? reason : "corrupt or unsupported image data";
  // stb names an unknown critical PNG chunk by its four bytes, whatever they are.
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  return text;
}

std::string png_chunk_error(const unsigned char* bytes, size_t size) {
  constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size < 8 || !std::equal(kSignature, kSignature + 8, bytes)) return {};
  size_t at = 8;
  for (int chunk = 0; at < size; ++chunk) {
    if (size - at < 12) return "chunk " + std::to_string(chunk) + " is cut off at the end of the file";
    const uint64_t length = (uint64_t(bytes[at]) << 24) | (uint64_t(bytes[at + 1]) << 16) |
                            (uint64_t(bytes[at + 2]) << 8) | uint64_t(bytes[at + 3]);
    if (length > size - at - 12)
      return "chunk " + std::to_string(chunk) + " claims " + std::to_string(length) + " bytes, past the end of the file (" +
             std::to_string(size) + " bytes)";
    const bool end = std::equal(bytes + at + 4, bytes + at + 8, "IEND");
    at += 12 + size_t(length);
    if (end) break;
  }
  return {};
}

}  // namespace octrace
