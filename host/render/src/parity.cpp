// Parity plots: predicted against simulated value, one square panel per output side by side,
// training fit, test rows and out-of-fold (cross-validated) predictions in different colours and
// shapes, the y = x line, Pearson R of each in the legend.
#include "canvas2d.hpp"
#include "figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace spreadmap::render {

namespace {
double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  if (n < 2 || b.size() != n) return std::numeric_limits<double>::quiet_NaN();
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : std::numeric_limits<double>::quiet_NaN();
}

std::string r_text(double r) {
  if (!std::isfinite(r)) return "R n/a";
  char b[32];
  std::snprintf(b, sizeof b, "R = %.4f", r);
  return b;
}
}  // namespace

void parity(const ParityInput& in, const std::filesystem::path& png, const Options& opt) {
  using namespace detail;
  if (in.panels.empty()) throw RenderError("render: parity needs at least one panel (one per output)");
  for (const auto& p : in.panels)
    if (p.train_simulated.size() != p.train_predicted.size() || p.test_simulated.size() != p.test_predicted.size() ||
        p.cv_simulated.size() != p.cv_predicted.size())
      throw RenderError("render: parity panel '" + p.quantity.name +
                        "': simulated and predicted arrays differ in length");
  auto lock = lock_rendering();
  Figure fig(opt);
  const double s = fig.scale(), font = 22 * s;
  Canvas c(fig.renderer(), s);
  const Rgb train_colour{0.12, 0.47, 0.71}, test_colour{0.95, 0.45, 0.05}, cv_colour{0.8, 0.1, 0.45};
  const std::size_t n = in.panels.size();
  const double top = (opt.title.empty() ? 50 : 100) * s, bottom = 140 * s, gap = 170 * s, left = 170 * s;
  const double cell_w = (fig.width() - left - 60 * s - gap * (n - 1)) / n;
  const double side = std::min(cell_w, fig.height() - top - bottom);
  const double used = n * side + (n - 1) * gap;
  const double x_start = left + 0.5 * (fig.width() - left - 60 * s - used);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& p = in.panels[k];
    const auto unit = display_unit(p.quantity.unit);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto* v : {&p.train_simulated, &p.train_predicted, &p.test_simulated, &p.test_predicted,
                          &p.cv_simulated, &p.cv_predicted})
      for (double x : *v)
        if (std::isfinite(x)) lo = std::min(lo, x * unit.scale), hi = std::max(hi, x * unit.scale);
    if (!(hi >= lo)) lo = 0, hi = 1;
    if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) lo -= 0.5, hi += 0.5;
    const double pad = 0.06 * (hi - lo);
    const double step = nice_step(lo - pad, hi + pad, 6);
    lo = std::floor((lo - pad) / step) * step;
    hi = std::ceil((hi + pad) / step) * step;
    PlotFrame f{x_start + k * (side + gap), bottom, side, side, lo, hi, lo, hi};
    draw_frame(c, f, "simulated " + axis_label(p.quantity.name, unit.label),
               "predicted " + axis_label(p.quantity.name, unit.label), font, 6, 6, true);
    c.polyline({f.at(lo, lo), f.at(hi, hi)}, {0.3, 0.3, 0.3}, 2 * s, LineStyle::dashed);
    const double ms = 16 * s;
    for (std::size_t i = 0; i < p.train_simulated.size(); ++i)
      c.marker(f.px(p.train_simulated[i] * unit.scale), f.py(p.train_predicted[i] * unit.scale), Marker::circle, ms,
               train_colour, {0, 0, 0});
    // out-of-fold predictions under the fit: the error to expect on a new case
    for (std::size_t i = 0; i < p.cv_simulated.size(); ++i)
      c.marker(f.px(p.cv_simulated[i] * unit.scale), f.py(p.cv_predicted[i] * unit.scale), Marker::square, 0.9 * ms,
               cv_colour, {0, 0, 0});
    for (std::size_t i = 0; i < p.test_simulated.size(); ++i)
      c.marker(f.px(p.test_simulated[i] * unit.scale), f.py(p.test_predicted[i] * unit.scale), Marker::diamond,
               1.1 * ms, test_colour, {0, 0, 0});
    c.text(p.quantity.name, f.px0 + 0.5 * f.pw, f.py0 + f.ph + 10 * s, 26 * s, 1, 0, {0, 0, 0}, 0, true);
    std::vector<LegendEntry> legend;
    legend.push_back({"train (" + std::to_string(p.train_simulated.size()) + "), " +
                          r_text(pearson(p.train_simulated, p.train_predicted)),
                      train_colour, false, LineStyle::solid, true, Marker::circle});
    if (!p.test_simulated.empty())
      legend.push_back({"test (" + std::to_string(p.test_simulated.size()) + "), " +
                            r_text(pearson(p.test_simulated, p.test_predicted)),
                        test_colour, false, LineStyle::solid, true, Marker::diamond});
    if (!p.cv_simulated.empty())
      legend.push_back({"cross-validated (" + std::to_string(p.cv_simulated.size()) + "), " +
                            r_text(pearson(p.cv_simulated, p.cv_predicted)),
                        cv_colour, false, LineStyle::solid, true, Marker::square});
    legend.push_back({"y = x", {0.3, 0.3, 0.3}, true, LineStyle::dashed});
    c.legend(f.px0 + 12 * s, f.py0 + f.ph - 12 * s, legend, 20 * s);
  }
  fig.add_title();
  fig.write(png);
}

}  // namespace spreadmap::render
