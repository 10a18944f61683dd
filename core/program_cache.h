#pragma once
// Compiled OpenCL programs kept on disk between processes, so that only the first process start
// pays for the compiler (Device::program uses it; nothing else needs to).
//
// Where: $ISOCURV_CACHE_DIR when set (an empty value turns the cache off), else
// $XDG_CACHE_HOME/isocurv, else $HOME/.cache/isocurv. One file per program, named by a hash of its
// key: the program's name, a hash of its source, the build options, and the platform, device and
// driver names and versions. The entry repeats the whole key and a checksum of the binary; an
// entry that does not match (corrupt, truncated, from another driver) or that the driver refuses
// to build is rebuilt from source and rewritten, never trusted. Entries are written atomically
// (a temporary renamed into place), so concurrent processes at worst both write the same entry.
// A folder that cannot be created or written disables the cache for the process, after one
// warning line on stderr (see set_program_cache_warnings).
//
// Threading: the functions here may be called from any thread; they touch only files.
// Tested in tests/core/test_program_cache.cpp.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace isocurv {

/// The cache folder by the rules above; empty when the cache is off (ISOCURV_CACHE_DIR="" or no
/// HOME).
std::string program_cache_dir();

/// Whether the one warning about an unwritable cache folder is printed (default true; the CLI's
/// --quiet turns it off).
void set_program_cache_warnings(bool enabled);

/// Process-wide totals of Device::program: wall time spent getting programs ready (compiling, or
/// loading from the cache and finishing the build), and how many came each way.
struct ProgramBuildStats {
  double ms = 0;                 ///< total milliseconds in Device::program builds
  std::uint64_t compiled = 0;    ///< programs compiled from source
  std::uint64_t from_cache = 0;  ///< programs built from a cached binary
  std::uint64_t rejected = 0;    ///< cache entries found but not trusted (rebuilt from source)
};
ProgramBuildStats program_build_stats();

namespace detail {

/// What identifies one compiled program (every field must match for a cached binary to be used).
struct ProgramKey {
  std::string name, source_hash, options, platform, device, driver;
  /// All fields on one text, as stored in the entry.
  std::string text() const;
  /// The entry's file name: `<name>-<16 hex digits>.bin`.
  std::string file_name() const;
};

/// A 128-bit hash of `data` as 32 hex digits (two 64-bit FNV-1a variants; not cryptographic).
std::string hash_hex(const std::string& data);

/// The binary stored for `key` in `dir`, or nullopt when there is none or it does not verify
/// (`*rejected` set true for an entry that exists but does not verify).
std::optional<std::vector<unsigned char>> load_program_binary(const std::string& dir,
                                                              const ProgramKey& key,
                                                              bool* rejected = nullptr);

/// Stores `binary` for `key` in `dir` atomically. Returns false (after the one warning) when the
/// folder cannot be created or written.
bool store_program_binary(const std::string& dir, const ProgramKey& key,
                          const std::vector<unsigned char>& binary);

/// Adds one Device::program build to program_build_stats().
void record_program_build(double ms, bool from_cache, bool rejected);

}  // namespace detail
}  // namespace isocurv
