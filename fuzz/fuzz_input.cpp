#include "fuzz/fuzz_input.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace isocurv::fuzz {
namespace fs = std::filesystem;

const std::string& InputFiles::folder() {
  if (folder_.empty()) {
    const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    folder_ = (base / ("isocurv-fuzz-" + std::to_string(::getpid()))).string();
    fs::create_directories(folder_);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(input_files().folder(), ec);
    });
  }
  return folder_;
}

std::string InputFiles::write(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = folder() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

void InputFiles::clear() {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder(), ec)) fs::remove_all(entry.path(), ec);
}

InputFiles& input_files() {
  static InputFiles files;
  return files;
}

void require(bool ok, const std::string& what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz harness: a successful load broke its promise: %s\n", what.c_str());
  std::abort();
}

}  // namespace isocurv::fuzz
