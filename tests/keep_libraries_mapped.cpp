// Linked into every executable of the sanitizer build (OCTRACE_SANITIZE) only.
// The Vulkan loader unloads lavapipe, LLVM and the validation layer with
// dlclose when the instance is destroyed; the leaks they keep for the life of
// the process are then reported at exit with their frames in an "<unknown
// module>", which tools/lsan.supp cannot name. A dlclose that unloads nothing
// keeps every library mapped, so each leak names its library: suppressed if
// it is one of those in tools/lsan.supp, reported if it is octrace's.
extern "C" int dlclose(void*) { return 0; }
