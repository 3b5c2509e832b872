#include "render_image_check.hpp"

#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkUnsignedCharArray.h>
#include <vtkPointData.h>

namespace spreadmap::render::testing {

Image read_png(const std::filesystem::path& png) {
  if (!std::filesystem::exists(png)) throw std::runtime_error("no such image: " + png.string());
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  Image im;
  int dims[3];
  data->GetDimensions(dims);
  im.width = dims[0];
  im.height = dims[1];
  vtkDataArray* scalars = data->GetPointData()->GetScalars();
  const int comps = scalars->GetNumberOfComponents();
  im.pixels.resize(static_cast<std::size_t>(im.width) * im.height);
  for (std::size_t i = 0; i < im.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k)
      im.pixels[i][k] = static_cast<std::uint8_t>(scalars->GetComponent(static_cast<vtkIdType>(i), comps >= 3 ? k : 0));
  return im;
}

std::size_t distinct_colours(const Image& im) {
  std::set<std::uint32_t> seen;
  for (const auto& p : im.pixels) seen.insert(p[0] << 16 | p[1] << 8 | p[2]);
  return seen.size();
}

std::size_t count_colour(const Image& im, const std::array<int, 3>& rgb, int tolerance) {
  std::size_t n = 0;
  for (const auto& p : im.pixels)
    if (std::abs(p[0] - rgb[0]) <= tolerance && std::abs(p[1] - rgb[1]) <= tolerance &&
        std::abs(p[2] - rgb[2]) <= tolerance)
      ++n;
  return n;
}

double mean_abs_difference(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) return 255.0;
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k) sum += std::abs(int(a.pixels[i][k]) - int(b.pixels[i][k]));
  return sum / (3.0 * static_cast<double>(a.pixels.size()));
}

bool regenerate_references() {
  const char* v = std::getenv("SPREADMAP_REGENERATE_REFERENCES");
  return v && std::string(v) == "1";
}

std::filesystem::path reference_path(const std::string& name) {
  return std::filesystem::path(SPREADMAP_SOURCE_DIR) / "tests/unit/data/render" / (name + ".png");
}

}  // namespace spreadmap::render::testing
