// Errors the library throws. The front end catches them once, prints the message
// as one line, and exits 2 for bad input and 1 for a runtime failure.
#pragma once

#include <stdexcept>
#include <string>

namespace octrace {

// Something the user gave us is wrong: a flag, a scene file, an image path.
// The message names the input ("scene.json: spheres[12].radius: must be > 0").
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The input was fine but the machine could not do it: no device, device lost,
// out of memory, an I/O failure while writing.
struct RuntimeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace octrace
