// StageBar on a terminal: a bouncing block for work of unknown size, a filled bar with the
// percentage and the time left once the stage reports how far it is; Progress and StageCounter
// feed the running stage's bar.
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "core/progress.h"

namespace isocurv {
namespace {

/// For its lifetime, stderr is the slave side of a pseudo-terminal; text() drains the master.
class StderrOnATerminal {
 public:
  StderrOnATerminal() {
    if (openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) return;
    saved_ = dup(STDERR_FILENO);
    dup2(slave_, STDERR_FILENO);
    setenv("ISOCURV_PROGRESS_DELAY_MS", "0", 1);
  }
  ~StderrOnATerminal() {
    restore();
    if (master_ >= 0) close(master_);
    unsetenv("ISOCURV_PROGRESS_DELAY_MS");
  }
  bool ok() const { return master_ >= 0; }
  void restore() {
    if (saved_ < 0) return;
    fflush(stderr);
    dup2(saved_, STDERR_FILENO);
    close(saved_);
    close(slave_);
    saved_ = -1;
  }
  std::string text() {
    std::string out;
    char buf[4096];
    for (;;) {
      pollfd p{master_, POLLIN, 0};
      if (poll(&p, 1, 50) <= 0) break;
      const ssize_t got = read(master_, buf, sizeof buf);
      if (got <= 0) break;
      out.append(buf, std::size_t(got));
    }
    return out;
  }

 private:
  int master_ = -1, slave_ = -1, saved_ = -1;
};

TEST(StageBar, ShowsThePercentageAndTimeLeftOnceTheStageReportsIt) {
  StderrOnATerminal term;
  ASSERT_TRUE(term.ok());
  {
    StageBar bar("crunch");
    std::this_thread::sleep_for(std::chrono::milliseconds(150));  // unknown size: bouncing block
    EXPECT_EQ(stage_progress(), -1.0);
    report_stage_progress(0.25);
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    EXPECT_EQ(stage_progress(), 0.25);
  }
  term.restore();
  const std::string t = term.text();
  EXPECT_NE(t.find("crunch"), std::string::npos) << t;
  EXPECT_NE(t.find("====="), std::string::npos) << "no bouncing block before progress: " << t;
  EXPECT_NE(t.find(" 25%"), std::string::npos) << t;
  EXPECT_NE(t.find("[######      "), std::string::npos) << "a quarter of the 24-wide bar: " << t;
  EXPECT_NE(t.find(" left"), std::string::npos) << t;
}

TEST(StageBar, ProgressAndCountersFeedTheRunningBarInsteadOfDrawingTheirOwn) {
  StderrOnATerminal term;
  ASSERT_TRUE(term.ok());
  {
    StageBar bar("stage");
    Progress inner("inner", 4);
    inner.set(3);
    EXPECT_DOUBLE_EQ(stage_progress(), 0.75);
    StageCounter counter(1000);
    std::vector<std::thread> threads;
    for (int i = 0; i < 4; ++i)
      threads.emplace_back([&] {
        for (int k = 0; k < 50; ++k) counter.add(5);
      });
    for (auto& th : threads) th.join();
    EXPECT_DOUBLE_EQ(stage_progress(), 1.0);  // 4 x 50 x 5 = 1000 units
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
  }
  EXPECT_EQ(stage_progress(), 1.0);  // kept after the bar ends; the next bar resets it
  StageBar next("next");
  EXPECT_EQ(stage_progress(), -1.0);
  next.finish();
  term.restore();
  const std::string t = term.text();
  EXPECT_EQ(t.find("inner"), std::string::npos) << "the inner Progress drew a bar: " << t;
  EXPECT_NE(t.find("100%"), std::string::npos) << t;
}

TEST(Progress, OnItsOwnDrawsTheStageBarsLineAndErasesIt) {
  // Outside a stage (deform's frames): the same line as a StageBar with known progress.
  StderrOnATerminal term;
  ASSERT_TRUE(term.ok());
  {
    Progress p("frames", 8);
    p.set(4);
    std::this_thread::sleep_for(std::chrono::milliseconds(120));  // one redraw per 100 ms
    p.set(6);
  }
  term.restore();
  const std::string t = term.text();
  EXPECT_NE(t.find("frames"), std::string::npos) << t;
  EXPECT_NE(t.find("[##################      ]  75%"), std::string::npos) << "three quarters of 24: " << t;
  EXPECT_NE(t.find(" left"), std::string::npos) << t;
  EXPECT_EQ(t.back(), '\r') << "the bar is erased at the end: " << t;
}

TEST(StageBar, NothingWhenStderrIsNotATerminal) {
  // The test's stderr is a pipe or a file under ctest; a bar must not draw, but progress is kept.
  if (isatty(STDERR_FILENO)) GTEST_SKIP() << "stderr is a terminal here";
  StageBar bar("quiet");
  report_stage_progress(2.0);
  EXPECT_EQ(stage_progress(), 1.0) << "clamped to 1";
  report_stage_progress(-3.0);
  EXPECT_EQ(stage_progress(), 0.0) << "clamped to 0";
}

}  // namespace
}  // namespace isocurv
