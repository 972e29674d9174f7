// core/hash.h: an array hashed piece by piece (add_piece, end_pieces) has the
// hash of the same bytes added whole, so a form of the scene made only for
// the checkpoint hash (render/gpu_scene.cpp make_materials) hashes as it did
// when it was stored; other bytes or another length give another hash.
#include "core/hash.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace octrace {
namespace {

TEST(Hash64, PiecesHashAsTheWhole) {
  std::vector<uint64_t> words(40);
  for (size_t i = 0; i < words.size(); ++i) words[i] = 0x9e3779b97f4a7c15ull * (i + 1);
  for (size_t piece : {size_t(1), size_t(2), size_t(8), size_t(10)}) {
    Hash64 pieces;
    pieces.add(&piece, sizeof piece);  // something before, as the scene's other arrays
    for (size_t i = 0; i < words.size(); i += piece) pieces.add_piece(&words[i], piece * sizeof(uint64_t));
    pieces.end_pieces(words.size() * sizeof(uint64_t));
    Hash64 whole;
    whole.add(&piece, sizeof piece).add_vector(words);
    EXPECT_EQ(pieces.value(), whole.value()) << piece << " words a piece";
  }
  Hash64 empty_pieces, empty_whole;
  empty_pieces.end_pieces(0);
  empty_whole.add_vector(std::vector<uint64_t>());
  EXPECT_EQ(empty_pieces.value(), empty_whole.value());

  Hash64 whole, shorter, changed;
  whole.add_vector(words);
  shorter.add_piece(words.data(), 39 * sizeof(uint64_t)).end_pieces(39 * sizeof(uint64_t));
  words[7] ^= 1;
  changed.add_vector(words);
  EXPECT_NE(whole.value(), shorter.value());
  EXPECT_NE(whole.value(), changed.value());
}

}  // namespace
}  // namespace octrace
