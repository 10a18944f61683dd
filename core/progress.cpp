#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace isocurv {
namespace {
std::atomic<bool> g_enabled{true};
/// The running stage's reported fraction (-1: none reported) and whether a StageBar runs.
std::atomic<double> g_stage_fraction{-1.0};
std::atomic<int> g_stage_bars{0};

/// "1.2 s" or "2 min 5 s".
std::string format_seconds(double s) {
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  else
    std::snprintf(buf, sizeof buf, "%d min %d s", int(s / 60), int(s) % 60);
  return buf;
}

constexpr int kBarWidth = 24;  // the bar's inner width, in characters

/// The bar's text after the label: "[########        ]  33%  2.1 s, 4.2 s left" for a known
/// fraction, "[   =====        ]  2.1 s" (the block at `frame`'s place) for an unknown one (< 0).
std::string bar_text(double fraction, double seconds, int frame) {
  constexpr int kBlock = 5;  // the bouncing block's width
  char bar[kBarWidth + 1];
  std::string tail = format_seconds(seconds);
  if (fraction >= 0) {  // known progress: a filled bar, the percentage, the time left
    const int filled = static_cast<int>(kBarWidth * std::min(fraction, 1.0));
    for (int i = 0; i < kBarWidth; ++i) bar[i] = i < filled ? '#' : ' ';
    char pct[16];
    std::snprintf(pct, sizeof pct, "%3d%%  ", static_cast<int>(100 * std::min(fraction, 1.0)));
    tail = pct + tail;
    if (fraction > 0.02 && fraction < 1)
      tail += ", " + format_seconds(seconds * (1 - fraction) / fraction) + " left";
  } else {  // unknown: the block bounces from end to end
    const int period = 2 * (kBarWidth - kBlock);
    const int phase = frame % period, at = phase <= kBarWidth - kBlock ? phase : period - phase;
    for (int i = 0; i < kBarWidth; ++i) bar[i] = (i >= at && i < at + kBlock) ? '=' : ' ';
  }
  bar[kBarWidth] = '\0';
  return std::string("[") + bar + "] " + tail;
}

/// Draws "\r<label> <bar text>" on stderr, padded over what a longer earlier line left; `widest`
/// is the longest line drawn so far (updated).
void draw_line(const std::string& label, const std::string& text, std::size_t& widest) {
  char line[256];
  const int len = std::snprintf(line, sizeof line, "\r%-12s %s", label.c_str(), text.c_str());
  const std::size_t shown = len > 0 ? std::min(std::size_t(len), sizeof line - 1) : 0;
  std::fprintf(stderr, "%s%*s", line, int(widest > shown ? widest - shown : 0), "");
  widest = std::max(widest, shown);
  std::fflush(stderr);
}

/// Erases a line of `widest` characters drawn by draw_line.
void erase_line(std::size_t widest) {
  if (widest == 0) return;
  std::fprintf(stderr, "\r%*s\r", static_cast<int>(widest), "");
  std::fflush(stderr);
}
}  // namespace

void report_stage_progress(double fraction) {
  if (!(fraction >= 0)) fraction = 0;
  g_stage_fraction.store(fraction > 1 ? 1.0 : fraction, std::memory_order_relaxed);
}

double stage_progress() { return g_stage_fraction.load(std::memory_order_relaxed); }

void StageCounter::add(std::uint64_t units) {
  const std::uint64_t done = done_.fetch_add(units, std::memory_order_relaxed) + units;
  report_stage_progress(double(done) / double(total_));
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
    : label_(std::move(label)),
      total_(total ? total : 1),
      active_(progress_visible() && g_stage_bars.load() == 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(std::uint64_t units) { set(done_ + units); }

void Progress::set(std::uint64_t done) {
  done_ = done > total_ ? total_ : done;
  if (g_stage_bars.load(std::memory_order_relaxed) > 0)
    report_stage_progress(double(done_) / double(total_));
  draw(false);
}

void Progress::draw(bool force) {
  if (!active_) return;
  auto now = std::chrono::steady_clock::now();
  // Only show a bar for steps that take more than a moment.
  if (!force && (now - start_ < progress_delay() || now - last_ < std::chrono::milliseconds(100)))
    return;
  last_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  draw_line(label_, bar_text(double(done_) / double(total_), seconds, 0), widest_);
}

void Progress::finish() {
  if (active_) erase_line(widest_);
  widest_ = 0;
  active_ = false;
}

StageBar::StageBar(std::string label) : label_(std::move(label)) {
  g_stage_fraction = -1.0;
  ++g_stage_bars;
  if (progress_visible()) thread_ = std::thread([this] { run(); });
}

StageBar::~StageBar() { finish(); }

void StageBar::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (done_) return;
    done_ = true;
  }
  --g_stage_bars;
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void StageBar::run() {
  constexpr auto kRedraw = std::chrono::milliseconds(100);
  const auto start = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  if (wake_.wait_for(lock, progress_delay(), [this] { return done_; })) return;  // quick: no bar
  std::size_t widest = 0;  // the longest line drawn, to erase it
  for (int frame = 0; !done_; ++frame) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    draw_line(label_, bar_text(g_stage_fraction.load(std::memory_order_relaxed), s, frame), widest);
    wake_.wait_for(lock, kRedraw, [this] { return done_; });
  }
  erase_line(widest);
}

}  // namespace isocurv
