// The sampled height map seen from above: one flat-coloured cell per sample (true aspect ratio),
// x and y in mm, heights in um on the colour bar, region size and cell size in the caption.
#include "canvas2d.hpp"
#include "figure.hpp"
#include "palette.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <vtkActor2D.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkLookupTable.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper2D.h>

namespace sm = spreadmap;

namespace spreadmap::render {

void heightmap(const HeightmapInput& in, const std::filesystem::path& png, const Options& opt) {
  using namespace detail;
  if (in.nx < 1 || in.ny < 1 || in.height.size() != static_cast<std::size_t>(in.nx) * in.ny)
    throw RenderError("render: heightmap needs nx, ny >= 1 and nx*ny heights (nx " + std::to_string(in.nx) + ", ny " +
                      std::to_string(in.ny) + ", " + std::to_string(in.height.size()) + " heights)");
  if (!(in.cell[0] > 0) || !(in.cell[1] > 0))
    throw RenderError("render: heightmap cell size must be > 0 in x and y (metres)");
  auto lock = lock_rendering();
  const double um = 1e6, mm = 1e3;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double h : in.height)
    if (std::isfinite(h)) lo = std::min(lo, h * um), hi = std::max(hi, h * um);
  if (!(hi >= lo)) lo = 0, hi = 1;  // no finite sample
  if (hi - lo < 1e-9) hi = lo + 1;

  Figure fig(opt);
  const double s = fig.scale(), font = 24 * s;
  Canvas c(fig.renderer(), s);
  // Plot rectangle with the region's true aspect ratio inside the free area.
  const double left = 150 * s, right = 250 * s, bottom = 150 * s, top = (opt.title.empty() ? 70 : 110) * s;
  const double aw = fig.width() - left - right, ah = fig.height() - bottom - top;
  const double wx = in.nx * in.cell[0], wy = in.ny * in.cell[1];
  const double k = std::min(aw / wx, ah / wy);
  PlotFrame f{left + 0.5 * (aw - k * wx),
              bottom + 0.5 * (ah - k * wy),
              k * wx,
              k * wy,
              in.origin[0] * mm,
              (in.origin[0] + wx) * mm,
              in.origin[1] * mm,
              (in.origin[1] + wy) * mm};

  vtkNew<vtkPoints> pts;
  pts->SetNumberOfPoints(static_cast<vtkIdType>(in.nx + 1) * (in.ny + 1));
  for (int j = 0; j <= in.ny; ++j)
    for (int i = 0; i <= in.nx; ++i)
      pts->SetPoint(static_cast<vtkIdType>(j) * (in.nx + 1) + i, f.px0 + f.pw * i / in.nx, f.py0 + f.ph * j / in.ny, 0);
  vtkNew<vtkCellArray> quads;
  vtkNew<vtkFloatArray> h;
  h->SetName("height");
  for (int j = 0; j < in.ny; ++j)
    for (int i = 0; i < in.nx; ++i) {
      const vtkIdType a = static_cast<vtkIdType>(j) * (in.nx + 1) + i;
      const vtkIdType q[4] = {a, a + 1, a + in.nx + 2, a + in.nx + 1};
      quads->InsertNextCell(4, q);
      const double v = in.height[static_cast<std::size_t>(j) * in.nx + i];
      h->InsertNextValue(static_cast<float>(std::isfinite(v) ? v * um : std::numeric_limits<double>::quiet_NaN()));
    }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(quads);
  pd->GetCellData()->SetScalars(h);
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(pd);
  mapper->SetScalarModeToUseCellData();
  mapper->SetLookupTable(make_lookup_table(ColourMap::viridis, lo, hi));
  mapper->SetScalarRange(lo, hi);
  mapper->UseLookupTableScalarRangeOn();
  vtkNew<vtkActor2D> image;
  image->SetMapper(mapper);
  fig.renderer()->AddActor2D(image);

  draw_frame(c, f, "x [mm]", "y [mm]", font, 8, std::max(2, std::min(6, static_cast<int>(f.ph / (70 * s)))));
  const std::string um_label = display_unit("m").label;
  const double bar_h = std::clamp(0.8 * f.ph, 300 * s, 0.6 * fig.height());
  c.colour_bar(fig.width() - 190 * s, f.py0 + 0.5 * (f.ph - bar_h), 32 * s, bar_h, ColourMap::viridis, lo, hi,
               "height [" + um_label + "]", 22 * s);
  double sum = 0, sum2 = 0;
  std::size_t filled = 0;
  for (double v : in.height)
    if (std::isfinite(v)) sum += v * um, sum2 += v * um * v * um, ++filled;
  const double mean = filled ? sum / filled : 0.0,
               rq = filled ? std::sqrt(std::max(0.0, sum2 / filled - mean * mean)) : 0.0;
  char caption[320];
  std::snprintf(caption, sizeof caption,
                "region %.2f x %.2f mm, %d x %d cells of %.0f x %.0f %s;  mean %.1f %s, R_q %.1f %s%s", wx * mm,
                wy * mm, in.nx, in.ny, in.cell[0] * um, in.cell[1] * um, um_label.c_str(), mean, um_label.c_str(), rq,
                um_label.c_str(), filled < in.height.size() ? ";  grey: empty" : "");
  c.text(caption, f.px0 + 0.5 * f.pw, f.py0 + f.ph + 12 * s, 22 * s, 1, 0, {0.2, 0.2, 0.2});
  fig.add_title();
  fig.write(png);
}

}  // namespace spreadmap::render
