#include "io/image.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <utility>
#include <string>
#include <vector>

#include "core/errors.h"
#include "io/deflate.h"
#include "io/file.h"

namespace octrace {
namespace {

namespace fs = std::filesystem;

// An empty folder of its own for each test, under OCTRACE_TEST_TMP.
std::string fresh_folder() {
  const auto* test = testing::UnitTest::GetInstance()->current_test_info();
  fs::path folder = fs::path(OCTRACE_TEST_TMP) / (std::string("image_test_") + test->name());
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

std::vector<std::string> files_in(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<unsigned char> file_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The message of the exception of type E that `f` throws ("" if none).
template <class E, class F>
std::string message_of(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception";
  return "";
}

// A smooth image with values in [0, 1]: a diagonal ramp per channel.
Image ramp(int width, int height) {
  Image image{width, height, std::vector<float>(size_t(3) * width * height)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* p = image.pixel(x, y);
      p[0] = float(x) / (width - 1);
      p[1] = float(y) / (height - 1);
      p[2] = 0.5f * (p[0] + p[1]);
    }
  return image;
}

// Linear values no 8-bit format could hold: large, negative, tiny, subnormal.
Image hdr_image() {
  Image image{7, 5, {}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> exponent(-40.0f, 40.0f);
  for (int i = 0; i < 3 * 7 * 5; ++i)
    image.rgb.push_back((i % 5 == 0 ? -1.0f : 1.0f) * std::exp2(exponent(rng)));
  image.rgb[4] = std::numeric_limits<float>::denorm_min();
  image.rgb[5] = 0.0f;
  return image;
}

Image with_noise(const Image& image, float sigma, unsigned seed) {
  Image noisy = image;
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  for (float& v : noisy.rgb) v += noise(rng);
  return noisy;
}

// zlib_deflate's pieces make one zlib stream: zlib's own inflate (which
// checks the Adler-32) gives the data back, for one piece, several, and more
// pieces than bytes; data long runs (back-references across the pieces'
// seams, through the dictionary), a ramp and noise.
TEST(Deflate, PiecesInflateToTheData) {
  std::vector<unsigned char> data(300000);
  std::mt19937 rng(5);
  for (size_t i = 0; i < data.size(); ++i)
    data[i] = i < 100000 ? 0 : i < 200000 ? static_cast<unsigned char>(i / 7) : static_cast<unsigned char>(rng());
  for (const std::vector<unsigned char>& input : {data, std::vector<unsigned char>(data.begin(), data.begin() + 3),
                                                  std::vector<unsigned char>{}}) {
    for (size_t pieces : {1, 2, 3, 7, 1000}) {
      const std::vector<unsigned char> z = zlib_deflate(input.data(), input.size(), pieces);
      ASSERT_FALSE(z.empty());
      std::vector<unsigned char> back(input.size() + 1);
      uLongf size = uLongf(back.size());
      ASSERT_EQ(uncompress(back.data(), &size, z.data(), uLong(z.size())), Z_OK)
          << pieces << " pieces of " << input.size() << " bytes";
      back.resize(size);
      EXPECT_EQ(back, input) << pieces << " pieces of " << input.size() << " bytes";
    }
  }
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A set of files (a state's three) is written as one: every file flushed to
// its temporary before any is renamed, so a failure while writing one
// leaves the others as they were (a render's --state wrote its .mean.pfm
// and .count.pfm, then failed on .accum) and no temporary behind.
TEST(FileSets, AFailedWriteLeavesEveryFileOfTheSetAsItWas) {
  const std::string folder = fresh_folder();
  const std::string a = folder + "/a.txt", b = folder + "/b.txt";
  std::ofstream(a) << "old a";
  const std::string new_a = "new a", new_b = "new b", new_c = "new c";
  const std::string c = folder + "/missing/c.txt";
  EXPECT_THROW(write_files_atomically({{a, new_a.data(), new_a.size()},
                                       {b, new_b.data(), new_b.size()},
                                       {c, new_c.data(), new_c.size()}}),
               RuntimeError);
  EXPECT_EQ(contents(a), "old a");
  EXPECT_FALSE(fs::exists(b));
  EXPECT_EQ(files_in(folder), (std::vector<std::string>{"a.txt"}));
  write_files_atomically({{a, new_a.data(), new_a.size()}, {b, new_b.data(), new_b.size()}});
  EXPECT_EQ(contents(a), "new a");
  EXPECT_EQ(contents(b), "new b");
  EXPECT_EQ(files_in(folder), (std::vector<std::string>{"a.txt", "b.txt"}));
}

TEST(ImageIo, PngRoundTripIsWithinEightBitQuantisation) {
  std::string path = fresh_folder() + "/ramp.png";
  Image image = ramp(40, 30);
  image.rgb[0] = 7.0f;   // shown as white
  image.rgb[1] = -2.0f;  // shown as black
  write_image(image, path);
  Image read = read_image(path);
  ASSERT_EQ(read.width, 40);
  ASSERT_EQ(read.height, 30);
  EXPECT_EQ(read.rgb[0], 1.0f);
  EXPECT_EQ(read.rgb[1], 0.0f);
  for (size_t i = 2; i < image.rgb.size(); ++i)
    ASSERT_NEAR(srgb_encode(read.rgb[i]), srgb_encode(image.rgb[i]), 0.5 / 255 + 1e-6) << i;
}

TEST(ImageIo, PfmAndExrRoundTripsAreBitExact) {
  std::string folder = fresh_folder();
  Image image = hdr_image();
  for (const char* name : {"/hdr.pfm", "/hdr.exr"}) {
    write_image(image, folder + name);
    Image read = read_image(folder + name);
    EXPECT_EQ(read.width, image.width) << name;
    EXPECT_EQ(read.height, image.height) << name;
    EXPECT_EQ(read.rgb, image.rgb) << name;
  }
}

TEST(ImageIo, ExtensionIsCaseInsensitive) {
  std::string path = fresh_folder() + "/upper.PFM";
  Image image = hdr_image();
  write_image(image, path);
  EXPECT_EQ(read_image(path).rgb, image.rgb);
}

TEST(ImageIo, PfmStoresBottomRowFirst) {
  std::string path = fresh_folder() + "/rows.pfm";
  Image image{1, 2, {1.0f, 2.0f, 3.0f, /* bottom row: */ 4.0f, 5.0f, 6.0f}};
  write_image(image, path);
  std::vector<unsigned char> bytes = file_bytes(path);
  std::string header = "PF\n1 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + long(header.size())), header);
  // Little-endian, as the negative scale says.
  float first[3];
  std::memcpy(first, bytes.data() + header.size(), sizeof first);
  EXPECT_EQ(first[0], 4.0f);
  EXPECT_EQ(first[1], 5.0f);
  EXPECT_EQ(first[2], 6.0f);
}

TEST(ImageIo, ReadsBigEndianGreyscalePfm) {
  std::string path = fresh_folder() + "/grey.pfm";
  // 2x1 greyscale, big-endian (positive scale): 1.0 = 3f800000, 0.5 = 3f000000.
  std::string header = "Pf\n2 1\n1.0\n";
  std::vector<unsigned char> bytes(header.begin(), header.end());
  for (unsigned char b : {0x3f, 0x80, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x00}) bytes.push_back(b);
  write_bytes(path, bytes);
  Image read = read_image(path);
  ASSERT_EQ(read.width, 2);
  ASSERT_EQ(read.height, 1);
  EXPECT_EQ(read.rgb, (std::vector<float>{1.0f, 1.0f, 1.0f, 0.5f, 0.5f, 0.5f}));
}

// Found by tests/fuzz/fuzz_image.cpp (tools/sanitize.sh reports the first
// two again): a broken header, which tinyexr's LoadEXRFromMemory leaked;
// pixels that fail to decode, which tinyexr frees itself and octrace freed a
// second time; a data window of 2^31 rows, for which tinyexr asked for an
// offset table of 2^61 bytes; 3.7 million pixels in 390 bytes, which tinyexr
// decoded from data that is not there, for seconds; a PIZ chunk at the end
// of the file whose bitmap range tinyexr read past the file's bytes (ASan,
// in the fuzz run; here only its message can be checked).
TEST(ImageIo, BrokenExrFilesAreInputErrorsOfOneLine) {
  const std::string corpus = std::string(OCTRACE_SOURCE_DIR) + "/tests/fuzz/corpus/image/";
  for (const auto& [file, message] : {std::pair{"regression_exr_header_leak.exr", "Failed to read attribute."},
                                      std::pair{"regression_exr_freed_twice.exr",
                                                "Invalid data found when decoding pixels."},
                                      std::pair{"regression_exr_huge_window.exr", "bad data window 3x2147483650"},
                                      std::pair{"regression_exr_short_data.exr",
                                                "3670019x2 pixels cannot be stored in 390 bytes"},
                                      std::pair{"regression_exr_piz_bitmap_past_end.exr",
                                                "Invalid data found when decoding pixels."}}) {
    const std::string path = corpus + file;
    EXPECT_EQ(message_of<InputError>([&] { read_image(path); }), path + ": not a valid EXR file: " + message);
  }
}

// Headers on which Debian's tinyexr ends the process in an assert instead
// of returning an error: a "type" attribute it does not know (found by
// tests/fuzz/fuzz_image.cpp in a CI run), one that contradicts the header's
// tiles, and a "tiles" attribute of other than 9 bytes in a tiled file.
TEST(ImageIo, ExrHeadersTinyexrWouldAssertOnAreInputErrors) {
  const std::string found = std::string(OCTRACE_SOURCE_DIR) + "/tests/fuzz/corpus/image/regression_exr_unknown_type.exr";
  EXPECT_EQ(message_of<InputError>([&] { read_image(found); }),
            found + ": not a valid EXR file: its \"type\" attribute is \"l\", not scanlineimage, tiledimage, "
                    "deepscanline or deeptile");
  // The magic number, version 2 (with the tiled bit 0x200 where asked), one
  // attribute and the empty name that ends the list.
  auto header = [](bool tiled, const std::string& name, const std::string& type, const std::string& value) {
    std::string bytes("\x76\x2f\x31\x01\x02", 5);
    bytes += tiled ? std::string("\x02\0\0", 3) : std::string("\0\0\0", 3);
    const std::uint32_t length = std::uint32_t(value.size());
    bytes += name + '\0' + type + '\0' + std::string(reinterpret_cast<const char*>(&length), 4) + value + '\0';
    return std::vector<unsigned char>(bytes.begin(), bytes.end());
  };
  const std::string folder = fresh_folder();
  const struct {
    std::vector<unsigned char> bytes;
    std::string message;
  } cases[] = {
      {header(false, "type", "string", "tiledimage"), "its \"type\" attribute is tiledimage, but the header has no tiles"},
      {header(true, "tiles", "tiledesc", std::string(4, '\0')), "its \"tiles\" attribute has 4 bytes, not 9"},
  };
  for (const auto& c : cases) {
    const std::string path = folder + "/header.exr";
    write_bytes(path, c.bytes);
    EXPECT_EQ(message_of<InputError>([&] { read_image(path); }), path + ": not a valid EXR file: " + c.message);
  }
}

// Found by tests/fuzz/fuzz_image.cpp: stb_image read a PGM header of
// 8888888x3 pixels given as .png, which took seconds; a .png must be a PNG.
TEST(ImageIo, APngWithoutThePngSignatureIsAnInputError) {
  const std::string path = std::string(OCTRACE_SOURCE_DIR) + "/tests/fuzz/corpus/image/regression_pgm_as_png.png";
  EXPECT_EQ(message_of<InputError>([&] { read_image(path); }), path + ": not a valid PNG file: no PNG signature");
}

// A chunk whose length runs past the end of the file: stb_image reserved
// 2 GiB for it (found by tests/fuzz/fuzz_image.cpp in a CI run).
TEST(ImageIo, APngChunkPastTheEndIsAnInputError) {
  const std::string path = std::string(OCTRACE_SOURCE_DIR) + "/tests/fuzz/corpus/image/regression_png_chunk_past_end.png";
  EXPECT_EQ(message_of<InputError>([&] { read_image(path); }),
            path + ": not a valid PNG file: chunk 2 claims 1862271002 bytes, past the end of the file (115 bytes)");
}

// A PNG whose compressed data is corrupt, on which stb_image fails without
// giving a reason: the message says so instead of crashing on the null
// reason (found by tests/fuzz/fuzz_gltf.cpp as a texture of a .glb).
TEST(ImageIo, APngStbImageRejectsWithoutAReasonIsAnInputError) {
  const std::string path =
      std::string(OCTRACE_SOURCE_DIR) + "/tests/fuzz/corpus/image/regression_png_without_failure_reason.png";
  EXPECT_EQ(message_of<InputError>([&] { read_image(path); }),
            path + ": not a valid PNG file: corrupt or unsupported image data");
}

// An EXR compressed by a method tinyexr does not read (DWAA and DWAB: Debian's
// blender-data HDRIs are DWAB) is named, with what to do about it. The file
// is one of ours (ZIP) with its compression attribute set to DWAB.
TEST(ImageIo, UnsupportedExrCompressionIsNamed) {
  const std::string path = fresh_folder() + "/dwab.exr";
  write_image(ramp(4, 4), path);
  std::vector<unsigned char> bytes = file_bytes(path);
  const std::string attribute("compression\0compression\0\x01\0\0\0", 28);
  const auto at = std::search(bytes.begin(), bytes.end(), attribute.begin(), attribute.end());
  ASSERT_NE(at, bytes.end());
  *(at + ptrdiff_t(attribute.size())) = 9;  // DWAB
  write_bytes(path, bytes);
  EXPECT_EQ(message_of<InputError>([&] { read_image(path); }),
            path + ": not a valid EXR file: compression DWAB is not supported (tinyexr reads none, RLE, ZIPS, ZIP and "
                   "PIZ): re-save it with ZIP or PIZ, e.g. exrmaketiled -z zip IN.exr OUT.exr (Debian: openexr)");
}

TEST(ImageIo, UnknownExtensionIsAnInputError) {
  std::string path = fresh_folder() + "/out.jpg";
  std::string expected = path + ": unknown image format \".jpg\" (expected .png, .pfm or .exr)";
  EXPECT_EQ(message_of<InputError>([&] { check_image_path(path); }), expected);
  EXPECT_EQ(message_of<InputError>([&] { write_image(ramp(4, 4), path); }), expected);
  // Reading also knows Radiance .hdr (environment maps), which is never written.
  EXPECT_EQ(message_of<InputError>([&] { read_image(path); }),
            path + ": unknown image format \".jpg\" (expected .png, .pfm, .exr or .hdr)");
  EXPECT_TRUE(files_in(fs::path(path).parent_path()).empty());
}

TEST(ImageIo, CheckImagePathAcceptsGoodPathsAndRejectsMissingFolders) {
  std::string folder = fresh_folder();
  EXPECT_NO_THROW(check_image_path(folder + "/a.png"));
  EXPECT_NO_THROW(check_image_path(folder + "/a.EXR"));
  EXPECT_NO_THROW(check_image_path("relative.pfm"));
  std::string missing = folder + "/no/such/folder/a.png";
  EXPECT_EQ(message_of<InputError>([&] { check_image_path(missing); }),
            missing + ": folder does not exist");
}

TEST(ImageIo, MissingFileIsAnInputError) {
  std::string path = fresh_folder() + "/missing.exr";
  EXPECT_EQ(message_of<InputError>([&] { read_image(path); }).rfind(path + ": cannot open file", 0),
            0u);
}

TEST(ImageIo, TruncatedPfmSaysWhatIsMissing) {
  std::string path = fresh_folder() + "/short.pfm";
  write_image(ramp(4, 3), path);
  std::vector<unsigned char> bytes = file_bytes(path);
  write_bytes(path, std::vector<unsigned char>(bytes.begin(), bytes.end() - 5));
  EXPECT_EQ(message_of<InputError>([&] { read_image(path); }),
            path + ": not a valid PFM file: truncated pixel data (expected 144 bytes, found 139)");
}

// Every prefix of a valid file, in every format, is either rejected with an
// InputError naming the file or, when only bytes the decoder does not need are
// missing (stb ignores the PNG end chunk), read as the full image: never a
// crash or a garbage image.
TEST(ImageIo, EveryTruncationOfAFileIsAnInputError) {
  std::string folder = fresh_folder();
  for (const char* name : {"/t.pfm", "/t.png", "/t.exr"}) {
    std::string path = folder + name;
    write_image(ramp(5, 4), path);
    Image full = read_image(path);
    std::vector<unsigned char> whole = file_bytes(path);
    for (size_t size = 0; size < whole.size(); ++size) {
      write_bytes(path, std::vector<unsigned char>(whole.begin(), whole.begin() + long(size)));
      try {
        Image read = read_image(path);
        ASSERT_EQ(read.rgb, full.rgb) << name << ", " << size << " bytes";
      } catch (const InputError& e) {
        ASSERT_EQ(std::string(e.what()).rfind(path + ": not a valid", 0), 0u)
            << size << " bytes: " << e.what();
      }
    }
  }
}

TEST(ImageIo, WriteIntoMissingFolderFailsAndLeavesNothing) {
  std::string folder = fresh_folder();
  std::string path = folder + "/missing/out.png";
  std::string message = message_of<RuntimeError>([&] { write_image(ramp(4, 4), path); });
  EXPECT_EQ(message.rfind(path + ": cannot write image: ", 0), 0u) << message;
  EXPECT_TRUE(files_in(folder).empty());
}

TEST(ImageIo, SuccessfulWritesLeaveOnlyTheImages) {
  std::string folder = fresh_folder();
  for (const char* name : {"/a.png", "/a.pfm", "/a.exr"}) write_image(ramp(8, 8), folder + name);
  EXPECT_EQ(files_in(folder), (std::vector<std::string>{"a.exr", "a.pfm", "a.png"}));
}

TEST(ImageIo, OverwritingReplacesTheFile) {
  std::string path = fresh_folder() + "/again.exr";
  write_image(ramp(16, 16), path);
  Image second = hdr_image();
  write_image(second, path);
  Image read = read_image(path);
  EXPECT_EQ(read.width, second.width);
  EXPECT_EQ(read.rgb, second.rgb);
}

// When the final rename fails (here: the target is a folder), the temporary
// file is removed and the error names the target.
TEST(ImageIo, FailedRenameRemovesTheTemporaryFile) {
  std::string folder = fresh_folder();
  std::string path = folder + "/taken.pfm";
  fs::create_directories(path + "/inside");
  std::string message = message_of<RuntimeError>([&] { write_image(ramp(4, 4), path); });
  EXPECT_EQ(message.rfind(path + ": cannot write image: ", 0), 0u) << message;
  EXPECT_EQ(files_in(folder), (std::vector<std::string>{"taken.pfm"}));
}

TEST(Srgb, KnownValues) {
  EXPECT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_NEAR(srgb_encode(1.0f), 1.0f, 1e-6);
  EXPECT_NEAR(srgb_decode(1.0f), 1.0f, 1e-6);
  // The linear segment below the break point, and both sides of it agree.
  EXPECT_NEAR(srgb_encode(0.001f), 0.01292f, 1e-7);
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.04045f, 1e-6);
  EXPECT_NEAR(srgb_decode(0.04045f), 0.0031308f, 1e-7);
  // Middle grey: 18% reflectance shows as 46.1% of full scale, and an encoded
  // 0.5 is 21.4% linear.
  EXPECT_NEAR(srgb_encode(0.18f), 0.461356f, 1e-5);
  EXPECT_NEAR(srgb_decode(0.5f), 0.214041f, 1e-5);
}

TEST(Srgb, DecodeInvertsEncode) {
  for (int i = 0; i <= 1000; ++i) {
    float linear = float(i) / 1000;
    EXPECT_NEAR(srgb_decode(srgb_encode(linear)), linear, 1e-6f + 1e-5f * linear) << linear;
  }
}

TEST(Metrics, IdenticalImagesHaveNoError) {
  Image image = ramp(32, 24);
  ErrorMetrics m = compare_images(image, image);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.rel_mse, 0.0);
  EXPECT_EQ(m.psnr, std::numeric_limits<double>::infinity());
  EXPECT_NEAR(m.ssim, 1.0, 1e-12);
}

TEST(Metrics, SmallExampleByHand) {
  // 2x2 grey 0.5 reference; the test image has one channel at 0.6.
  Image reference{2, 2, std::vector<float>(12, 0.5f)};
  Image test = reference;
  test.rgb[7] = 0.6f;
  ErrorMetrics m = compare_images(test, reference);
  double d = double(0.6f) - 0.5;  // 0.1 up to float rounding
  EXPECT_NEAR(m.rmse, std::sqrt(d * d / 12), 1e-12);
  EXPECT_NEAR(m.psnr, 10 * std::log10(12 / (d * d)), 1e-9);  // about 30.79 dB
  EXPECT_NEAR(m.rel_mse, d * d / (0.25 + 0.01) / 12, 1e-12);
}

// For flat images the contrast-structure term is 1 and SSIM is the luminance
// term (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1) of the displayed (sRGB) luma.
TEST(Metrics, SsimOfFlatImagesUsesDisplayedLuma) {
  Image a{16, 16, std::vector<float>(3 * 256, srgb_decode(0.5f))};
  Image b{16, 16, std::vector<float>(3 * 256, srgb_decode(0.25f))};
  double c1 = 1e-4;
  double expected = (2 * 0.5 * 0.25 + c1) / (0.25 + 0.0625 + c1);
  EXPECT_NEAR(compare_images(a, b).ssim, expected, 1e-6);
}

TEST(Metrics, SsimFallsWithNoiseAndIsSymmetric) {
  Image clean = ramp(96, 64);
  double previous = 1.0;
  for (float sigma : {0.01f, 0.03f, 0.1f, 0.3f}) {
    Image noisy = with_noise(clean, sigma, 1);
    double forward = compare_images(noisy, clean).ssim;
    EXPECT_LT(forward, previous) << sigma;
    EXPECT_GT(forward, 0.0) << sigma;
    EXPECT_NEAR(compare_images(clean, noisy).ssim, forward, 1e-12) << sigma;
    previous = forward;
  }
}

TEST(Metrics, SsimOfImagesSmallerThanTheWindow) {
  Image clean = ramp(6, 20);
  EXPECT_NEAR(compare_images(clean, clean).ssim, 1.0, 1e-12);
  EXPECT_LT(compare_images(with_noise(clean, 0.1f, 2), clean).ssim, 0.99);
}

TEST(Metrics, SizeMismatchIsAnInputError) {
  EXPECT_EQ(message_of<InputError>([] { compare_images(ramp(96, 64), ramp(120, 80)); }),
            "image sizes differ: 96x64 vs 120x80");
}

}  // namespace
}  // namespace octrace
