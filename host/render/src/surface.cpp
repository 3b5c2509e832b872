// A model's prediction over (U, omega) as a 3-D surface coloured by value, with the simulated cases
// as markers (training: dark spheres, test: red cubes). The plot box is normalised so that both
// inputs and the value get comparable lengths; the axes show true values in display units.
#include "canvas2d.hpp"
#include "figure.hpp"
#include "palette.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCubeAxesActor.h>
#include <vtkCubeSource.h>
#include <vtkFloatArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLookupTable.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>

namespace spreadmap::render {

namespace {
constexpr double box_u = 1.5, box_w = 1.0, box_v = 0.75;  // plot box lengths (normalised units)

vtkSmartPointer<vtkActor> markers(const std::vector<std::array<double, 3>>& at, bool cube, double size,
                                  const detail::Rgb& colour) {
  vtkNew<vtkPoints> pts;
  for (const auto& p : at) pts->InsertNextPoint(p.data());
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(pd);
  if (cube) {
    vtkNew<vtkCubeSource> c;
    c->SetXLength(size * 1.6);
    c->SetYLength(size * 1.6);
    c->SetZLength(size * 1.6);
    mapper->SetSourceConnection(c->GetOutputPort());
  } else {
    vtkNew<vtkSphereSource> sph;
    sph->SetRadius(size);
    sph->SetThetaResolution(16);
    sph->SetPhiResolution(12);
    mapper->SetSourceConnection(sph->GetOutputPort());
  }
  mapper->ScalingOff();
  mapper->ScalarVisibilityOff();
  auto a = vtkSmartPointer<vtkActor>::New();
  a->SetMapper(mapper);
  a->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  a->GetProperty()->SetSpecular(0.3);
  return a;
}
}  // namespace

void surface(const SurfaceInput& in, const std::filesystem::path& png, const Options& opt) {
  using namespace detail;
  const std::size_t nu = in.u.size(), nw = in.omega.size();
  if (nu < 2 || nw < 2 || in.values.size() != nu * nw)
    throw RenderError("render: surface needs at least 2 x 2 grid axes and u.size() * omega.size() values (" +
                      std::to_string(nu) + " x " + std::to_string(nw) + ", " + std::to_string(in.values.size()) +
                      " values)");
  auto lock = lock_rendering();
  const auto unit = display_unit(in.quantity.unit);
  const double u0 = in.u.front() * 1e3, u1 = in.u.back() * 1e3, w0 = in.omega.front(), w1 = in.omega.back();
  double v0 = std::numeric_limits<double>::infinity(), v1 = -v0;
  for (double v : in.values)
    if (std::isfinite(v)) v0 = std::min(v0, v * unit.scale), v1 = std::max(v1, v * unit.scale);
  for (const auto& p : in.points) v0 = std::min(v0, p.value * unit.scale), v1 = std::max(v1, p.value * unit.scale);
  if (!(v1 > v0)) v1 = v0 + 1;
  const double colour_lo = v0, colour_hi = v1;
  const double vpad = 0.05 * (v1 - v0);
  v0 -= vpad, v1 += vpad;
  auto X = [&](double u_mm_s) { return (u_mm_s - u0) / (u1 - u0) * box_u; };
  auto Y = [&](double w) { return (w - w0) / (w1 - w0) * box_w; };
  auto Z = [&](double v) { return (v - v0) / (v1 - v0) * box_v; };

  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> value;
  value->SetName("value");
  for (std::size_t j = 0; j < nw; ++j)
    for (std::size_t i = 0; i < nu; ++i) {
      const double v = in.values[j * nu + i] * unit.scale;
      pts->InsertNextPoint(X(in.u[i] * 1e3), Y(in.omega[j]), Z(std::isfinite(v) ? v : v0));
      value->InsertNextValue(static_cast<float>(v));
    }
  vtkNew<vtkCellArray> quads;
  for (std::size_t j = 0; j + 1 < nw; ++j)
    for (std::size_t i = 0; i + 1 < nu; ++i) {
      const vtkIdType a = static_cast<vtkIdType>(j * nu + i);
      const vtkIdType q[4] = {a, a + 1, a + static_cast<vtkIdType>(nu) + 1, a + static_cast<vtkIdType>(nu)};
      quads->InsertNextCell(4, q);
    }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(quads);
  pd->GetPointData()->SetScalars(value);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(pd);
  normals->SplittingOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->SetLookupTable(make_lookup_table(ColourMap::viridis, colour_lo, colour_hi));
  mapper->UseLookupTableScalarRangeOn();
  mapper->InterpolateScalarsBeforeMappingOn();
  vtkNew<vtkActor> surf;
  surf->SetMapper(mapper);
  surf->GetProperty()->SetAmbient(0.35);
  surf->GetProperty()->SetDiffuse(0.7);
  surf->GetProperty()->SetSpecular(0.1);
  Figure fig(opt);
  auto* ren = fig.renderer();
  ren->AddActor(surf);

  std::vector<std::array<double, 3>> train, test;
  for (const auto& p : in.points)
    (p.test ? test : train).push_back({X(p.u * 1e3), Y(p.omega), Z(p.value * unit.scale)});
  const double size = 0.022;
  const Rgb train_colour{0.08, 0.08, 0.1}, test_colour{0.9, 0.1, 0.1};
  if (!train.empty()) ren->AddActor(markers(train, false, size, train_colour));
  if (!test.empty()) ren->AddActor(markers(test, true, size, test_colour));

  auto* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(0.5 * box_u, 0.5 * box_w, 0.4 * box_v);
  cam->SetPosition(0.5 * box_u - 2.6, 0.5 * box_w - 3.0, 0.4 * box_v + 2.2);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(30);
  const double s = fig.scale();

  vtkNew<vtkCubeAxesActor> axes;
  axes->SetBounds(0, box_u, 0, box_w, 0, box_v);
  axes->SetXAxisRange(u0, u1);
  axes->SetYAxisRange(w0, w1);
  axes->SetZAxisRange(v0, v1);
  axes->SetCamera(cam);
  axes->SetXTitle("U [mm/s]");
  axes->SetYTitle((omega_symbol() + " [rad/s]").c_str());
  axes->SetZTitle("");  // drawn level above the axis below: along it, it lies over the tick labels
  axes->SetXUnits(nullptr);
  axes->SetFlyModeToOuterEdges();
  axes->XAxisMinorTickVisibilityOff();
  axes->YAxisMinorTickVisibilityOff();
  axes->ZAxisMinorTickVisibilityOff();
  axes->SetGridLineLocation(vtkCubeAxesActor::VTK_GRID_LINES_FURTHEST);
  axes->DrawXGridlinesOn();
  axes->DrawYGridlinesOn();
  axes->DrawZGridlinesOn();
  axes->SetUse2DMode(1);
  axes->SetLabelOffset(12 * s);
  axes->SetTitleOffset(40 * s);
  for (int k = 0; k < 3; ++k) {
    style_text(axes->GetTitleTextProperty(k), 26 * s, {0, 0, 0});
    style_text(axes->GetLabelTextProperty(k), 21 * s, {0, 0, 0});
    axes->GetXAxesLinesProperty()->SetColor(0, 0, 0);
    axes->GetYAxesLinesProperty()->SetColor(0, 0, 0);
    axes->GetZAxesLinesProperty()->SetColor(0, 0, 0);
    axes->GetXAxesGridlinesProperty()->SetColor(0.8, 0.8, 0.8);
    axes->GetYAxesGridlinesProperty()->SetColor(0.8, 0.8, 0.8);
    axes->GetZAxesGridlinesProperty()->SetColor(0.8, 0.8, 0.8);
  }
  ren->AddActor(axes);
  ren->ResetCamera(0, box_u, 0, box_w, 0, box_v);
  cam->Zoom(1.05);
  ren->ResetCameraClippingRange();

  Canvas c(ren, s);
  // The z axis stands at the edge U = U_min, omega = omega_max (the camera is fixed to the box).
  ren->SetWorldPoint(0, box_w, box_v, 1);
  ren->WorldToDisplay();
  double z_top[3];
  ren->GetDisplayPoint(z_top);
  c.text(axis_label(in.quantity.name, unit.label), z_top[0], z_top[1] + 34 * s, 26 * s, 1, 0);
  c.colour_bar(fig.width() - 170 * s, 0.22 * fig.height(), 32 * s, 0.5 * fig.height(), ColourMap::viridis, colour_lo,
               colour_hi, axis_label(in.quantity.name, unit.label), 22 * s);
  std::vector<LegendEntry> legend;
  legend.push_back({"model prediction",
                    {0, 0, 0},
                    false,
                    LineStyle::solid,
                    false,
                    Marker::circle,
                    {0, 0, 0},
                    colour_at(ColourMap::viridis, 0.6)});
  if (!train.empty())
    legend.push_back({"training case (" + std::to_string(train.size()) + ")", train_colour, false, LineStyle::solid,
                      true, Marker::circle});
  if (!test.empty())
    legend.push_back({"test case (" + std::to_string(test.size()) + ")", test_colour, false, LineStyle::solid, true,
                      Marker::square});
  c.legend(20 * s, fig.height() - (opt.title.empty() ? 20 : 70) * s, legend, 20 * s);
  fig.add_title();
  fig.write(png);
}

}  // namespace spreadmap::render
