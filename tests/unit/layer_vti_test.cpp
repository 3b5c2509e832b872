// The height map's VTK ImageData file: a valid XML header with origin at the first cell centre, every
// value round-tripping through the text, written atomically (no temporary left behind). Read back
// with VTK's own reader when VTK is available.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/heightmap_vti.hpp"

#ifdef SPREADMAP_TEST_WITH_VTK
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>
#endif

namespace {

namespace fs = std::filesystem;

TEST(LayerVti, WritesImageDataThatReadsBack) {
  const fs::path dir = fs::temp_directory_path() / ("layer_vti_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "heightmap.vti";
  const std::uint32_t nx = 5, ny = 3;
  const double x0 = 1e-3, y0 = -2e-3, cell = 5e-5;
  std::vector<double> h(nx * ny);
  for (std::size_t k = 0; k < h.size(); ++k) h[k] = 1e-4 / 3 * static_cast<double>(k);  // not exact in decimal
  spreadmap::write_heightmap_vti(file, nx, ny, x0, y0, cell, h.data());

  std::size_t entries = 0;
  for (const auto &e : fs::directory_iterator(dir)) entries += e.is_regular_file();
  EXPECT_EQ(entries, 1u);  // the temporary was renamed, not left beside

  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  EXPECT_NE(s.find("WholeExtent=\"0 4 0 2 0 0\""), std::string::npos);
  const std::size_t at = s.find("Origin=\"");
  ASSERT_NE(at, std::string::npos);
  std::istringstream origin_text(s.substr(at + 8, 80));
  double ox = 0, oy = 0;
  origin_text >> ox >> oy;
  EXPECT_EQ(ox, x0 + cell / 2);  // samples at cell centres
  EXPECT_EQ(oy, y0 + cell / 2);
  const std::size_t begin = s.find('>', s.find("<DataArray")) + 1, end = s.find("</DataArray>");
  std::istringstream values(s.substr(begin, end - begin));
  for (std::size_t k = 0; k < h.size(); ++k) {
    double v = -1;
    values >> v;
    EXPECT_EQ(v, h[k]) << k;  // %.17g round-trips exactly
  }

#ifdef SPREADMAP_TEST_WITH_VTK
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkImageData *image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 5);
  EXPECT_EQ(dims[1], 3);
  double origin[3];
  image->GetOrigin(origin);
  EXPECT_DOUBLE_EQ(origin[0], x0 + cell / 2);
  auto *array = image->GetPointData()->GetArray("height");
  ASSERT_NE(array, nullptr);
  EXPECT_EQ(array->GetTuple1(7), h[7]);
#endif
  fs::remove_all(dir);
  EXPECT_THROW(spreadmap::write_heightmap_vti(file, 0, 3, x0, y0, cell, h.data()), std::invalid_argument);
}

}  // namespace
