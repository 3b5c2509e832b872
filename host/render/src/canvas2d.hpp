// 2-D drawing on top of a renderer in display pixels (origin bottom-left): lines, markers, text,
// axes with round ticks, colour bars and legends. Plots map their data into a pixel rectangle
// themselves (PlotFrame), so axes show true values whatever the aspect ratio.
#pragma once

#include "figure.hpp"
#include "palette.hpp"

#include <array>
#include <string>
#include <vector>

namespace spreadmap::render::detail {

using Point2 = std::array<double, 2>;

enum class Marker { circle, square, diamond, triangle, star };
enum class Side { bottom, left, right };
enum class LineStyle { solid, dashed };

struct LegendEntry {
  std::string label;
  Rgb colour{0, 0, 0};
  bool line = false;  // a line sample ...
  LineStyle style = LineStyle::solid;
  bool marker = false;  // ... and/or a marker sample
  Marker shape = Marker::circle;
  Rgb edge{0, 0, 0};
  Rgb fill_box{-1, -1, -1};  // a filled swatch (bands) when fill_box[0] >= 0
};

// Round tick values (1, 2, 5 x 10^k steps) inside [lo, hi], about `count` of them: never more than
// 2 count + 2, and none when a bound is not finite (a NaN, an infinity or a span that overflows).
std::vector<double> nice_ticks(double lo, double hi, int count);
double nice_step(double lo, double hi, int count);
// k step for the whole numbers k from k0 to k1, at most `max` of them; none unless all are finite.
// Counting k, not adding step, ends where step is below the spacing of doubles near the values.
std::vector<double> step_multiples(double k0, double k1, double step, std::size_t max);
std::string format_value(double v, double step);  // as many decimals as the step needs

class Canvas {
 public:
  Canvas(vtkRenderer* renderer, double scale) : r_(renderer), s_(scale) {}
  double s() const { return s_; }

  void polyline(const std::vector<Point2>& pts, const Rgb& colour, double width_px, LineStyle style = LineStyle::solid,
                bool closed = false, double opacity = 1.0);
  void rectangle(double x0, double y0, double x1, double y1, const Rgb& fill, double opacity = 1.0);
  void marker(double x, double y, Marker shape, double size_px, const Rgb& fill, const Rgb& edge);
  // halign: 0 left, 1 centre, 2 right; valign: 0 bottom, 1 centre, 2 top. A background box
  // (white, 75 % opaque) keeps labels readable over contours.
  void text(const std::string& s, double x, double y, double size_px, int halign = 0, int valign = 0,
            const Rgb& colour = {0, 0, 0}, double angle_deg = 0, bool bold = false, bool background = false);

  // An axis along a plot edge: pixel extent [p0, p1] along it, at pixel `at` across it, showing
  // values [v0, v1] (v at p0 .. p1). Returns the pixel distance its labels reach from the edge.
  double axis(Side side, double p0, double p1, double at, double v0, double v1, const std::string& title,
              int tick_count = 6, double font_px = 24);
  // A continuous colour bar in [x0, x0 + w] x [y0, y0 + h]: values lo..hi, title above.
  void colour_bar(double x0, double y0, double w, double h, ColourMap map, double lo, double hi,
                  const std::string& title, double font_px = 22);
  // A discrete colour bar: band i spans levels[i]..levels[i+1] in colours[i].
  void band_bar(double x0, double y0, double w, double h, const std::vector<double>& levels,
                const std::vector<Rgb>& colours, const std::string& title, double font_px = 22);
  // Legend box with its top-left corner at (x, y).
  void legend(double x, double y, const std::vector<LegendEntry>& entries, double font_px = 22);

 private:
  vtkRenderer* r_;
  double s_;
};

// Maps data (x, y) to a pixel rectangle.
struct PlotFrame {
  double px0, py0, pw, ph;  // pixel rectangle
  double x0, x1, y0, y1;    // data ranges
  double px(double x) const { return px0 + (x - x0) / (x1 - x0) * pw; }
  double py(double y) const { return py0 + (y - y0) / (y1 - y0) * ph; }
  Point2 at(double x, double y) const { return {px(x), py(y)}; }
};

// Draws the frame box and both axes of a plot.
void draw_frame(Canvas& c, const PlotFrame& f, const std::string& x_title, const std::string& y_title, double font_px,
                int x_ticks = 7, int y_ticks = 6, bool grid = false);

}  // namespace spreadmap::render::detail
