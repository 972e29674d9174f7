// The environment of every test binary, set before main() and inherited by
// the octrace processes the tests start: lavapipe's XDG_RUNTIME_DIR, and the
// specialised SPIR-V modules (vk/specialize.h) cached in the build folder
// rather than in the user's ~/.cache. A value already set is kept (a run
// with OCTRACE_CACHE_DIR=none tests without the cache).
#include <cstdlib>

namespace {

const bool kTestEnvironment = [] {
  setenv("XDG_RUNTIME_DIR", "/tmp", 0);
  setenv("OCTRACE_CACHE_DIR", OCTRACE_TEST_CACHE_DIR, 0);
  return true;
}();

}  // namespace
