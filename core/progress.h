#pragma once
// A progress bar on stderr for long steps; silent when stderr is not a terminal or when quiet.
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

/// Progress of one step with `total` units. Draws at most ~10 times a second, erases itself when
/// finished or destroyed. Thread-compatible: call advance() from one thread.
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
  bool active_, drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

/// A bar for a step whose amount of work is not known in advance (loading a file, one library
/// call): once the step has run for progress_delay(), a thread of its own draws
/// "label  [    <=>    ]  1.2 s" on stderr ten times a second until finish() or destruction,
/// which erase it. Nothing when progress_visible() is false. Create and finish it from one thread.
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
