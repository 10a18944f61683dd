#include "volume/header_text.h"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include "core/error.h"

namespace isocurv::volume {

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::string to_lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::optional<std::vector<double>> parse_numbers(const std::string& s) {
  std::vector<double> out;
  const char* p = s.c_str();
  while (true) {
    while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (!*p) break;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(p, &end);
    if (end == p || (*end && !std::isspace(static_cast<unsigned char>(*end)))) return std::nullopt;
    out.push_back(v);
    p = end;
  }
  if (out.empty()) return std::nullopt;
  return out;
}

std::vector<double> parse_numbers_exact(const std::string& path, const std::string& s, std::size_t n,
                                        const std::string& what) {
  auto v = parse_numbers(s);
  if (!v || v->size() != n) throw Error(path, "bad " + what + " '" + trim(s) + "'");
  return *v;
}

std::vector<long long> parse_integers_exact(const std::string& path, const std::string& s, std::size_t n,
                                            const std::string& what) {
  const auto v = parse_numbers_exact(path, s, n, what);
  // Written as integers: digits with an optional sign. strtod alone took "41.0", "4.1e1" and
  // "0x29" as 41 (`sizes: 41 41.0 41`, the fuzzing campaign of issue 55).
  for (std::size_t i = 0; i < s.size();) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    const std::size_t digits = j;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    if (i < s.size() && (j == digits || (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j])))))
      throw Error(path, "bad " + what + " '" + trim(s) + "'");
    i = j;
  }
  std::vector<long long> out;
  for (double d : v) {
    // range first: casting a double beyond long long's range is undefined
    if (!(d >= -9e15 && d <= 9e15) || d != double((long long)d))
      throw Error(path, "bad " + what + " '" + trim(s) + "'");
    out.push_back((long long)d);
  }
  return out;
}

LargeBuffer<float> parse_ascii_voxels(const std::string& path, const char* begin, const char* end,
                                      std::uint64_t count) {
  // Each number takes at least two characters (digit and separator), bar the last one.
  if (count > std::uint64_t(end - begin) / 2 + 1)
    throw Error(path, "ASCII voxel data is truncated: too short for " + std::to_string(count) + " values");
  LargeBuffer<float> out(count);
  std::uint64_t n = 0;
  std::string token;
  const char* p = begin;
  while (n < count) {
    while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (p >= end) break;
    const char* q = p;
    while (q < end && !std::isspace(static_cast<unsigned char>(*q))) ++q;
    token.assign(p, q);
    char* stop = nullptr;
    const double v = std::strtod(token.c_str(), &stop);
    if (stop == token.c_str() || *stop) throw Error(path, "bad ASCII voxel value '" + token + "'");
    out[n++] = float(v);
    p = q;
  }
  if (n < count)
    throw Error(path, "ASCII voxel data is truncated: " + std::to_string(n) + " of " +
                          std::to_string(count) + " values");
  // A file cut inside its last number reads as a shorter number ("123" cut to "12"): the last
  // value must be followed by a space or line break, as every writer ends its lines.
  if (count > 0 && p >= end)
    throw Error(path, "ASCII voxel data ends inside its last value (no line break after it): the file may be "
                      "cut short");
  while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
  if (p < end)
    throw Error(path, "ASCII voxel data holds more than the header's " + std::to_string(count) +
                          " values (sizes do not match the data)");
  return out;
}

std::string directory_of(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

}  // namespace isocurv::volume
