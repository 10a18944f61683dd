#include "core/progress.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace isocurv {
namespace {
std::atomic<bool> g_enabled{true};
}

void set_progress_enabled(bool enabled) { g_enabled = enabled; }

std::chrono::milliseconds progress_delay() {
  constexpr long kDefaultDelayMs = 500;
  const char* env = std::getenv("ISOCURV_PROGRESS_DELAY_MS");
  if (env && *env) {
    char* end = nullptr;
    const long ms = std::strtol(env, &end, 10);
    if (end && *end == '\0' && ms >= 0) return std::chrono::milliseconds(ms);
  }
  return std::chrono::milliseconds(kDefaultDelayMs);
}

bool progress_visible() { return g_enabled && isatty(STDERR_FILENO); }

Progress::Progress(std::string label, std::uint64_t total)
    : label_(std::move(label)), total_(total ? total : 1),
      active_(progress_visible()),
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
  if (!force && (now - start_ < progress_delay() ||
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

StageBar::StageBar(std::string label) : label_(std::move(label)) {
  if (progress_visible()) thread_ = std::thread([this] { run(); });
}

StageBar::~StageBar() { finish(); }

void StageBar::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void StageBar::run() {
  constexpr int kWidth = 24, kBlock = 5;  // the bar's inner width; the moving block's
  constexpr auto kRedraw = std::chrono::milliseconds(100);
  const auto start = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  if (wake_.wait_for(lock, progress_delay(), [this] { return done_; })) return;  // quick: no bar
  bool drawn = false;
  for (int frame = 0; !done_; ++frame) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int period = 2 * (kWidth - kBlock);  // the block bounces from end to end
    const int phase = frame % period, at = phase <= kWidth - kBlock ? phase : period - phase;
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = (i >= at && i < at + kBlock) ? '=' : ' ';
    bar[kWidth] = '\0';
    std::fprintf(stderr, "\r%-12s [%s] %6.1f s", label_.c_str(), bar, s);
    std::fflush(stderr);
    drawn = true;
    wake_.wait_for(lock, kRedraw, [this] { return done_; });
  }
  if (drawn) {
    std::fprintf(stderr, "\r%*s\r", static_cast<int>(label_.size()) + kWidth + 24, "");
    std::fflush(stderr);
  }
}

}  // namespace isocurv
