// Batagelo & Wu's Fig. 2 and Fig. 3 protocols for every mesh estimator, beside the project's
// Rusinkiewicz estimator with the same normals (SEEDS-SPEC 3.2 (b)-(c), 3.4, Appendix A1-A2).
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <map>
#include <string>

#include "curvature/batagelo.h"
#include "curvature/cubic_fit.h"
#include "curvature/face_average_normals.h"
#include "curvature/normal_sampling.h"
#include "curvature/prantl.h"
#include "curvature/quadric_fit.h"
#include "curvature/reference.h"
#include "estimator_protocols.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;
using Fn = std::function<CurvatureField(const Mesh&, const curvature::Options&)>;

const std::vector<std::pair<std::string, Fn>>& estimators() {
  static const std::vector<std::pair<std::string, Fn>> e = {
      {"rusinkiewicz", [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_reference(m, o);
       }},
      {"batagelo", curvature::estimate_batagelo_reference},
      {"batagelo_w", [](const Mesh& m, const curvature::Options& o) {  // 1/|x|^2 weights
         curvature::Options w = o;
         w.batagelo_weights = curvature::NeighbourWeights::inverse_square;
         return curvature::estimate_batagelo_reference(m, w);
       }},
      {"quadric", curvature::estimate_quadric_fit_reference},
      {"cubic", curvature::estimate_cubic_fit_reference},
      {"sampling", curvature::estimate_normal_sampling_reference},
      {"prantl3", [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_prantl_reference(m, o, 3);
       }},
      {"prantl2", [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_prantl_reference(m, o, 2);
       }}};
  return e;
}

std::map<std::string, double> rms_K_all(const Torus& t, const std::vector<Vec3f>& normals) {
  curvature::Options o;
  o.vertex_normals = &normals;
  std::map<std::string, double> out;
  for (const auto& [name, fn] : estimators()) out[name] = torus_rms_K(fn(t.mesh, o), t);
  return out;
}

void print_row(const char* label, double x, const std::map<std::string, double>& e,
               const double* appendix) {
  std::printf("  %s %.3f:", label, x);
  int k = 0;
  for (const char* n : {"rusinkiewicz", "batagelo", "quadric", "cubic", "sampling", "prantl3",
                        "prantl2"})
    std::printf(" %s %.4f (%.4f)", n, e.at(n), appendix[k++]);
  std::printf("\n");
}

// Fig. 2: irregular sampling (jittered grid parameters), normals = normalised sum of unit face
// normals. Appendix A1 in brackets.
TEST(EstimatorProtocols, BatageloFig2Jitter) {
  const double jitters[] = {0, 0.1, 0.2, 0.3, 0.4};
  const double a1[5][7] = {{0.0418, 0.0676, 0.0516, 0.0767, 0.0029, 0.0426, 0.0634},
                           {0.0964, 0.1190, 0.1479, 0.1263, 0.1041, 0.0959, 0.1050},
                           {0.1969, 0.2286, 0.4185, 0.3262, 0.3806, 0.1892, 0.1903},
                           {0.3374, 0.3792, 0.7456, 0.8231, 0.9166, 0.3126, 0.3103},
                           {0.6774, 0.7882, 1.5909, 3.3996, 2.8170, 0.7189, 0.6801}};
  for (int k = 0; k < 5; ++k) {
    const Torus t = torus(1, 0.4, 60, 24, jitters[k]);
    const std::vector<Vec3f> n = curvature::face_average_normals(t.mesh);
    const std::map<std::string, double> e = rms_K_all(t, n);
    print_row("jitter", jitters[k], e, a1[k]);
    std::printf("    batagelo with 1/|x|^2 weights %.4f (uniform %.4f)\n", e.at("batagelo_w"), e.at("batagelo"));
    // Measured: near neighbours weighted up lower the one-pass error up to jitter 0.3 (to half of
    // it on the regular grid, below Rusinkiewicz's); at 0.4 both are alike.
    if (k <= 3) {
      EXPECT_LT(e.at("batagelo_w"), e.at("batagelo"));
    }
    EXPECT_LT(e.at("batagelo_w"), 1.1 * e.at("batagelo"));
    // Acceptance (b): one-pass within 1.7x (regular) and 1.3x (jittered) of Rusinkiewicz.
    EXPECT_LT(e.at("batagelo"), (k == 0 ? 1.7 : 1.3) * e.at("rusinkiewicz"));
    if (k == 0) {  // best without jitter
      EXPECT_LT(e.at("sampling"), e.at("rusinkiewicz") / 5);
    }
    if (k == 4) {  // the fits degrade fastest
      EXPECT_GT(e.at("quadric"), 1.5 * e.at("batagelo"));
      EXPECT_GT(e.at("cubic"), 1.5 * e.at("batagelo"));
    }
  }
}

// Fig. 3: positions displaced along the exact normal, exact normals kept. Appendix A2 in
// brackets.
TEST(EstimatorProtocols, BatageloFig3Displacement) {
  const double ds[] = {0, 0.005, 0.01, 0.02, 0.04};
  const double a2[5][7] = {{0.0387, 0.0644, 0.0643, 0.0800, 0.0064, 0.0396, 0.0621},
                           {0.0402, 0.0645, 0.8975, 0.0800, 0.8841, 0.0412, 0.0631},
                           {0.0448, 0.0647, 1.8068, 0.0803, 1.7771, 0.0459, 0.0663},
                           {0.0641, 0.0656, 3.7356, 0.0813, 3.6211, 0.0652, 0.0805},
                           {0.1391, 0.0691, 8.3986, 0.0856, 7.6757, 0.1389, 0.1461}};
  for (int k = 0; k < 5; ++k) {
    const Torus t = displaced_torus(1, 0.4, 60, 24, ds[k]);
    const std::vector<Vec3f> n = exact_normals(t);
    const std::map<std::string, double> e = rms_K_all(t, n);
    print_row("d", ds[k], e, a2[k]);
    std::printf("    batagelo with 1/|x|^2 weights %.4f (uniform %.4f)\n", e.at("batagelo_w"), e.at("batagelo"));
    EXPECT_LT(e.at("batagelo_w"), 0.7 * e.at("batagelo"));  // measured: 0.47-0.61 of it
    if (ds[k] == 0.005) {  // the position-only methods fail grossly; the cubic fit does not
      EXPECT_GT(e.at("quadric"), 10 * e.at("rusinkiewicz"));
      EXPECT_GT(e.at("sampling"), 10 * e.at("rusinkiewicz"));
      EXPECT_LT(e.at("cubic"), 1.5 * e.at("batagelo"));
    }
    if (ds[k] == 0.04) {  // acceptance (c)
      EXPECT_LT(e.at("batagelo"), 0.6 * e.at("rusinkiewicz"));
    }
  }
}

}  // namespace
}  // namespace isocurv::test
