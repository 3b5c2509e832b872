// The one exception of the scene library: an impossible or inconsistent request, with the numbers.
// The host maps it to its input-error exit code.
#pragma once
#include <stdexcept>

namespace spreadmap::powder {

struct PowderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace spreadmap::powder
