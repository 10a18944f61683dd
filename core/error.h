#pragma once
// The one exception type isocurv throws for bad input or an unusable environment.
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

}  // namespace isocurv
