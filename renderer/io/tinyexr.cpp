// tinyexr's implementation (EXR files: io/image.cpp, scene/envmap.cpp),
// compiled here from Debian's header (libtinyexr-dev) rather than linked
// from its libtinyexr, which is built without threads: here the blocks of
// an image are encoded and decoded on the host's threads (TINYEXR_USE_THREAD;
// a 1920x1080 EXR's write, 16-row blocks deflated at zlib's default level,
// was 718 ms on one thread: optimisation log 99). With zlib, as Debian's
// build has it (TINYEXR_USE_MINIZ 0). Debian's library keeps tinyexr's
// asserts, and io/image.cpp's checks of EXR headers are written against
// them (tests/io/image_test.cpp), so this copy keeps them in every build.
#undef NDEBUG
#include <cassert>
#include <zlib.h>

#define TINYEXR_USE_MINIZ 0
#define TINYEXR_USE_THREAD 1
#define TINYEXR_IMPLEMENTATION
#include <tinyexr.h>
