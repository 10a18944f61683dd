// Meshes other tools made (issue 12, section 5) and check's triangle quality (section 1): welding,
// inward orientation and --flip in curvature; offender lists, orientation and quality in check.
#include <gtest/gtest.h>

#include <string>

#include "cli.h"
#include "io/mesh_file.h"
#include "tests/curvature/test_meshes.h"

using namespace isocurv;
using namespace isocurv::test;
using nlohmann::json;

namespace {

// The bundled sphere (radius 0.8) written by extract, read back.
Mesh sphere_mesh(const TempDir& dir) {
  const std::string path = dir / "sphere.ply";
  const auto r = run_isocurv({"extract", dataset("sphere"), "-o", path, "--quiet"});
  EXPECT_TRUE(r.ok()) << r.describe();
  return io::read_mesh(path).mesh;
}


Mesh flipped(Mesh m) {
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

}  // namespace

// extract takes volumes: a mesh file is refused with one line, not written out again as if it
// had been extracted at isovalue 0 (which dropped its arrays).
TEST(MeshesFromElsewhere, ExtractRefusesAMeshFile) {
  TempDir dir("extract_mesh");
  sphere_mesh(dir);
  const std::string out = dir / "again.vtp";
  const auto r = run_isocurv({"extract", dir / "sphere.ply", "-o", out});
  expect_clean_failure(r, "a mesh file: extract takes a volume");
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(MeshesFromElsewhere, CurvatureWeldsAnUnweldedMesh) {
  TempDir dir("unwelded");
  const Mesh sphere = sphere_mesh(dir);
  io::write_mesh(dir / "u.ply", unwelded(sphere));
  const auto r = run_isocurv({"curvature", dir / "u.ply", "-o", dir / "c.vtp", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "curvature --json");
  EXPECT_EQ(j["welded_vertices"].get<std::size_t>(),
            3 * sphere.triangles.size() - sphere.positions.size());
  EXPECT_EQ(j["vertices"].get<std::size_t>(), sphere.positions.size());
  EXPECT_NEAR(j["curvature"]["H"]["p50"].get<double>(), 1.25, 0.2) << "not all zero: " << j.dump(2);
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r.describe();
  EXPECT_EQ(lines[0].rfind("isocurv: note:", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("welded"), std::string::npos) << lines[0];
  EXPECT_EQ(io::read_mesh(dir / "c.vtp").mesh.positions.size(), sphere.positions.size());
  // --quiet silences the note.
  const auto q = run_isocurv({"curvature", dir / "u.ply", "-o", dir / "q.vtp", "--quiet"});
  ASSERT_TRUE(q.ok()) << q.describe();
  EXPECT_TRUE(q.err.empty()) << q.err;
}

TEST(MeshesFromElsewhere, InwardClosedMeshWarnsAndFlipFixesIt) {
  TempDir dir("inward");
  io::write_mesh(dir / "in.ply", flipped(sphere_mesh(dir)));
  const auto r = run_isocurv({"curvature", dir / "in.ply", "-o", dir / "c.vtp", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r.describe();
  EXPECT_EQ(lines[0].rfind("isocurv: warning:", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("inward"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("--flip"), std::string::npos) << lines[0];
  EXPECT_LT(parse_json(r.out, "curvature --json")["curvature"]["H"]["p50"].get<double>(), 0.0);

  const auto f =
      run_isocurv({"curvature", dir / "in.ply", "--flip", "-o", dir / "f.vtp", "--json"});
  ASSERT_TRUE(f.ok()) << f.describe();
  EXPECT_TRUE(f.err.empty()) << f.err;
  const json fj = parse_json(f.out, "curvature --flip --json");
  EXPECT_TRUE(fj["flipped"].get<bool>());
  EXPECT_NEAR(fj["curvature"]["H"]["p50"].get<double>(), 1.25, 0.2);

  // An outward mesh gets no warning; --flip on a volume is an error.
  const auto out = run_isocurv({"curvature", dir / "sphere.ply", "-o", dir / "o.vtp", "--quiet"});
  ASSERT_TRUE(out.ok()) << out.describe();
  EXPECT_TRUE(out.err.empty()) << out.err;
  expect_clean_failure(run_isocurv({"curvature", dataset("sphere"), "--flip", "-o", dir / "v.vtp"}),
                       "--flip");
  EXPECT_FALSE(fs::exists(dir / "v.vtp"));
}

TEST(MeshesFromElsewhere, CheckReportsOrientationOfClosedComponents) {
  TempDir dir("check_inward");
  io::write_mesh(dir / "in.ply", flipped(sphere_mesh(dir)));
  const auto r = run_isocurv({"check", dir / "in.ply", "--json"});
  ASSERT_EQ(r.exit_code, 1) << "an inward mesh is a problem the check reports: " << r.describe();
  const json j = parse_json(r.out, "check --json");
  EXPECT_TRUE(j["problems_found"].get<bool>());
  EXPECT_TRUE(j["consistently_oriented"].get<bool>());
  EXPECT_EQ(j["orientation"], "inward");
  EXPECT_EQ(j["closed_components"].get<int>(), 1);
  EXPECT_EQ(j["inward_components"].get<int>(), 1);
  EXPECT_LT(j["closed_signed_volume"].get<double>(), 0.0);
  ASSERT_EQ(j["component_orientation"].size(), 1u);
  EXPECT_EQ(j["component_orientation"][0]["orientation"], "inward");
  const auto t = run_isocurv({"check", dir / "in.ply"});
  ASSERT_EQ(t.exit_code, 1) << t.describe();
  EXPECT_TRUE(t.err.empty()) << "a report, not an error: " << t.describe();
  EXPECT_NE(t.out.find("overall INWARD"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("--flip"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("PROBLEMS FOUND, watertight"), std::string::npos) << t.out;

  const auto good = run_isocurv({"check", dataset("sphere"), "--json"});
  ASSERT_TRUE(good.ok()) << "a clean mesh exits 0: " << good.describe();
  EXPECT_EQ(parse_json(good.out, "check --json")["orientation"], "outward")
      << "the mesher's own output";
  EXPECT_FALSE(parse_json(good.out, "check --json")["problems_found"].get<bool>());

  // An open sheet with an inward tetrahedron beside it (a CT's skin cut by the box, and a cavity
  // inside): the cavity is no problem, the orientation is not judged.
  write_file(dir / "open.obj",
             "v -5 -5 0\nv 5 -5 0\nv 5 5 0\nv -5 5 0\n"
             "v 0 0 1\nv 1 0 1\nv 0 1 1\nv 0 0 2\n"
             "f 1 2 3\nf 1 3 4\nf 5 6 7\nf 5 8 6\nf 5 7 8\nf 6 8 7\n");
  const auto open = run_isocurv({"check", dir / "open.obj", "--json"});
  ASSERT_TRUE(open.ok()) << "a cavity beside an open surface: " << open.describe();
  const json oj = parse_json(open.out, "check --json");
  EXPECT_EQ(oj["inward_components"].get<int>(), 1) << oj.dump(2);
  EXPECT_EQ(oj["orientation"], "n/a");
  EXPECT_FALSE(oj["problems_found"].get<bool>());
}

TEST(MeshesFromElsewhere, CheckListsOffendingVerticesAndEdges) {
  TempDir dir("check_ids");
  // Triangles 1-3 share edge 1-2 (vertex ids from 0: 0-1), the first two traversing it the same
  // way; vertex 6 duplicates vertex 3.
  write_file(dir / "fan.obj",
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 5 5 5\nv 0 -1 0\n"
             "f 1 2 3\nf 1 2 4\nf 2 1 5\nf 6 7 5\n");
  const auto r = run_isocurv({"check", dir / "fan.obj", "--json"});
  ASSERT_EQ(r.exit_code, 1) << r.describe();
  const json j = parse_json(r.out, "check --json");
  EXPECT_EQ(j["non_manifold_edges"].get<int>(), 1);
  EXPECT_EQ(j["non_manifold_edge_ids"], json::parse("[[0, 1]]"));
  EXPECT_EQ(j["misoriented_edges"].get<int>(), 1)
      << "two same-direction uses on a non-manifold edge";
  EXPECT_EQ(j["misoriented_edge_ids"], json::parse("[[0, 1]]"));
  EXPECT_FALSE(j["consistently_oriented"].get<bool>());
  EXPECT_EQ(j["duplicate_vertex_ids"], json::parse("[[6, 3]]"));
  const auto t = run_isocurv({"check", dir / "fan.obj"});
  ASSERT_EQ(t.exit_code, 1) << t.describe();
  EXPECT_NE(t.out.find("duplicate vertices    1 (6=3)"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("non-manifold 1) (0-1)"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("INCONSISTENT (1 edges"), std::string::npos) << t.out;

  // Many offenders: the text lists the first five, the JSON all of them.
  const Mesh sphere = sphere_mesh(dir);
  io::write_mesh(dir / "u.ply", unwelded(sphere));
  const auto u = run_isocurv({"check", dir / "u.ply", "--json"});
  ASSERT_EQ(u.exit_code, 1) << u.describe();
  const json uj = parse_json(u.out, "check --json");
  EXPECT_EQ(uj["duplicate_vertex_ids"].size(),
            3 * sphere.triangles.size() - sphere.positions.size());
  const auto ut = run_isocurv({"check", dir / "u.ply"});
  EXPECT_NE(ut.out.find(", ...)"), std::string::npos) << ut.out;
}

TEST(MeshesFromElsewhere, CheckReportsTriangleQuality) {
  TempDir dir("check_quality");
  // A unit right triangle and a sliver of height 1e-4 on the same base: mean edge length ~1.
  write_file(dir / "sliver.obj",
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 0.5 0.0001 1\nf 1 2 3\nf 4 5 6\n");
  const auto r = run_isocurv({"check", dir / "sliver.obj", "--json"});
  ASSERT_TRUE(r.ok()) << "thin and small triangles are reported, not problems: " << r.describe();
  const json q = parse_json(r.out, "check --json")["triangle_quality"];
  ASSERT_TRUE(q.is_object()) << r.out;
  EXPECT_NEAR(q["min_area"].get<double>(), 5e-5, 1e-7);
  EXPECT_NEAR(q["min_angle_degrees"].get<double>(), 0.01146, 1e-4);
  EXPECT_EQ(q["thin_triangles"].get<int>(), 1);
  EXPECT_EQ(q["small_area_triangles"].get<int>(), 1)
      << "5e-5 is under 1e-4 mean-edge-length^2 (0.902^2)";
  EXPECT_NEAR(q["small_area_below"].get<double>(), 1e-4 * 0.9024 * 0.9024, 1e-7);
  EXPECT_EQ(q["area_unit"], "mean-edge-length^2");
  const auto t = run_isocurv({"check", dir / "sliver.obj"});
  EXPECT_NE(t.out.find("mean-edge-length^2"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("(1 triangles under 1 degree)"), std::string::npos) << t.out;

  // Volume input: the unit is the voxel's face area; the bundled sphere's mesh has no sliver.
  const auto v = run_isocurv({"check", dataset("sphere"), "--json"});
  ASSERT_TRUE(v.ok()) << v.describe();
  const json vq = parse_json(v.out, "check --json")["triangle_quality"];
  EXPECT_EQ(vq["area_unit"], "voxel^2");
  EXPECT_GT(vq["area_unit_value"].get<double>(), 0.0);
  EXPECT_GT(vq["min_area"].get<double>(), 0.0);
  EXPECT_GT(vq["min_angle_degrees"].get<double>(), 0.0);
}
