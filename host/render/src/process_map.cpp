// The process map over (U, omega): R_q as filled bands (yellow = smooth .. red = rough), V_s as
// labelled lines, the model's standard deviation as dashed labelled lines when it has one, the
// efficient frontier and the chosen optimum. Values in um and mm^2/s, U in mm/s, omega in rad/s.
#include "canvas2d.hpp"
#include "figure.hpp"
#include "palette.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <vtkActor2D.h>
#include <vtkBandedPolyDataContourFilter.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkContourFilter.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkStripper.h>
#include <vtkUnsignedCharArray.h>

namespace spreadmap::render {

namespace {
using detail::Point2;
using detail::Rgb;

// Triangulated grid in pixel coordinates with one named point array per field (display units).
vtkSmartPointer<vtkPolyData> pixel_grid(const detail::PlotFrame& f, const MapInput& in) {
  const std::size_t nu = in.u.size(), nw = in.omega.size();
  vtkNew<vtkPoints> pts;
  for (std::size_t j = 0; j < nw; ++j)
    for (std::size_t i = 0; i < nu; ++i) pts->InsertNextPoint(f.px(in.u[i] * 1e3), f.py(in.omega[j]), 0);
  vtkNew<vtkCellArray> tris;
  for (std::size_t j = 0; j + 1 < nw; ++j)
    for (std::size_t i = 0; i + 1 < nu; ++i) {
      const vtkIdType a = static_cast<vtkIdType>(j * nu + i), b = a + 1, d = a + static_cast<vtkIdType>(nu), c = d + 1;
      const vtkIdType t1[3] = {a, b, c}, t2[3] = {a, c, d};
      tris->InsertNextCell(3, t1);
      tris->InsertNextCell(3, t2);
    }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(tris);
  auto add = [&](const char* name, const std::vector<double>& v, double scale) {
    if (v.empty()) return;
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    for (double x : v) a->InsertNextValue(static_cast<float>(x * scale));
    pd->GetPointData()->AddArray(a);
  };
  add("rq", in.rq, 1e6);
  add("vs", in.vs, 1e6);
  add("rq_std", in.rq_std, 1e6);
  add("vs_std", in.vs_std, 1e6);
  return pd;
}

std::vector<double> auto_levels(const std::vector<double>& field, double scale, int count) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : field)
    if (std::isfinite(v)) lo = std::min(lo, v * scale), hi = std::max(hi, v * scale);
  if (!(hi > lo)) return {};
  const double step = detail::nice_step(lo, hi, count);
  // from the multiple at or below lo to the first at or above hi
  return detail::step_multiples(std::floor(lo / step), std::ceil(hi / step + 0.999) - 1, step,
                                2 * std::size_t(count) + 4);
}

std::vector<double> scaled(const std::vector<double>& v, double scale) {
  std::vector<double> out;
  for (double x : v) out.push_back(x * scale);
  return out;
}

// Polylines of one iso-value of a named point array.
std::vector<std::vector<Point2>> iso_lines(vtkPolyData* grid, const char* array, double value) {
  grid->GetPointData()->SetActiveScalars(array);
  vtkNew<vtkContourFilter> contour;
  contour->SetInputData(grid);
  contour->SetValue(0, value);
  vtkNew<vtkStripper> strip;
  strip->SetInputConnection(contour->GetOutputPort());
  strip->JoinContiguousSegmentsOn();
  strip->Update();
  std::vector<std::vector<Point2>> out;
  vtkPolyData* pd = strip->GetOutput();
  auto* lines = pd->GetLines();
  lines->InitTraversal();
  vtkIdType n;
  const vtkIdType* ids;
  while (lines->GetNextCell(n, ids)) {
    std::vector<Point2> line;
    for (vtkIdType k = 0; k < n; ++k) {
      double p[3];
      pd->GetPoint(ids[k], p);
      line.push_back({p[0], p[1]});
    }
    out.push_back(std::move(line));
  }
  return out;
}

// Point at fraction t of a polyline's length, and the polyline's length.
std::pair<Point2, double> along(const std::vector<Point2>& line, double t) {
  double total = 0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    total += std::hypot(line[i + 1][0] - line[i][0], line[i + 1][1] - line[i][1]);
  double goal = t * total;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const double seg = std::hypot(line[i + 1][0] - line[i][0], line[i + 1][1] - line[i][1]);
    if (goal <= seg && seg > 0) {
      const double w = goal / seg;
      return {{line[i][0] + w * (line[i + 1][0] - line[i][0]), line[i][1] + w * (line[i + 1][1] - line[i][1])}, total};
    }
    goal -= seg;
  }
  return {line.back(), total};
}

std::string value_text(double v, double step, const std::string& unit) {
  return detail::format_value(v, step) + " " + unit;
}

double level_step(const std::vector<double>& levels) {
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < levels.size(); ++i) step = std::min(step, std::abs(levels[i + 1] - levels[i]));
  return std::isfinite(step) ? step : 1.0;
}

// Label boxes already drawn (pixels), so that a new label goes where it covers none of them.
struct LabelBoxes {
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> boxes;
  // The box of a centred one-line label of `chars` characters (UTF-8 bytes overcount a little).
  static Box around(double x, double y, std::size_t chars, double font) {
    const double half_w = 0.3 * font * double(chars) + 4, half_h = 0.65 * font + 2;
    return {x - half_w, y - half_h, x + half_w, y + half_h};
  }
  bool free(const Box& b) const {
    for (const auto& o : boxes)
      if (b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1) return false;
    return true;
  }
};

// Draws every iso-line of `levels`, each labelled where its label covers no earlier one: at fraction
// `where` of the line if free, else at the nearest free fraction, else not at all.
void labelled_lines(detail::Canvas& c, vtkPolyData* grid, const char* array, const std::vector<double>& levels,
                    const Rgb& colour, double width, detail::LineStyle style, const std::string& prefix,
                    const std::string& unit, double where, double font, LabelBoxes& placed) {
  const double step = level_step(levels);
  for (double level : levels)
    for (const auto& line : iso_lines(grid, array, level)) {
      c.polyline(line, colour, width, style);
      const std::string text = prefix + value_text(level, step, unit);
      for (double shift : {0.0, 0.12, -0.12, 0.24, -0.24, 0.36, -0.36}) {
        const double t = where + shift;
        if (t < 0.05 || t > 0.95) continue;
        const auto [p, length] = along(line, t);
        if (length <= 160 * c.s()) break;
        const auto box = LabelBoxes::around(p[0], p[1], text.size(), font);
        if (!placed.free(box)) continue;
        c.text(text, p[0], p[1], font, 1, 1, colour, 0, false, true);
        placed.boxes.push_back(box);
        break;
      }
    }
}
}  // namespace

void process_map(const MapInput& in, const std::filesystem::path& png, const Options& opt) {
  using namespace detail;
  const std::size_t nu = in.u.size(), nw = in.omega.size(), n = nu * nw;
  if (nu < 2 || nw < 2 || in.vs.size() != n || in.rq.size() != n)
    throw RenderError(
        "render: process_map needs at least 2 x 2 grid axes and u.size() * omega.size() values of vs "
        "and rq (" +
        std::to_string(nu) + " x " + std::to_string(nw) + ", vs " + std::to_string(in.vs.size()) + ", rq " +
        std::to_string(in.rq.size()) + ")");
  if ((!in.rq_std.empty() && in.rq_std.size() != n) || (!in.vs_std.empty() && in.vs_std.size() != n))
    throw RenderError("render: process_map rq_std / vs_std must be empty or have u.size() * omega.size() values");
  auto lock = lock_rendering();
  const std::string um = display_unit("m").label, mm2s = display_unit("m^2/s").label, w = omega_symbol();

  Figure fig(opt);
  const double s = fig.scale(), font = 24 * s;
  Canvas c(fig.renderer(), s);
  const double left = 150 * s, right = 430 * s, bottom = 140 * s, top = (opt.title.empty() ? 40 : 90) * s;
  PlotFrame f{left,
              bottom,
              fig.width() - left - right,
              fig.height() - bottom - top,
              in.u.front() * 1e3,
              in.u.back() * 1e3,
              in.omega.front(),
              in.omega.back()};
  auto grid = pixel_grid(f, in);

  // R_q bands, coloured by the band each piece lies in (mean of its corner values: the field is
  // linear on each piece, so that mean is inside the band).
  std::vector<double> rq_levels = in.rq_levels.empty() ? auto_levels(in.rq, 1e6, 8) : scaled(in.rq_levels, 1e6);
  std::sort(rq_levels.begin(), rq_levels.end());
  std::vector<Rgb> band_colours;
  // An untrusted R_q map keeps its bands but in greys: still readable, plainly not a result.
  for (std::size_t i = 0; i + 1 < rq_levels.size(); ++i) {
    const double t = rq_levels.size() > 2 ? i / double(rq_levels.size() - 2) : 0.5;
    band_colours.push_back(in.rq_greyed ? Rgb{0.93 - 0.35 * t, 0.93 - 0.35 * t, 0.93 - 0.35 * t}
                                        : colour_at(ColourMap::yellow_red, t));
  }
  LabelBoxes placed;  // every contour label, so that none is drawn over another
  if (rq_levels.size() >= 2) {
    grid->GetPointData()->SetActiveScalars("rq");
    vtkNew<vtkBandedPolyDataContourFilter> bands;
    bands->SetInputData(grid);
    for (std::size_t i = 0; i < rq_levels.size(); ++i) bands->SetValue(static_cast<int>(i), rq_levels[i]);
    bands->ClippingOff();
    bands->Update();
    vtkPolyData* out = bands->GetOutput();
    vtkDataArray* values = out->GetPointData()->GetArray("rq");
    if (!values) values = out->GetPointData()->GetScalars();
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetNumberOfComponents(3);
    for (vtkIdType cell = 0; cell < out->GetNumberOfCells(); ++cell) {
      vtkIdType np;
      const vtkIdType* ids;
      out->GetCellPoints(cell, np, ids);
      double mean = 0;
      for (vtkIdType k = 0; k < np; ++k) mean += values ? values->GetComponent(ids[k], 0) : 0;
      mean /= std::max<vtkIdType>(np, 1);
      std::size_t band = 0;
      while (band + 1 < band_colours.size() && mean > rq_levels[band + 1]) ++band;
      const Rgb col = band_colours[band];
      rgb->InsertNextTuple3(255 * col[0], 255 * col[1], 255 * col[2]);
    }
    out->GetCellData()->SetScalars(rgb);
    vtkNew<vtkPolyDataMapper2D> mapper;
    mapper->SetInputData(out);
    mapper->SetScalarModeToUseCellData();
    mapper->SetColorModeToDirectScalars();
    vtkNew<vtkActor2D> actor;
    actor->SetMapper(mapper);
    fig.renderer()->AddActor2D(actor);
    // Thin band edges, labelled near the lower-left third, away from most V_s labels.
    labelled_lines(c, grid, "rq", rq_levels, {0.45, 0.2, 0.1}, 1.2 * s, LineStyle::solid, "", um, 0.3, 17 * s, placed);
  }

  const Rgb vs_colour = in.vs_greyed ? Rgb{0.5, 0.5, 0.5} : Rgb{0.05, 0.1, 0.35};
  const Rgb std_colour{0.45, 0.1, 0.6}, frontier_colour{0.0, 0.45, 0.95};
  const auto vs_levels = in.vs_levels.empty() ? auto_levels(in.vs, 1e6, 7) : scaled(in.vs_levels, 1e6);
  labelled_lines(c, grid, "vs", vs_levels, vs_colour, 2.8 * s, in.vs_greyed ? LineStyle::dashed : LineStyle::solid,
                 "", mm2s, 0.65, 19 * s, placed);

  const bool has_std = !in.rq_std.empty();
  if (has_std) {
    const auto std_levels = in.std_levels.empty() ? auto_levels(in.rq_std, 1e6, 3) : scaled(in.std_levels, 1e6);
    labelled_lines(c, grid, "rq_std", std_levels, std_colour, 2.2 * s, LineStyle::dashed,
                   unicode_text() ? "σ " : "std ", um, 0.5, 17 * s, placed);
  }

  if (in.frontier.size() >= 2) {
    std::vector<Point2> line;
    for (const auto& p : in.frontier) line.push_back(f.at(p.u * 1e3, p.omega));
    c.polyline(line, {1, 1, 1}, 7.5 * s);  // halo keeps it visible on every band
    c.polyline(line, frontier_colour, 4.5 * s);
  }
  const Rgb case_colour{1, 1, 1};
  for (const auto& q : in.cases) {
    const Point2 p = f.at(q.u * 1e3, q.omega);
    c.marker(p[0], p[1], Marker::circle, 15 * s, case_colour, {0, 0, 0});
  }
  // proposed: green; verified by simulation: blue; simulated outside its interval: red
  const Rgb optimum_colour = in.optimum.verified < 0    ? Rgb{0.2, 0.95, 0.3}
                             : in.optimum.verified == 1 ? Rgb{0.1, 0.55, 1.0}
                                                        : Rgb{0.95, 0.15, 0.1};
  const std::string optimum_name = in.optimum.verified < 0    ? "optimum (proposed)"
                                   : in.optimum.verified == 1 ? "optimum, verified"
                                                              : "optimum, NOT verified";
  if (in.optimum.found) {
    const Point2 p = f.at(in.optimum.u * 1e3, in.optimum.omega);
    c.marker(p[0], p[1], Marker::star, 44 * s, optimum_colour, {0, 0, 0});
    char label[256];
    std::snprintf(label, sizeof label, "%s\nU = %.1f mm/s, %s = %.1f rad/s\nV_s = %.3g %s, R_q = %.1f %s%s",
                  optimum_name.c_str(), in.optimum.u * 1e3, w.c_str(), in.optimum.omega, in.optimum.vs * 1e6,
                  mm2s.c_str(), in.optimum.rq * 1e6, um.c_str(), "");
    std::string text = label;
    const char* le = unicode_text() ? "≤" : "<=";
    if (in.rq_target > 0) {
      char t[64];
      std::snprintf(t, sizeof t, "\nfor the target R_q %s %.1f %s", le, in.rq_target * 1e6, um.c_str());
      text += t;
    }
    if (in.optimum.probability >= 0 && in.rq_target > 0) {
      char t[96];
      std::snprintf(t, sizeof t, "\nP(R_q %s target) = %.2f%s", le, in.optimum.probability,
                    in.optimum.confidence > 0.5 ? "" : " (chosen by the mean)");
      text += t;
      if (in.optimum.confidence > 0.5) {
        std::snprintf(t, sizeof t, " %s %.2f asked", unicode_text() ? "≥" : ">=", in.optimum.confidence);
        text += t;
      }
    }
    if (in.rq_greyed || in.vs_greyed) text += "\nrests on an UNTRUSTED map";
    // on the side of the star where the label fits inside the plot (its longest line decides)
    std::size_t longest = 0, from = 0;
    for (std::size_t k = 0; k <= text.size(); ++k)
      if (k == text.size() || text[k] == '\n') longest = std::max(longest, k - from), from = k + 1;
    const double label_px = 0.55 * 19 * s * double(longest) + 30 * s;
    const bool left = p[0] + label_px > f.px0 + f.pw && p[0] - label_px >= f.px0;
    const bool upper_half = p[1] > f.py0 + 0.5 * f.ph;
    c.text(text, p[0] + (left ? -30 : 30) * s, p[1] + (upper_half ? -30 : 30) * s, 19 * s, left ? 2 : 0,
           upper_half ? 2 : 0, {0, 0, 0}, 0, false, true);
  }

  // What cannot be trusted, said on the figure itself, top left of the plot.
  for (std::size_t k = 0; k < in.notes.size(); ++k)
    c.text(in.notes[k], f.px0 + 14 * s, f.py0 + f.ph - (16 + 30 * double(k)) * s, 19 * s, 0, 2, {0.7, 0.0, 0.0}, 0,
           true, true);

  draw_frame(c, f, "U [mm/s]", w + " [rad/s]", font, 7, 8);

  // Right column: R_q colour key, then the legend.
  const double col_x = f.px0 + f.pw + 60 * s;
  if (rq_levels.size() >= 2)
    c.band_bar(col_x, f.py0 + 0.42 * f.ph, 36 * s, 0.46 * f.ph, rq_levels, band_colours, "R_q [" + um + "]", 21 * s);
  std::vector<LegendEntry> legend;
  legend.push_back({"R_q bands [" + um + "]",
                    {0.45, 0.2, 0.1},
                    false,
                    LineStyle::solid,
                    false,
                    Marker::circle,
                    {0, 0, 0},
                    band_colours.empty() ? Rgb{-1, -1, -1} : band_colours[band_colours.size() / 2]});
  legend.push_back({"V_s [" + mm2s + "]", vs_colour, true});
  if (has_std)
    legend.push_back(
        {std::string(unicode_text() ? "σ" : "std") + "(R_q) model [" + um + "]", std_colour, true, LineStyle::dashed});
  if (in.frontier.size() >= 2) legend.push_back({"efficient frontier", frontier_colour, true});
  if (!in.cases.empty())
    legend.push_back({"simulated cases", case_colour, false, LineStyle::solid, true, Marker::circle, {0, 0, 0}});
  if (in.optimum.found) legend.push_back({optimum_name, optimum_colour, false, LineStyle::solid, true, Marker::star});
  c.legend(col_x - 20 * s, f.py0 + 0.38 * f.ph, legend, 19 * s);
  fig.add_title();
  fig.write(png);
}

}  // namespace spreadmap::render
