// Formatting shared by messages and summaries.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

namespace octrace {

// Bytes as whole MiB, rounded up ("129 MiB"): what memory messages quote.
inline std::string mib_string(uint64_t bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB"; }
// The same, but exact below 1 MiB ("7872 bytes"), where whole MiB would say
// "1 MiB" of a few bytes (limits lowered by the tests' hooks).
inline std::string byte_string(uint64_t bytes) {
  return bytes < (uint64_t(1) << 20) ? std::to_string(bytes) + " bytes" : mib_string(bytes);
}

// The shortest text that reads back to the same float ("0.2", "1e-07", "nan").
inline std::string float_string(float v) {
  char buf[32];
  return {buf, std::to_chars(buf, buf + sizeof buf, v).ptr};
}

// The same for a double ("1.5", "nan").
inline std::string float_string(double v) {
  char buf[32];
  return {buf, std::to_chars(buf, buf + sizeof buf, v).ptr};
}

// "[x, y, z]", each as float_string.
inline std::string vec3_string(glm::vec3 v) {
  // Appended rather than "[" + ..., which trips GCC 12's -Wrestrict false positive.
  std::string out = "[";
  out += float_string(v.x) + ", " + float_string(v.y) + ", " + float_string(v.z) + "]";
  return out;
}

}  // namespace octrace
