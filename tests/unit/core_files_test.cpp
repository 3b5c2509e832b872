// Atomic files: the final name only ever holds a whole file; a failed writer leaves the previous
// content and no temporary behind. stable_hash is pinned to fixed values: run directories written by
// an older build must still recognise their finished cases.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>

#include "core/error.hpp"
#include "core/files.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

class CoreFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("spreadmap_core_files_" + std::to_string(::getpid()) + "_" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  // Every entry of the folder, recursively, as relative paths.
  std::vector<std::string> listing() const {
    std::vector<std::string> out;
    for (const auto &e : fs::recursive_directory_iterator(dir)) out.push_back(fs::relative(e.path(), dir).string());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path dir;
};

}  // namespace

TEST_F(CoreFiles, WriteAtomicLeavesOnlyTheTarget) {
  sm::write_atomic(dir / "a.json", "{\"x\": 1}\n");
  EXPECT_EQ(sm::read_text(dir / "a.json"), "{\"x\": 1}\n");
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.json"}));
}

TEST_F(CoreFiles, WriteAtomicReplacesAndCreatesFolders) {
  sm::write_atomic(dir / "sub/deeper/m.json", "old");
  sm::write_atomic(dir / "sub/deeper/m.json", "new content");
  EXPECT_EQ(sm::read_text(dir / "sub/deeper/m.json"), "new content");
  EXPECT_EQ(listing(), (std::vector<std::string>{"sub", "sub/deeper", "sub/deeper/m.json"}));
}

TEST_F(CoreFiles, ThrowingWriterKeepsTheOldContentAndNoTemporary) {
  sm::write_atomic(dir / "state.vtp", "the previous whole file");
  fs::path seen;
  EXPECT_THROW(sm::write_atomic_with(dir / "state.vtp",
                                     [&](const fs::path &tmp) {
                                       seen = tmp;
                                       std::FILE *f = std::fopen(tmp.c_str(), "wb");
                                       std::fputs("half a fi", f);
                                       std::fclose(f);
                                       throw std::runtime_error("disk on fire");
                                     }),
               std::runtime_error);
  EXPECT_EQ(seen.parent_path(), dir);  // the temporary lies beside the target (same file system)
  EXPECT_NE(seen.filename(), "state.vtp");
  EXPECT_FALSE(fs::exists(seen));
  EXPECT_EQ(sm::read_text(dir / "state.vtp"), "the previous whole file");
  EXPECT_EQ(listing(), (std::vector<std::string>{"state.vtp"}));
}

TEST_F(CoreFiles, FailedRenameLeavesNoTemporary) {
  fs::create_directories(dir / "occupied" / "child");  // a non-empty folder cannot be replaced by a file
  EXPECT_ANY_THROW(sm::write_atomic(dir / "occupied", "text"));
  EXPECT_EQ(listing(), (std::vector<std::string>{"occupied", "occupied/child"}));
}

TEST_F(CoreFiles, TemporaryNamesAreUniqueAndHidden) {
  const fs::path a = sm::temporary_beside(dir / "case.json"), b = sm::temporary_beside(dir / "case.json");
  EXPECT_NE(a, b);
  EXPECT_EQ(a.parent_path(), dir);
  EXPECT_EQ(a.filename().string().front(), '.');
  EXPECT_NE(a.filename().string().find(".tmp"), std::string::npos);
  EXPECT_EQ(a.extension(), ".json");  // writers that pick a format by extension still work
}

TEST_F(CoreFiles, ReadTextOfAMissingFileNamesIt) {
  try {
    sm::read_text(dir / "nothere.yaml");
    FAIL() << "no error";
  } catch (const sm::InputError &e) {
    EXPECT_NE(std::string(e.what()).find((dir / "nothere.yaml").string()), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code, sm::exit_input);
  }
}

TEST(CoreHash, StableHashIsPinned) {
  EXPECT_EQ(sm::stable_hash(""), "14650fb0739d0383");
  EXPECT_EQ(sm::stable_hash("a"), "44bd8ad473cd9906");
  EXPECT_EQ(sm::stable_hash("foobar"), "88fad7c0a8ff07f2");
}

TEST(CoreHash, StableHashSeparatesNearbyInputs) {
  EXPECT_EQ(sm::stable_hash("{\"U\":0.1}").size(), 16u);
  EXPECT_NE(sm::stable_hash("{\"U\":0.1}"), sm::stable_hash("{\"U\":0.2}"));
  EXPECT_NE(sm::stable_hash("ab"), sm::stable_hash("ba"));
  EXPECT_EQ(sm::stable_hash(std::string(1000, 'x')), sm::stable_hash(std::string(1000, 'x')));
}
