// The .vdb layout walked here is the one OpenVDB's readers follow (io::Archive::readGrid, the
// tree nodes' readTopology and readBuffers, io::readCompressedValues); each step names the
// OpenVDB function whose reads it mirrors.
#include "volume/detail/vdb_length_check.h"

#include <openvdb/io/Compression.h>
#include <openvdb/version.h>

#include <algorithm>
#include <bitset>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/error.h"

namespace isocurv::volume::detail {
namespace {

/// Sequential reads through a window of the file, so that walking a tree of a million leaves
/// costs a million memcpys, not a million system calls.
class Cursor {
 public:
  Cursor(const std::string& path, std::uint64_t size) : size_(size), in_(path, std::ios::binary) {}

  std::uint64_t pos() const { return pos_; }
  std::uint64_t left() const { return size_ - pos_; }
  void seek(std::uint64_t pos) { pos_ = std::min(pos, size_); }

  /// Copies the next `n` bytes to `out`; false if the file has fewer left.
  bool bytes(void* out, std::size_t n) {
    if (left() < n || !in_) return false;
    if (n > kWindow) {
      in_.seekg(std::streamoff(pos_));
      in_.read(static_cast<char*>(out), std::streamsize(n));
      pos_ += n;
      return bool(in_);
    }
    if (pos_ < start_ || pos_ + n > start_ + window_.size()) {
      window_.resize(std::size_t(std::min<std::uint64_t>(kWindow, left())));
      in_.seekg(std::streamoff(pos_));
      in_.read(window_.data(), std::streamsize(window_.size()));
      if (!in_) return false;
      start_ = pos_;
    }
    std::memcpy(out, window_.data() + (pos_ - start_), n);
    pos_ += n;
    return true;
  }
  template <class T>
  bool read(T& value) {
    return bytes(&value, sizeof(T));
  }
  /// Moves past `n` bytes; false if the file has fewer left.
  bool skip(std::uint64_t n) {
    if (left() < n) return false;
    pos_ += n;
    return true;
  }

 private:
  static constexpr std::size_t kWindow = 64 * 1024;
  const std::uint64_t size_;
  std::ifstream in_;
  std::vector<char> window_;
  std::uint64_t start_ = 0, pos_ = 0;
};

/// A bit mask of a tree node (util::NodeMask): 2^(3 log2dim) bits, stored as raw 64-bit words.
struct NodeMask {
  std::vector<std::uint64_t> words;
  explicit NodeMask(int log2dim) : words(std::size_t(1) << (3 * log2dim) >> 6) {}
  std::uint64_t bits() const { return words.size() * 64; }
  std::uint64_t bytes() const { return words.size() * 8; }
  std::uint64_t count() const {
    std::uint64_t n = 0;
    for (std::uint64_t w : words) n += std::bitset<64>(w).count();
    return n;
  }
};

/// The node layout of a grid type such as "Tree_float_5_4_3" (internal nodes of 2^5 and 2^4
/// children per axis, leaves of 2^3 voxels per axis), for the value types
/// openvdb::initialize() registers except points.
struct TreeLayout {
  int value_bytes = 0;        ///< 0: a layout the walk does not know
  int half_bytes = 0;         ///< a value saved as half; 0 for types never saved so
  std::vector<int> log2dims;  ///< the internal nodes' from the root down, then the leaves'
  /// Bool and mask leaves store their voxels as bit masks (LeafNodeBool.h, LeafNodeMask.h):
  /// leaf blocks of value mask, origin and value bits (bool), or value bits and origin (mask), in
  /// masks; 0 for the others, whose leaf blocks are compressed values.
  int leaf_block_masks = 0;
};

TreeLayout tree_layout(std::string type) {
  const std::string half_suffix = "_HalfFloat";  // GridDescriptor's marker; the metadata decides
  if (type.size() > half_suffix.size() &&
      type.compare(type.size() - half_suffix.size(), half_suffix.size(), half_suffix) == 0)
    type.resize(type.size() - half_suffix.size());
  TreeLayout layout;
  struct Value {
    const char* tree;
    int bytes, half_bytes;  // half_bytes 0: not a real type, never stored as half
    int leaf_block_masks;
  };
  static const Value values[] = {
      {"Tree_float", 4, 2, 0},  {"Tree_double", 8, 2, 0}, {"Tree_int32", 4, 0, 0},
      {"Tree_int64", 8, 0, 0},  {"Tree_vec3s", 12, 6, 0}, {"Tree_vec3d", 24, 6, 0},
      {"Tree_vec3i", 12, 0, 0}, {"Tree_bool", 1, 0, 2},   {"Tree_mask", 1, 0, 1}};
  for (const Value& value : values) {
    const std::string prefix = value.tree;
    if (type.compare(0, prefix.size(), prefix) != 0) continue;
    std::vector<int> dims;
    std::size_t at = prefix.size();
    while (at + 1 < type.size() && type[at] == '_' && type[at + 1] >= '1' && type[at + 1] <= '9' &&
           (at + 2 == type.size() || type[at + 2] == '_')) {
      dims.push_back(type[at + 1] - '0');
      at += 2;
    }
    // NodeMask is a plain array of 64-bit words from 2^3 bits per axis up; 2^7 is the most
    // the walk reads (a 256 KiB mask), more than any tree configuration OpenVDB registers.
    if (at != type.size() || dims.size() < 2 ||
        std::any_of(dims.begin(), dims.end(), [](int d) { return d < 3 || d > 7; }))
      return layout;
    layout.value_bytes = value.bytes;
    layout.half_bytes = value.half_bytes;
    layout.leaf_block_masks = value.leaf_block_masks;
    layout.log2dims = dims;
  }
  return layout;
}

/// Bytes of the map a transform type name announces (the maps' read()), 0 when not fixed.
std::uint64_t map_bytes(const std::string& type) {
  constexpr std::uint64_t vec3d = 24, mat4d = 128;
  if (type == "AffineMap" || type == "UnitaryMap") return mat4d;
  if (type == "ScaleMap" || type == "UniformScaleMap") return 5 * vec3d;
  if (type == "ScaleTranslateMap" || type == "UniformScaleTranslateMap") return 6 * vec3d;
  if (type == "TranslationMap") return vec3d;
  return 0;  // NonlinearFrustumMap (a nested map) or one the walk does not know
}

/// Bytes of a metadata value of a fixed-size type openvdb::initialize() registers, 0 for the
/// others ("string", "__delayedload", and types not registered, which are read by their length).
std::uint64_t fixed_metadata_bytes(const std::string& type) {
  static const std::pair<const char*, std::uint64_t> sizes[] = {
      {"bool", 1},   {"float", 4},  {"double", 8}, {"int32", 4},  {"int64", 8},  {"vec2i", 8},
      {"vec2s", 8},  {"vec2d", 16}, {"vec3i", 12}, {"vec3s", 12}, {"vec3d", 24}, {"vec4i", 16},
      {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64}, {"mat4d", 128}};
  for (const auto& [name, bytes] : sizes)
    if (type == name) return bytes;
  return 0;
}

class VdbLengthCheck {
 public:
  VdbLengthCheck(const std::string& path, std::uint64_t size)
      : path_(path), size_(size), in_(path, size) {}

  VdbLengthWalk run() {
    std::int64_t magic = 0;
    std::uint32_t major = 0, minor = 0;
    if (!in_.read(magic) || magic != openvdb::OPENVDB_MAGIC || !in_.read(version_)) return walk_;
    // The layouts before 222 differ in every part walked here, and OpenVDB itself now refuses
    // files before 221. (Later versions are read as OpenVDB 10 reads them: as 224.)
    if (version_ < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
      throw Error(path_, "OpenVDB file format " + std::to_string(version_) +
                             " is older than 222 (OpenVDB 3, 2014), the oldest isocurv reads; "
                             "save it again with a newer OpenVDB");
    if (version_ > openvdb::OPENVDB_FILE_VERSION)  // OpenVDB would read it as its own, warning
      throw Error(path_, "OpenVDB file format " + std::to_string(version_) + " is newer than " +
                             std::to_string(openvdb::OPENVDB_FILE_VERSION) +
                             ", the newest this build's OpenVDB " OPENVDB_LIBRARY_VERSION_STRING
                             " reads");
    char has_offsets = 1;
    if (!in_.read(major) || !in_.read(minor) || !in_.read(has_offsets)) return walk_;
    // The UUID: 32 hex digits and 4 hyphens, each read by a formatted `is >> c` (boost::uuids'
    // operator>>), which skips white space first.
    for (int i = 0; i < 36; ++i) {
      char c = ' ';
      while (in_.read(c) && (c == ' ' || (c >= '\t' && c <= '\r'))) {
      }
      if (c == ' ' || (c >= '\t' && c <= '\r')) return walk_;  // the file ended
    }
    bool half = false;
    if (!metadata("the file's", half)) return walk_;
    std::int32_t grids = 0;
    const std::uint64_t grids_at = in_.pos();
    if (!in_.read(grids)) return walk_;
    // io::Stream reserves a descriptor per grid first; each takes 36 bytes or more of the file
    // (three lengths and three offsets).
    constexpr std::uint64_t descriptor_bytes = 36;
    if (grids < 0 || std::uint64_t(grids) > in_.left() / descriptor_bytes)
      throw Error(path_, "file is truncated or corrupt: its grid count at byte " +
                             std::to_string(grids_at) + " is " + std::to_string(grids) +
                             ", more than its " + std::to_string(size_) + " bytes can hold");
    for (std::int32_t g = 0; g < grids; ++g) {
      std::string name, type, parent;
      if (!text(name, "a grid name") || !text(type, "a grid type name")) return walk_;
      if (!text(parent, "an instance parent name")) return walk_;
      ++walk_.grids;
      std::int64_t grid_pos = 0, block_pos = 0, end_pos = 0;
      if (!in_.read(grid_pos) || !in_.read(block_pos) || !in_.read(end_pos)) return walk_;
      grid_ = name;
      // io::Stream reads the grids one after the other and never seeks to the offsets: the walk
      // goes on from where the grid ends, and stops where it cannot follow a grid to its end.
      if (!grid(type, !parent.empty())) return walk_;
      if (has_offsets && in_.pos() == std::uint64_t(end_pos)) ++walk_.trees_walked;
    }
    return walk_;
  }

 private:
  /// One grid after its descriptor (Archive::readGrid): compression flags, metadata, transform,
  /// then, unless it is an instance of another grid's tree, topology and voxel blocks. True when
  /// the walk reached the grid's end.
  bool grid(const std::string& type, bool instance) {
    compression_ = openvdb::io::COMPRESS_NONE;
    if (!in_.read(compression_)) return false;
    half_ = false;
    if (!metadata("a grid's", half_)) return false;
    std::string map;
    if (!text(map, "a transform type name")) return false;
    const std::uint64_t map_size = map_bytes(map);
    if (map_size == 0 || !in_.skip(map_size)) return false;
    if (instance) return true;
    const TreeLayout layout = tree_layout(type);
    if (layout.value_bytes == 0) return false;
    value_bytes_ = layout.value_bytes;
    half_bytes_ = half_ ? layout.half_bytes : 0;
    tree(layout);
    return true;
  }

  /// Tree::readTopology (a buffer count), RootNode::readTopology (background, tiles, children),
  /// then the voxel blocks, one per leaf (LeafNode::readBuffers: the leaf's value mask again,
  /// then its values).
  void tree(const TreeLayout& layout) {
    std::int32_t buffer_count = 0;
    std::uint32_t tiles = 0, children = 0;
    const std::uint64_t at = in_.pos();
    need(in_.read(buffer_count));
    if (buffer_count != 1)  // OpenVDB prints a warning and reads one buffer per leaf
      throw Error(path_, "file is corrupt: the tree of grid '" + grid_ + "' has " +
                             std::to_string(buffer_count) + " buffers per leaf (at byte " +
                             std::to_string(at) + "); OpenVDB reads only trees of one");
    need(in_.skip(value_bytes_) && in_.read(tiles) && in_.read(children));
    const std::uint64_t tile_bytes = 12 + value_bytes_ + 1;  // origin, value, active flag
    need(tiles <= in_.left() / tile_bytes);
    for (std::uint32_t t = 0; t < tiles; ++t) {
      std::uint8_t active = 0;
      in_.skip(12 + value_bytes_);
      in_.read(active);
      if (active > 1) bad_bool("a root tile's active flag", in_.pos() - 1, active);
    }
    levels_.clear();
    for (std::size_t i = 0; i + 1 < layout.log2dims.size(); ++i)
      levels_.push_back({NodeMask(layout.log2dims[i]), NodeMask(layout.log2dims[i])});
    NodeMask leaf(layout.log2dims.back());
    std::uint64_t leaves = 0;
    for (std::uint32_t c = 0; c < children; ++c) {
      need(in_.skip(12));  // the child's origin
      internal_topology(0, leaf.bytes(), leaves);
    }
    if (layout.leaf_block_masks > 0) {  // fixed-size leaf blocks: masks and the origin
      const std::uint64_t block = layout.leaf_block_masks * leaf.bytes() + 12;
      need(leaves <= in_.left() / block && in_.skip(leaves * block));
      return;
    }
    for (std::uint64_t l = 0; l < leaves; ++l) {
      need(in_.bytes(leaf.words.data(), leaf.bytes()));
      values(leaf.bits(), leaf.count(), leaf.bytes());
    }
  }

  /// InternalNode::readTopology of a node at `level` (0: the root's children): child mask, value
  /// mask, the node's tile values, then each child; a leaf's topology is its value mask alone.
  /// Counts the leaves into `leaves`.
  void internal_topology(std::size_t level, std::uint64_t leaf_mask_bytes, std::uint64_t& leaves) {
    Level& node = levels_[level];  // deeper calls use deeper levels: the masks stay valid
    need(in_.bytes(node.child.words.data(), node.child.bytes()) &&
         in_.bytes(node.value.words.data(), node.value.bytes()));
    values(node.value.bits(), node.value.count(), node.value.bytes());
    const bool leaf_children = level + 1 == levels_.size();
    for (std::uint64_t n = node.child.count(); n > 0; --n) {
      if (leaf_children) {
        need(in_.skip(leaf_mask_bytes));
        ++leaves;
      } else {
        internal_topology(level + 1, leaf_mask_bytes, leaves);
      }
    }
  }

  /// io::readCompressedValues: a flag byte saying what follows, up to two inactive values, a
  /// selection mask, then the values (only the active ones under mask compression), as half
  /// floats when the grid says so, raw or in a zip or blosc block with an int64 length before it.
  void values(std::uint64_t count, std::uint64_t active, std::uint64_t mask_bytes) {
    using namespace openvdb::io;
    std::int8_t flag = 0;
    need(in_.read(flag));
    if (flag == NO_MASK_AND_ONE_INACTIVE_VAL || flag == MASK_AND_ONE_INACTIVE_VAL)
      need(in_.skip(value_bytes_));
    if (flag == MASK_AND_TWO_INACTIVE_VALS) need(in_.skip(2 * std::uint64_t(value_bytes_)));
    if (flag == MASK_AND_NO_INACTIVE_VALS || flag == MASK_AND_ONE_INACTIVE_VAL ||
        flag == MASK_AND_TWO_INACTIVE_VALS)
      need(in_.skip(mask_bytes));
    if ((compression_ & COMPRESS_ACTIVE_MASK) && flag != NO_MASK_AND_ALL_VALS) count = active;
    if (half_bytes_ && count == 0) return;  // HalfReader reads nothing at all then
    const std::uint64_t bytes = count * (half_bytes_ ? half_bytes_ : value_bytes_);
    if (!(compression_ & (COMPRESS_BLOSC | COMPRESS_ZIP))) {
      need(in_.skip(bytes));
      return;
    }
    const std::uint64_t at = in_.pos();
    std::int64_t length = 0;
    need(in_.read(length));
    if (length <= 0) {  // stored uncompressed: minus its length
      // bloscFromStream reads the block into the node's buffer before comparing the sizes (a
      // heap overflow, found by the vdb fuzzer); unzipFromStream compares first, then throws.
      if (length != -std::int64_t(bytes))
        throw Error(path_, "file is corrupt: grid '" + grid_ + "' has an uncompressed block of " +
                               std::to_string(std::uint64_t(0) - std::uint64_t(length)) +
                               " bytes at byte " + std::to_string(at) + " where its node holds " +
                               std::to_string(bytes));
      need(in_.skip(bytes));
      return;
    }
    if (std::uint64_t(length) > in_.left())
      throw Error(path_, "file is truncated or corrupt: grid '" + grid_ +
                             "' has a compressed block of " + std::to_string(length) +
                             " bytes at byte " + std::to_string(at) + " that runs past its end (" +
                             std::to_string(size_) + " bytes)");
    in_.skip(std::uint64_t(length));
  }

  /// A tree read that runs past the end: OpenVDB would allocate the nodes it describes until the
  /// file ran out, then fail.
  void need(bool ok) {
    if (!ok)
      throw Error(path_, "file is truncated or corrupt: the tree of grid '" + grid_ +
                             "' needs more bytes than the file's " + std::to_string(size_) +
                             " (it runs past the end at byte " + std::to_string(in_.pos()) + ")");
  }

  /// OpenVDB reads such bytes straight into a bool: any value but 0 or 1 is undefined behaviour
  /// (a fuzzer-made is_saved_as_half_float of 101 later overran a string copy in load_vdb).
  [[noreturn]] void bad_bool(const std::string& what, std::uint64_t at, std::uint8_t byte) {
    throw Error(path_, "file is corrupt: " + what + " at byte " + std::to_string(at) +
                           " is a bool holding " + std::to_string(byte) + ", not 0 or 1");
  }

  [[noreturn]] void text_past_end(const std::string& what, std::uint64_t n, std::uint64_t at) {
    throw Error(path_, "file is truncated or corrupt: " + what + " of " + std::to_string(n) +
                           " bytes at byte " + std::to_string(at) + " runs past its end (" +
                           std::to_string(size_) + " bytes)");
  }

  /// A uint32 length and that many bytes (io::readString); keeps short ones in `out`.
  bool text(std::string& out, const std::string& what) {
    const std::uint64_t at = in_.pos();
    std::uint32_t n = 0;
    if (!in_.read(n)) return false;
    if (n > in_.left()) text_past_end(what, n, at);
    out.clear();
    if (n > kKeptText) return in_.skip(n);
    out.resize(n);
    return in_.bytes(out.data(), n);
  }

  /// A MetaMap (MetaMap::readMeta): a count, then per entry a name, a type name and a sized
  /// value. Sets `half` from the entry that makes the grid's floats half-precision.
  bool metadata(const std::string& whose, bool& half) {
    std::uint32_t count = 0;
    if (!in_.read(count)) return false;
    std::string name, type, value;
    for (std::uint32_t i = 0; i < count; ++i) {  // each entry takes 12 bytes or more
      if (!text(name, whose + " metadata name") || !text(type, whose + " metadata type name"))
        return false;
      if (type == "__delayedload") {  // io::DelayedLoadMetadata::staticTypeName()
        if (!delayed_load_value(whose)) return false;
        continue;
      }
      if (const std::uint64_t fixed = fixed_metadata_bytes(type)) {
        // TypedMetadata::readValue reads its type's size, whatever length the file gives.
        std::uint32_t ignored = 0;
        value.resize(fixed);
        if (!in_.read(ignored) || !in_.bytes(value.data(), fixed)) return false;
      } else if (!text(value, whose + " metadata value")) {  // a string, or a type not registered
        return false;
      }
      if (type == "bool" && std::uint8_t(value[0]) > 1)
        bad_bool(whose + " metadata '" + name + "'", in_.pos() - 1, std::uint8_t(value[0]));
      if (name == "is_saved_as_half_float")  // GridBase::META_SAVE_HALF_FLOAT; asBool()
        half = std::any_of(value.begin(), value.end(), [](char c) { return c != 0; });
    }
    return true;
  }

  /// The value of io::DelayedLoadMetadata (which io::File writes with each grid): a leaf count,
  /// then a table of one flag byte per leaf and one of an int64 block size per leaf, each raw or
  /// blosc-compressed after a uint32 length. OpenVDB's readValue reads all this from the stream
  /// whatever the value's own length says, allocates both tables from the count (and a compressed
  /// one from its blosc header's size), and then skips what is left of the value, if anything.
  bool delayed_load_value(const std::string& whose) {
    std::uint32_t n = 0;
    const std::uint64_t at = in_.pos();
    if (!in_.read(n)) return false;
    if (n > in_.left()) text_past_end(whose + " metadata value", n, at);
    const std::uint64_t start = in_.pos();
    if (n == 0) return true;
    std::uint32_t leaves = 0, bytes = 0;
    if (!in_.read(leaves) || !in_.read(bytes)) return false;
    // Each leaf takes at least its value mask twice (topology, voxel block): 128 bytes.
    if (leaves > size_ / 128)
      throw Error(path_, "file is truncated or corrupt: " + whose +
                             " delayed-load metadata at byte " + std::to_string(at) + " lists " +
                             std::to_string(leaves) + " leaves, more than a file of " +
                             std::to_string(size_) + " bytes can hold");
    if (!delayed_load_table(whose, bytes, leaves, 1)) return false;
    if (!in_.read(bytes)) return false;
    if (bytes != 0xffffffffu && !delayed_load_table(whose, bytes, leaves, 8)) return false;
    in_.seek(std::max(in_.pos(), start + n));
    return true;
  }

  /// One table of `leaves` entries of `entry_bytes`: raw when `bytes` is 0, else `bytes` of blosc
  /// data whose 16-byte header gives the uncompressed size at offset 4.
  bool delayed_load_table(const std::string& whose, std::uint32_t bytes, std::uint32_t leaves,
                          std::uint32_t entry_bytes) {
    const std::uint64_t at = in_.pos();
    const std::uint64_t raw = std::uint64_t(leaves) * entry_bytes;
    const std::string what = whose + " delayed-load table of " + std::to_string(leaves) + " leaves";
    if (bytes == 0) {
      if (raw > in_.left()) text_past_end(what, raw, at);
      return in_.skip(raw);
    }
    constexpr std::uint32_t kBloscHeader = 16;
    if (bytes > in_.left()) text_past_end(what, bytes, at);
    std::uint8_t header[kBloscHeader] = {};
    if (bytes < kBloscHeader || !in_.bytes(header, kBloscHeader))
      throw Error(path_, "file is corrupt: " + what + " at byte " + std::to_string(at) +
                             " is compressed into " + std::to_string(bytes) +
                             " bytes, too few for a blosc header");
    std::uint32_t unpacked = 0;
    std::memcpy(&unpacked, header + 4, 4);
    constexpr std::uint32_t kBloscPad = 128;  // OpenVDB pads short tables before compressing
    if (unpacked > raw + kBloscPad)
      throw Error(path_, "file is corrupt: " + what + " at byte " + std::to_string(at) +
                             " claims " + std::to_string(unpacked) +
                             " bytes uncompressed, more than " + std::to_string(raw + kBloscPad));
    return in_.skip(bytes - kBloscHeader);
  }

  static constexpr std::uint32_t kKeptText = 256;
  const std::string& path_;
  const std::uint64_t size_;
  Cursor in_;
  std::uint32_t version_ = 0;
  std::uint32_t compression_ = 0;
  bool half_ = false;
  int value_bytes_ = 0;
  int half_bytes_ = 0;  ///< the size values are stored at when the grid saves them as half
  std::string grid_;
  struct Level {
    NodeMask child, value;
  };
  std::vector<Level> levels_;  ///< the masks of the internal node being walked at each depth
  VdbLengthWalk walk_;
};

}  // namespace

VdbLengthWalk check_vdb_lengths(const std::string& path, std::uint64_t size) {
  return VdbLengthCheck(path, size).run();
}

}  // namespace isocurv::volume::detail
