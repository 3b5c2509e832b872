// Reading STL: the ASCII and binary files of one part give the same triangles bit for bit, and every
// damaged file is refused with its name, the place and the fix.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "plugins/spreader/mesh/stl_files.hpp"

namespace fs = std::filesystem;
namespace sm = spreadmap;
using namespace sm::mesh::testing;

namespace {


void write_text(const std::string &file, const std::string &text) { std::ofstream(file, std::ios::binary) << text; }

// The refusal's text, or "" when the file is read.
std::string refusal(const std::string &file, double scale = 1e-3) {
  try {
    sm::mesh::read_stl(file, scale);
  } catch (const sm::ParamError &e) {
    return e.what();
  }
  return "";
}

const std::string one_facet = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";

}  // namespace

TEST(MeshStl, AsciiAndBinaryOfOnePartGiveTheSameTrianglesBitForBit) {
  Folder f("spreadmap_mesh_stl");
  auto part = box({0.1f, -35.0f, 0.3f}, {2.7f, 35.0f, 10.3f});
  const auto tip = pyramid(0.37f, 1.1f);
  part.insert(part.end(), tip.begin(), tip.end());
  write_ascii(f.file("part.stl"), part);
  write_binary(f.file("part_bin.stl"), part);
  const auto a = sm::mesh::read_stl(f.file("part.stl"), 1e-3), b = sm::mesh::read_stl(f.file("part_bin.stl"), 1e-3);
  ASSERT_EQ(a.size(), part.size());
  ASSERT_EQ(b.size(), part.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]), 0);
  EXPECT_EQ(a[0].corner[0][0], double(0.1f) * 1e-3) << "single precision, then the unit";
}

TEST(MeshStl, AMissingEmptyOrTruncatedFileIsRefusedNamingItAndTheFix) {
  Folder f("spreadmap_mesh_stl");
  EXPECT_NE(refusal(f.file("none.stl")).find("none.stl: cannot be opened"), std::string::npos);
  write_text(f.file("empty.stl"), "");
  EXPECT_NE(refusal(f.file("empty.stl")).find("empty.stl: the file is empty"), std::string::npos);
  write_binary(f.file("cut.stl"), plate(2, 1.0f));
  fs::resize_file(f.file("cut.stl"), 84 + 50 * 8 - 7);
  const std::string cut = refusal(f.file("cut.stl"));
  EXPECT_NE(cut.find("header counts 8 facets (484 bytes) but the file has 477 bytes"), std::string::npos) << cut;
  EXPECT_NE(cut.find("export it again"), std::string::npos) << cut;
  write_text(f.file("cut_ascii.stl"), one_facet);
  const std::string ascii = refusal(f.file("cut_ascii.stl"));
  EXPECT_NE(ascii.find("cut_ascii.stl:line 6: the file ends inside a facet"), std::string::npos) << ascii;
  write_text(f.file("short.stl"), "abc");
  EXPECT_NE(refusal(f.file("short.stl")).find("not an STL file"), std::string::npos);
  write_text(f.file("none_inside.stl"), "solid t\nendsolid t\n");
  EXPECT_NE(refusal(f.file("none_inside.stl")).find("holds no triangles"), std::string::npos);
}

TEST(MeshStl, NonFiniteCornersAndDegenerateTrianglesAreRefusedWithTheirPlace) {
  Folder f("spreadmap_mesh_stl");
  for (const char *bad : {"nan", "inf", "-inf", "1e99"}) {
    write_text(f.file("bad.stl"), one_facet + "vertex 0 " + bad + " 0\nendloop\nendfacet\nendsolid t\n");
    const std::string why = refusal(f.file("bad.stl"));
    EXPECT_NE(why.find("bad.stl:line 2: a corner has a coordinate that is not a finite number"), std::string::npos)
        << bad << ": " << why;
  }
  auto part = plate(2, 1.0f);
  part[5] = {0, 0, 0, 1, 1, 0, 2, 2, 0};  // three corners on a line
  write_binary(f.file("sliver.stl"), part);
  const std::string sliver = refusal(f.file("sliver.stl"));
  EXPECT_NE(sliver.find("sliver.stl:facet 6: a degenerate triangle"), std::string::npos) << sliver;
  write_text(f.file("word.stl"), one_facet + "vertex 0 x1 0\nendloop\nendfacet\nendsolid t\n");
  EXPECT_NE(refusal(f.file("word.stl")).find("line 6: 'x1' is not a number"), std::string::npos);
  part[5] = {0, 0, 0, 1, 0, 0, 1, 0, std::numeric_limits<float>::quiet_NaN()};
  write_binary(f.file("nan.stl"), part);
  EXPECT_NE(refusal(f.file("nan.stl")).find("nan.stl:facet 6: a corner has a coordinate"), std::string::npos);
}
