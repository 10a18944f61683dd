#include "volume/file_bytes.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
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

struct GzipReader::State {
  std::ifstream file;
  std::vector<std::uint8_t> buffer = std::vector<std::uint8_t>(std::size_t(1) << 18);
  z_stream zs{};          // next_in / avail_in: the buffer's bytes not yet consumed (plain files too)
  bool inflating = false;  // inflateInit2 done
  bool gzip = false;       // else a plain file, read as it is
  bool eof = false;        // the file has no more bytes
  bool done = false;       // the end of the last member's trailer was reached
  ~State() {
    if (inflating) inflateEnd(&zs);
  }
};

GzipReader::GzipReader(const std::string& path) : path_(path), s_(std::make_unique<State>()) {
  file_size(path);
  s_->file.open(path, std::ios::binary);
  if (!s_->file) throw Error(path, "cannot open file");
  fill(2);
  s_->gzip = s_->zs.avail_in >= 2 && s_->zs.next_in[0] == 0x1f && s_->zs.next_in[1] == 0x8b;
  if (s_->gzip) {
    if (inflateInit2(&s_->zs, 15 + 16) != Z_OK) throw Error(path, "zlib initialisation failed");
    s_->inflating = true;
  }
}

GzipReader::~GzipReader() = default;

bool GzipReader::fill(std::size_t want) {
  // Moves the unconsumed bytes to the front of the buffer and reads more after them, until
  // `want` are there or the file ends. False when fewer than `want` are left.
  State& s = *s_;
  std::size_t have = s.zs.avail_in;
  if (have >= want) return true;
  if (s.eof) return false;
  if (have > 0) std::memmove(s.buffer.data(), s.zs.next_in, have);
  while (have < want && !s.eof) {
    s.file.read(reinterpret_cast<char*>(s.buffer.data() + have), std::streamsize(s.buffer.size() - have));
    have += std::size_t(s.file.gcount());
    if (s.file.bad()) throw Error(path_, "read error");
    if (!s.file) s.eof = true;  // a short read: the end of the file
  }
  s.zs.next_in = s.buffer.data();
  s.zs.avail_in = uInt(have);
  return have >= want;
}

std::size_t GzipReader::read(void* out, std::size_t n) {
  State& s = *s_;
  auto* dst = static_cast<std::uint8_t*>(out);
  std::size_t total = 0;
  if (!s.gzip) {
    while (total < n && (s.zs.avail_in > 0 || fill(1))) {
      const std::size_t k = std::min<std::size_t>(n - total, s.zs.avail_in);
      std::memcpy(dst + total, s.zs.next_in, k);
      s.zs.next_in += k;
      s.zs.avail_in -= uInt(k);
      total += k;
    }
    return total;
  }
  while (total < n && !s.done) {
    if (s.zs.avail_in == 0) fill(1);
    const uInt chunk = uInt(std::min<std::size_t>(n - total, std::size_t(1) << 30));
    s.zs.next_out = dst + total;
    s.zs.avail_out = chunk;
    const int rc = inflate(&s.zs, Z_NO_FLUSH);
    total += chunk - s.zs.avail_out;
    if (rc == Z_STREAM_END) {
      // The member's trailer matched (zlib checks the CRC-32 and length). Another member may
      // follow; bytes that do not start one are ignored, as gzip and gzread do.
      fill(2);
      if (s.zs.avail_in >= 2 && s.zs.next_in[0] == 0x1f && s.zs.next_in[1] == 0x8b)
        inflateReset(&s.zs);
      else
        s.done = true;
    } else if (rc == Z_BUF_ERROR && s.zs.avail_in == 0) {
      // No progress and no input left: the file ends inside the stream, whatever its size.
      throw Error(path_, "gzip stream is truncated: the file ends before the stream does (its data or its "
                         "CRC-32 and length trailer is cut short)");
    } else if (rc != Z_OK) {
      throw Error(path_, std::string("corrupt gzip stream (") +
                             (s.zs.msg ? s.zs.msg : "error " + std::to_string(rc)) + ")");
    }
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
