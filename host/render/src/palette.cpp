#include "palette.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <vtkLookupTable.h>

namespace spreadmap::render::detail {

namespace {
struct Stop {
  double t;
  Rgb c;
};

const std::vector<Stop>& stops(ColourMap map) {
  static const std::vector<Stop> viridis{
      {0.000, {0.267, 0.005, 0.329}}, {0.125, {0.283, 0.141, 0.458}}, {0.250, {0.254, 0.265, 0.530}},
      {0.375, {0.207, 0.372, 0.553}}, {0.500, {0.164, 0.471, 0.558}}, {0.625, {0.128, 0.567, 0.551}},
      {0.750, {0.267, 0.678, 0.480}}, {0.875, {0.525, 0.791, 0.319}}, {1.000, {0.993, 0.906, 0.144}}};
  static const std::vector<Stop> rainbow{
      {0.00, {0.19, 0.07, 0.55}}, {0.15, {0.16, 0.35, 0.92}}, {0.30, {0.10, 0.70, 0.93}}, {0.45, {0.20, 0.90, 0.60}},
      {0.60, {0.65, 0.97, 0.25}}, {0.75, {0.98, 0.80, 0.15}}, {0.88, {0.97, 0.45, 0.08}}, {1.00, {0.75, 0.07, 0.03}}};
  static const std::vector<Stop> yellow_red{
      {0.000, {1.000, 1.000, 0.800}}, {0.125, {1.000, 0.929, 0.627}}, {0.250, {0.996, 0.851, 0.463}},
      {0.375, {0.996, 0.698, 0.298}}, {0.500, {0.992, 0.553, 0.235}}, {0.625, {0.988, 0.306, 0.165}},
      {0.750, {0.890, 0.102, 0.110}}, {0.875, {0.741, 0.000, 0.149}}, {1.000, {0.502, 0.000, 0.149}}};
  switch (map) {
    case ColourMap::viridis:
      return viridis;
    case ColourMap::rainbow:
      return rainbow;
    case ColourMap::yellow_red:
      return yellow_red;
  }
  return viridis;
}
}  // namespace

Rgb colour_at(ColourMap map, double t) {
  const auto& s = stops(map);
  if (!(t > 0)) return s.front().c;  // also NaN
  if (t >= 1) return s.back().c;
  std::size_t i = 1;
  while (s[i].t < t) ++i;
  const double w = (t - s[i - 1].t) / (s[i].t - s[i - 1].t);
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = s[i - 1].c[k] + w * (s[i].c[k] - s[i - 1].c[k]);
  return c;
}

vtkSmartPointer<vtkLookupTable> make_lookup_table(ColourMap map, double lo, double hi, int entries) {
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  if (!(hi > lo)) hi = lo + (std::abs(lo) > 0 ? 1e-6 * std::abs(lo) : 1.0);
  lut->SetNumberOfTableValues(entries);
  lut->SetTableRange(lo, hi);
  for (int i = 0; i < entries; ++i) {
    const Rgb c = colour_at(map, entries > 1 ? i / double(entries - 1) : 0.0);
    lut->SetTableValue(i, c[0], c[1], c[2], 1.0);
  }
  lut->SetNanColor(0.85, 0.85, 0.85, 1.0);
  lut->UseBelowRangeColorOff();
  lut->UseAboveRangeColorOff();
  lut->Build();
  // Build() may overwrite the table from its HSV ramp when called first; set the values again.
  for (int i = 0; i < entries; ++i) {
    const Rgb c = colour_at(map, entries > 1 ? i / double(entries - 1) : 0.0);
    lut->SetTableValue(i, c[0], c[1], c[2], 1.0);
  }
  return lut;
}

}  // namespace spreadmap::render::detail
