// The spreader as drawn in snapshots: a roller is a grey cylinder with one red stripe along its
// length and a red spoke on its front face, both at the roller's angle, so successive frames show
// it turning; a blade is a box. Millimetres.
#include "snapshot_scene.hpp"

#include <algorithm>
#include <cmath>

#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkCylinderSource.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkUnsignedCharArray.h>

namespace spreadmap::render::detail {

namespace {
constexpr double mm = 1e3;
constexpr double pi = 3.14159265358979323846;
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

std::pair<double, double> y_extent(const SpreaderPose& p, const Box& d) {
  if (!(p.length > 0)) return {d.lo[1], d.hi[1]};
  return {std::max(p.centre[1] - 0.5 * p.length, d.lo[1]), std::min(p.centre[1] + 0.5 * p.length, d.hi[1])};
}

std::vector<vtkSmartPointer<vtkActor>> roller(const SpreaderPose& p, const Box& d) {
  if (!(p.radius > 0)) throw RenderError("render: snapshot spreader 'cylinder' needs radius > 0 (m)");
  const auto [y0, y1] = y_extent(p, d);
  const double r = p.radius * mm, len = (y1 - y0) * mm, yc = 0.5 * (y0 + y1) * mm;
  vtkNew<vtkCylinderSource> cyl;  // axis along y, centred at the origin
  cyl->SetRadius(r);
  cyl->SetHeight(len);
  cyl->SetResolution(72);
  cyl->CappingOn();
  cyl->Update();
  vtkPolyData* pd = cyl->GetOutput();
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  colours->SetName("colour");
  const double stripe_half_width = 9.0 / deg;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c) {
    double b[6];
    pd->GetCell(c)->GetBounds(b);
    const double x = 0.5 * (b[0] + b[1]), z = 0.5 * (b[4] + b[5]);
    const bool side = std::hypot(x, z) > 0.5 * r;
    // Angle from +z towards +x: the stripe at angle 0 is on top, moving forward as the angle grows.
    const double a = std::remainder(std::atan2(x, z) - p.angle, 2 * pi);
    if (side && std::abs(a) < stripe_half_width) colours->InsertNextTuple3(210, 30, 30);
    else if (side) colours->InsertNextTuple3(150, 155, 165);
    else colours->InsertNextTuple3(120, 125, 135);
  }
  pd->GetCellData()->SetScalars(colours);
  vtkNew<vtkTransform> place;
  place->Translate(p.centre[0] * mm, yc, p.centre[2] * mm);
  vtkNew<vtkTransformPolyDataFilter> body;
  body->SetInputData(pd);
  body->SetTransform(place);

  // Spoke on the front face (the camera looks from -y): centre to rim at the roller's angle.
  vtkNew<vtkCubeSource> spoke;
  spoke->SetXLength(0.12 * r);
  spoke->SetYLength(0.02 * r);
  spoke->SetZLength(0.95 * r);
  spoke->SetCenter(0, 0, 0.475 * r);
  vtkNew<vtkTransform> turn;
  turn->Translate(p.centre[0] * mm, yc - 0.5 * len - 0.011 * r, p.centre[2] * mm);
  turn->RotateY(p.angle * deg);  // right-hand rotation about +y: +z turns towards +x
  vtkNew<vtkTransformPolyDataFilter> spoke_placed;
  spoke_placed->SetInputConnection(spoke->GetOutputPort());
  spoke_placed->SetTransform(turn);

  auto body_actor = actor_of(body->GetOutputPort(), true);
  auto spoke_actor = actor_of(spoke_placed->GetOutputPort(), false);
  spoke_actor->GetProperty()->SetColor(0.82, 0.12, 0.12);
  return {body_actor, spoke_actor};
}

std::vector<vtkSmartPointer<vtkActor>> blade(const SpreaderPose& p, const Box& d) {
  if (!(p.thickness > 0) || !(p.height > 0))
    throw RenderError("render: snapshot spreader 'blade' needs thickness > 0 and height > 0 (m)");
  const auto [y0, y1] = y_extent(p, d);
  vtkNew<vtkCubeSource> box;
  box->SetXLength(p.thickness * mm);
  box->SetYLength((y1 - y0) * mm);
  box->SetZLength(p.height * mm);
  vtkNew<vtkTransform> place;
  place->Translate(p.centre[0] * mm, 0.5 * (y0 + y1) * mm, p.centre[2] * mm);
  place->RotateY(p.angle * deg);
  vtkNew<vtkTransformPolyDataFilter> placed;
  placed->SetInputConnection(box->GetOutputPort());
  placed->SetTransform(place);
  auto a = actor_of(placed->GetOutputPort(), false);
  a->GetProperty()->SetColor(0.55, 0.58, 0.65);
  return {a};
}
}  // namespace

std::vector<vtkSmartPointer<vtkActor>> spreader_actors(const SpreaderPose& pose, const Box& domain) {
  if (pose.shape.empty() || pose.shape == "none") return {};
  if (pose.shape == "cylinder" || pose.shape == "roller") return roller(pose, domain);
  if (pose.shape == "blade") return blade(pose, domain);
  throw RenderError("render: snapshot spreader shape '" + pose.shape + "' is not one of cylinder, blade, none");
}

}  // namespace spreadmap::render::detail
