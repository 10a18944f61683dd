#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "core/error.h"

namespace isocurv {
namespace {

namespace fs = std::filesystem;

// ---- The registry of live temporaries, read by the signal handler ----
// A slot is free (0), being filled (1) or live (2); the handler only reads live slots, and only
// with async-signal-safe calls (unlink, raise).
constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;
struct Slot {
  std::atomic<int> state{0};
  bool folder = false;  // rmdir (when empty) instead of unlink, after every file
  char path[kPathBytes];
};
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
constexpr int kSignalCount = 4;
// The action each signal had before ours (another library's, e.g. LLVM's in PoCL's compiler, or
// the default), restored by our handler before the signal is raised again.
struct sigaction g_previous[kSignalCount];

extern "C" void remove_temporaries_and_reraise(int sig) {
  for (Slot& s : g_slots)
    if (s.state.load() == 2 && !s.folder) unlink(s.path);
  for (int i = kSlots - 1; i >= 0; --i)  // new folders, once their temporaries are gone
    if (g_slots[i].state.load() == 2 && g_slots[i].folder) rmdir(g_slots[i].path);
  // Hand the signal on: restore the previous action (the default ends the process as it would
  // have without us; a chained handler does its own work and then usually does the same). The
  // signal is blocked until this handler returns, then delivered again.
  for (int i = 0; i < kSignalCount; ++i)
    if (kSignals[i] == sig) sigaction(sig, &g_previous[i], nullptr);
  raise(sig);
}

// Installs the handler for every signal not ignored, chaining to whatever was there: called on
// each registration, since a library may install its own handlers later (PoCL compiles kernels
// with LLVM, which does), and ours must stay first.
void install_handlers() {
  for (int i = 0; i < kSignalCount; ++i) {
    struct sigaction old {};
    if (sigaction(kSignals[i], nullptr, &old) != 0) continue;
    if (!(old.sa_flags & SA_SIGINFO) && old.sa_handler == remove_temporaries_and_reraise) continue;
    if (!(old.sa_flags & SA_SIGINFO) && old.sa_handler == SIG_IGN) continue;  // e.g. nohup
    g_previous[i] = old;
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&action.sa_mask);
    sigaction(kSignals[i], &action, nullptr);
  }
}

/// Registers `path` for removal on a fatal signal (a file, or an empty `folder`); returns its
/// slot, or -1 when none is free.
int register_temporary(const std::string& path, bool folder = false) {
  static std::mutex installing;
  {
    std::lock_guard<std::mutex> lock(installing);
    install_handlers();
  }
  if (path.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].folder = folder;
      g_slots[i].state.store(2);
      return i;
    }
  }
  return -1;
}

void release_temporary(int& slot) {
  if (slot >= 0) g_slots[slot].state.store(0);
  slot = -1;
}

/// `text` with every occurrence of `from` replaced by `to`.
std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); !from.empty() && at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

/// The name under which commit() keeps a file it replaces until the whole set is in place.
std::string backup_path_for(const std::string& path) {
  fs::path p(path);
  return (p.parent_path() /
          ("." + p.stem().string() + ".old" + std::to_string(getpid()) + p.extension().string()))
      .string();
}

}  // namespace

std::string temporary_path_for(const std::string& path) {
  fs::path p(path);
  std::string name =
      "." + p.stem().string() + ".tmp" + std::to_string(getpid()) + p.extension().string();
  return (p.parent_path() / name).string();
}

void require_writable_file(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path, "cannot write: this is a folder, not a file");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw Error(path, "cannot write: folder " + parent.string() + " does not exist");
  const std::string probe = temporary_path_for(path) + ".probe";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    const int err = errno;
    if (err != EEXIST)
      throw Error(path, "cannot write: folder " +
                            (parent.empty() ? std::string(".") : parent.string()) +
                            " is not writable (" + std::strerror(err) + ")");
    return;  // a stale probe: the folder took files before
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write) {
  AtomicFileSet set;
  set.write(path, write);
  set.commit();
}

AtomicFileSet::~AtomicFileSet() {
  for (Entry& e : entries_) {
    std::error_code ec;
    fs::remove(e.tmp, ec);
    release_temporary(e.slot);
  }
}

void AtomicFileSet::write(const std::string& path,
                          const std::function<void(const std::string&)>& write) {
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw Error(path, "cannot write: folder " + parent.string() + " does not exist");
  Entry e;
  e.path = path;
  e.tmp = temporary_path_for(path);
  e.slot = register_temporary(e.tmp);
  try {
    write(e.tmp);
  } catch (const Error& error) {
    std::error_code ec;
    fs::remove(e.tmp, ec);
    release_temporary(e.slot);
    throw Error(replace_all(error.what(), e.tmp, path));
  } catch (...) {
    std::error_code ec;
    fs::remove(e.tmp, ec);
    release_temporary(e.slot);
    throw;
  }
  entries_.push_back(std::move(e));
}

void AtomicFileSet::commit() {
  for (const Entry& e : entries_)
    if (!fs::exists(e.tmp)) throw Error(e.path, "writer produced no file");
  // One file needs no backup: rename() replaces it atomically or not at all.
  const bool several = entries_.size() > 1;
  const std::size_t n = entries_.size();
  std::vector<std::string> backups(n);
  std::vector<int> backup_slots(n, -1);
  std::vector<char> existed(n, 0);
  std::size_t done = 0;
  try {
    for (; done < n; ++done) {
      Entry& e = entries_[done];
      existed[done] = several && fs::exists(e.path);
      if (existed[done]) {
        const std::string b = backup_path_for(e.path);
        std::error_code ec;
        fs::remove(b, ec);
        backup_slots[done] = register_temporary(b);
        if (link(e.path.c_str(), b.c_str()) == 0) backups[done] = b;
      }
      if (std::rename(e.tmp.c_str(), e.path.c_str()) != 0)
        throw Error(e.path, std::string("cannot write: ") + std::strerror(errno));
      release_temporary(e.slot);
    }
  } catch (...) {
    // Put back what the renames so far replaced, remove what they added; the failing file still
    // has its old contents.
    std::error_code ec;
    for (std::size_t j = 0; j < done; ++j) {
      if (!backups[j].empty())
        std::rename(backups[j].c_str(), entries_[j].path.c_str());
      else if (!existed[j])
        fs::remove(entries_[j].path, ec);
    }
    if (done < n && !backups[done].empty()) fs::remove(backups[done], ec);
    for (int& slot : backup_slots) release_temporary(slot);
    entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(done));
    throw;  // the destructor removes the temporaries not yet renamed
  }
  for (std::size_t j = 0; j < n; ++j) {
    std::error_code ec;
    if (!backups[j].empty()) fs::remove(backups[j], ec);
    release_temporary(backup_slots[j]);
  }
  entries_.clear();
}

NewFolder::NewFolder(const std::string& path) : path_(path) {
  std::error_code ec;
  if (fs::exists(path_, ec)) {
    if (!fs::is_directory(path_, ec)) throw Error(path_, "exists and is not a folder");
    return;
  }
  created_ = fs::create_directories(path_, ec);
  if (ec || !fs::is_directory(path_, ec))
    throw Error(path_, "cannot create the folder: " + (ec ? ec.message() : std::string("unknown error")));
  if (created_) slot_ = register_temporary(path_, true);
}

NewFolder::~NewFolder() {
  release_temporary(slot_);
  std::error_code ignored;
  if (created_) fs::remove(path_, ignored);  // only when still empty
}

}  // namespace isocurv
