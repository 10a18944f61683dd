#pragma once
// Running the real `isocurv` executable as a subprocess for the end-to-end tests: stdout, stderr
// and exit status captured, a timeout, DISPLAY unset (rendering must start its own Xvfb).
#include "tests/test_paths.h"
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace isocurv::test {

namespace fs = std::filesystem;

/// What one run of the executable produced.
struct CliResult {
  int exit_code = -1;     ///< exit status, or -1 when killed by a signal
  int signal = 0;         ///< terminating signal, 0 when it exited
  bool timed_out = false;
  std::string out, err;
  std::string command;    ///< for failure messages

  bool ok() const { return exit_code == 0 && !timed_out; }
  /// The non-empty lines of stderr.
  std::vector<std::string> err_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string l; std::getline(in, l);)
      if (!l.empty()) lines.push_back(l);
    return lines;
  }
  /// Everything useful for a failure message.
  std::string describe() const {
    std::ostringstream s;
    s << "command: " << command << "\nexit " << exit_code << (signal ? " signal " + std::to_string(signal) : "")
      << (timed_out ? " (TIMED OUT)" : "") << "\n--- stdout\n" << out.substr(0, 4000) << "\n--- stderr\n"
      << err.substr(0, 4000);
    return s.str();
  }
};

inline std::string build_dir() { return isocurv::test_paths::build_dir(); }
/// The executable under test: this build's, or ISOCURV_TEST_EXE (e.g. an older build, to see
/// which tests fail without a fix).
inline std::string isocurv_exe() {
  const char* other = std::getenv("ISOCURV_TEST_EXE");
  return other && *other ? std::string(other) : build_dir() + "/app/isocurv";
}
/// A bundled dataset generated at build time (64^3 by default).
inline std::string dataset(const std::string& name) { return build_dir() + "/datasets/" + name + ".vdb"; }

/// Runs `exe args...` (an absolute path: isocurv, or mpirun running it) with DISPLAY unset and
/// stdin from /dev/null, plus `env` ("NAME=VALUE" entries set in the child; "NAME=" sets it
/// empty); kills its process group after timeout_s seconds.
inline CliResult run_program(const std::string& exe, const std::vector<std::string>& args, double timeout_s = 60,
                             const std::vector<std::string>& env = {}) {
  CliResult r;
  r.command = fs::path(exe).filename().string();
  for (const auto& a : args) r.command += " " + a;
  if (access(exe.c_str(), X_OK) != 0) {
    r.err = "the executable is missing: " + exe + " (build the isocurv target)";
    return r;
  }
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(exe.c_str()));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  int out_pipe[2], err_pipe[2];
  if (pipe(out_pipe) != 0 || pipe(err_pipe) != 0) {
    r.err = "pipe() failed";
    return r;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    unsetenv("DISPLAY");
    for (const auto& e : env) {
      const auto eq = e.find('=');
      if (eq != std::string::npos) setenv(e.substr(0, eq).c_str(), e.substr(eq + 1).c_str(), 1);
    }
    const int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, STDIN_FILENO);
    dup2(out_pipe[1], STDOUT_FILENO);
    dup2(err_pipe[1], STDERR_FILENO);
    close(out_pipe[0]);
    close(out_pipe[1]);
    close(err_pipe[0]);
    close(err_pipe[1]);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  close(out_pipe[1]);
  close(err_pipe[1]);
  if (pid < 0) {
    close(out_pipe[0]);
    close(err_pipe[0]);
    r.err = "fork() failed";
    return r;
  }
  setpgid(pid, pid);  // also from the parent, so the group exists before any kill

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::array<pollfd, 2> fds{{{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}}};
  std::string* sinks[2] = {&r.out, &r.err};
  int open_fds = 2;
  char buf[65536];
  while (open_fds > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      r.timed_out = true;
      kill(-pid, SIGKILL);
      break;
    }
    const int n = poll(fds.data(), fds.size(), static_cast<int>(std::min<std::int64_t>(left.count(), 1000)));
    if (n < 0 && errno != EINTR) break;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t got = read(fds[i].fd, buf, sizeof buf);
      if (got > 0) {
        sinks[i]->append(buf, static_cast<std::size_t>(got));
      } else if (got == 0 || errno != EINTR) {
        close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      }
    }
  }
  for (auto& f : fds)
    if (f.fd >= 0) close(f.fd);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    r.signal = WTERMSIG(status);
  }
  return r;
}

/// run_program on this build's isocurv.
inline CliResult run_isocurv(const std::vector<std::string>& args, double timeout_s = 60,
                             const std::vector<std::string>& env = {}) {
  return run_program(isocurv_exe(), args, timeout_s, env);
}

/// A fresh, empty temporary folder per test, removed at the end when the test passed.
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string tag = name;
    if (info) tag = std::string(info->test_suite_name()) + "_" + info->name();
    path_ = fs::temp_directory_path() / ("isocurv_app_test_" + std::to_string(::getpid()) + "_" + tag);
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    if (!::testing::Test::HasFailure()) {
      std::error_code ec;
      fs::remove_all(path_, ec);
    }
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }
  /// Names of the entries in the folder, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// A CT-like ball written as a raw uint8 file named with its dimensions and type
/// (`prefix`NxNxN_uint8.raw in `dir`): radius R voxels about the centre of the n^3 volume moved
/// by `offset` voxels along each axis, its edge blurred (Gaussian profile, sigma 1 voxel), values
/// 20 outside and 220 inside, uniform noise of +-noise/2 grey levels (a linear congruential
/// sequence from `seed`), quantised.
inline std::string write_ct_ball(const std::string& dir, int n, double R, double noise, std::uint32_t seed,
                                 double offset = 0, const std::string& prefix = "ball_") {
  std::string bytes(std::size_t(n) * n * n, '\0');
  const double c = (n - 1) / 2.0 + offset;
  std::size_t i = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double r = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
        seed = seed * 1664525u + 1013904223u;
        const double u = (double(seed >> 8) / double(1u << 24) - 0.5) * noise;
        const double v = 20 + 200 * 0.5 * (1 + std::erf((R - r) / std::sqrt(2.0))) + u;
        bytes[i++] = char(std::uint8_t(std::lround(std::min(255.0, std::max(0.0, v)))));
      }
  const std::string size = std::to_string(n);
  const std::string path = dir + "/" + prefix + size + "x" + size + "x" + size + "_uint8.raw";
  write_file(path, bytes);
  return path;
}

/// Parses stdout as JSON; on failure returns null and records a test failure.
inline nlohmann::json parse_json(const std::string& text, const std::string& what) {
  try {
    return nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << " is not JSON: " << e.what() << "\n" << text.substr(0, 2000);
    return nullptr;
  }
}

/// Width and height from a PNG's IHDR chunk; {0, 0} when the file is not a PNG.
inline std::array<std::uint32_t, 2> png_size(const std::string& path) {
  const std::string b = read_file(path);
  static const char sig[] = "\x89PNG\r\n\x1a\n";
  if (b.size() < 24 || b.compare(0, 8, std::string(sig, 8)) != 0 || b.compare(12, 4, "IHDR") != 0) return {0, 0};
  auto be32 = [&b](std::size_t at) {
    return (std::uint32_t(std::uint8_t(b[at])) << 24) | (std::uint32_t(std::uint8_t(b[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(b[at + 2])) << 8) | std::uint32_t(std::uint8_t(b[at + 3]));
  };
  return {be32(16), be32(20)};
}

/// Exactly one line on stderr, starting with "isocurv:" and containing `mention`.
inline void expect_one_error_line(const CliResult& r, const std::string& mention) {
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << "want exactly one line on stderr\n" << r.describe();
  EXPECT_EQ(lines[0].rfind("isocurv:", 0), 0u) << r.describe();
  EXPECT_NE(lines[0].find(mention), std::string::npos)
      << "stderr should mention '" << mention << "'\n"
      << r.describe();
}

/// A usage error (README, "Exit status"): status 2, one line on stderr starting with "isocurv:"
/// and naming `mention` (the offending option or command), nothing on stdout.
inline void expect_usage_error(const CliResult& r, const std::string& mention) {
  EXPECT_FALSE(r.timed_out) << r.describe();
  EXPECT_EQ(r.signal, 0) << "crashed\n" << r.describe();
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_TRUE(r.out.empty()) << r.describe();
  expect_one_error_line(r, mention);
}

/// A failure as DESIGN.md wants it: no crash or hang, exit status 1 (bad input or a failure),
/// exactly one line on stderr starting with "isocurv:" and containing `mention` (e.g. the file
/// name).
inline void expect_clean_failure(const CliResult& r, const std::string& mention) {
  EXPECT_FALSE(r.timed_out) << r.describe();
  EXPECT_EQ(r.signal, 0) << "crashed\n" << r.describe();
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << "want exactly one line on stderr\n" << r.describe();
  EXPECT_EQ(lines[0].rfind("isocurv:", 0), 0u) << r.describe();
  EXPECT_NE(lines[0].find(mention), std::string::npos) << "stderr should mention '" << mention << "'\n" << r.describe();
}

}  // namespace isocurv::test
