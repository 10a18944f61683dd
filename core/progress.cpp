#include "core/progress.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>

namespace isocurv {
namespace {
std::atomic<bool> g_enabled{true};
}

void set_progress_enabled(bool enabled) { g_enabled = enabled; }

Progress::Progress(std::string label, std::uint64_t total)
    : label_(std::move(label)), total_(total ? total : 1),
      active_(g_enabled && isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(std::uint64_t units) { set(done_ + units); }

void Progress::set(std::uint64_t done) {
  done_ = done > total_ ? total_ : done;
  draw(false);
}

void Progress::draw(bool force) {
  if (!active_) return;
  auto now = std::chrono::steady_clock::now();
  // Only show a bar for steps that take more than a moment.
  if (!force && (now - start_ < std::chrono::milliseconds(300) ||
                 now - last_ < std::chrono::milliseconds(100)))
    return;
  last_ = now;
  const int width = 30;
  const int filled = static_cast<int>(width * done_ / total_);
  std::fprintf(stderr, "\r%-12s [", label_.c_str());
  for (int i = 0; i < width; ++i) std::fputc(i < filled ? '#' : ' ', stderr);
  std::fprintf(stderr, "] %3d%%", static_cast<int>(100 * done_ / total_));
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (active_ && drawn_) {
    std::fprintf(stderr, "\r%60s\r", "");
    std::fflush(stderr);
  }
  active_ = false;
}

}  // namespace isocurv
