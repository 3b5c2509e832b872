// Particles coloured by speed, the substrate and the spreader, seen obliquely from the front-left
// and above so that the heap, the spread layer and the spreader's turning stripe are all visible.
// Geometry is drawn in millimetres; speed in mm/s.
#include "canvas2d.hpp"
#include "figure.hpp"
#include "palette.hpp"
#include "snapshot_scene.hpp"

#include <algorithm>
#include <cmath>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCubeSource.h>
#include <vtkCylinderSource.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLookupTable.h>
#include <vtkOutlineSource.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkCellData.h>

namespace sm = spreadmap;

namespace spreadmap::render::detail {

namespace {

void check_input(const SnapshotInput& in) {
  const std::size_t n = in.x.size();
  if (in.y.size() != n || in.z.size() != n || in.r.size() != n || in.speed.size() != n)
    throw RenderError("render: snapshot arrays x, y, z, r, speed must have the same length (x has " +
                      std::to_string(n) + ", y " + std::to_string(in.y.size()) + ", z " + std::to_string(in.z.size()) +
                      ", r " + std::to_string(in.r.size()) + ", speed " + std::to_string(in.speed.size()) + ")");
  for (int k = 0; k < 3; ++k)
    if (!(in.domain.hi[k] > in.domain.lo[k]))
      throw RenderError("render: snapshot domain box is empty along axis " + std::to_string(k) +
                        "; give domain.lo < domain.hi in metres");
}

vtkSmartPointer<vtkActor> particles_actor(const SnapshotInput& in, double speed_top) {
  const vtkIdType n = static_cast<vtkIdType>(in.x.size());
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToFloat();
  pts->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> radius, speed;
  radius->SetName("radius");
  speed->SetName("speed");
  radius->SetNumberOfValues(n);
  speed->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i) {
    pts->SetPoint(i, in.x[i] * mm, in.y[i] * mm, in.z[i] * mm);
    radius->SetValue(i, static_cast<float>(in.r[i] * mm));
    speed->SetValue(i, static_cast<float>(in.speed[i] * 1e3));  // mm/s
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->GetPointData()->AddArray(radius);
  pd->GetPointData()->AddArray(speed);

  // Few facets per sphere: 235,000 instanced spheres must draw in seconds with software GL.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(10);
  sphere->SetPhiResolution(7);
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(pd);
  mapper->SetSourceConnection(sphere->GetOutputPort());
  mapper->SetScaleArray("radius");
  mapper->SetScaleModeToScaleByMagnitude();
  mapper->SetScaleFactor(1.0);
  mapper->OrientOff();
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("speed");
  mapper->SetLookupTable(make_lookup_table(ColourMap::rainbow, 0.0, speed_top * 1e3));
  mapper->SetScalarRange(0.0, speed_top * 1e3);
  mapper->ScalarVisibilityOn();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.25);
  actor->GetProperty()->SetSpecularPower(20);
  return actor;
}

vtkSmartPointer<vtkActor> substrate_actor(const DomainBox& d) {
  const double mx = 0.04 * (d.hi[0] - d.lo[0]), my = 0.3 * (d.hi[1] - d.lo[1]);
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin((d.lo[0] - mx) * mm, (d.lo[1] - my) * mm, d.lo[2] * mm);
  plane->SetPoint1((d.hi[0] + mx) * mm, (d.lo[1] - my) * mm, d.lo[2] * mm);
  plane->SetPoint2((d.lo[0] - mx) * mm, (d.hi[1] + my) * mm, d.lo[2] * mm);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.78, 0.80, 0.83);
  actor->GetProperty()->SetAmbient(0.25);
  return actor;
}

vtkSmartPointer<vtkActor> outline_actor(const DomainBox& d) {
  vtkNew<vtkOutlineSource> box;
  box->SetBounds(d.lo[0] * mm, d.hi[0] * mm, d.lo[1] * mm, d.hi[1] * mm, d.lo[2] * mm, d.hi[2] * mm);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(box->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.7, 0.7, 0.75);
  actor->GetProperty()->SetLineWidth(1.0f);
  return actor;
}
}  // namespace

SnapshotScene build_snapshot_scene(const SnapshotInput& in, double speed_top) {
  check_input(in);
  SnapshotScene scene;
  scene.actors.push_back(substrate_actor(in.domain));
  scene.actors.push_back(outline_actor(in.domain));
  if (!in.x.empty()) scene.actors.push_back(particles_actor(in, speed_top));
  for (auto& a : spreader_actors(in.spreader, in.domain)) scene.actors.push_back(a);
  return scene;
}

double largest_speed(const SnapshotInput& in) {
  double top = 0;
  for (double v : in.speed)
    if (std::isfinite(v)) top = std::max(top, v);
  return top;
}

void render_snapshot(const SnapshotInput& in, const std::filesystem::path& png, const Options& opt, double speed_top) {
  if (!(speed_top > 0)) speed_top = 1e-3;  // all at rest: a 0..1 mm/s bar
  Figure fig(opt);
  auto* ren = fig.renderer();
  for (auto& a : build_snapshot_scene(in, speed_top).actors) ren->AddActor(a);

  // Oblique camera from the front (-y) left (-x) and above, looking at the domain's centre,
  // fitted to the domain box so that every figure of a run is framed alike.
  const DomainBox& d = in.domain;
  const double cx = 0.5 * (d.lo[0] + d.hi[0]) * mm, cy = 0.5 * (d.lo[1] + d.hi[1]) * mm;
  const double lx = (d.hi[0] - d.lo[0]) * mm;
  double top = d.lo[2] * mm;
  for (std::size_t i = 0; i < in.z.size(); ++i) top = std::max(top, (in.z[i] + in.r[i]) * mm);
  if (!in.spreader.outline_x.empty()) top = std::max(top, spreader_top(in.spreader) * mm);
  top = std::min(top, d.hi[2] * mm);
  const double cz = d.lo[2] * mm + 0.35 * (top - d.lo[2] * mm);
  auto* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(cx, cy, cz);
  const double dir[3] = {-0.28, -1.0, 0.62};
  const double dn = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  const double dist = 1.45 * lx;
  cam->SetPosition(cx + dist * dir[0] / dn, cy + dist * dir[1] / dn, cz + dist * dir[2] / dn);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(28);
  ren->ResetCameraClippingRange();
  // Horizontal field of view must take in the whole strip length with a margin.
  const double aspect = double(fig.width()) / fig.height();
  const double needed = 1.05 * lx / (2 * dist * std::tan(14 * 3.14159265358979 / 180) * aspect);
  if (needed > 1) cam->Zoom(1 / needed);

  Canvas c(ren, fig.scale());
  const double s = fig.scale();
  c.colour_bar(fig.width() - 150 * s, 0.2 * fig.height(), 32 * s, 0.55 * fig.height(), ColourMap::rainbow, 0.0,
               speed_top * 1e3, "speed [mm/s]", 22 * s);
  char info[160];
  std::snprintf(info, sizeof info, "%zu particles   domain %.1f x %.1f x %.1f mm", in.x.size(),
                (d.hi[0] - d.lo[0]) * mm, (d.hi[1] - d.lo[1]) * mm, (d.hi[2] - d.lo[2]) * mm);
  c.text(info, 20 * s, 18 * s, 20 * s, 0, 0, {0.25, 0.25, 0.25});
  fig.add_title();
  fig.write(png);
}

}  // namespace spreadmap::render::detail

namespace spreadmap::render {

void snapshot(const SnapshotInput& in, const std::filesystem::path& png, const Options& opt) {
  auto lock = detail::lock_rendering();
  detail::render_snapshot(in, png, opt, in.speed_max > 0 ? in.speed_max : detail::largest_speed(in));
}

std::vector<std::filesystem::path> animation_frames(const std::vector<SnapshotInput>& frames,
                                                    const std::filesystem::path& directory, const std::string& stem,
                                                    const Options& opt) {
  auto lock = detail::lock_rendering();
  double top = 0;
  for (const auto& f : frames) top = std::max(top, f.speed_max > 0 ? f.speed_max : detail::largest_speed(f));
  std::vector<std::filesystem::path> written;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "_%04zu.png", i);
    written.push_back(directory / (stem + name));
    detail::render_snapshot(frames[i], written.back(), opt, top);
  }
  return written;
}

}  // namespace spreadmap::render
