// curvature::Topology: per-frame estimates on a prepared topology are bit-identical to cold ones.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "curvature/estimator.h"
#include "curvature/mesh_estimators.h"
#include "curvature/topology.h"
#include "deform/affine.h"
#include "deform/noise_displace.h"
#include "tests/deform/deform_fixtures.h"

namespace isocurv {
namespace {

using curvature::Estimator;
using curvature::MeshEstimator;

MeshEstimator mesh_estimator(Estimator e) {
  switch (e) {
    case Estimator::batagelo:
      return MeshEstimator::batagelo;
    case Estimator::prantl3:
      return MeshEstimator::prantl3;
    case Estimator::prantl2:
      return MeshEstimator::prantl2;
    default:
      return MeshEstimator::rusinkiewicz;
  }
}

// Three different frames of `rest`: itself, a noise displacement and an anisotropic scaling.
std::vector<Positions> frames_of(const Mesh& rest) {
  std::vector<Vec3f> up(rest.vertex_count(), Vec3f{0, 0, 1});
  return {rest.positions, deform::noise_displace_reference(rest.positions, up, 2.0, 0.05),
          deform::affine_reference(rest.positions, deform::scaling(1.3, 0.8, 0.6))};
}

void expect_prepared_matches_cold(const Mesh& rest, Estimator e, bool given_normals,
                                  const std::string& what) {
  Device& dev = test::device();
  curvature::Topology topo = curvature::prepare(rest.triangles, rest.vertex_count(), dev);
  curvature::CurvatureField prepared;  // reused across frames, as a sequence would
  int frame = 0;
  for (const Positions& p : frames_of(rest)) {
    SCOPED_TRACE(what + " frame " + std::to_string(frame++));
    Mesh m;
    m.positions = p;
    m.triangles = rest.triangles;
    std::vector<Vec3f> normals;
    curvature::Options o;
    if (given_normals) {
      for (const Vec3f& q : p) normals.push_back({q[0], 0.5f * q[1], 2 * q[2]});
      normals[0] = {0, 0, 0};  // a zero entry falls back to the mesh normal
      o.vertex_normals = &normals;
    }
    const curvature::CurvatureField cold = curvature::estimate_mesh(mesh_estimator(e), m, &dev, o);
    ASSERT_FALSE(cold.k1.empty());
    if (e == Estimator::rusinkiewicz) {
      curvature::estimate(p, topo, dev, o, prepared);
      EXPECT_TRUE(test::bit_identical(cold, prepared)) << "estimate(positions, topology)";
    }
    curvature::upload_positions(p, topo);
    curvature::Timings t;
    curvature::estimate_resident(e, topo, dev, o, prepared, &t);
    EXPECT_TRUE(test::bit_identical(cold, prepared)) << "estimate_resident";
    EXPECT_EQ(t.adjacency, 0.0);
  }
}

class PreparedTopology : public ::testing::TestWithParam<Estimator> {};

TEST_P(PreparedTopology, BitIdenticalToColdOnEveryFrame) {
  const Estimator e = GetParam();
  expect_prepared_matches_cold(test::lumpy_sphere(3), e, false, "lumpy sphere");
  expect_prepared_matches_cold(test::lumpy_sphere(3), e, true, "lumpy sphere, given normals");
  expect_prepared_matches_cold(test::cone_fan(13), e, false, "large open fan");
  expect_prepared_matches_cold(test::quadric_patch(17, 1.0f, 0.8f, -0.3f), e, false, "patch");
  expect_prepared_matches_cold(test::torus(0.6, 0.25, 40, 24, 0.2).mesh, e, false, "torus");
}

INSTANTIATE_TEST_SUITE_P(Estimators, PreparedTopology,
                         ::testing::Values(Estimator::rusinkiewicz, Estimator::batagelo,
                                           Estimator::prantl3, Estimator::prantl2),
                         [](const auto& info) {
                           switch (info.param) {
                             case Estimator::batagelo:
                               return std::string("batagelo");
                             case Estimator::prantl3:
                               return std::string("prantl3");
                             case Estimator::prantl2:
                               return std::string("prantl2");
                             default:
                               return std::string("rusinkiewicz");
                           }
                         });

TEST(PreparedTopology, AlternatingTopologiesStayIndependent) {
  // Two prepared meshes on one device, interleaved with cold calls that reuse the session's
  // buffers: each still gives its own cold result.
  Device& dev = test::device();
  const Mesh a = test::lumpy_sphere(2), b = test::torus(0.6, 0.25, 30, 20).mesh;
  curvature::Topology ta = curvature::prepare(a.triangles, a.vertex_count(), dev);
  curvature::Topology tb = curvature::prepare(b.triangles, b.vertex_count(), dev);
  curvature::CurvatureField fa, fb;
  curvature::estimate(a.positions, ta, dev, {}, fa);
  const curvature::CurvatureField cold_b = curvature::estimate(b, dev);
  curvature::estimate(b.positions, tb, dev, {}, fb);
  EXPECT_TRUE(test::bit_identical(fb, cold_b));
  const curvature::CurvatureField cold_a = curvature::estimate(a, dev);
  curvature::estimate_resident(ta, dev, {}, fa);  // positions still on the device
  EXPECT_TRUE(test::bit_identical(fa, cold_a));
}

TEST(PreparedTopology, BadInputIsAnError) {
  Device& dev = test::device();
  const Mesh m = test::icosphere(1);
  Triangles bad = m.triangles;
  bad[3][1] = 999;
  EXPECT_THROW(curvature::prepare(bad, m.vertex_count(), dev), Error);
  curvature::Topology topo = curvature::prepare(m.triangles, m.vertex_count(), dev);
  curvature::CurvatureField out;
  Positions few(m.positions.begin(), m.positions.end() - 1);
  EXPECT_THROW(curvature::estimate(few, topo, dev, {}, out), Error);
  Positions nan = m.positions;
  nan[5][2] = std::nanf("");
  EXPECT_THROW(curvature::estimate(nan, topo, dev, {}, out), Error);
  std::vector<Vec3f> normals(3);
  curvature::Options o;
  o.vertex_normals = &normals;
  EXPECT_THROW(curvature::estimate(m.positions, topo, dev, o, out), Error);
  EXPECT_THROW(curvature::estimate_resident(Estimator::quadric, topo, dev, {}, out), Error);
}

// The prepared path is exactly the mesh estimators with kernels; every other estimator is refused
// in one line that names it and those that have the path (isocurv deform and the Python Topology
// repeat it).
TEST(PreparedTopology, EveryEstimatorWithoutThePathIsRefusedByName) {
  Device& dev = test::device();
  const Mesh m = test::icosphere(1);
  curvature::Topology topo = curvature::prepare(m.triangles, m.vertex_count(), dev);
  curvature::upload_positions(m.positions, topo);
  const std::vector<Estimator> all = {Estimator::rusinkiewicz, Estimator::volume,
                                      Estimator::batagelo,     Estimator::prantl3,
                                      Estimator::prantl2,      Estimator::quadric,
                                      Estimator::cubic,        Estimator::sampling,
                                      Estimator::meyer};
  ASSERT_EQ(all.size(), curvature::estimator_names().size());
  for (Estimator e : all) {
    const std::string name = curvature::estimator_name(e);
    SCOPED_TRACE(name);
    const std::optional<MeshEstimator> me = curvature::mesh_estimator_from_name(name);
    EXPECT_EQ(curvature::has_prepared_path(e), me && curvature::mesh_estimator_info(*me).kernels);
    curvature::CurvatureField out;
    if (curvature::has_prepared_path(e)) {
      EXPECT_TRUE(curvature::no_prepared_path_reason(e).empty());
      curvature::estimate_resident(e, topo, dev, {}, out);
      EXPECT_EQ(out.H.size(), m.vertex_count());
      continue;
    }
    const std::string reason = curvature::no_prepared_path_reason(e);
    EXPECT_EQ(reason.rfind(name + " ", 0), 0u) << reason;
    EXPECT_EQ(reason.find('\n'), std::string::npos) << reason;
    try {
      curvature::estimate_resident(e, topo, dev, {}, out);
      ADD_FAILURE() << "estimate_resident ran " << name;
    } catch (const Error& err) {
      const std::string what = err.what();
      EXPECT_NE(what.find(reason), std::string::npos) << what;
      EXPECT_NE(what.find("rusinkiewicz, batagelo, prantl3 and prantl2"), std::string::npos)
          << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(PreparedTopology, EmptyMeshGivesEmptyField) {
  Device& dev = test::device();
  curvature::Topology topo = curvature::prepare({}, 0, dev);
  curvature::CurvatureField out;
  curvature::estimate(Positions{}, topo, dev, {}, out);
  EXPECT_TRUE(out.k1.empty());
}

}  // namespace
}  // namespace isocurv
