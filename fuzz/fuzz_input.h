#pragma once
// What every harness shares: the fuzz input written to a file in /dev/shm (the loaders take
// paths), and the check that aborts when a successful load breaks what a load promises.
#include <cstddef>
#include <cstdint>
#include <string>

namespace isocurv::fuzz {

/// Files of one fuzz input in a private folder under /dev/shm (else the temp folder), emptied for
/// each input and removed at exit.
class InputFiles {
 public:
  /// Writes `size` bytes of `data` to `name` in the folder and returns its path.
  std::string write(const std::string& name, const std::uint8_t* data, std::size_t size);
  /// Removes the files of the previous input.
  void clear();
  /// The folder (created on first use).
  const std::string& folder();

 private:
  std::string folder_;
};

/// The process's InputFiles.
InputFiles& input_files();

/// Aborts with `what` on stderr unless `ok`: a successful load broke a promise.
void require(bool ok, const std::string& what);

}  // namespace isocurv::fuzz
