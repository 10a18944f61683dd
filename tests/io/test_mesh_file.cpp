// io::write_mesh / io::read_mesh: round trips in every format, bad files, atomic writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "io/field_arrays.h"
#include "io/compression.h"
#include "io/mesh_file.h"
#include "test_meshes.h"

namespace fs = std::filesystem;
using namespace isocurv;

namespace {

class IoMeshFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name)
      if (c == '/') c = '_';  // parameterised tests are named "Test/param"
    dir_ = fs::temp_directory_path() / ("isocurv_io_test_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

void expect_same_field(const curvature::CurvatureField& a, const curvature::CurvatureField& b) {
  // Walk both fields in step: for_each_array visits the arrays in the same order.
  std::vector<std::string> mismatched;
  std::vector<const void*> bs;
  io::for_each_array(b, [&](const char*, const auto& values) { bs.push_back(&values); });
  std::size_t i = 0;
  io::for_each_array(a, [&](const char* name, const auto& values) {
    using V = std::decay_t<decltype(values)>;
    if (!test::same_bits(values, *static_cast<const V*>(bs[i++]))) mismatched.push_back(name);
  });
  EXPECT_TRUE(mismatched.empty()) << "arrays differ: " << ::testing::PrintToString(mismatched);
}

void expect_error_naming(const std::function<void()>& fn, const std::string& file) {
  try {
    fn();
    ADD_FAILURE() << "no Error thrown for " << file;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
  }
}

}  // namespace

class IoExactFormats : public IoMeshFileTest, public ::testing::WithParamInterface<const char*> {
  void SetUp() override { IoMeshFileTest::SetUp(); }
};

TEST_F(IoMeshFileTest, WritingAVtpReportsVtkProgressToTheWriteStage) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  StageBar bar("write");
  ASSERT_EQ(stage_progress(), -1.0);
  io::write_mesh(path("p.vtp"), mesh, &field);
  EXPECT_EQ(stage_progress(), 1.0) << "VTK's writer reports up to 1";
}

TEST_P(IoExactFormats, EveryArrayRoundTripsBitForBit) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  const std::string p = path(std::string("m") + GetParam());
  io::write_mesh(p, mesh, &field);
  const io::MeshFile back = io::read_mesh(p);
  EXPECT_TRUE(test::same_bits(back.mesh.positions, mesh.positions));
  EXPECT_TRUE(test::same_bits(back.mesh.triangles, mesh.triangles));
  ASSERT_TRUE(back.field.has_value());
  expect_same_field(*back.field, field);
}

TEST_P(IoExactFormats, PartialFieldKeepsAbsentArraysEmpty) {
  const Mesh mesh = test::grid_mesh();
  auto full = test::random_field(mesh.vertex_count());
  curvature::CurvatureField some;
  some.H = full.H;
  some.dir2 = full.dir2;
  some.boundary = full.boundary;
  const std::string p = path(std::string("partial") + GetParam());
  io::write_mesh(p, mesh, &some);
  const io::MeshFile back = io::read_mesh(p);
  ASSERT_TRUE(back.field.has_value());
  expect_same_field(*back.field, some);
}

TEST_P(IoExactFormats, NoFieldReadsBackAsNoField) {
  const Mesh mesh = test::grid_mesh(3, 3);
  const std::string p = path(std::string("plain") + GetParam());
  io::write_mesh(p, mesh);
  const io::MeshFile back = io::read_mesh(p);
  EXPECT_TRUE(test::same_bits(back.mesh.positions, mesh.positions));
  EXPECT_TRUE(test::same_bits(back.mesh.triangles, mesh.triangles));
  EXPECT_FALSE(back.field.has_value());
}

TEST_P(IoExactFormats, ExtraArraysRoundTripUnderTheirNames) {
  // The features and multi-scale arrays (names with '_' and '.') come back, in order, bit for bit.
  const Mesh mesh = test::grid_mesh();
  const auto full = test::random_field(mesh.vertex_count());
  curvature::CurvatureField f;
  f.H = full.H;
  f.extra.push_back({"LBE_r0.2", full.k1});
  f.extra.push_back({"H_s2", full.k2});
  const std::string p = path(std::string("extras") + GetParam());
  io::write_mesh(p, mesh, &f);
  const io::MeshFile back = io::read_mesh(p);
  ASSERT_TRUE(back.field.has_value());
  ASSERT_EQ(back.field->extra.size(), 2u);
  EXPECT_EQ(back.field->extra[0].name, "LBE_r0.2");
  EXPECT_EQ(back.field->extra[1].name, "H_s2");
  expect_same_field(*back.field, f);
}

TEST_P(IoExactFormats, EmptyMeshRoundTrips) {
  const std::string p = path(std::string("empty") + GetParam());
  io::write_mesh(p, Mesh{});
  const io::MeshFile back = io::read_mesh(p);
  EXPECT_EQ(back.mesh.vertex_count(), 0u);
  EXPECT_EQ(back.mesh.triangle_count(), 0u);
}

INSTANTIATE_TEST_SUITE_P(VtpPly, IoExactFormats, ::testing::Values(".vtp", ".ply"),
                         [](const auto& info) { return std::string(info.param + 1); });

TEST_F(IoMeshFileTest, ObjCarriesGeometryAndNormalsExactly) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  const std::string p = path("m.obj");
  io::write_mesh(p, mesh, &field);
  const io::MeshFile back = io::read_mesh(p);
  EXPECT_TRUE(test::same_bits(back.mesh.positions, mesh.positions));
  EXPECT_TRUE(test::same_bits(back.mesh.triangles, mesh.triangles));
  ASSERT_TRUE(back.field.has_value());
  EXPECT_TRUE(test::same_bits(back.field->normals, field.normals));
  EXPECT_TRUE(back.field->k1.empty());
  EXPECT_TRUE(back.field->H.empty());
}

TEST_F(IoMeshFileTest, ObjReaderHandlesPolygonsSlashFormsAndNegativeIndices) {
  const std::string p = path("quad.obj");
  spit(p,
       "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
       "f 1/1/1 2/1/1 3/1/1 4/1/1\nf -4//1 -3//1 -1//1\n");
  const io::MeshFile back = io::read_mesh(p);
  ASSERT_EQ(back.mesh.triangle_count(), 3u);
  EXPECT_EQ(back.mesh.triangles[0], (Tri{0, 1, 2}));
  EXPECT_EQ(back.mesh.triangles[1], (Tri{0, 2, 3}));
  EXPECT_EQ(back.mesh.triangles[2], (Tri{0, 1, 3}));
  ASSERT_TRUE(back.field.has_value());
  EXPECT_EQ(back.field->normals[2], (Vec3f{0, 0, 1}));
}

TEST_F(IoMeshFileTest, StlCarriesGeometry) {
  const Mesh mesh = test::grid_mesh();
  const std::string p = path("m.stl");
  io::write_mesh(p, mesh);
  const io::MeshFile back = io::read_mesh(p);
  EXPECT_EQ(back.mesh.vertex_count(), mesh.vertex_count());
  ASSERT_EQ(back.mesh.triangle_count(), mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(back.mesh.positions[back.mesh.triangles[t][c]], mesh.positions[mesh.triangles[t][c]]);
  EXPECT_FALSE(back.field.has_value());
}

TEST_F(IoMeshFileTest, VtpUsesDesignArrayNamesAppendedCompressed) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  const std::string p = path("m.vtp");
  io::write_mesh(p, mesh, &field);
  const std::string text = slurp(p);
  EXPECT_NE(text.find("format=\"appended\""), std::string::npos);
  EXPECT_NE(text.find("vtkLZ4DataCompressor"), std::string::npos);  // the default (io/compression.h)
  EXPECT_NE(text.find("Normals=\"Normals\""), std::string::npos);  // the active point normals
  for (const char* name : {"Normals", "Area", "k1", "k2", "dir1", "dir2", "H", "K", "dcurv", "ShapeIndex",
                           "Curvedness", "AO", "Boundary"})
    EXPECT_NE(text.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
  EXPECT_NE(text.find("Name=\"dcurv\" NumberOfComponents=\"4\""), std::string::npos);
}

TEST_F(IoMeshFileTest, VtpCompressorsAsAskedAndTheSameArraysBack) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  const struct {
    const char* text;
    const char* marker;  // in the file's header; nullptr: no compressor named
  } cases[] = {{"zlib:1", "vtkZLibDataCompressor"}, {"lz4:9", "vtkLZ4DataCompressor"}, {"none", nullptr}};
  for (const auto& c : cases) {
    const std::string p = path(std::string("c") + c.text[0] + ".vtp");
    io::write_mesh(p, mesh, &field, io::parse_compression(c.text));
    const std::string text = slurp(p);
    if (c.marker) EXPECT_NE(text.find(c.marker), std::string::npos) << c.text;
    else EXPECT_EQ(text.find("compressor="), std::string::npos) << c.text;
    const io::MeshFile back = io::read_mesh(p);
    ASSERT_TRUE(back.field.has_value()) << c.text;
    EXPECT_EQ(back.field->k1, field.k1) << c.text;
    EXPECT_EQ(back.field->dcurv, field.dcurv) << c.text;
  }
}

TEST(IoCompression, ParsesTheDocumentedFormsOnly) {
  EXPECT_EQ(io::to_string(io::parse_compression("lz4")), "lz4:1");
  EXPECT_EQ(io::to_string(io::parse_compression("zlib")), "zlib:1");
  EXPECT_EQ(io::to_string(io::parse_compression("zlib:9")), "zlib:9");
  EXPECT_EQ(io::to_string(io::parse_compression("none")), "none");
  EXPECT_EQ(io::to_string(io::Compression{}), "lz4:1");
  for (const char* bad : {"", "gzip", "zlib:0", "zlib:10", "lz4:", "none:1", "zlib:x", "LZ4"})
    EXPECT_THROW(io::parse_compression(bad), Error) << bad;
}

TEST_F(IoMeshFileTest, PlyHeaderIsAsDocumented) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  const std::string p = path("m.ply");
  io::write_mesh(p, mesh, &field);
  const std::string text = slurp(p);
  const std::string header = text.substr(0, text.find("end_header"));
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  for (const char* line : {"element vertex 35\n", "property float x\n", "property float nx\n", "property float nz\n",
                           "property float Area\n", "property float k1\n", "property float dir1_0\n",
                           "property float dir2_2\n", "property float dcurv_3\n", "property float ShapeIndex\n",
                           "property float AO\n", "property uchar Boundary\n", "element face 48\n",
                           "property list uchar int vertex_indices\n"})
    EXPECT_NE(header.find(line), std::string::npos) << line;
}

TEST_F(IoMeshFileTest, AsciiPlyWithPolygonsReads) {
  const std::string p = path("ascii.ply");
  spit(p,
       "ply\nformat ascii 1.0\ncomment hand made\nelement vertex 4\nproperty double x\nproperty double y\n"
       "property double z\nproperty float k1\nproperty uchar quality\nelement face 1\n"
       "property list uchar uint vertex_index\n"
       "end_header\n0 0 0 1 7\n1 0 0 2 8\n1 1 0 3 9\n0 1 0 4 10\n4 0 1 2 3\n");
  const io::MeshFile back = io::read_mesh(p);
  ASSERT_EQ(back.mesh.triangle_count(), 2u);
  EXPECT_EQ(back.mesh.triangles[1], (Tri{0, 2, 3}));
  ASSERT_TRUE(back.field.has_value());
  EXPECT_EQ(back.field->k1, (std::vector<float>{1, 2, 3, 4}));
  EXPECT_TRUE(back.field->k2.empty());
  ASSERT_EQ(back.field->extra.size(), 1u);  // another tool's property is kept as an extra array
  EXPECT_EQ(back.field->extra[0].name, "quality");
  EXPECT_EQ(back.field->extra[0].values, (std::vector<float>{7, 8, 9, 10}));
}

// ---- bad files

TEST_F(IoMeshFileTest, MissingFileIsAnError) {
  for (const char* ext : {".vtp", ".ply", ".obj", ".stl"}) {
    const std::string p = path(std::string("missing") + ext);
    expect_error_naming([&] { io::read_mesh(p); }, p);
  }
}

TEST_F(IoMeshFileTest, UnknownExtensionIsAnError) {
  const std::string p = path("m.xyz");
  expect_error_naming([&] { io::write_mesh(p, test::grid_mesh()); }, p);
  EXPECT_FALSE(fs::exists(p));
  spit(p, "1 2 3\n");
  expect_error_naming([&] { io::read_mesh(p); }, p);
}

TEST_F(IoMeshFileTest, TruncatedPlyIsAnError) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  const std::string good = path("good.ply");
  io::write_mesh(good, mesh, &field);
  const std::string bytes = slurp(good);
  for (double fraction : {0.9, 0.5, 0.1}) {
    const std::string p = path("cut.ply");
    spit(p, bytes.substr(0, static_cast<std::size_t>(bytes.size() * fraction)));
    expect_error_naming([&] { io::read_mesh(p); }, p);
  }
  const std::string p = path("cut_face.ply");
  spit(p, bytes.substr(0, bytes.size() - 1));
  expect_error_naming([&] { io::read_mesh(p); }, p);
}

TEST_F(IoMeshFileTest, PlyWithBadIndexIsAnError) {
  const std::string p = path("bad_index.ply");
  spit(p, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expect_error_naming([&] { io::read_mesh(p); }, p);
}

TEST_F(IoMeshFileTest, PlyAnnouncingHugeCountIsAnErrorNotACrash) {
  const std::string p = path("huge.ply");
  spit(p, "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
          "property float y\nproperty float z\nend_header\n\x01\x02\x03");
  expect_error_naming([&] { io::read_mesh(p); }, p);
}

TEST_F(IoMeshFileTest, GarbageVtpIsAnError) {
  const std::string p = path("garbage.vtp");
  spit(p, "this is not XML at all \x01\x02\x03");
  expect_error_naming([&] { io::read_mesh(p); }, p);
  const std::string empty = path("empty.vtp");
  spit(empty, "");
  expect_error_naming([&] { io::read_mesh(empty); }, empty);
}

TEST_F(IoMeshFileTest, TruncatedVtpIsAnError) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  const std::string good = path("good.vtp");
  io::write_mesh(good, mesh, &field);
  const std::string bytes = slurp(good);
  for (double fraction : {0.95, 0.6, 0.3}) {
    const std::string p = path("cut.vtp");
    spit(p, bytes.substr(0, static_cast<std::size_t>(bytes.size() * fraction)));
    expect_error_naming([&] { io::read_mesh(p); }, p);
  }
}

TEST_F(IoMeshFileTest, BadObjIsAnError) {
  const std::string p = path("bad.obj");
  spit(p, "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  expect_error_naming([&] { io::read_mesh(p); }, p);
  spit(p, "v 0 zero 0\n");
  expect_error_naming([&] { io::read_mesh(p); }, p);
}

TEST_F(IoMeshFileTest, GarbageStlIsAnError) {
  const std::string p = path("garbage.stl");
  spit(p, "solid x\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0\n");
  expect_error_naming([&] { io::read_mesh(p); }, p);
  // binary STL has no magic number: a size that does not match the triangle count gives it away
  std::string bytes(1500, '\x5a');
  spit(p, bytes);
  expect_error_naming([&] { io::read_mesh(p); }, p);
}

// ---- atomic writes

TEST_F(IoMeshFileTest, WriteIntoMissingFolderLeavesNothing) {
  const std::string p = path("no/such/folder/m.vtp");
  expect_error_naming([&] { io::write_mesh(p, test::grid_mesh()); }, p);
  EXPECT_FALSE(fs::exists(path("no")));
}

TEST_F(IoMeshFileTest, FailedWriteKeepsTheExistingFile) {
  const Mesh mesh = test::grid_mesh();
  for (const char* ext : {".vtp", ".ply", ".obj", ".stl"}) {
    const std::string p = path(std::string("keep") + ext);
    io::write_mesh(p, mesh);
    const std::string before = slurp(p);
    // Block the writer midway: its temporary name is taken by a non-empty folder, so opening it fails.
    const fs::path blocker = temporary_path_for(p);
    fs::create_directories(blocker / "x");
    expect_error_naming([&] { io::write_mesh(p, test::grid_mesh(9, 9)); }, p);
    EXPECT_EQ(slurp(p), before) << ext;
    fs::remove_all(blocker);
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_EQ(entry.path().filename().string().find(".keep.tmp"), std::string::npos) << entry.path();
  }
}

TEST_F(IoMeshFileTest, MismatchedFieldIsRefusedBeforeWriting) {
  const Mesh mesh = test::grid_mesh();
  const std::string p = path("m.ply");
  io::write_mesh(p, mesh);
  const std::string before = slurp(p);
  auto field = test::random_field(mesh.vertex_count());
  field.k2.pop_back();
  try {
    io::write_mesh(p, mesh, &field);
    ADD_FAILURE() << "no Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("k2"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(p), before);
}

TEST_F(IoMeshFileTest, TriangleIndexOutOfRangeIsRefused) {
  Mesh mesh = test::grid_mesh();
  mesh.triangles.push_back({0, 1, 999});
  const std::string p = path("m.obj");
  expect_error_naming([&] { io::write_mesh(p, mesh); }, p);
  EXPECT_FALSE(fs::exists(p));
}
