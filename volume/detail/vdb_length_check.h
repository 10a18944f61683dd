#pragma once
// Checks the lengths a .vdb file gives before OpenVDB reads it. Internal to volume/load_vdb.cpp,
// not installed.
//
// OpenVDB sizes many reads from the file and allocates before it reads: a name, type name or
// metadata value (a uint32 length, then that many bytes; allocated and zero-filled first, 4.3 GB
// resident for a 1,978-byte file the fuzzer made), and each zip or blosc block of voxel values (an
// int64 length, allocated whole). It also builds the tree node by node from child masks, so a
// corrupt mask or node count makes it allocate node after node until the file runs out, at up to
// 30 bytes of memory per byte of file. This walk goes through the file as OpenVDB will and
// refuses, before anything is allocated, any length the rest of the file cannot hold and any tree
// that needs more bytes than the file has.
#include <cstdint>
#include <string>

namespace isocurv::volume::detail {

/// What `check_vdb_lengths` covered.
struct VdbLengthWalk {
  int grids = 0;         ///< grid descriptors read
  int trees_walked = 0;  ///< grids walked to exactly the end their descriptor records
};

/// Walks the header, the file's metadata and every grid: descriptor, metadata, transform and,
/// for the trees of every value type openvdb::initialize() registers but points (float, double,
/// int32, int64, vec3s, vec3d, vec3i, bool, mask), the topology and every voxel block, reading each
/// part as OpenVDB 10 does. Like io::Stream, it goes from each grid to the next without seeking; a
/// layout it does not know (point trees, a frustum transform) ends the walk there. Apart from files
/// older than format 222 (OpenVDB 3, 2014), whose layouts differ throughout and which OpenVDB
/// itself no longer reads, and files newer than the format this OpenVDB knows (which it reads as
/// its own, with a warning), it never refuses a file OpenVDB reads correctly. Reads the file in 64
/// KiB windows and allocates nothing sized by the file. Thread-safe (no shared state).
/// @param path  the file
/// @param size  its size in bytes
/// @return what was walked (tests use it to check that the walk knows the layouts OpenVDB writes)
/// @throw isocurv::Error naming `path`: "file is truncated or corrupt: ..." with the length that
///        does not fit, where it was read and the file's size
VdbLengthWalk check_vdb_lengths(const std::string& path, std::uint64_t size);

}  // namespace isocurv::volume::detail
