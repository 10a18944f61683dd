#include "core/program_cache.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "core/atomic_file.h"
#include "core/error.h"

namespace isocurv {
namespace {

namespace fs = std::filesystem;

/// First line of every entry; a new layout gets a new number (older entries are then rejected).
constexpr char kMagic[] = "isocurv program binary v1\n";
/// Entries larger than this are not read (a program binary here is well under 10 MiB).
constexpr std::uint64_t kMaxEntryBytes = 256ull << 20;

std::atomic<bool> warnings_enabled{true};
std::once_flag warned;
std::mutex stats_mutex;
ProgramBuildStats stats;

std::uint64_t fnv1a(const unsigned char* p, std::size_t n, std::uint64_t h) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

void put_u64(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

bool get_u64(const std::string& in, std::size_t& pos, std::uint64_t& v) {
  if (in.size() < pos + 8) return false;
  v = 0;
  for (int i = 0; i < 8; ++i)
    v |= std::uint64_t(static_cast<unsigned char>(in[pos + i])) << (8 * i);
  pos += 8;
  return true;
}

std::uint64_t checksum(const std::string& key_text, const unsigned char* bin, std::size_t n) {
  const auto* k = reinterpret_cast<const unsigned char*>(key_text.data());
  return fnv1a(bin, n, fnv1a(k, key_text.size(), 14695981039346656037ull));
}

void warn_once(const std::string& dir, const std::string& why) {
  if (!warnings_enabled) return;
  std::call_once(warned, [&] {
    std::fprintf(stderr,
                 "isocurv: warning: OpenCL program cache %s is not writable (%s); programs are "
                 "compiled on every start (set ISOCURV_CACHE_DIR to another folder, or to nothing "
                 "to turn the cache off)\n",
                 dir.c_str(), why.c_str());
  });
}

}  // namespace

std::string program_cache_dir() {
  if (const char* d = std::getenv("ISOCURV_CACHE_DIR")) return d;  // "" turns it off
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    return (fs::path(x) / "isocurv").string();
  if (const char* h = std::getenv("HOME"); h && *h)
    return (fs::path(h) / ".cache" / "isocurv").string();
  return "";
}

void set_program_cache_warnings(bool enabled) { warnings_enabled = enabled; }

ProgramBuildStats program_build_stats() {
  std::lock_guard<std::mutex> lock(stats_mutex);
  return stats;
}

namespace detail {

std::string ProgramKey::text() const {
  return "name=" + name + "\nsource=" + source_hash + "\noptions=" + options +
         "\nplatform=" + platform + "\ndevice=" + device + "\ndriver=" + driver + "\n";
}

std::string ProgramKey::file_name() const {
  return name + "-" + hash_hex(text()).substr(0, 16) + ".bin";
}

std::string hash_hex(const std::string& data) {
  const auto* p = reinterpret_cast<const unsigned char*>(data.data());
  // Two FNV-1a runs from different offset bases, the second over the length-prefixed data.
  const std::uint64_t a = fnv1a(p, data.size(), 14695981039346656037ull);
  std::uint64_t b = 0x9e3779b97f4a7c15ull ^ (data.size() * 0xff51afd7ed558ccdull);
  b = fnv1a(p, data.size(), b);
  return hex64(a) + hex64(b);
}

std::optional<std::vector<unsigned char>> load_program_binary(const std::string& dir,
                                                              const ProgramKey& key,
                                                              bool* rejected) {
  if (rejected) *rejected = false;
  if (dir.empty()) return std::nullopt;
  const fs::path path = fs::path(dir) / key.file_name();
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return std::nullopt;  // no entry
  auto reject = [&]() -> std::optional<std::vector<unsigned char>> {
    if (rejected) *rejected = true;
    return std::nullopt;
  };
  if (size > kMaxEntryBytes) return reject();
  std::ifstream in(path, std::ios::binary);
  std::string data(size, '\0');
  if (!in.read(data.data(), std::streamsize(size))) return reject();
  const std::size_t magic_len = std::strlen(kMagic);
  if (data.compare(0, magic_len, kMagic) != 0) return reject();
  std::size_t pos = magic_len;
  std::uint64_t key_len = 0, bin_len = 0, sum = 0;
  const std::string want = key.text();
  if (!get_u64(data, pos, key_len) || key_len != want.size() || data.size() < pos + key_len)
    return reject();
  if (data.compare(pos, key_len, want) != 0) return reject();
  pos += key_len;
  if (!get_u64(data, pos, bin_len) || bin_len == 0 || data.size() != pos + bin_len + 8)
    return reject();
  std::vector<unsigned char> bin(data.begin() + std::ptrdiff_t(pos),
                                 data.begin() + std::ptrdiff_t(pos + bin_len));
  pos += bin_len;
  if (!get_u64(data, pos, sum) || sum != checksum(want, bin.data(), bin.size())) return reject();
  return bin;
}

bool store_program_binary(const std::string& dir, const ProgramKey& key,
                          const std::vector<unsigned char>& binary) {
  if (dir.empty() || binary.empty()) return false;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    warn_once(dir, ec ? ec.message() : "not a folder");
    return false;
  }
  const std::string text = key.text();
  std::string entry = kMagic;
  put_u64(entry, text.size());
  entry += text;
  put_u64(entry, binary.size());
  entry.append(reinterpret_cast<const char*>(binary.data()), binary.size());
  put_u64(entry, checksum(text, binary.data(), binary.size()));
  const std::string path = (fs::path(dir) / key.file_name()).string();
  try {
    write_atomically(path, [&](const std::string& tmp) {
      std::ofstream out(tmp, std::ios::binary);
      out.write(entry.data(), std::streamsize(entry.size()));
      out.close();
      if (!out) throw Error(tmp, "cannot write");
    });
  } catch (const std::exception&) {
    warn_once(dir, "cannot write " + key.file_name());
    return false;
  }
  return true;
}

void record_program_build(double ms, bool from_cache, bool rejected) {
  std::lock_guard<std::mutex> lock(stats_mutex);
  stats.ms += ms;
  (from_cache ? stats.from_cache : stats.compiled) += 1;
  if (rejected) stats.rejected += 1;
}

}  // namespace detail
}  // namespace isocurv
