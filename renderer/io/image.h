// Images on the CPU: linear RGB float pixels, file I/O by extension, and the
// error metrics of `octrace compare`.
#pragma once

#include <string>
#include <vector>

namespace octrace {

// Linear RGB, row-major, top row first, 3 floats per pixel.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;

  float* pixel(int x, int y) { return &rgb[3 * (size_t(y) * width + x)]; }
  const float* pixel(int x, int y) const { return &rgb[3 * (size_t(y) * width + x)]; }
};

// The format follows the extension: .png (8-bit sRGB, clamped), .pfm (linear
// float, rows bottom to top as the format defines), .exr (linear, float).
// Written atomically: a temporary file in the same folder, then rename, so a
// failed run never leaves a truncated image. Throws InputError for an unknown
// extension, RuntimeError when the file cannot be written.
void write_image(const Image& image, const std::string& path);
// The file's bytes that write_image writes (for several files written as
// one set: write_files_atomically).
std::vector<unsigned char> encode_image(const Image& image, const std::string& path);
// Throws InputError if the extension is unknown before anything is rendered.
void check_image_path(const std::string& path);

// Reads .png (decoded from sRGB to linear), .pfm or .exr. Throws InputError
// naming the file when it is missing or not a readable image.
Image read_image(const std::string& path);
// The same from the file's bytes; the format follows `path`'s extension, and
// `path` names the file in messages. The fuzz target tests/fuzz/fuzz_image.cpp
// calls it.
Image decode_image(const std::string& bytes, const std::string& path);

// For bytes that start with the PNG signature: walks the chunks (PNG
// specification 5.3: length, type, data, CRC) and returns a one-line reason
// if one runs past the end of the data, else an empty string. stb_image
// trusts chunk lengths and reserves memory for them before reading: a
// 100-byte file claimed 2 GiB (found by tests/fuzz/fuzz_image.cpp).
std::string png_chunk_error(const unsigned char* bytes, size_t size);

// stb_image's reason for its last failure, or "corrupt or unsupported image
// data" where it gave none: some of its paths fail without one, and adding
// that null pointer to a std::string crashed (found by
// tests/fuzz/fuzz_gltf.cpp).
std::string stb_failure_reason();

float srgb_encode(float linear);
float srgb_decode(float encoded);

struct ErrorMetrics {
  double rmse = 0;     // over all channels, linear values
  double rel_mse = 0;  // mean of (a-b)^2 / (b^2 + 1e-2), b = reference
  double psnr = 0;     // 10 log10(1 / MSE), peak 1; +inf for identical images
  double ssim = 0;     // Wang et al. 2004 on sRGB-encoded luminance (see image.cpp)
};

// `reference` is the second image. Throws InputError if the sizes differ.
ErrorMetrics compare_images(const Image& test, const Image& reference);

}  // namespace octrace
