// The estimator on marching-cubes meshes of analytic fields: kernels against the reference, and
// both normal sources against the exact curvature, beside vtkCurvatures on the same meshes.
#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCurvatures.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <map>
#include <string>

#include "compare.h"
#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "mc/extract.h"
#include "test_meshes.h"
#include "volume/gradient_normals.h"

namespace isocurv::test {
namespace {

struct McCase {
  std::unique_ptr<datasets::Field> field;
  volume::Volume volume;
  Mesh mesh;
};

McCase mc_case(const std::string& name, int resolution) {
  openvdb::initialize();
  McCase c;
  c.field = datasets::make_field(name);
  c.volume = datasets::sample(*c.field, resolution);
  mc::Options mo; mo.snap = std::getenv("SNAPV") ? std::atof(std::getenv("SNAPV")) : mc::kDefaultSnap;
  c.mesh = mc::extract(c.volume, float(c.field->isovalue()), Device::default_device(), mo);
  return c;
}

// Relative RMS errors of H and K against the exact curvature at each vertex's projection onto
// the surface, over the vertices away from open boundaries (and their neighbours).
struct OracleError {
  double H = 0, K = 0;
  std::size_t vertices = 0;
};

std::vector<bool> interior(const Mesh& m, const std::vector<std::uint8_t>& boundary) {
  std::vector<bool> keep(m.vertex_count(), true);
  for (const Tri& t : m.triangles)
    if (boundary[t[0]] || boundary[t[1]] || boundary[t[2]])
      keep[t[0]] = keep[t[1]] = keep[t[2]] = false;
  return keep;
}

struct Exact {
  std::vector<double> H, K;
};

Exact exact_at_vertices(const datasets::Field& field, const Mesh& m) {
  Exact e;
  for (const Vec3f& p : m.positions) {
    const Eigen::Vector3d q = datasets::project_to_surface(field, Eigen::Vector3d(p[0], p[1], p[2]));
    const datasets::SurfaceCurvature c = datasets::exact_curvature(field, q);
    e.H.push_back(c.H), e.K.push_back(c.K);
  }
  return e;
}

OracleError oracle_error(const std::vector<float>& H, const std::vector<float>& K, const Exact& e,
                         const std::vector<bool>& keep) {
  std::vector<double> h, k, eh, ek;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) h.push_back(H[i]), k.push_back(K[i]), eh.push_back(e.H[i]), ek.push_back(e.K[i]);
  return {relative_rms(h, eh), relative_rms(k, ek), h.size()};
}

// vtkCurvatures' mean and Gaussian curvature of the same mesh (same sign conventions).
std::pair<std::vector<float>, std::vector<float>> vtk_curvatures_float(const Mesh& m) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  for (const Vec3f& p : m.positions) points->InsertNextPoint(p[0], p[1], p[2]);
  vtkNew<vtkCellArray> polys;
  for (const Tri& t : m.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    polys->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(polys);
  std::vector<float> H(m.vertex_count()), K(m.vertex_count());
  for (int type : {VTK_CURVATURE_MEAN, VTK_CURVATURE_GAUSS}) {
    vtkNew<vtkCurvatures> c;
    c->SetInputData(poly);
    c->SetCurvatureType(type);
    c->Update();
    vtkDataArray* a = c->GetOutput()->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
      (type == VTK_CURVATURE_MEAN ? H : K)[i] = float(a->GetTuple1(i));
  }
  return {H, K};
}

std::vector<Vec3f> gradient_normals(const McCase& c) {
  return volume::gradient_normals(c.volume, c.mesh.positions);
}

TEST(MarchingCubes, KernelsMatchReference) {
  for (const char* name : {"sphere", "torus", "gyroid"}) {
    const McCase c = mc_case(name, 64);
    for (bool given : {false, true}) {
      const std::vector<Vec3f> normals = given ? gradient_normals(c) : std::vector<Vec3f>{};
      curvature::Options o;
      if (given) o.vertex_normals = &normals;
      const curvature::CurvatureField ref = curvature::estimate_reference(c.mesh, o);
      const curvature::CurvatureField cl = curvature::estimate(c.mesh, Device::default_device(), o);
      double scale = 0;
      for (float x : ref.curvedness) scale = std::max(scale, double(x));
      const FieldDifference d = compare(cl, ref, 0.05 * scale);
      std::printf("  %s 64^3, %s normals, %zu vertices: %s\n", name, given ? "volume" : "mesh",
                  c.mesh.vertex_count(), d.str().c_str());
      EXPECT_LT(d.k1, 1e-5);
      EXPECT_LT(d.k2, 1e-5);
      EXPECT_LT(d.H, 1e-5);
      EXPECT_LT(d.K, 1e-5);
      EXPECT_LT(d.dir_angle, 1e-3);
      EXPECT_TRUE(d.same_boundary);
      EXPECT_TRUE(all_finite(cl));
    }
  }
}

// Against the exact curvature: errors shrink as the resolution doubles, and the volume-gradient
// normals beat both the mesh normals and vtkCurvatures on the same mesh.
TEST(MarchingCubes, ConvergesToExactCurvature) {
  for (const char* name : {"sphere", "torus", "ellipsoid", "f1", "f2"}) {
    OracleError first_given, last_given;
    for (int res : {32, 64, 128}) {
      const McCase c = mc_case(name, res);
      const std::vector<Vec3f> normals = gradient_normals(c);
      curvature::Options given;
      given.vertex_normals = &normals;
      Device& d = Device::default_device();
      const curvature::CurvatureField mesh_n = curvature::estimate(c.mesh, d);
      const curvature::CurvatureField vol_n = curvature::estimate(c.mesh, d, given);
      curvature::Options area_w;
      area_w.normal_weights = curvature::NormalWeights::area;
      const curvature::CurvatureField area_n = curvature::estimate(c.mesh, d, area_w);
      const auto [vtk_H, vtk_K] = vtk_curvatures_float(c.mesh);
      const Exact exact = exact_at_vertices(*c.field, c.mesh);
      const std::vector<bool> keep = interior(c.mesh, mesh_n.boundary);
      const OracleError em = oracle_error(mesh_n.H, mesh_n.K, exact, keep);
      const OracleError eg = oracle_error(vol_n.H, vol_n.K, exact, keep);
      const OracleError ea = oracle_error(area_n.H, area_n.K, exact, keep);
      const OracleError ev = oracle_error(vtk_H, vtk_K, exact, keep);
      std::printf("  %-9s %3d^3 %6zu vertices, relative RMS H / K: volume normals %.4f / %.4f, "
                  "mesh normals (Max) %.4f / %.4f, (area) %.4f / %.4f, vtkCurvatures %.4f / %.4f\n",
                  name, res, eg.vertices, eg.H, eg.K, em.H, em.K, ea.H, ea.K, ev.H, ev.K);
      EXPECT_LT(eg.H, ev.H) << name << " " << res;
      EXPECT_LT(eg.K, ev.K) << name << " " << res;
      if (res == 32) first_given = eg;
      last_given = eg;
    }
    EXPECT_LT(last_given.H, 0.5 * first_given.H) << name;
    EXPECT_LT(last_given.K, 0.5 * first_given.K) << name;
  }
}

}  // namespace
}  // namespace isocurv::test
