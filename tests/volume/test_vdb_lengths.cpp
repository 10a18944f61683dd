// The .vdb length walk (volume/detail/vdb_length_check): every length and count OpenVDB would
// allocate from is checked against the file before OpenVDB reads it, and the walk knows every
// layout OpenVDB writes, so it refuses no good file.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cstring>
#include <fstream>
#include <string>

#include "test_files.h"
#include "tests/test_paths.h"
#include "volume/detail/vdb_length_check.h"
#include "volume/load.h"
#include "volume/vdb_grid_names.h"

using namespace isocurv::volume;
using namespace voltest;

// Lengths that OpenVDB allocates (zero-filled) before reading what they size, names, type names
// and metadata values, are checked against the file first. The fuzzer's 1,978-byte files claimed
// a grid type name of 1.9 GB and a metadata value of 4.3 GB (4.3 GB resident before the check).
// In a file of two grids, the second grid's metadata is reached after the first grid's tree.
TEST(VolumeBadInput, VdbLengthsBeyondTheFileAreRefusedBeforeAllocating) {
  const std::string fuzz =
      std::string(isocurv::test_paths::source_dir()) + "/tests/data/fuzz/volume/";
  expect_error([&] { load(fuzz + "vdb_grid_type_name_1.9e9.vdb"); }, "vdb_grid_type_name_1.9e9.vdb",
               "a grid type name of 1936457728 bytes at byte 71 runs past its end (1978 bytes)");
  expect_error([&] { load(fuzz + "vdb_metadata_value_4.3e9.vdb"); }, "vdb_metadata_value_4.3e9.vdb",
               "a grid's metadata name of 4294967295 bytes at byte 290");
  // The grid listing of `isocurv series` reads the metadata through io::File: walked first too.
  expect_error([&] { vdb_grid_names(fuzz + "vdb_grid_type_name_1.9e9.vdb"); },
               "vdb_grid_type_name_1.9e9.vdb", "a grid type name of 1936457728 bytes");
  // OpenVDB's delayed-load metadata sizes its tables from counts inside its value (1.6 GB asked).
  expect_error(
      [&] { load(fuzz + "vdb_delayed_load_table_1.6e9.vdb"); }, "vdb_delayed_load_table_1.6e9.vdb",
      "delayed-load metadata at byte 328 lists 131 leaves, more than a file of 9987 bytes");
  // OpenVDB 10 still reads format 0 (a 1.6 GB metadata string here); the walk knows 222 on.
  expect_error([&] { load(fuzz + "vdb_format_0_string_1.6e9.vdb"); },
               "vdb_format_0_string_1.6e9.vdb", "OpenVDB file format 0 is older than 222");
  // A format newer than OpenVDB 10's, which it would read as its own (with warnings on stderr).
  expect_error([&] { load(fuzz + "vdb_format_545.vdb"); }, "vdb_format_545.vdb",
               "OpenVDB file format 545 is newer than 224");
  // A 2.2 GB grid name after an int64 grid, which the walk must follow to reach it.
  expect_error([&] { load(fuzz + "vdb_name_after_int64_grid_2.2e9.vdb"); },
               "vdb_name_after_int64_grid_2.2e9.vdb",
               "a grid name of 2224193135 bytes at byte 637 runs past its end (2268 bytes)");
  // OpenVDB reads file bytes straight into bools; a 64 there later overran a string copy.
  expect_error([&] { load(fuzz + "vdb_half_flag_bool_64.vdb"); }, "vdb_half_flag_bool_64.vdb",
               "metadata 'is_saved_as_half_float' at byte 473 is a bool holding 64, not 0 or 1");
  // io::Stream reserves a descriptor per grid before reading any (274 GB asked for this one).
  expect_error([&] { load(fuzz + "vdb_grid_count_1.7e9.vdb"); }, "vdb_grid_count_1.7e9.vdb",
               "its grid count at byte 61 is 1711276033, more than its 272 bytes can hold");
  // bloscFromStream reads an uncompressed block of the length the file gives into the node's
  // buffer before comparing it with the node's size: a heap overflow (then abort) before the walk.
  expect_error([&] { load(fuzz + "vdb_blosc_raw_block_overflow.vdb"); },
               "vdb_blosc_raw_block_overflow.vdb",
               "grid 'ls' has an uncompressed block of 2025524839466146845 bytes at byte 9858 "
               "where its node holds 220");
  // A vec3i value's length was 13,324, which OpenVDB ignores: it reads 12 bytes and then, in
  // step with the walk, a type name of 1.6 GB.
  expect_error([&] { load(fuzz + "vdb_typed_metadata_length_1.6e9.vdb"); },
               "vdb_typed_metadata_length_1.6e9.vdb",
               "a grid's metadata type name of 1635131493 bytes at byte 4343");
  openvdb::initialize();
  TempDir dir;
  openvdb::GridPtrVec grids;
  for (const char* name : {"a", "b"}) {
    auto g = openvdb::FloatGrid::create(0.0f);
    g->setName(name);
    g->tree().setValue(openvdb::Coord(0), 1.0f);
    g->insertMeta("note", openvdb::StringMetadata(std::string("note-of-grid-") + name));
    grids.push_back(g);
  }
  openvdb::MetaMap file_meta;
  file_meta.insertMeta("note", openvdb::StringMetadata("note-of-the-file"));
  const std::string two = dir.file("two.vdb");
  openvdb::io::File(two).write(grids, file_meta);
  EXPECT_NO_THROW(load(two));  // a valid file passes the walk
  const std::string bytes = file_text(two);
  const std::pair<const char*, const char*> cases[] = {
      {"note-of-the-file", "the file's metadata value of 2147418112 bytes"},
      {"note-of-grid-b", "a grid's metadata value of 2147418112 bytes"}};
  for (const auto& [marker, message] : cases) {
    std::string corrupt = bytes;
    const std::size_t at = corrupt.find(marker);
    ASSERT_NE(at, std::string::npos) << marker;
    std::uint32_t length = 0;
    std::memcpy(&length, &corrupt[at - 4], 4);
    ASSERT_EQ(length, std::strlen(marker)) << "a metadata value: its length, then its bytes";
    const std::uint32_t huge = 0x7fff0000;
    std::memcpy(&corrupt[at - 4], &huge, 4);
    write_file(dir.file("corrupt.vdb"), corrupt);
    expect_error([&] { load(dir.file("corrupt.vdb")); }, "corrupt.vdb", message);
  }
  // io::Stream reads grid after grid and never seeks to the offsets the descriptors give: with
  // grid a's end offset corrupted, OpenVDB still reads grid b's descriptor right after grid a.
  {
    const std::string tree_type = std::string("\x10\0\0\0", 4) + "Tree_float_5_4_3";
    const std::size_t a = bytes.find(std::string("\x01\0\0\0a", 5) + tree_type);
    const std::size_t b = bytes.find(std::string("\x01\0\0\0b", 5) + tree_type);
    ASSERT_NE(a, std::string::npos);
    ASSERT_NE(b, std::string::npos);
    std::string shuffled = bytes;
    const std::size_t offsets = a + 5 + tree_type.size() + 4;     // after the empty parent name
    std::memcpy(&shuffled[offsets + 16], &shuffled[offsets], 8);  // end offset := start offset
    const std::uint32_t huge = 0x7fff0000;
    std::memcpy(&shuffled[b], &huge, 4);
    write_file(dir.file("corrupt.vdb"), shuffled);
    expect_error([&] { load(dir.file("corrupt.vdb")); }, "corrupt.vdb",
                 "a grid name of 2147418112 bytes at byte " + std::to_string(b));
  }
  // io::File writes a delayed-load table with each grid: its compressed length, corrupted.
  const std::size_t type = bytes.find("__delayedload");
  ASSERT_NE(type, std::string::npos);
  std::string corrupt = bytes;
  const std::size_t table_length =
      type + std::strlen("__delayedload") + 4 + 4;  // value size, leaves
  const std::uint32_t huge = 0x7fff0000;
  std::memcpy(&corrupt[table_length], &huge, 4);
  write_file(dir.file("corrupt.vdb"), corrupt);
  expect_error([&] { load(dir.file("corrupt.vdb")); }, "corrupt.vdb",
               "a grid's delayed-load table of 1 leaves of 2147418112 bytes at byte " +
                   std::to_string(table_length + 4) + " runs past its end");
}

namespace {

/// An empty grid of type G (background zero), made by OpenVDB's own registry: constructing G here
/// would compile every virtual function of G and its tree into this test (over a minute for the
/// seven types below).
template <typename G>
typename G::Ptr from_registry() {
  return openvdb::gridPtrCast<G>(openvdb::GridBase::createGrid(G::gridType()));
}

/// Grids that between them make OpenVDB write every kind of value block: a level set (inactive
/// values of both signs, interior tiles), a fog volume with tiles at each level, a grid with more
/// than two inactive values, a double grid, an empty one, and one of each other value type the
/// walk knows.
openvdb::GridPtrVec grids_of_every_block_kind(bool half) {
  auto level_set =
      openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(20.0f, openvdb::Vec3f(3), 1.0f);
  level_set->setName("level_set");
  auto fog = openvdb::FloatGrid::create(0.0f);
  fog->setName("fog");
  fog->tree().fill(openvdb::CoordBBox(openvdb::Coord(-200), openvdb::Coord(300)), 0.5f, true);
  fog->tree().setValue(openvdb::Coord(7, 8, 9), 2.0f);
  auto mixed = openvdb::FloatGrid::create(1.0f);
  mixed->setName("mixed");
  for (int i = 0; i < 40; ++i) {
    mixed->tree().setValue(openvdb::Coord(i, 2 * i, 3), float(i) * 0.25f);
    mixed->tree().setValueOff(openvdb::Coord(i, 2 * i + 1, 3), float(i % 5) - 7.0f);
  }
  auto dbl = openvdb::DoubleGrid::create(0.0);
  dbl->setName("double");
  for (int i = 0; i < 30; ++i) dbl->tree().setValue(openvdb::Coord(i, -i, 5 * i), 0.1 * i);
  auto empty = openvdb::FloatGrid::create(3.0f);
  empty->setName("empty");
  openvdb::GridPtrVec grids{level_set, fog, mixed, dbl, empty};
  // The other value types the walk knows, each with tiles, active and inactive voxels.
  auto add = [&](auto grid, auto value) {
    grid->setName(std::string("of_type_") + grid->valueType());
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15)), value, true);
    for (int i = 0; i < 20; ++i) grid->tree().setValueOff(openvdb::Coord(40 + i, 3, i), value);
    grids.push_back(grid);
  };
  add(from_registry<openvdb::Int32Grid>(), 7);
  add(from_registry<openvdb::Int64Grid>(), openvdb::Int64(1) << 40);
  add(from_registry<openvdb::Vec3SGrid>(), openvdb::Vec3s(1, 2, 3));
  add(from_registry<openvdb::Vec3DGrid>(), openvdb::Vec3d(1, 2, 3));
  add(from_registry<openvdb::Vec3IGrid>(), openvdb::Vec3i(1, 2, 3));
  add(from_registry<openvdb::BoolGrid>(), true);
  add(from_registry<openvdb::MaskGrid>(), true);
  for (auto& g : grids) g->setSaveFloatAsHalf(half);
  return grids;
}

/// The first 8-byte position p in `bytes` holding an int64 equal to the bytes after it: the
/// length before the file's last compressed block.
std::size_t last_block_length_at(const std::string& bytes) {
  for (std::size_t p = bytes.size() - 9; p > 0; --p) {
    std::int64_t n = 0;
    std::memcpy(&n, &bytes[p], 8);
    if (n > 0 && std::uint64_t(n) == bytes.size() - p - 8) return p;
  }
  return std::string::npos;
}

}  // namespace

// The length walk must know every layout OpenVDB writes, or it would leave them unchecked (and a
// wrong model could refuse good files): each grid of each compression and precision is walked to
// exactly the end the file records for it, and loads.
TEST(VolumeBadInput, VdbLengthWalkCoversEveryBlockLayoutOpenVdbWrites) {
  openvdb::initialize();
  TempDir dir;
  using openvdb::io::COMPRESS_ACTIVE_MASK;
  std::vector<std::uint32_t> compressions{openvdb::io::COMPRESS_NONE, COMPRESS_ACTIVE_MASK,
                                          openvdb::io::COMPRESS_ZIP,
                                          openvdb::io::COMPRESS_ZIP | COMPRESS_ACTIVE_MASK};
  if (openvdb::io::Archive::hasBloscCompression())
    compressions.push_back(openvdb::io::COMPRESS_BLOSC | COMPRESS_ACTIVE_MASK);
  for (std::uint32_t compression : compressions) {
    for (bool half : {false, true}) {
      SCOPED_TRACE("compression " + std::to_string(compression) + (half ? ", half" : ""));
      const std::string path = dir.file("every.vdb");
      openvdb::io::File file(path);
      file.setCompression(compression);
      file.write(grids_of_every_block_kind(half));
      const auto walk = isocurv::volume::detail::check_vdb_lengths(path, file_text(path).size());
      EXPECT_EQ(walk.grids, 12);
      EXPECT_EQ(walk.trees_walked, 12);
      LoadOptions options;
      for (const char* grid : {"level_set", "fog", "mixed", "double"}) {
        options.grid = grid;
        EXPECT_NO_THROW(load(path, options)) << grid;
      }
    }
  }
  // And the real files, from other writers.
  for (const char* name : {"vdb_sphere/sphere.vdb", "vdb_cube/cube.vdb", "vdb_smoke/smoke.vdb"}) {
    const std::string path = std::string(isocurv::test_paths::shared_datasets()) + "/" + name;
    if (!std::ifstream(path)) continue;
    const auto walk = isocurv::volume::detail::check_vdb_lengths(path, file_text(path).size());
    EXPECT_GT(walk.grids, 0) << name;
    EXPECT_EQ(walk.trees_walked, walk.grids) << name;
  }
}

// OpenVDB allocates a zip block whole from its int64 length, and builds tree nodes from child
// masks until the file runs out: both are refused from the lengths, before anything is read.
TEST(VolumeBadInput, VdbTreeLengthsBeyondTheFileAreRefused) {
  openvdb::initialize();
  TempDir dir;
  auto g = openvdb::FloatGrid::create(0.0f);
  g->setName("g");
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) g->tree().setValue(openvdb::Coord(i, j, 0), float(i + j) * 0.5f);
  const std::string path = dir.file("one_leaf.vdb");
  openvdb::io::File file(path);
  file.setCompression(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
  file.write({g});
  ASSERT_NO_THROW(load(path));
  const std::string bytes = file_text(path);
  const std::string corrupt = dir.file("corrupt.vdb");

  const std::size_t at = last_block_length_at(bytes);
  ASSERT_NE(at, std::string::npos) << "the leaf's values end the file, in a zip block";
  std::string huge_block = bytes;
  const std::int64_t huge = std::int64_t(2) << 30;
  std::memcpy(&huge_block[at], &huge, 8);
  write_file(corrupt, huge_block);
  expect_error([&] { load(corrupt); }, "corrupt.vdb",
               "grid 'g' has a compressed block of 2147483648 bytes at byte " + std::to_string(at) +
                   " that runs past its end");

  // The root's child: one child (the first bit) in a child mask of 4096 bytes, an empty value
  // mask after it. Every bit set asks for 32,768 nodes of at least 1,025 bytes each.
  const std::string one_child = std::string(1, '\x01') + std::string(4096 * 2 - 1, '\0');
  const std::size_t mask = bytes.find(one_child);
  ASSERT_NE(mask, std::string::npos);
  std::string many_children = bytes;
  std::memset(&many_children[mask], 0xff, 4096);
  write_file(corrupt, many_children);
  expect_error([&] { load(corrupt); }, "corrupt.vdb",
               "the tree of grid 'g' needs more bytes than the file's");

  // The tree starts with its buffer count, after the transform's 120-byte UniformScaleMap.
  // OpenVDB warns on stderr about any count but 1 and then reads one buffer per leaf anyway.
  const std::string map = "UniformScaleMap";
  const std::size_t tree = bytes.find(map) + map.size() + 120;
  ASSERT_LT(tree + 4, bytes.size());
  std::int32_t buffers = 0;
  std::memcpy(&buffers, &bytes[tree], 4);
  ASSERT_EQ(buffers, 1);
  std::string two_buffers = bytes;
  buffers = 2;
  std::memcpy(&two_buffers[tree], &buffers, 4);
  write_file(corrupt, two_buffers);
  expect_error([&] { load(corrupt); }, "corrupt.vdb",
               "the tree of grid 'g' has 2 buffers per leaf");

  // A root tile (a whole 4096^3 block) and its active flag, read by OpenVDB into a bool.
  auto tiled = openvdb::FloatGrid::create(0.0f);
  tiled->setName("g");
  tiled->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(4095)), 1.0f, true);
  const std::string tiled_path = dir.file("tiled.vdb");
  openvdb::io::File(tiled_path).write({tiled});
  ASSERT_NO_THROW(load(tiled_path));
  std::string bad_flag = file_text(tiled_path);
  const std::size_t root = bad_flag.find(map) + map.size() + 120 + 4;  // after the buffer count
  std::uint32_t tiles = 0;
  std::memcpy(&tiles, &bad_flag[root + 4], 4);
  ASSERT_EQ(tiles, 1u);
  const std::size_t flag = root + 12 + 12 + 4;  // background, counts; the tile's origin, value
  ASSERT_EQ(bad_flag[flag], 1);
  bad_flag[flag] = 7;
  write_file(corrupt, bad_flag);
  expect_error(
      [&] { load(corrupt); }, "corrupt.vdb",
      "a root tile's active flag at byte " + std::to_string(flag) + " is a bool holding 7");
}

// TypedMetadata reads its type's size and ignores the length the file gives, so a wrong length
// there is harmless to OpenVDB: the walk must read such values the same way, or it would refuse
// good files and walk the rest out of step (a fuzzer-made file then slipped a 1.6 GB string past).
TEST(VolumeBadInput, VdbFixedSizeMetadataIgnoresItsLength) {
  openvdb::initialize();
  const char* fixed[] = {"bool",  "float", "double", "int32", "int64", "vec2i", "vec2s", "vec2d",
                         "vec3i", "vec3s", "vec3d",  "vec4i", "vec4s", "vec4d", "mat4s", "mat4d"};
  for (const char* type : fixed) EXPECT_TRUE(openvdb::Metadata::isRegisteredType(type)) << type;
  // Read by their length (UnknownMetadata); registered ones would need a size in the walk.
  for (const char* type : {"half", "int8", "uint8", "int16", "uint32", "vec3u8", "mat3s", "mat3d",
                           "quats", "quatd", "mask"})
    EXPECT_FALSE(openvdb::Metadata::isRegisteredType(type)) << type;
  TempDir dir;
  auto g = openvdb::FloatGrid::create(0.0f);
  g->setName("g");
  g->tree().setValue(openvdb::Coord(1, 2, 3), 1.0f);
  for (const char* type : fixed) {
    auto meta = openvdb::Metadata::createMetadata(type);
    g->insertMeta(std::string("meta_of_type_") + type, *meta);
  }
  const std::string path = dir.file("typed.vdb");
  openvdb::io::File(path).write({g});
  const std::string bytes = file_text(path);
  std::string corrupt = bytes;
  for (const char* type : fixed) {
    const std::string name = std::string("meta_of_type_") + type;
    const std::size_t at = corrupt.find(name);
    ASSERT_NE(at, std::string::npos) << name;
    const std::size_t length = at + name.size() + 4 + std::strlen(type);  // after the type name
    const std::uint32_t huge = 0x7fff0000;
    std::memcpy(&corrupt[length], &huge, 4);
  }
  const std::string bad = dir.file("typed_lengths.vdb");
  write_file(bad, corrupt);
  const auto walk = isocurv::volume::detail::check_vdb_lengths(bad, corrupt.size());
  EXPECT_EQ(walk.trees_walked, 1);
  EXPECT_NO_THROW(load(bad));
}
