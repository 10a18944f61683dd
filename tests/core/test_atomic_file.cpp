// core/atomic_file: single files and sets of files appear whole or not at all, and a temporary
// being written when SIGTERM or SIGINT arrives is removed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "core/atomic_file.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace {

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("isocurv_atomic_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

void put(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}
std::string get(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
auto writes(const std::string& text) {
  return [text](const std::string& tmp) { put(tmp, text); };
}

/// Forks a child that starts writing `target` atomically and never finishes (it writes the
/// temporary, then sleeps); kills it with `sig` once the temporary exists. Returns the child's
/// wait status.
// A handler as LLVM installs one (PoCL's kernel compiler, in every process that builds an OpenCL
// program): it restores the default action and raises the signal again.
extern "C" void foreign_handler(int sig) {
  signal(sig, SIG_DFL);
  raise(sig);
}

int kill_during_write(const std::string& target, int sig, bool as_set, bool foreign = false) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (foreign) {  // a first write installs ours; then another library installs its own
      isocurv::write_atomically(target + ".before", writes("x"));
      signal(SIGINT, foreign_handler);
      signal(SIGTERM, foreign_handler);
    }
    auto endless = [](const std::string& tmp) {
      put(tmp, std::string(1 << 20, 'x'));
      for (;;) pause();
    };
    if (as_set) {
      isocurv::AtomicFileSet set;
      set.write(target + ".first", writes("done"));
      set.write(target, endless);
    } else {
      isocurv::write_atomically(target, endless);
    }
    _exit(0);
  }
  // The child's temporary: temporary_path_for's name, with the child's process id.
  const fs::path t(target);
  const std::string tmp_in_child =
      (t.parent_path() /
       ("." + t.stem().string() + ".tmp" + std::to_string(pid) + t.extension().string()))
          .string();
  for (int i = 0; i < 500 && !fs::exists(tmp_in_child); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(fs::exists(tmp_in_child)) << "the child never started writing";
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

}  // namespace

TEST_F(AtomicFile, WritesAndReplacesWhole) {
  put(at("a.txt"), "old");
  isocurv::write_atomically(at("a.txt"), writes("new"));
  EXPECT_EQ(get(at("a.txt")), "new");
  EXPECT_THROW(isocurv::write_atomically(at("a.txt"),
                                         [](const std::string& tmp) {
                                           put(tmp, "half");
                                           throw std::runtime_error("disk full");
                                         }),
               std::runtime_error);
  EXPECT_EQ(get(at("a.txt")), "new");
  EXPECT_EQ(entries(), std::vector<std::string>{"a.txt"});
}

TEST_F(AtomicFile, AnErrorNamingTheTemporaryNamesTheTarget) {
  try {
    isocurv::write_atomically(
        at("b.png"), [](const std::string& tmp) { throw isocurv::Error(tmp, "cannot write"); });
    FAIL() << "no exception";
  } catch (const isocurv::Error& e) {
    EXPECT_EQ(std::string(e.what()), at("b.png") + ": cannot write");
  }
}

TEST_F(AtomicFile, ASetAppearsOnlyWhenCommitted) {
  put(at("stats.json"), "old stats");
  {
    isocurv::AtomicFileSet set;
    set.write(at("mesh.vtp"), writes("mesh"));
    set.write(at("stats.json"), writes("new stats"));
    EXPECT_FALSE(fs::exists(at("mesh.vtp")));
    EXPECT_EQ(get(at("stats.json")), "old stats");
    // Destroyed without commit (a later step failed): nothing new, nothing changed.
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"stats.json"});
  EXPECT_EQ(get(at("stats.json")), "old stats");

  isocurv::AtomicFileSet set;
  set.write(at("mesh.vtp"), writes("mesh"));
  set.write(at("stats.json"), writes("new stats"));
  set.commit();
  EXPECT_EQ(get(at("mesh.vtp")), "mesh");
  EXPECT_EQ(get(at("stats.json")), "new stats");
  EXPECT_EQ(entries(), (std::vector<std::string>{"mesh.vtp", "stats.json"}));
}

TEST_F(AtomicFile, AFailedRenameRollsTheSetBack) {
  put(at("a.txt"), "old a");
  fs::create_directories(at("b"));  // a non-empty folder where the set wants the file b
  put(at("b/keep"), "x");
  {
    isocurv::AtomicFileSet set;
    set.write(at("new.txt"), writes("new"));
    set.write(at("a.txt"), writes("new a"));
    set.write(at("b"), writes("new b"));
    EXPECT_THROW(set.commit(), isocurv::Error);
  }
  EXPECT_EQ(get(at("a.txt")), "old a") << "the replaced file is restored";
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.txt", "b"}))
      << "new files removed, no temporaries left";
}

TEST_F(AtomicFile, SigtermDuringAWriteRemovesTheTemporary) {
  const int status = kill_during_write(at("big.vtp"), SIGTERM, false);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM)
      << "the signal still ends the process";
  EXPECT_TRUE(entries().empty()) << ::testing::PrintToString(entries());
}

TEST_F(AtomicFile, SignalHandlersOfOtherLibrariesDoNotHideTheTemporaries) {
  // Installed after our first write (as LLVM's are when PoCL compiles a kernel), another
  // library's handler must not keep ours from running: the temporary goes, the signal still ends
  // the process.
  const int status = kill_during_write(at("big.vtp"), SIGTERM, false, true);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_EQ(entries(), std::vector<std::string>{"big.vtp.before"});
}

TEST_F(AtomicFile, SigintDuringASetRemovesEveryTemporary) {
  const int status = kill_during_write(at("big.png"), SIGINT, true);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
  EXPECT_TRUE(entries().empty()) << ::testing::PrintToString(entries());
}

// A folder made for the outputs goes again when nothing lands in it: on a failure (the guard's
// destruction) and when the process is interrupted (an interrupted `isocurv run` left an empty
// new folder behind); an existing folder and a folder holding files stay.
TEST_F(AtomicFile, ANewFolderLeftEmptyIsRemovedAlsoOnASignal) {
  const std::string made = at("out/deeper");
  {
    const isocurv::NewFolder f(made);
    EXPECT_TRUE(f.created());
    EXPECT_TRUE(fs::is_directory(made));
  }
  EXPECT_FALSE(fs::exists(made)) << "an empty new folder stays";
  {
    const isocurv::NewFolder f(made);
    put(made + "/result.txt", "kept");
  }
  EXPECT_TRUE(fs::exists(made + "/result.txt")) << "a folder with outputs went";
  {
    const isocurv::NewFolder f(made);  // exists already
    EXPECT_FALSE(f.created());
  }
  fs::remove_all(at("out"));
  put(at("file"), "x");
  EXPECT_THROW(isocurv::NewFolder(at("file")), isocurv::Error);

  const std::string interrupted = at("interrupted");
  const pid_t pid = fork();
  if (pid == 0) {
    isocurv::NewFolder f(interrupted);
    isocurv::write_atomically(interrupted + "/mesh.vtp", [](const std::string& tmp) {
      put(tmp, std::string(1 << 16, 'x'));
      for (;;) pause();
    });
    _exit(0);
  }
  for (int i = 0; i < 500 && !(fs::exists(interrupted) && !fs::is_empty(interrupted)); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(interrupted)) << "the child never made its folder";
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT);
  EXPECT_FALSE(fs::exists(interrupted)) << "the interrupted run's new folder stays";
}
