// A private X server for headless rendering. Debian's VTK 9.1 draws only through X (no OSMesa or
// EGL window), so when DISPLAY is unset we start `Xvfb -displayfd` (it picks a free display number
// and reports it once it accepts clients), point DISPLAY at it and stop it at process exit.
#pragma once

#include <string>

namespace spreadmap::render::detail {

// Makes sure DISPLAY names a usable X server; starts the private Xvfb on the first call when
// DISPLAY is unset. Thread-safe; one server per process. Throws RenderError when Xvfb is missing
// (naming the Debian package) or does not start. Returns the display in use (":N").
std::string ensure_display();

// True when this process started (and owns) an Xvfb.
bool owns_private_display();

}  // namespace spreadmap::render::detail
