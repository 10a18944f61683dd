#include "io/compression.h"

#include <cctype>

#include "core/error.h"

namespace isocurv::io {

Compression parse_compression(const std::string& text) {
  const std::string forms = "expected none, lz4, lz4:LEVEL, zlib or zlib:LEVEL (LEVEL 1..9)";
  const std::size_t colon = text.find(':');
  const std::string name = text.substr(0, colon);
  Compression c;
  if (name == "none") {
    if (colon != std::string::npos) throw Error("--compress '" + text + "': none takes no level");
    c.compressor = Compressor::none;
    c.level = 0;
    return c;
  }
  if (name == "lz4")
    c.compressor = Compressor::lz4;
  else if (name == "zlib")
    c.compressor = Compressor::zlib;
  else
    throw Error("--compress '" + text + "': " + forms);
  c.level = 1;
  if (colon != std::string::npos) {
    const std::string level = text.substr(colon + 1);
    if (level.size() != 1 || level[0] < '1' || level[0] > '9')
      throw Error("--compress '" + text + "': " + forms);
    c.level = level[0] - '0';
  }
  return c;
}

std::string to_string(const Compression& c) {
  switch (c.compressor) {
    case Compressor::none:
      return "none";
    case Compressor::lz4:
      return "lz4:" + std::to_string(c.level);
    case Compressor::zlib:
      return "zlib:" + std::to_string(c.level);
  }
  return "none";
}

}  // namespace isocurv::io
