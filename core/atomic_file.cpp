#include "core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace isocurv {

std::string temporary_path_for(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  std::string name = "." + p.stem().string() + ".tmp" + std::to_string(getpid()) + p.extension().string();
  return (p.parent_path() / name).string();
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw Error(path, "cannot write: folder " + parent.string() + " does not exist");
  const std::string tmp = temporary_path_for(path);
  try {
    write(tmp);
    if (!fs::exists(tmp)) throw Error(path, "writer produced no file");
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw Error(path, std::string("cannot write: ") + std::strerror(errno));
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace isocurv
