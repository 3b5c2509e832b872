// Atomic files: the final name only ever holds a whole file, the old one or the new one, also while
// threads and processes write it at once; a failed write (a throwing writer, a full disk, a folder
// that cannot be made) leaves the previous content and no temporary behind. stable_hash is pinned to
// fixed values: run directories written by an older build must still recognise their finished cases.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

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
  try {
    sm::write_atomic(dir / "occupied", "text");
    FAIL() << "no error";
  } catch (const sm::RunFailure &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot write " + (dir / "occupied").string()), std::string::npos) << what;
    EXPECT_NE(what.find("move it away"), std::string::npos) << what;
  }
  EXPECT_EQ(listing(), (std::vector<std::string>{"occupied", "occupied/child"}));
}

// An output path that is a symbolic link, a FIFO or a device is refused, never replaced by a regular
// file (as root, --out /dev/stdout would otherwise replace the device): each stays what it was.
TEST_F(CoreFiles, ALinkAFifoOrADeviceIsRefusedNotReplaced) {
  sm::write_atomic(dir / "target.csv", "the link's target\n");
  fs::create_symlink(dir / "target.csv", dir / "link.csv");
  ASSERT_EQ(::mkfifo((dir / "pipe.csv").c_str(), 0644), 0);
  for (const auto &[path, what] : std::vector<std::pair<fs::path, std::string>>{
           {dir / "link.csv", "a symbolic link"}, {dir / "pipe.csv", "a FIFO"}, {"/dev/null", "a device"}}) {
    try {
      sm::write_atomic(path, "text");
      FAIL() << path << " was written";
    } catch (const sm::RunFailure &e) {
      EXPECT_NE(std::string(e.what()).find("cannot write " + path.string() + ": it is " + what), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("never replaces"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  EXPECT_EQ(fs::status(dir / "pipe.csv").type(), fs::file_type::fifo);
  EXPECT_EQ(fs::status("/dev/null").type(), fs::file_type::character);
  EXPECT_EQ(sm::read_text(dir / "target.csv"), "the link's target\n");
  std::vector<std::string> names;  // (listing() would resolve the link to its target's name)
  for (const auto &e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"link.csv", "pipe.csv", "target.csv"})) << "no temporary is left";
}

// The write stops half way, as on a full disk: the file size limit (which binds root too) makes
// write() fail with EFBIG once 4 KiB of the 1 MiB are written.
TEST_F(CoreFiles, DiskFullHalfWayKeepsTheOldFileAndNoTemporary) {
  sm::write_atomic(dir / "metrics.csv", "the previous whole file\n");
  const std::string big(1 << 20, 'x');
  rlimit before{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &before), 0);
  rlimit small = before;
  small.rlim_cur = 4096;
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // report EFBIG instead of killing the test
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string what;
  try {
    sm::write_atomic(dir / "metrics.csv", big);
  } catch (const sm::RunFailure &e) {
    what = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(what.find("cannot write " + (dir / "metrics.csv").string()), std::string::npos) << what;
  EXPECT_NE(what.find("free some disk space"), std::string::npos) << what;
  EXPECT_EQ(sm::read_text(dir / "metrics.csv"), "the previous whole file\n");
  EXPECT_EQ(listing(), (std::vector<std::string>{"metrics.csv"}));
}

TEST_F(CoreFiles, AFolderThatCannotBeMadeNamesTheFileAndTheFix) {
  sm::write_atomic(dir / "train", "a file where the writer wants a folder");
  try {
    sm::write_atomic(dir / "train" / "bpnn" / "model.json", "{}");
    FAIL() << "no error";
  } catch (const sm::RunFailure &e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("cannot write " + (dir / "train" / "bpnn" / "model.json").string(), 0), 0u) << what;
    EXPECT_NE(what.find("a file stands where a folder of this path should be"), std::string::npos) << what;
    EXPECT_EQ(e.exit_code, sm::exit_failure);
  }
  EXPECT_EQ(sm::read_text(dir / "train"), "a file where the writer wants a folder");
  EXPECT_EQ(listing(), (std::vector<std::string>{"train"}));
}

TEST_F(CoreFiles, TheWriterGetsAnEmptyTemporaryBesideTheTarget) {
  sm::write_atomic_with(dir / "snapshot.png", [&](const fs::path &tmp) {
    EXPECT_EQ(tmp.parent_path(), dir);  // the same file system, so the rename is atomic
    EXPECT_EQ(tmp.extension(), ".png");
    ASSERT_TRUE(fs::is_regular_file(tmp));  // created exclusively, before the writer runs
    EXPECT_EQ(fs::file_size(tmp), 0u);
    std::FILE *f = std::fopen(tmp.c_str(), "wb");
    std::fputs("picture", f);
    std::fclose(f);
  });
  EXPECT_EQ(sm::read_text(dir / "snapshot.png"), "picture");
  EXPECT_EQ(listing(), (std::vector<std::string>{"snapshot.png"}));
}

// Four threads rewrite one file, each with its own content of its own length, while a reader reads
// it: every read is one of the whole contents, and so is the end state.
TEST_F(CoreFiles, ConcurrentWritersAndAReaderOnlyEverSeeWholeFiles) {
  const fs::path target = dir / "manifest.json";
  std::vector<std::string> contents;
  for (char c : {'a', 'b', 'c', 'd'}) contents.push_back(std::string(65536 + 977 * (c - 'a'), c));
  sm::write_atomic(target, contents[0]);
  std::atomic<int> writing{4};
  std::atomic<int> reads{0}, torn{0};
  std::thread reader([&] {
    while (writing > 0) {
      const std::string seen = sm::read_text(target);
      ++reads;
      if (std::find(contents.begin(), contents.end(), seen) == contents.end()) ++torn;
    }
  });
  std::vector<std::thread> writers;
  for (const auto &content : contents)
    writers.emplace_back([&] {
      for (int k = 0; k < 25; ++k) sm::write_atomic(target, content);
      --writing;
    });
  for (auto &w : writers) w.join();
  reader.join();
  EXPECT_GT(reads.load(), 0);
  EXPECT_EQ(torn.load(), 0) << "reads that were no whole content, of " << reads.load();
  EXPECT_NE(std::find(contents.begin(), contents.end(), sm::read_text(target)), contents.end());
  EXPECT_EQ(listing(), (std::vector<std::string>{"manifest.json"}));
}

// Two processes (the same counter after fork, other pids) rewrite one file: both succeed every
// time, the end state is one whole content.
TEST_F(CoreFiles, TwoProcessesWritingOneFileLeaveAWholeOne) {
  const fs::path target = dir / "case.json";
  const std::string parent(50000, 'p'), child(70000, 'c');
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    int failed = 0;
    for (int k = 0; k < 25; ++k) try {
        sm::write_atomic(target, child);
      } catch (...) {
        failed = 1;
      }
    ::_exit(failed);
  }
  for (int k = 0; k < 25; ++k) sm::write_atomic(target, parent);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the child's writes failed";
  const std::string end = sm::read_text(target);
  EXPECT_TRUE(end == parent || end == child) << end.size() << " bytes";
  EXPECT_EQ(listing(), (std::vector<std::string>{"case.json"}));
}

TEST_F(CoreFiles, TemporaryNamesAreUniqueAndHidden) {
  const fs::path a = sm::temporary_beside(dir / "case.json");
  EXPECT_EQ(a.parent_path(), dir);
  EXPECT_EQ(a.filename().string().rfind(".case.json.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << a;
  EXPECT_EQ(a.extension(), ".json");  // writers that pick a format by extension still work
  // Eight threads draw 1000 names each for the same target: no two alike.
  std::mutex m;
  std::set<fs::path> names{a};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&] {
      std::vector<fs::path> mine;
      for (int k = 0; k < 1000; ++k) mine.push_back(sm::temporary_beside(dir / "case.json"));
      std::lock_guard lock(m);
      names.insert(mine.begin(), mine.end());
    });
  for (auto &t : threads) t.join();
  EXPECT_EQ(names.size(), 8001u);
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
