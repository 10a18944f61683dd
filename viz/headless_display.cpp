#include "viz/headless_display.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>

#include <vtkRenderWindow.h>

#include "core/error.h"

// Last: Xlib defines macros (Bool, Status, None, Success) that other headers would trip over.
#include <X11/Xlib.h>

namespace isocurv::viz {
namespace {

constexpr const char* kFailure = "no X display and Xvfb could not be started: apt-get install xvfb";

/// The private Xvfb server; stopped when the process exits (static destruction).
class Xvfb {
 public:
  ~Xvfb() { stop(); }

  bool running() const { return pid_ > 0; }

  /// Starts the server and returns its display number, or -1 on failure.
  int start() {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) return -1;
    // Everything the child needs is prepared before fork (only async-signal-safe calls after).
    const std::string fd_arg = std::to_string(fds[1]);
    const char* argv[] = {"Xvfb", "-displayfd", fd_arg.c_str(), "-screen", "0", "1280x1024x24",
                          "-nolisten", "tcp", "-noreset", nullptr};
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
      close(fds[0]);
      close(fds[1]);
      return -1;
    }
    if (pid == 0) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the process that started it
      if (getppid() != parent) _exit(1);
      setpgid(0, 0);                     // keep terminal signals (Ctrl-C) to ourselves
      fcntl(fds[1], F_SETFD, 0);         // the write end survives exec
      const int null = open("/dev/null", O_RDWR);
      if (null >= 0) {
        dup2(null, STDIN_FILENO);
        dup2(null, STDOUT_FILENO);
        dup2(null, STDERR_FILENO);
      }
      execvp("Xvfb", const_cast<char* const*>(argv));
      _exit(127);
    }
    close(fds[1]);
    pid_ = pid;
    const int display = read_display(fds[0]);
    close(fds[0]);
    if (display < 0) stop();
    return display;
  }

  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    for (int i = 0; i < 100; ++i) {  // up to ~2 s, then force
      if (waitpid(pid_, nullptr, WNOHANG) == pid_) return void(pid_ = -1);
      usleep(20000);
    }
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  /// Xvfb writes "<number>\n" to the -displayfd pipe once it accepts connections; EOF means it
  /// died (missing binary, no free display, ...).
  static int read_display(int fd) {
    std::string text;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (text.find('\n') == std::string::npos) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) return -1;
      pollfd p{fd, POLLIN, 0};
      const int r = poll(&p, 1, static_cast<int>(left.count()));
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) return -1;
      char buffer[32];
      const ssize_t n = read(fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return -1;
      text.append(buffer, static_cast<std::size_t>(n));
    }
    char* end = nullptr;
    const long number = std::strtol(text.c_str(), &end, 10);
    return end == text.c_str() || number < 0 ? -1 : static_cast<int>(number);
  }

  pid_t pid_ = -1;
};

std::mutex g_mutex;

Xvfb& server() {
  static Xvfb instance;
  return instance;
}

/// True when an X client can connect to `name` (XOpenDisplay: the socket, the server's
/// handshake and authorisation).
bool display_opens(const char* name) {
  Display* d = XOpenDisplay(name);
  if (!d) return false;
  XCloseDisplay(d);
  return true;
}

}  // namespace

void ensure_display(DisplayUse use) {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (server().running()) return;
  const char* env = std::getenv("DISPLAY");
  const std::string display = env ? env : "";
  if (!display.empty()) {
    if (display_opens(display.c_str())) return;
    if (use == DisplayUse::interactive)
      throw Error("cannot open X display '" + display +
                  "' (is the X server running, and may we connect?)");
  }
  const int number = server().start();
  if (number < 0)
    throw Error(display.empty() ? std::string(kFailure)
                                : "cannot open X display '" + display +
                                      "' and Xvfb could not be started: apt-get install xvfb");
  setenv("DISPLAY", (":" + std::to_string(number)).c_str(), 1);
}

void check_opengl(vtkRenderWindow* window) {
  static bool checked = false;  // guarded by g_mutex
  std::lock_guard<std::mutex> lock(g_mutex);
  if (checked) return;
  if (!window->SupportsOpenGL()) {
    const char* display = std::getenv("DISPLAY");
    throw Error(std::string("OpenGL 3.2 is not available on X display ") + (display ? display : "(none)") +
                " (VTK needs it to render; with Xvfb, Mesa's llvmpipe provides it: apt-get install libgl1-mesa-dri)");
  }
  checked = true;
}

bool using_private_display() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return server().running();
}

}  // namespace isocurv::viz
