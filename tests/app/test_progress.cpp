// Progress bars: drawn on a terminal (a pseudo-terminal here), never into a pipe or with --quiet.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "cli.h"

using namespace isocurv::test;

namespace {

/// Runs isocurv with stderr on the slave side of a pseudo-terminal (stdout to /dev/null) and
/// returns what arrived on the master side; DISPLAY unset, `env` set.
std::string stderr_on_a_terminal(const std::vector<std::string>& args,
                                 const std::vector<std::string>& env, int* exit_code) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return "openpty failed";
  const std::string exe = isocurv_exe();
  std::vector<char*> argv{const_cast<char*>(exe.c_str())};
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    setsid();
    unsetenv("DISPLAY");
    for (const auto& e : env) {
      const auto eq = e.find('=');
      setenv(e.substr(0, eq).c_str(), e.substr(eq + 1).c_str(), 1);
    }
    const int devnull = open("/dev/null", O_RDWR);
    dup2(devnull, STDIN_FILENO);
    dup2(devnull, STDOUT_FILENO);
    dup2(slave, STDERR_FILENO);
    close(master);
    close(slave);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  close(slave);
  std::string text;
  char buf[4096];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  for (;;) {
    pollfd p{master, POLLIN, 0};
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      break;
    }
    if (poll(&p, 1, 1000) <= 0) continue;
    const ssize_t got = read(master, buf, sizeof buf);
    if (got <= 0) break;  // EIO once the child has closed the slave side
    text.append(buf, static_cast<std::size_t>(got));
  }
  close(master);
  int status = 0;
  waitpid(pid, &status, 0);
  *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return text;
}

}  // namespace

TEST(Progress, BarsOnATerminalNoneWhenPipedOrQuiet) {
  TempDir dir("progress");
  // A zero delay makes every stage show its bar (normally only those over half a second).
  const std::vector<std::string> env = {"ISOCURV_PROGRESS_DELAY_MS=0"};
  const std::vector<std::string> args = {"run",       dataset("gyroid"), "-o",
                                         dir / "out", "--size",          "160x120"};
  int code = -1;
  const std::string tty = stderr_on_a_terminal(args, env, &code);
  EXPECT_EQ(code, 0) << tty;
  EXPECT_NE(tty.find('\r'), std::string::npos) << "no bar drawn on the terminal: " << tty;
  for (const char* stage : {"load", "extract", "curvature", "render"})
    EXPECT_NE(tty.find(stage), std::string::npos) << stage << " has no bar: " << tty;
  EXPECT_NE(tty.find(" s"), std::string::npos) << "bars show the elapsed time";

  const auto piped =
      run_isocurv({"run", dataset("gyroid"), "-o", dir / "piped", "--size", "160x120"}, 120, env);
  EXPECT_TRUE(piped.ok()) << piped.describe();
  EXPECT_EQ(piped.err.find('\r'), std::string::npos) << "a bar went into a pipe: " << piped.err;
  EXPECT_EQ(piped.err.find('['), std::string::npos) << piped.err;

  const std::string quiet = stderr_on_a_terminal(
      {"run", dataset("gyroid"), "-o", dir / "quiet", "--size", "160x120", "--quiet"}, env, &code);
  EXPECT_EQ(code, 0) << quiet;
  EXPECT_EQ(quiet.find('\r'), std::string::npos) << "--quiet drew a bar: " << quiet;
}

TEST(Progress, StagesThatKnowTheirSizeShowAPercentageInOneBar) {
  TempDir dir("progress_pct");
  // A CT-like uint8 ball (blurred edge, quantised) written as NRRD; `features` counts vertices.
  const int n = 80;
  std::string voxels(std::size_t(n) * n * n, '\0');
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double r =
            std::sqrt(double((x - 40) * (x - 40) + (y - 38) * (y - 38) + (z - 41) * (z - 41)));
        const double v = 200.0 / (1.0 + std::exp((r - 30.0) / 1.2)) + 20.0;
        voxels[(std::size_t(z) * n + y) * n + x] =
            static_cast<char>(static_cast<unsigned char>(std::lround(v)));
      }
  write_file(dir / "ball.nrrd",
             "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 80 80 80\nencoding: raw\n\n" + voxels);
  int code = -1;
  const std::string tty = stderr_on_a_terminal(
      {"features", dir / "ball.nrrd", "--iso", "120", "--radius", "4", "-o", dir / "ball.vtp"},
      {"ISOCURV_PROGRESS_DELAY_MS=0"}, &code);
  ASSERT_EQ(code, 0) << tty;
  auto shows_percent = [&](const std::string& stage) {
    // The stage's label, then its bar, then "NN%" before the next carriage return.
    for (std::size_t at = tty.find("\r" + stage); at != std::string::npos;
         at = tty.find("\r" + stage, at + 1)) {
      const std::size_t end = tty.find('\r', at + 1);
      const std::string line =
          tty.substr(at, end == std::string::npos ? std::string::npos : end - at);
      if (line.find('%') != std::string::npos && line.find('#') != std::string::npos) return true;
    }
    return false;
  };
  // Loading and writing this volume take less than a redraw (their counting is tested in
  // tests/core and tests/io); the features loop runs for about a second.
  EXPECT_TRUE(shows_percent("features")) << tty;
  // One bar per line: the features loop feeds the stage's bar instead of drawing its own (whose
  // inner width, 30, differs from the stage bar's 24).
  EXPECT_FALSE(std::regex_search(tty, std::regex("\\[[# ]{30}\\]"))) << tty;
}
