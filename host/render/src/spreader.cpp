// The spreader as drawn in snapshots, whatever its kind: its cross-section extruded along y, placed
// and turned as the plugin's pose says. A body that turns gets a red stripe along its length and a
// red spoke on its front face, both at its angle, so successive frames show it turning. Millimetres.
#include "snapshot_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>

namespace spreadmap::render::detail {

namespace {
using std::numbers::pi;
constexpr double deg = 180.0 / pi;

vtkSmartPointer<vtkActor> actor_of(vtkAlgorithmOutput* port, bool cell_colours) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(port);
  if (cell_colours) {
    mapper->SetScalarModeToUseCellData();
    mapper->SetColorModeToDirectScalars();
  } else {
    mapper->ScalarVisibilityOff();
  }
  auto a = vtkSmartPointer<vtkActor>::New();
  a->SetMapper(mapper);
  a->GetProperty()->SetSpecular(0.4);
  a->GetProperty()->SetSpecularPower(30);
  return a;
}

std::pair<double, double> y_extent(const SpreaderShape& s, const DomainBox& d) {
  if (!(s.length > 0)) return {d.lo[1], d.hi[1]};
  return {std::max(s.y_centre - 0.5 * s.length, d.lo[1]), std::min(s.y_centre + 0.5 * s.length, d.hi[1])};
}

// The prism in the body frame (mm), y from y0 to y1: a side quad per outline edge and two caps.
// Cell colours: caps darker; on a turning body, the side quads facing within 9 degrees of +z red.
vtkSmartPointer<vtkPolyData> prism(const SpreaderShape& s, double y0, double y1) {
  const vtkIdType n = static_cast<vtkIdType>(s.outline_x.size());
  vtkNew<vtkPoints> points;
  for (vtkIdType k = 0; k < n; ++k) {
    points->InsertNextPoint(s.outline_x[k] * mm, y0 * mm, s.outline_z[k] * mm);
    points->InsertNextPoint(s.outline_x[k] * mm, y1 * mm, s.outline_z[k] * mm);
  }
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  colours->SetName("colour");
  const double stripe_half_width = 9.0 / deg;
  for (vtkIdType k = 0; k < n; ++k) {
    const vtkIdType j = (k + 1) % n;
    const vtkIdType quad[4] = {2 * k, 2 * j, 2 * j + 1, 2 * k + 1};
    cells->InsertNextCell(4, quad);
    const double xm = 0.5 * (s.outline_x[k] + s.outline_x[j]), zm = 0.5 * (s.outline_z[k] + s.outline_z[j]);
    if (s.turns && std::abs(std::atan2(xm, zm)) < stripe_half_width) colours->InsertNextTuple3(210, 30, 30);
    else colours->InsertNextTuple3(150, 155, 165);
  }
  for (int end = 0; end < 2; ++end) {
    std::vector<vtkIdType> cap;
    for (vtkIdType k = 0; k < n; ++k) cap.push_back(2 * (end ? k : n - 1 - k) + end);  // outward facing
    cells->InsertNextCell(n, cap.data());
    colours->InsertNextTuple3(120, 125, 135);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(cells);
  pd->GetCellData()->SetScalars(colours);
  return pd;
}

double largest_extent(const SpreaderShape& s) {
  double r = 0;
  for (std::size_t k = 0; k < s.outline_x.size(); ++k) r = std::max(r, std::hypot(s.outline_x[k], s.outline_z[k]));
  return r;
}
}  // namespace

std::vector<vtkSmartPointer<vtkActor>> spreader_actors(const SpreaderShape& s, const DomainBox& d) {
  if (s.outline_x.empty()) return {};
  if (s.outline_x.size() < 3 || s.outline_x.size() != s.outline_z.size())
    throw RenderError("render: a spreader's outline needs at least 3 vertices, with as many x as z");
  const auto [y0, y1] = y_extent(s, d);
  vtkNew<vtkTransform> place;  // body frame -> world: turned about +y, then moved to the reference
  place->Translate(s.reference[0] * mm, 0, s.reference[2] * mm);
  place->RotateY(s.angle * deg);        // right-hand rotation about +y: +z turns towards +x
  vtkNew<vtkTriangleFilter> triangles;  // caps of any (also concave) outline
  triangles->SetInputData(prism(s, y0, y1));
  vtkNew<vtkPolyDataNormals> normals;  // smooth across gently curved sides, sharp at the caps
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->SetFeatureAngle(30);
  vtkNew<vtkTransformPolyDataFilter> body;
  body->SetInputConnection(normals->GetOutputPort());
  body->SetTransform(place);
  std::vector<vtkSmartPointer<vtkActor>> actors{actor_of(body->GetOutputPort(), true)};
  if (!s.turns) return actors;

  // Spoke on the front face (the camera looks from -y): reference point to rim at the body's angle.
  const double r = largest_extent(s) * mm;
  vtkNew<vtkCubeSource> spoke;
  spoke->SetXLength(0.12 * r);
  spoke->SetYLength(0.02 * r);
  spoke->SetZLength(0.95 * r);
  spoke->SetCenter(0, 0, 0.475 * r);
  vtkNew<vtkTransform> turn;
  turn->Translate(s.reference[0] * mm, y0 * mm - 0.011 * r, s.reference[2] * mm);
  turn->RotateY(s.angle * deg);
  vtkNew<vtkTransformPolyDataFilter> spoke_placed;
  spoke_placed->SetInputConnection(spoke->GetOutputPort());
  spoke_placed->SetTransform(turn);
  auto spoke_actor = actor_of(spoke_placed->GetOutputPort(), false);
  spoke_actor->GetProperty()->SetColor(0.82, 0.12, 0.12);
  actors.push_back(spoke_actor);
  return actors;
}

double spreader_top(const SpreaderShape& s) {
  double top = -1e300;
  const double c = std::cos(s.angle), sn = std::sin(s.angle);
  for (std::size_t k = 0; k < s.outline_x.size(); ++k)
    top = std::max(top, s.reference[2] - s.outline_x[k] * sn + s.outline_z[k] * c);
  return top;
}

}  // namespace spreadmap::render::detail
