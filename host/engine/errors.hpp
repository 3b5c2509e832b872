// Engine errors. SetupError: the scene as given cannot run (bad domain, refused time step, bad
// checkpoint); RunError: a running case became unphysical (NaN, excessive overlap, exploding
// energy). Both derive from the host's error classes so main() prints them with the right exit code.
#pragma once
#include <core/error.hpp>

namespace spreadmap::engine {

struct SetupError : InputError {
  explicit SetupError(const std::string &what) : InputError(what) {}
};
struct RunError : RunFailure {
  explicit RunError(const std::string &what) : RunFailure(what) {}
};

}  // namespace spreadmap::engine
