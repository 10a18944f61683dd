#pragma once
// Writing output files safely: to a temporary name beside the target, then renamed over it; a
// set of files all together or not at all. Temporaries still being written are removed when the
// process is killed by SIGINT, SIGTERM, SIGHUP or SIGQUIT.
// Tested in tests/core/test_atomic_file.cpp, tests/io/test_mesh_file.cpp.
#include <functional>
#include <string>
#include <vector>

namespace isocurv {

/// Calls write(tmp_path) to produce the file under a temporary name in the same folder, then
/// renames it to `path`. If write throws (or the rename fails) the temporary is removed, the
/// exception propagates and any existing file at `path` is left untouched. (An AtomicFileSet of
/// one file.)
void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write);

/// Checks, before any work, that write_atomically(path, ...) can succeed as far as the file system
/// goes: `path` is not a folder, and its folder exists and lets this process create files (probed
/// by creating and removing a temporary file there).
/// @throw Error naming `path` (one line: which of the three it is) otherwise.
void require_writable_file(const std::string& path);

/// The temporary name write_atomically uses for `path` (same folder, same extension so that
/// writers choosing a format by extension still work).
std::string temporary_path_for(const std::string& path);

/// Several output files that appear together or not at all (isocurv run's mesh, PNG and
/// stats.json). Each write() produces its file under a temporary name; commit() renames them all
/// into place. A set destroyed without commit() removes its temporaries, so a failure anywhere
/// before commit() leaves no new file and every existing one untouched. If a rename inside commit()
/// fails, the files already renamed are rolled back (a replaced file is restored from a hard link
/// made before the rename; where the filesystem cannot link, the new file stays).
///
/// While a temporary exists (here or in write_atomically) it is registered, and a handler for
/// SIGINT, SIGTERM, SIGHUP and SIGQUIT (installed on first use, only for signals whose action is
/// still the default) removes the registered temporaries with unlink() and re-raises the signal.
/// Up to 64 temporaries are registered at once; more are still written, just not removed on a
/// signal.
class AtomicFileSet {
 public:
  AtomicFileSet() = default;
  ~AtomicFileSet();
  AtomicFileSet(const AtomicFileSet&) = delete;
  AtomicFileSet& operator=(const AtomicFileSet&) = delete;

  /// Calls write(tmp_path) to produce `path`'s new contents under a temporary name in its folder
  /// (an Error whose message names the temporary is reworded to name `path`). Throws Error when
  /// the folder does not exist; if write throws, its temporary is removed and the exception
  /// propagates (the set's other temporaries stay until commit or destruction).
  void write(const std::string& path, const std::function<void(const std::string&)>& write);

  /// Renames every temporary to its path, in the order written. Throws Error (after the rollback
  /// described above) when a writer produced no file or a rename fails.
  void commit();

 private:
  struct Entry {
    std::string path, tmp;
    int slot = -1;  // in the signal handler's registry, -1 when not registered
  };
  std::vector<Entry> entries_;
};

/// An output folder made for this run's files: created (with its parents) when it does not exist.
/// When it was new, it is removed again if it is still empty when this object is destroyed (a
/// failure before any file was put in it) or when the process is killed by SIGINT, SIGTERM,
/// SIGHUP or SIGQUIT (after the registered temporaries inside it). An existing folder is never
/// removed.
class NewFolder {
 public:
  /// @throw Error naming `path` when it exists and is not a folder, or cannot be created.
  explicit NewFolder(const std::string& path);
  ~NewFolder();
  NewFolder(const NewFolder&) = delete;
  NewFolder& operator=(const NewFolder&) = delete;
  bool created() const { return created_; }

 private:
  std::string path_;
  bool created_ = false;
  int slot_ = -1;  // in the signal handler's registry, -1 when not registered
};

}  // namespace isocurv
