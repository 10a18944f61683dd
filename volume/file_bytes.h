#pragma once
// Reading voxel payloads from disk: whole files, byte ranges, zlib and gzip streams. Every
// function throws isocurv::Error(path, problem) on a missing, unreadable or truncated input, and
// never allocates more than the data can justify (a compressed stream is inflated into a buffer
// that grows with the data actually produced, capped at the expected size).
// Tested through the loaders: tests/volume/test_loaders.cpp, tests/volume/test_bad_input.cpp.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "volume/large_buffer.h"

namespace isocurv::volume {

/// Deflate (zlib, gzip) emits at most about 1032 bytes per input byte; with a margin, the bound
/// every compressed payload is checked against before its output is allocated.
constexpr std::uint64_t kMaxInflateRatio = 1040;
/// The most bytes `compressed` bytes of deflate data can inflate to.
constexpr std::uint64_t max_inflated(std::uint64_t compressed) { return compressed * kMaxInflateRatio + 1024; }

/// Size of a regular file in bytes; throws when it does not exist or is not a regular file.
std::uint64_t file_size(const std::string& path);

/// `length` bytes of `path` starting at `offset`; throws when the file is shorter.
Bytes read_bytes(const std::string& path, std::uint64_t offset, std::uint64_t length);

/// Inflates the zlib (RFC 1950) or gzip (RFC 1952) stream in `data` (format auto-detected), which
/// must hold exactly `expected` bytes: fewer is "truncated", more is a size mismatch. The stream
/// must end with its checksum trailer (Adler-32, or CRC-32 and length), which zlib verifies;
/// bytes after the end of the stream are ignored.
/// `what` names the payload in messages (e.g. "voxel data").
Bytes inflate_exact(const std::string& path, const std::uint8_t* data, std::size_t size,
                                        std::uint64_t expected, const std::string& what);

/// Reads a gzip-compressed file incrementally, so headers can be parsed before the payload size is
/// known; a file that does not start with the gzip magic (1f 8b) is read as it is. The stream is
/// inflated here (not by zlib's gzread, whose end-of-file check depended on where its buffers
/// ended: a trailer cut by a few bytes passed above about 80^3 voxels). The end of the data is
/// only reported after the end of the last member and its CRC-32 and length trailer, which zlib
/// checks; a file that ends before that is "truncated" at every size. Members in sequence (pigz,
/// bgzip, `cat a.gz b.gz`) are one stream, as gzip reads them; bytes after the last member that do
/// not start another are ignored (as gzread did).
class GzipReader {
 public:
  explicit GzipReader(const std::string& path);
  ~GzipReader();
  GzipReader(const GzipReader&) = delete;
  GzipReader& operator=(const GzipReader&) = delete;

  /// Reads up to `n` bytes (fewer only at the complete end of the stream); throws on a corrupt
  /// stream or one the file cuts short.
  std::size_t read(void* out, std::size_t n);
  /// Reads exactly `n` bytes into `out`, throwing "truncated <what>" at a premature end.
  void read_exact(void* out, std::size_t n, const std::string& what);
  /// Skips `n` bytes (throws at a premature end).
  void skip(std::size_t n, const std::string& what);
  /// True when the whole stream, trailer included, has been consumed (throws when it is cut).
  bool at_end();

 private:
  struct State;
  bool fill(std::size_t want);
  std::string path_;
  std::unique_ptr<State> s_;
};

/// Inflates a whole gzip file that must hold exactly `expected` bytes.
Bytes read_gzip_exact(const std::string& path, std::uint64_t expected, const std::string& what);

}  // namespace isocurv::volume
