#include "canvas2d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <vtkActor2D.h>
#include <vtkCellArray.h>
#include <vtkCoordinate.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty2D.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

namespace spreadmap::render::detail {

namespace {
using std::numbers::pi;

vtkSmartPointer<vtkActor2D> actor_for(vtkPolyData* pd, const Rgb& colour, double opacity) {
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(pd);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor2D>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  actor->GetProperty()->SetOpacity(opacity);
  return actor;
}

// Outline of a marker of unit size, centred at the origin (star: alternating radii).
std::vector<Point2> marker_outline(Marker shape) {
  std::vector<Point2> p;
  auto ring = [&](int n, double phase, double r_out, double r_in) {
    for (int i = 0; i < n; ++i) {
      const double a = phase + 2 * pi * i / n;
      const double r = (r_in > 0 && i % 2 == 1) ? r_in : r_out;
      p.push_back({r * std::cos(a), r * std::sin(a)});
    }
  };
  switch (shape) {
    case Marker::circle:
      ring(24, 0, 0.5, 0);
      break;
    case Marker::square:
      ring(4, pi / 4, 0.5 * std::sqrt(2.0) * 0.85, 0);
      break;
    case Marker::diamond:
      ring(4, 0, 0.6, 0);
      break;
    case Marker::triangle:
      ring(3, pi / 2, 0.6, 0);
      break;
    case Marker::star:
      ring(10, pi / 2, 0.7, 0.3);
      break;
  }
  return p;
}

// Filled, star-shaped polygon as a triangle fan around `centre` (valid for all our markers).
vtkSmartPointer<vtkPolyData> fan(const Point2& centre, const std::vector<Point2>& ring) {
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(centre[0], centre[1], 0);
  for (const auto& q : ring) pts->InsertNextPoint(q[0], q[1], 0);
  vtkNew<vtkCellArray> tris;
  const vtkIdType n = static_cast<vtkIdType>(ring.size());
  for (vtkIdType i = 0; i < n; ++i) {
    const vtkIdType t[3] = {0, 1 + i, 1 + (i + 1) % n};
    tris->InsertNextCell(3, t);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(tris);
  return pd;
}
}  // namespace

double nice_step(double lo, double hi, int count) {
  const double span = std::abs(hi - lo);
  if (!(span > 0) || count < 1) return 1.0;
  const double raw = span / count;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  const double nice = f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10;
  return nice * mag;
}

std::vector<double> step_multiples(double k0, double k1, double step, std::size_t max) {
  std::vector<double> out;
  if (!std::isfinite(k0) || !std::isfinite(k1) || !std::isfinite(step) || !(step > 0)) return out;
  for (double k = k0; k <= k1 && out.size() < max; ++k) {
    out.push_back(k * step);
    if (k + 1 == k) break;  // past 2^53 a double holds no next whole number
  }
  return out;
}

std::vector<double> nice_ticks(double lo, double hi, int count) {
  if (lo > hi) std::swap(lo, hi);
  const double step = nice_step(lo, hi, count);
  const double eps = 1e-9 * step;
  constexpr std::size_t most = 1000;  // far more than an axis can label, however large count is
  auto t = step_multiples(std::ceil((lo - eps) / step), std::floor((hi + eps) / step), step,
                          std::min(2 * std::size_t(std::max(count, 1)) + 2, most));
  for (double &v : t)
    if (std::abs(v) < eps) v = 0.0;
  return t;
}

std::string format_value(double v, double step) {
  int decimals = 0;
  if (step > 0) decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  // 2.5-type steps need one more digit than their magnitude says.
  if (step > 0 &&
      std::abs(std::round(step / std::pow(10.0, -decimals)) * std::pow(10.0, -decimals) - step) > 1e-9 * step)
    ++decimals;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 8), v);
  std::string s = buf;
  if (s == "-0" || (s.rfind("-0.", 0) == 0 && std::stod(s) == 0)) s = s.substr(1);
  return s;
}

void Canvas::polyline(const std::vector<Point2>& pts, const Rgb& colour, double width_px, LineStyle style, bool closed,
                      double opacity) {
  if (pts.size() < 2) return;
  std::vector<Point2> path = pts;
  if (closed) path.push_back(pts.front());
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  if (style == LineStyle::solid) {
    for (const auto& p : path) points->InsertNextPoint(p[0], p[1], 0);
    lines->InsertNextCell(static_cast<vtkIdType>(path.size()));
    for (vtkIdType i = 0; i < static_cast<vtkIdType>(path.size()); ++i) lines->InsertCellPoint(i);
  } else {
    // OpenGL2 has no line stipple: cut the path into dashes measured along its length.
    const double dash = 12 * s_, gap = 8 * s_;
    double phase = 0;  // distance into the current dash+gap period
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const Point2 a = path[i], b = path[i + 1];
      const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
      if (!(len < 1e6)) continue;  // a NaN, infinite or absurd point: millions of dashes off any figure
      double d = 0;
      while (d < len) {
        const bool on = phase < dash;
        const double step = std::min(len - d, on ? dash - phase : dash + gap - phase);
        if (on) {
          const vtkIdType i0 =
              points->InsertNextPoint(a[0] + (b[0] - a[0]) * d / len, a[1] + (b[1] - a[1]) * d / len, 0);
          const vtkIdType i1 = points->InsertNextPoint(a[0] + (b[0] - a[0]) * (d + step) / len,
                                                       a[1] + (b[1] - a[1]) * (d + step) / len, 0);
          const vtkIdType seg[2] = {i0, i1};
          lines->InsertNextCell(2, seg);
        }
        d += step;
        phase = std::fmod(phase + step, dash + gap);
      }
    }
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetLines(lines);
  auto actor = actor_for(pd, colour, opacity);
  actor->GetProperty()->SetLineWidth(static_cast<float>(width_px));
  r_->AddActor2D(actor);
}

void Canvas::rectangle(double x0, double y0, double x1, double y1, const Rgb& fill, double opacity) {
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(x0, y0, 0);
  pts->InsertNextPoint(x1, y0, 0);
  pts->InsertNextPoint(x1, y1, 0);
  pts->InsertNextPoint(x0, y1, 0);
  vtkNew<vtkCellArray> polys;
  const vtkIdType q[4] = {0, 1, 2, 3};
  polys->InsertNextCell(4, q);
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  r_->AddActor2D(actor_for(pd, fill, opacity));
}

void Canvas::marker(double x, double y, Marker shape, double size_px, const Rgb& fill, const Rgb& edge) {
  auto ring = marker_outline(shape);
  for (auto& q : ring) q = {x + q[0] * size_px, y + q[1] * size_px};
  r_->AddActor2D(actor_for(fan({x, y}, ring), fill, 1.0));
  polyline(ring, edge, std::max(1.0, 1.5 * s_), LineStyle::solid, true);
}

void Canvas::text(const std::string& s, double x, double y, double size_px, int halign, int valign, const Rgb& colour,
                  double angle_deg, bool bold, bool background) {
  vtkNew<vtkTextActor> t;
  t->SetInput(s.c_str());
  auto* p = t->GetTextProperty();
  style_text(p, size_px, colour, bold);
  if (halign == 0) p->SetJustificationToLeft();
  else if (halign == 1) p->SetJustificationToCentered();
  else p->SetJustificationToRight();
  if (valign == 0) p->SetVerticalJustificationToBottom();
  else if (valign == 1) p->SetVerticalJustificationToCentered();
  else p->SetVerticalJustificationToTop();
  p->SetOrientation(angle_deg);
  if (background) {
    p->SetBackgroundColor(1, 1, 1);
    p->SetBackgroundOpacity(0.75);
  }
  t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
  t->SetPosition(x, y);
  r_->AddActor2D(t);
}

double Canvas::axis(Side side, double p0, double p1, double at, double v0, double v1, const std::string& title,
                    int tick_count, double font_px) {
  const double tick = 8 * s_, pad = 6 * s_, lw = std::max(1.0, 1.5 * s_);
  const double step = nice_step(v0, v1, tick_count);
  double reach = tick + pad;
  std::size_t longest = 0;
  for (double v : nice_ticks(v0, v1, tick_count)) {
    const double p = p0 + (v - v0) / (v1 - v0) * (p1 - p0);
    const std::string label = format_value(v, step);
    longest = std::max(longest, label.size());
    switch (side) {
      case Side::bottom:
        polyline({{p, at}, {p, at - tick}}, {0, 0, 0}, lw);
        text(label, p, at - tick - pad, font_px, 1, 2);
        break;
      case Side::left:
        polyline({{at, p}, {at - tick, p}}, {0, 0, 0}, lw);
        text(label, at - tick - pad, p, font_px, 2, 1);
        break;
      case Side::right:
        polyline({{at, p}, {at + tick, p}}, {0, 0, 0}, lw);
        text(label, at + tick + pad, p, font_px, 0, 1);
        break;
    }
  }
  const double mid = 0.5 * (p0 + p1);
  const double title_px = 1.1 * font_px;
  switch (side) {
    case Side::bottom:
      reach += 1.3 * font_px;
      text(title, mid, at - reach - pad, title_px, 1, 2);
      reach += 1.5 * title_px;
      break;
    case Side::left:
      reach += 0.62 * font_px * static_cast<double>(longest) + pad;
      text(title, at - reach - pad, mid, title_px, 1, 0, {0, 0, 0}, 90);
      reach += 1.5 * title_px;
      break;
    case Side::right:
      reach += 0.62 * font_px * static_cast<double>(longest) + pad;
      if (!title.empty()) text(title, at + reach + pad, mid, title_px, 1, 2, {0, 0, 0}, 90);
      reach += 1.5 * title_px;
      break;
  }
  return reach;
}

void Canvas::colour_bar(double x0, double y0, double w, double h, ColourMap map, double lo, double hi,
                        const std::string& title, double font_px) {
  const int n = 128;
  for (int i = 0; i < n; ++i) {
    const Rgb c = colour_at(map, (i + 0.5) / n);
    rectangle(x0, y0 + h * i / n, x0 + w, y0 + h * (i + 1) / n + 0.5, c);
  }
  polyline({{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}}, {0, 0, 0}, std::max(1.0, 1.2 * s_),
           LineStyle::solid, true);
  axis(Side::right, y0, y0 + h, x0 + w, lo, hi, "", 6, font_px);
  text(title, x0 + 0.5 * w, y0 + h + 12 * s_, 1.05 * font_px, 1, 0);
}

void Canvas::band_bar(double x0, double y0, double w, double h, const std::vector<double>& levels,
                      const std::vector<Rgb>& colours, const std::string& title, double font_px) {
  if (levels.size() < 2) return;
  const std::size_t bands = levels.size() - 1;
  double step = std::abs(levels.back() - levels.front());
  for (std::size_t i = 0; i + 1 < levels.size(); ++i) step = std::min(step, std::abs(levels[i + 1] - levels[i]));
  for (std::size_t i = 0; i < bands; ++i) {
    const double ya = y0 + h * i / bands, yb = y0 + h * (i + 1) / bands;
    rectangle(x0, ya, x0 + w, yb, colours[std::min(i, colours.size() - 1)]);
  }
  for (std::size_t i = 0; i <= bands; ++i) {
    const double y = y0 + h * i / bands;
    polyline({{x0, y}, {x0 + w + 8 * s_, y}}, {0, 0, 0}, std::max(1.0, 1.2 * s_));
    text(format_value(levels[i], step), x0 + w + 14 * s_, y, font_px, 0, 1);
  }
  polyline({{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}}, {0, 0, 0}, std::max(1.0, 1.2 * s_),
           LineStyle::solid, true);
  text(title, x0 + 0.5 * w, y0 + h + 12 * s_, 1.05 * font_px, 1, 0);
}

void Canvas::legend(double x, double y, const std::vector<LegendEntry>& entries, double font_px) {
  const double row = 1.6 * font_px, sample = 46 * s_, pad = 10 * s_;
  std::size_t longest = 0;
  for (const auto& e : entries) longest = std::max(longest, e.label.size());
  const double w = pad * 3 + sample + 0.58 * font_px * static_cast<double>(longest);
  const double h = pad * 2 + row * static_cast<double>(entries.size());
  rectangle(x, y - h, x + w, y, {1, 1, 1}, 0.88);
  polyline({{x, y - h}, {x + w, y - h}, {x + w, y}, {x, y}}, {0.4, 0.4, 0.4}, std::max(1.0, s_), LineStyle::solid,
           true);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const auto& e = entries[i];
    const double cy = y - pad - row * (static_cast<double>(i) + 0.5);
    const double sx0 = x + pad, sx1 = x + pad + sample;
    if (e.fill_box[0] >= 0) rectangle(sx0 + 4 * s_, cy - 0.35 * font_px, sx1 - 4 * s_, cy + 0.35 * font_px, e.fill_box);
    if (e.line) polyline({{sx0, cy}, {sx1, cy}}, e.colour, 3 * s_, e.style);
    if (e.marker) marker(0.5 * (sx0 + sx1), cy, e.shape, 0.75 * font_px, e.colour, e.edge);
    text(e.label, sx1 + pad, cy, font_px, 0, 1);
  }
}

void draw_frame(Canvas& c, const PlotFrame& f, const std::string& x_title, const std::string& y_title, double font_px,
                int x_ticks, int y_ticks, bool grid) {
  if (grid) {
    const Rgb g{0.88, 0.88, 0.88};
    for (double v : nice_ticks(f.x0, f.x1, x_ticks)) c.polyline({f.at(v, f.y0), f.at(v, f.y1)}, g, c.s());
    for (double v : nice_ticks(f.y0, f.y1, y_ticks)) c.polyline({f.at(f.x0, v), f.at(f.x1, v)}, g, c.s());
  }
  c.polyline({{f.px0, f.py0}, {f.px0 + f.pw, f.py0}, {f.px0 + f.pw, f.py0 + f.ph}, {f.px0, f.py0 + f.ph}}, {0, 0, 0},
             std::max(1.0, 1.5 * c.s()), LineStyle::solid, true);
  c.axis(Side::bottom, f.px0, f.px0 + f.pw, f.py0, f.x0, f.x1, x_title, x_ticks, font_px);
  c.axis(Side::left, f.py0, f.py0 + f.ph, f.px0, f.y0, f.y1, y_title, y_ticks, font_px);
}

}  // namespace spreadmap::render::detail
