#include "volume/file_bytes.h"

#include <zlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.h"

namespace isocurv::volume {
namespace fs = std::filesystem;

std::uint64_t file_size(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw Error(path, "file not found");
  if (!fs::is_regular_file(st)) throw Error(path, "not a regular file");
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) throw Error(path, "cannot read file size: " + ec.message());
  return size;
}

Bytes read_bytes(const std::string& path, std::uint64_t offset, std::uint64_t length) {
  const std::uint64_t size = file_size(path);
  if (offset > size || length > size - offset)
    throw Error(path, "file is truncated: needs " + std::to_string(offset + length) + " bytes, has " +
                          std::to_string(size));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open file");
  Bytes bytes(length);
  in.seekg(std::streamoff(offset));
  if (length > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(length)))
    throw Error(path, "read error");
  return bytes;
}

Bytes inflate_exact(const std::string& path, const std::uint8_t* data, std::size_t size,
                                        std::uint64_t expected, const std::string& what) {
  // Deflate cannot expand more than ~1032:1; a header asking for more than that is wrong, and
  // reserving the expected size up front is then safe.
  const std::uint64_t max_plausible = max_inflated(size);
  if (expected > max_plausible)
    throw Error(path, what + " is truncated: " + std::to_string(size) + " compressed bytes cannot hold " +
                          std::to_string(expected) + " bytes");
  Bytes out(expected);
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw Error(path, "zlib initialisation failed");
  zs.next_in = const_cast<Bytef*>(data);
  std::size_t in_left = size, produced = 0;
  int rc = Z_OK;
  std::uint8_t extra;  // one byte past the expected size detects oversized streams
  bool overflow = false;
  while (rc != Z_STREAM_END) {
    if (zs.avail_in == 0) {
      const std::size_t chunk = std::min<std::size_t>(in_left, std::numeric_limits<uInt>::max());
      zs.avail_in = uInt(chunk);
      in_left -= chunk;
    }
    if (produced < expected) {
      zs.next_out = out.data() + produced;
      zs.avail_out = uInt(std::min<std::uint64_t>(expected - produced, std::numeric_limits<uInt>::max()));
    } else {
      zs.next_out = &extra;
      zs.avail_out = 1;
    }
    const uInt before = zs.avail_out;
    rc = inflate(&zs, Z_NO_FLUSH);
    const std::size_t got = before - zs.avail_out;
    if (produced >= expected && got > 0) {
      overflow = true;
      break;
    }
    produced += got;
    if (rc == Z_STREAM_END) break;
    if (rc == Z_BUF_ERROR && zs.avail_in == 0 && in_left == 0) break;  // input ran out: truncated
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      const std::string msg = zs.msg ? zs.msg : "error " + std::to_string(rc);
      inflateEnd(&zs);
      throw Error(path, what + " is not a valid zlib/gzip stream (" + msg + ")");
    }
  }
  inflateEnd(&zs);
  if (overflow)
    throw Error(path, what + " inflates to more than the expected " + std::to_string(expected) +
                          " bytes (dimensions do not match the data)");
  if (produced < expected)
    throw Error(path, what + " is truncated: inflates to " + std::to_string(produced) + " bytes, expected " +
                          std::to_string(expected));
  // All the data came out but the stream did not end: its trailer (the zlib Adler-32 or gzip
  // CRC-32 and length, which inflate checks) is missing, so nothing vouches for the bytes.
  if (rc != Z_STREAM_END)
    throw Error(path, what + " is truncated: the compressed stream ends before its checksum trailer");
  return out;
}

GzipReader::GzipReader(const std::string& path) : path_(path) {
  file_size(path);
  file_ = gzopen(path.c_str(), "rb");
  if (!file_) throw Error(path, "cannot open file");
  gzbuffer(static_cast<gzFile>(file_), 1 << 17);
}

GzipReader::~GzipReader() {
  if (file_) gzclose(static_cast<gzFile>(file_));
}

std::size_t GzipReader::read(void* out, std::size_t n) {
  auto* dst = static_cast<char*>(out);
  std::size_t total = 0;
  while (total < n) {
    const unsigned chunk = unsigned(std::min<std::size_t>(n - total, 1u << 30));
    const int got = gzread(static_cast<gzFile>(file_), dst + total, chunk);
    if (got < 0) {
      int err = 0;
      const char* msg = gzerror(static_cast<gzFile>(file_), &err);
      throw Error(path_, std::string("corrupt or truncated gzip stream (") + (msg ? msg : "unknown error") + ")");
    }
    if (got == 0) break;
    total += std::size_t(got);
  }
  if (total < n) {
    // gzread reports a truncated stream as end of data plus an error state.
    int err = 0;
    const char* msg = gzerror(static_cast<gzFile>(file_), &err);
    if (err != Z_OK && err != Z_STREAM_END)
      throw Error(path_, std::string("corrupt or truncated gzip stream (") + (msg ? msg : "unknown error") + ")");
  }
  return total;
}

void GzipReader::read_exact(void* out, std::size_t n, const std::string& what) {
  const std::size_t got = read(out, n);
  if (got < n)
    throw Error(path_, what + " is truncated: " + std::to_string(got) + " of " + std::to_string(n) + " bytes");
}

void GzipReader::skip(std::size_t n, const std::string& what) {
  std::vector<char> buf(std::min<std::size_t>(n, 1 << 16));
  while (n > 0) {
    const std::size_t chunk = std::min(n, buf.size());
    read_exact(buf.data(), chunk, what);
    n -= chunk;
  }
}

bool GzipReader::at_end() {
  char c;
  return read(&c, 1) == 0;
}

Bytes read_gzip_exact(const std::string& path, std::uint64_t expected, const std::string& what) {
  const std::uint64_t compressed = file_size(path);
  if (expected > max_inflated(compressed))
    throw Error(path, what + " is truncated: " + std::to_string(compressed) + " compressed bytes cannot hold " +
                          std::to_string(expected) + " bytes");
  GzipReader in(path);
  Bytes out(expected);
  in.read_exact(out.data(), out.size(), what);
  if (!in.at_end())
    throw Error(path, what + " inflates to more than the expected " + std::to_string(expected) +
                          " bytes (dimensions do not match the data)");
  return out;
}

}  // namespace isocurv::volume
