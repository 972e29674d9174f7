// A 64-bit FNV-1a hash over bytes, eight at a time (the checkpoint's
// fingerprint of a scene: equal arrays give equal hashes; not cryptographic).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace octrace {

class Hash64 {
 public:
  Hash64& add(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
      uint64_t word;
      std::memcpy(&word, p + i, 8);
      mix(word);
    }
    uint64_t tail = 0;
    if (i < size) {
      std::memcpy(&tail, p + i, size - i);
      mix(tail);
    }
    mix(size);
    return *this;
  }
  template <class Vector>
  Hash64& add_vector(const Vector& v) {
    return add(v.data(), v.size() * sizeof(v[0]));
  }
  // add() of an array that is not stored whole: each piece's bytes in turn
  // with add_piece (a multiple of 8 bytes each), then end_pieces with their
  // total size; the same hash as add() of the pieces laid end to end.
  Hash64& add_piece(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i + 8 <= size; i += 8) {
      uint64_t word;
      std::memcpy(&word, p + i, 8);
      mix(word);
    }
    return *this;
  }
  Hash64& end_pieces(size_t total_size) {
    mix(total_size);
    return *this;
  }
  uint64_t value() const { return h_; }

 private:
  void mix(uint64_t word) {
    h_ ^= word;
    h_ *= 0x100000001b3ull;
  }
  uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace octrace
