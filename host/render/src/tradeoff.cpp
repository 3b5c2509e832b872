// The speed-accuracy trade: the error of each fidelity against the reference (|error| in % of the
// reference's mean) over its cost, both axes logarithmic. V_s and R_q are two marker series; the
// heap-to-heap scatter of the reference (its relative standard deviation) is drawn for each as a
// dashed line: errors below their line are inside the noise of a single case. The reference has
// no error of its own; a dotted vertical line marks its cost.
#include "canvas2d.hpp"
#include "figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace spreadmap::render {

namespace {

// Decade bounds [10^lo, 10^hi] around the positive values, at least one decade wide.
std::array<double, 2> decades(const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (v > 0 && std::isfinite(v)) lo = std::min(lo, std::log10(v)), hi = std::max(hi, std::log10(v));
  if (!(hi >= lo)) return {0, 1};
  lo = std::floor(lo - 0.15), hi = std::ceil(hi + 0.15);
  if (hi - lo < 1) hi = lo + 1;
  return {lo, hi};
}

std::string decade_label(int k) {
  char b[32];
  if (k >= 0) std::snprintf(b, sizeof b, "%.0f", std::pow(10.0, k));
  else std::snprintf(b, sizeof b, "%.*f", -k, std::pow(10.0, k));
  return b;
}

// Ticks at 1, 2 and 5 x 10^k (labels at the decades), frame and titles of a log-log plot.
void log_log_frame(detail::Canvas& c, const detail::PlotFrame& f, const std::string& x_title,
                   const std::string& y_title, double font) {
  using namespace detail;
  const double s = c.s(), tick = 8 * s, minor = 5 * s, pad = 6 * s, lw = std::max(1.0, 1.5 * s);
  const Rgb grid{0.88, 0.88, 0.88};
  c.polyline({{f.px0, f.py0}, {f.px0 + f.pw, f.py0}, {f.px0 + f.pw, f.py0 + f.ph}, {f.px0, f.py0 + f.ph}}, {0, 0, 0},
             lw, LineStyle::solid, true);
  std::size_t longest = 0;
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = axis == 0 ? f.x0 : f.y0, hi = axis == 0 ? f.x1 : f.y1;
    for (int k = int(lo); k <= int(hi); ++k)
      for (double m : {1.0, 2.0, 5.0}) {
        const double v = k + std::log10(m);
        if (v < lo - 1e-9 || v > hi + 1e-9) continue;
        const bool major = m == 1.0;
        const double len = major ? tick : minor;
        if (axis == 0) {
          const double p = f.px(v);
          if (major) c.polyline({{p, f.py0}, {p, f.py0 + f.ph}}, grid, s);
          c.polyline({{p, f.py0}, {p, f.py0 - len}}, {0, 0, 0}, lw);
          if (major) c.text(decade_label(k), p, f.py0 - tick - pad, font, 1, 2);
        } else {
          const double p = f.py(v);
          if (major) c.polyline({{f.px0, p}, {f.px0 + f.pw, p}}, grid, s);
          c.polyline({{f.px0, p}, {f.px0 - len, p}}, {0, 0, 0}, lw);
          if (major) {
            const std::string label = decade_label(k);
            longest = std::max(longest, label.size());
            c.text(label, f.px0 - tick - pad, p, font, 2, 1);
          }
        }
      }
  }
  c.text(x_title, f.px0 + 0.5 * f.pw, f.py0 - tick - 2 * pad - 1.3 * font, 1.1 * font, 1, 2);
  c.text(y_title, f.px0 - tick - 3 * pad - 0.62 * font * double(longest), f.py0 + 0.5 * f.ph, 1.1 * font, 1, 0,
         {0, 0, 0}, 90);
}

}  // namespace

void tradeoff(const TradeoffInput& in, const std::filesystem::path& png, const Options& opt) {
  using namespace detail;
  if (in.points.empty()) throw RenderError("render: tradeoff needs at least one fidelity");
  std::vector<double> costs, errors;
  for (const auto& p : in.points) {
    if (!(p.cost > 0) || !std::isfinite(p.cost))
      throw RenderError("render: tradeoff fidelity '" + p.name + "' has no positive cost (" + std::to_string(p.cost) +
                        ")");
    costs.push_back(p.cost);
    if (p.reference) continue;
    errors.push_back(std::abs(p.vs_error));
    errors.push_back(std::abs(p.rq_error));
  }
  errors.push_back(in.vs_scatter);
  errors.push_back(in.rq_scatter);
  auto lock = lock_rendering();
  Figure fig(opt);
  const double s = fig.scale(), font = 22 * s;
  Canvas c(fig.renderer(), s);
  const auto xr = decades(costs), yr = decades(errors);
  const double top = (opt.title.empty() ? 60 : 110) * s, left = 190 * s, bottom = 150 * s, right = 60 * s;
  PlotFrame f{left, bottom, fig.width() - left - right, fig.height() - top - bottom, xr[0], xr[1], yr[0], yr[1]};
  log_log_frame(c, f, in.cost_label, "|error against the reference| [%]", font);
  const Rgb vs_colour{0.12, 0.47, 0.71}, rq_colour{0.84, 0.15, 0.16};
  const double ms = 18 * s;
  auto clamp_y = [&](double v) { return std::clamp(std::log10(std::max(v, 1e-300)), f.y0, f.y1); };
  for (const auto& [level, colour] : {std::pair{in.vs_scatter, vs_colour}, std::pair{in.rq_scatter, rq_colour}})
    if (level > 0)
      c.polyline({f.at(f.x0, clamp_y(level)), f.at(f.x1, clamp_y(level))}, colour, 2 * s, LineStyle::dashed);
  for (const auto& p : in.points) {
    const double x = std::log10(p.cost);
    if (p.reference) {
      c.polyline({f.at(x, f.y0), f.at(x, f.y1)}, {0.35, 0.35, 0.35}, 2 * s, LineStyle::dashed, false, 0.6);
      c.text(p.name, f.px(x) - 8 * s, f.py0 + 12 * s, 0.9 * font, 2, 0, {0.3, 0.3, 0.3}, 0, false, true);
      continue;
    }
    const double yv = clamp_y(std::abs(p.vs_error)), yr_ = clamp_y(std::abs(p.rq_error));
    c.marker(f.px(x), f.py(yv), Marker::circle, ms, vs_colour, {0, 0, 0});
    c.marker(f.px(x), f.py(yr_), Marker::diamond, 1.1 * ms, rq_colour, {0, 0, 0});
    c.text(p.name, f.px(x) + 14 * s, f.py(std::max(yv, yr_)) + 10 * s, 0.85 * font, 0, 0, {0.15, 0.15, 0.15}, 0, false,
           true);
  }
  std::vector<LegendEntry> legend{
      {"V_s", vs_colour, false, LineStyle::solid, true, Marker::circle},
      {"R_q", rq_colour, false, LineStyle::solid, true, Marker::diamond},
      {"V_s heap-to-heap scatter (reference)", vs_colour, true, LineStyle::dashed},
      {"R_q heap-to-heap scatter (reference)", rq_colour, true, LineStyle::dashed},
  };
  // top right: cheap fidelities err most (top left), the reference sits right
  c.legend(f.px0 + f.pw - 560 * s, f.py0 + f.ph - 14 * s, legend, 20 * s);
  fig.add_title();
  fig.write(png);
}

}  // namespace spreadmap::render
