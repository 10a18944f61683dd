#pragma once
// A progress bar on stderr for long steps; silent when stderr is not a terminal or when quiet.
// Tested in tests/core/test_progress.cpp, tests/io/test_mesh_file.cpp.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace isocurv {

/// Globally silences every progress bar (the CLI's --quiet).
void set_progress_enabled(bool enabled);

/// How long a step runs before its bar appears: 500 ms, or ISOCURV_PROGRESS_DELAY_MS when that
/// is set to a number of milliseconds (tests set 0).
std::chrono::milliseconds progress_delay();

/// True when bars are drawn: enabled and stderr is a terminal.
bool progress_visible();

/// Tells the running StageBar how far its stage has come (0..1, clamped). The bar then shows a
/// filled bar, the percentage and the time left instead of a bouncing block. Ignored when no
/// StageBar runs. Cheap (one relaxed atomic store); any thread may call it.
void report_stage_progress(double fraction);

/// The fraction last reported since the latest StageBar started, or -1 when none was.
double stage_progress();

/// Counts the units of work of a parallel loop inside a stage and reports done/total through
/// report_stage_progress. Thread-safe: add() from any thread (one atomic add per call; call it
/// per chunk, not per element).
class StageCounter {
 public:
  explicit StageCounter(std::uint64_t total) : total_(total ? total : 1) {}
  void add(std::uint64_t units);

 private:
  std::uint64_t total_;
  std::atomic<std::uint64_t> done_{0};
};

/// Progress of one step with `total` units. Inside a running StageBar it draws nothing itself and
/// feeds that bar (report_stage_progress), so one line shows one bar; otherwise it draws its own
/// as a StageBar with known progress does ("label  [####      ]  42%  1.2 s, 1.6 s left"), at most
/// ~10 times a second, and erases itself when finished or destroyed. Thread-compatible:
/// call advance() from one thread.
class Progress {
 public:
  Progress(std::string label, std::uint64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void advance(std::uint64_t units = 1);  ///< adds units done
  void set(std::uint64_t done);           ///< sets units done
  void finish();                          ///< erases the bar

 private:
  void draw(bool force);
  std::string label_;
  std::uint64_t total_, done_ = 0;
  bool active_;
  std::size_t widest_ = 0;  // the longest line drawn (0: nothing drawn yet)
  std::chrono::steady_clock::time_point start_, last_;
};

/// The bar of one pipeline stage (app's StageTimer makes one per stage): once the stage has run
/// for progress_delay(), a thread of its own draws on stderr, ten times a second until finish()
/// or destruction (which erase it), either "label  [####      ]  42%  1.2 s, 1.6 s left" when the
/// stage's code reports how far it is (report_stage_progress, StageCounter, Progress), or
/// "label  [   =====    ]  1.2 s" for work of unknown size (one library call). Nothing when
/// progress_visible() is false. One StageBar at a time; create and finish it from one thread.
class StageBar {
 public:
  explicit StageBar(std::string label);
  ~StageBar();
  StageBar(const StageBar&) = delete;
  StageBar& operator=(const StageBar&) = delete;
  void finish();  ///< stops the thread and erases the bar (idempotent)

 private:
  void run();
  std::string label_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace isocurv
