#include "io/deflate.h"

#include <zlib.h>

#include <algorithm>

#include "core/parallel.h"

namespace octrace {
namespace {

constexpr size_t kWindow = 32 * 1024;  // deflate's window: a piece's dictionary

struct Piece {
  std::vector<unsigned char> bytes;  // raw deflate
  size_t length = 0;                 // of the data it holds
  uLong adler = 0;                   // of the data it holds
  bool ok = false;
};

Piece deflate_piece(const unsigned char* data, size_t begin, size_t end, bool last) {
  Piece p;
  p.length = end - begin;
  z_stream z{};
  if (deflateInit2(&z, Z_BEST_SPEED, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return p;
  const size_t dictionary = std::min(begin, kWindow);
  bool ok = dictionary == 0 || deflateSetDictionary(&z, data + begin - dictionary, uInt(dictionary)) == Z_OK;
  // deflateBound, and room for the sync flush's empty stored block.
  p.bytes.resize(deflateBound(&z, uLong(p.length)) + 16);
  z.next_in = const_cast<unsigned char*>(data + begin);
  z.avail_in = uInt(p.length);
  z.next_out = p.bytes.data();
  z.avail_out = uInt(p.bytes.size());
  const int result = ok ? deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH) : Z_STREAM_ERROR;
  p.ok = ok && (last ? result == Z_STREAM_END : result == Z_OK && z.avail_in == 0 && z.avail_out > 0);
  p.bytes.resize(p.bytes.size() - z.avail_out);
  deflateEnd(&z);
  p.adler = adler32(adler32(0, nullptr, 0), data + begin, uInt(p.length));
  return p;
}

}  // namespace

std::vector<unsigned char> zlib_deflate(const unsigned char* data, size_t size, size_t pieces) {
  pieces = clamp_ranges(size, pieces);
  std::vector<Piece> parts(pieces);
  parallel_ranges(size, pieces, [&](size_t k, size_t begin, size_t end) {
    parts[k] = deflate_piece(data, begin, end, k + 1 == pieces);
  });
  // CMF 0x78: deflate with a 32 KiB window; FLG 0x01: the fastest level, no
  // preset dictionary, (CMF * 256 + FLG) a multiple of 31.
  std::vector<unsigned char> out{0x78, 0x01};
  uLong adler = adler32(0, nullptr, 0);
  for (const Piece& p : parts) {
    if (!p.ok) return {};
    out.insert(out.end(), p.bytes.begin(), p.bytes.end());
    adler = adler32_combine(adler, p.adler, z_off_t(p.length));
  }
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(adler >> shift));
  return out;
}

}  // namespace octrace
