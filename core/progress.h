#pragma once
// A progress bar on stderr for long steps; silent when stderr is not a terminal or when quiet.
#include <chrono>
#include <cstdint>
#include <string>

namespace isocurv {

/// Globally silences every progress bar (the CLI's --quiet).
void set_progress_enabled(bool enabled);

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

}  // namespace isocurv
