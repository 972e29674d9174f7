// zlib streams (RFC 1950) deflated in pieces on the host's threads.
#pragma once

#include <cstddef>
#include <vector>

namespace octrace {

// `data` as one zlib stream at zlib's fastest level, deflated in `pieces`
// contiguous pieces at once (core/parallel.h), as pigz does: each piece a
// raw deflate stream primed with the 32 KiB before it (deflateSetDictionary),
// ended by a sync flush (byte-aligned, not final), the last by the final
// block; the pieces' output in order between the zlib header and the
// Adler-32 of all the data (adler32_combine of the pieces'). Any zlib
// decoder inflates it to `data`. A piece starts its Huffman codes afresh, so
// more pieces make a slightly larger stream. Empty if zlib fails (memory).
std::vector<unsigned char> zlib_deflate(const unsigned char* data, size_t size, size_t pieces);

}  // namespace octrace
