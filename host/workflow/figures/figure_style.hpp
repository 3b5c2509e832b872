// A stage's `render:` option: how (and whether) it draws its figures.
//   render: false                                  no figures
//   render: true                                   figures at their default sizes (the default)
//   render: {width: 1920, vector: pdf, frames: true}
// width: every figure this many pixels wide, each keeping its own aspect; vector: a pdf, svg or eps
// copy beside each PNG (gl2ps; raster parts stay raster); frames (simulate only): numbered PNG frames
// of each case's snapshot series (time.snapshots > 0), cases/cNNN/frames/frame_0000.png ...
#pragma once
#include "core/yaml_fwd.hpp"

#include <string>

#include "core/diagnostics.hpp"

namespace spreadmap::figures {

struct Style {
  bool on = true;
  int width = 0;       // 0 = each figure's default
  std::string vector;  // "", "pdf", "svg" or "eps"
  bool frames = false;
};

// Reads a stage's `render` node (absent: {on = default_on}); errors name file:line:column and key.
Style read_style(const YAML::Node &node, bool default_on, bool frames_allowed, const std::string &file,
                 const std::string &key, Diagnostics &diag);

// The style of the figures drawn from now on. Stages run one at a time; set it before any thread draws.
void use_style(const Style &style);
const Style &current_style();

}  // namespace spreadmap::figures
