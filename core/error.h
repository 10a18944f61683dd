#pragma once
// The one exception type isocurv throws for bad input or an unusable environment.
// Tested in tests/core/test_atomic_file.cpp, tests/core/test_camera.cpp.
#include <stdexcept>
#include <string>

namespace isocurv {

/// A user-facing failure: what() is one line, naming the file (when there is one) and the problem.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  /// "<path>: <problem>"
  Error(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem) {}
};

/// `text` on one line, as error messages are printed: newlines, tabs and runs of blanks become
/// single spaces, and trailing blanks go (a library's multi-line message, e.g. VTK's).
inline std::string one_line(const std::string& text) {
  std::string line;
  for (char c : text) {
    const char d = (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
    if (!(d == ' ' && (line.empty() || line.back() == ' '))) line.push_back(d);
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line;
}

}  // namespace isocurv
