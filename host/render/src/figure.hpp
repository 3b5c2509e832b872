// One off-screen figure: a render window of the requested size with one white renderer, written
// to PNG atomically (write_atomic_with). Also the small shared vocabulary of all figures: text style, display units.
#pragma once

#include <spreadmap/render/figures.hpp>

#include <array>
#include <filesystem>
#include <mutex>
#include <string>

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

class vtkTextProperty;

namespace spreadmap::render::detail {

using Rgb = std::array<double, 3>;

// Serialises all VTK rendering in the process (one figure at a time).
std::unique_lock<std::mutex> lock_rendering();

class Figure {
 public:
  explicit Figure(const Options& opt);  // starts the private display if needed
  vtkRenderer* renderer() { return renderer_; }
  vtkRenderWindow* window() { return window_; }
  int width() const { return opt_.width; }
  int height() const { return opt_.height; }
  // Pixel scale relative to a 1000-pixel-high figure: fonts and line widths grow with the image.
  double scale() const { return opt_.height / 1000.0; }
  void add_title();                              // Options::title, top centre (no-op when empty)
  void write(const std::filesystem::path& png);  // render, PNG (atomic), optional vector copy

 private:
  Options opt_;
  vtkNew<vtkRenderWindow> window_;
  vtkNew<vtkRenderer> renderer_;
};

// Text in DejaVu Sans when installed (it has Greek and superscripts), else VTK's Arial.
void style_text(vtkTextProperty* p, double size_px, const Rgb& colour = {0, 0, 0}, bool bold = false);
bool unicode_text();  // DejaVu found: labels may use ω, µ, ²

struct DisplayUnit {
  double scale;       // display value = SI value * scale
  std::string label;  // "mm²/s"
};
DisplayUnit display_unit(const std::string& si_unit);
std::string omega_symbol();                                                // "ω" or "omega"
std::string axis_label(const std::string& name, const std::string& unit);  // "U [mm/s]"
std::string pretty_name(const std::string& name);                          // "V_s" -> "Vₛ"? kept plain: "V_s"

}  // namespace spreadmap::render::detail
