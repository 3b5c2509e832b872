// Particle files: VTP round trip (exact), PVD series, CSV input and its error messages.
#include <engine/csv_input.hpp>
#include <engine/errors.hpp>
#include <engine/vtp_io.hpp>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

#include "temporaries.hpp"

namespace sm = spreadmap;
using namespace sm::engine;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / fmt::format("engine_io_{}", ::getpid());
  fs::create_directories(d);
  return d;
}

fs::path write_text(const fs::path &path, const std::string &text) {
  std::ofstream(path) << text;
  return path;
}

std::string read_text(const fs::path &path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string error_of(const fs::path &path) {
  try {
    read_particles_csv(path);
  } catch (const SetupError &e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(EngineVtp, RoundTripIsExact) {
  ParticleSet s;
  s.x = {0.1, 1.0 / 3.0, -2.5e-7};
  s.y = {0.2, 2.0 / 3.0, 1e-300};
  s.z = {0.3, 0.7, 123456.789};
  s.vx = {1, 2, 3};
  s.vy = {-1, -2, -3};
  s.vz = {0.5, 0.25, 0.125};
  s.wx = {10, 20, 30};
  s.wy = {0, 0, 0};
  s.wz = {-1e-3, 1e3, 0.1};
  s.radius = {1.25e-4, 1.25e-4, 1.3e-4};
  s.mass = {3.1e-8, 3.2e-8, 3.3e-8};
  s.id = {7, 3, 4000000000u};
  const fs::path path = temp_dir() / "state.vtp";
  write_vtp(path, s, 0.123456789);
  EXPECT_TRUE(temporaries_beside(path).empty());
  const VtpContent back = read_vtp(path);
  EXPECT_EQ(back.time, 0.123456789);
  EXPECT_EQ(back.particles.x, s.x);
  EXPECT_EQ(back.particles.y, s.y);
  EXPECT_EQ(back.particles.z, s.z);
  EXPECT_EQ(back.particles.vz, s.vz);
  EXPECT_EQ(back.particles.wz, s.wz);
  EXPECT_EQ(back.particles.radius, s.radius);
  EXPECT_EQ(back.particles.mass, s.mass);
  EXPECT_EQ(back.particles.id, s.id);
  const std::string text = read_text(path);
  for (const char *needle : {"<VTKFile type=\"PolyData\"", "Name=\"velocity\"", "Name=\"omega\"", "Name=\"radius\"",
                             "Name=\"id\"", "Name=\"TIME\"", "NumberOfPoints=\"3\""})
    EXPECT_NE(text.find(needle), std::string::npos) << needle;
}

// Fixed particles stay fixed through a file (a multi-layer bed is read back from its state.vtp); a
// set without the column writes none and reads back without one.
TEST(EngineVtp, FixedColumnRoundTrips) {
  ParticleSet s;
  s.x = {0.1, 0.2, 0.3};
  s.y = s.z = {0.1, 0.1, 0.1};
  s.radius = {1e-4, 1e-4, 1e-4};
  s.fixed = {1, 0, 1};
  const fs::path path = temp_dir() / "fixed.vtp";
  write_vtp(path, s, 0);
  EXPECT_EQ(read_vtp(path).particles.fixed, s.fixed);
  s.fixed.clear();
  write_vtp(path, s, 0);
  EXPECT_EQ(read_text(path).find("fixed"), std::string::npos);
  EXPECT_TRUE(read_vtp(path).particles.fixed.empty());
  std::string text;
  {
    s.fixed = {1, 0, 1};
    write_vtp(path, s, 0);
    text = read_text(path);
    const auto at = text.find("1 0 1", text.find("Name=\"fixed\""));
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 5, "1 2 1");
  }
  write_text(path, text);
  EXPECT_THROW(read_vtp(path), SetupError);
}

TEST(EngineVtp, RejectsAForeignFile) {
  const fs::path path = write_text(temp_dir() / "foreign.vtp", "<VTKFile type=\"ImageData\"></VTKFile>");
  EXPECT_THROW(read_vtp(path), SetupError);
}

TEST(EnginePvd, ListsTheSeries) {
  const fs::path path = temp_dir() / "series.pvd";
  write_pvd(path, {{0.0, "series/000000.vtp"}, {0.5, "series/000001.vtp"}});
  const std::string text = read_text(path);
  EXPECT_NE(text.find("type=\"Collection\""), std::string::npos);
  EXPECT_NE(text.find("timestep=\"0.5\" group=\"\" part=\"0\" file=\"series/000001.vtp\""), std::string::npos) << text;
}

TEST(EngineCsv, ReadsRequiredAndOptionalColumnsInAnyOrder) {
  const fs::path path = write_text(temp_dir() / "ok.csv",
                                   "# a comment\nradius, X,y,z,vz\n1e-4,0.001,0.002,0.003,-0.5\n\n1.5e-4,1,2,3,0\n");
  const ParticleSet s = read_particles_csv(path);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.x, (std::vector<double>{0.001, 1}));
  EXPECT_EQ(s.radius, (std::vector<double>{1e-4, 1.5e-4}));
  EXPECT_EQ(s.vz, (std::vector<double>{-0.5, 0}));
  EXPECT_TRUE(s.vx.empty());
  EXPECT_TRUE(s.mass.empty());
}

TEST(EngineCsv, ErrorsNameFileLineAndColumn) {
  const fs::path d = temp_dir();
  const std::string bad_number = error_of(write_text(d / "bad.csv", "x,y,z,radius\n0,0,0,1e-4\n0,0, abc,1e-4\n"));
  EXPECT_NE(bad_number.find("bad.csv:3:6: column 'z' holds 'abc'"), std::string::npos) << bad_number;
  const std::string missing = error_of(write_text(d / "missing.csv", "x,y,z\n0,0,0\n"));
  EXPECT_NE(missing.find("missing.csv:1:1: the header has no 'radius' column"), std::string::npos) << missing;
  const std::string unknown = error_of(write_text(d / "unknown.csv", "x,y,z,radius,colour\n"));
  EXPECT_NE(unknown.find("unknown.csv:1:14: unknown column 'colour'"), std::string::npos) << unknown;
  const std::string short_line = error_of(write_text(d / "short.csv", "x,y,z,radius\n0,0,0\n"));
  EXPECT_NE(short_line.find("short.csv:2:"), std::string::npos) << short_line;
  EXPECT_NE(short_line.find("3 values on this line, the header names 4 columns"), std::string::npos) << short_line;
  const std::string negative = error_of(write_text(d / "neg.csv", "x,y,z,radius\n0,0,0,-1\n"));
  EXPECT_NE(negative.find("neg.csv:2:7: radius = -1 m"), std::string::npos) << negative;
  EXPECT_NE(error_of(d / "does_not_exist.csv").find("cannot open"), std::string::npos);
}
