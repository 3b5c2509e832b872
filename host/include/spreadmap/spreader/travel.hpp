// Straight travel of a spreader along +x: the part of a spreader's parameters and motion that every
// straight-travelling spreader shares (start, U, travel or end).
//
// Time t is the time since the spreader started (the engine passes Particles::t, offset by the host).
// The spreader rests at `start` for t < 0, moves at U for 0 <= t < duration, and rests at
// start + travel for t >= duration: its surface velocity (translation and rotation) is zero
// whenever it rests. The travel is given either as `travel` (a distance) or as `end` (the x it
// stops at, which must exceed `start`). `end` = 0 means "not given": a scene whose spreader
// must stop exactly at x = 0 gives `travel` instead.
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/hd.hpp>
#include <spreadmap/params.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace spreadmap::spreader {

// "%g" text of a number for error messages (std::to_string would export weak template symbols
// from the module and prints 6 fixed decimals, 0.000006 for 6 um).
inline std::string text_of(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

struct Travel {
  double start;     // x of the reference point (e.g. an axis, a mid-plane) at t <= 0 [m]
  double speed;     // U [m/s], > 0
  double distance;  // travel [m], >= 0
  double duration;  // distance / speed [s]
  double end;       // start + distance, or `end` as given [m]

  // Time spent moving by time t, in [0, duration].
  template <class Real> SM_HD Real elapsed(Real t) const { return clamp(t, Real(0), static_cast<Real>(duration)); }
  template <class Real> SM_HD bool moving(Real t) const { return t >= Real(0) && t < static_cast<Real>(duration); }
  template <class Real> SM_HD Real x(Real t) const {
    return static_cast<Real>(start) + static_cast<Real>(speed) * elapsed(t);
  }
  template <class Real> SM_HD Real velocity(Real t) const { return moving(t) ? static_cast<Real>(speed) : Real(0); }

  // Host only: the travel part of the spreader's description.
  void describe(sm_spreader_description_v2 *out) const {
    out->start = start;
    out->end = end;
    out->speed = speed;
    out->duration = duration;
  }

  // Host only. Reads start, U, travel and end.
  static Travel bind(const Values &v) {
    const double start = v["start"], speed = v["U"], end = v["end"];
    double distance = v["travel"];
    if (end != 0.0) {
      if (!(end > start))
        throw ParamError("end = " + text_of(end) + " m must exceed start = " + text_of(start) +
                         " m (the spreader moves in +x); or leave end = 0 and give travel");
      distance = end - start;
    }
    return {start, speed, distance, distance / speed, end != 0.0 ? end : start + distance};
  }
};

// Schema entries shared by every straight-travelling spreader (the same names, units and ranges).
constexpr sm_param_v1 param_gap(const char *doc) { return number("gap", "m", 0.0, 0.1, 0.5e-3, doc); }
constexpr sm_param_v1 param_speed() {
  return number("U", "m/s", 1e-6, 100.0, 0.1, "U: translation speed along +x while spreading");
}
constexpr sm_param_v1 param_start(const char *doc) { return number("start", "m", -10.0, 10.0, 6e-3, doc); }
constexpr sm_param_v1 param_travel() {
  return number("travel", "m", 0.0, 10.0, 26e-3,
                "distance travelled along +x (ignored when end is given); duration = travel / U");
}
constexpr sm_param_v1 param_end() {
  return number("end", "m", -10.0, 10.0, 0.0,
                "x of the reference at the end of the travel, > start; 0 = not given (use travel)");
}
constexpr sm_param_v1 param_length(const char *doc) { return number("length", "m", 1e-6, 10.0, 70e-3, doc); }
constexpr sm_param_v1 param_y_centre() {
  return number("y_centre", "m", -10.0, 10.0, 0.0,
                "y of the spreader's mid-length; with the default 0 and a periodic strip [0, W] "
                "narrower than length/2 the spreader spans the whole strip");
}

}  // namespace spreadmap::spreader
