# Run at every build (app/CMakeLists.txt, target octrace_version): writes
# OUT, a header with OCTRACE_COMMIT, the source tree's commit as
# `git describe --always --dirty` gives it ("a1b2c3d", "a1b2c3d-dirty"), or
# "unknown" outside a git checkout. The file is rewritten only when the
# text changes, so an unchanged commit recompiles nothing.
#   cmake -D SRC=<source dir> -D OUT=<header> -P version.cmake
find_package(Git QUIET)
set(commit "unknown")
if(GIT_FOUND)
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SRC}" describe --always --dirty --abbrev=7
                  OUTPUT_VARIABLE described RESULT_VARIABLE failed OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT failed AND described)
    set(commit "${described}")
  endif()
endif()
set(text "// Written by app/version.cmake at build time.\n#pragma once\n#define OCTRACE_COMMIT \"${commit}\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE "${OUT}" "${text}")
endif()
