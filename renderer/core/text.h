// Formatting shared by messages and summaries.
#pragma once

#include <cstdint>
#include <string>

namespace octrace {

// Bytes as whole MiB, rounded up ("129 MiB"): what memory messages quote.
inline std::string mib_string(uint64_t bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB"; }

}  // namespace octrace
