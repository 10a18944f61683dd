#include "screen/pull_back.h"

#include <cmath>

#include "core/error.h"
#include "core/framing_points.h"
#include "screen/rasterise.h"

namespace isocurv::screen {
namespace {

/// The camera of `fit` moved back along its view to `factor` times its distance.
Camera pulled_back(const Camera& fit, double factor) {
  Camera c = fit;
  for (int k = 0; k < 3; ++k)
    c.position[k] = fit.focal_point[k] + factor * (fit.position[k] - fit.focal_point[k]);
  return c;
}

PullBackError compare(const ScreenCurvature& c, const std::vector<float>& H,
                      const std::vector<float>& K, bool with_k) {
  PullBackError e;
  double ref_h = 0, ref_k = 0;
  for (std::size_t i = 0; i < c.valid.size(); ++i) {
    if (!c.valid[i] || !std::isfinite(H[i])) continue;
    const double dh = double(c.H[i]) - H[i], dk = with_k ? double(c.K[i]) - K[i] : 0.0;
    e.mse_H += dh * dh, e.mse_K += dk * dk;
    ref_h += double(H[i]) * H[i], ref_k += double(K[i]) * K[i];
    ++e.pixels;
  }
  if (e.pixels == 0) return e;
  e.mse_H /= e.pixels, e.mse_K /= e.pixels;
  e.rel_H = ref_h > 0 ? e.mse_H * e.pixels / ref_h : 0;
  e.rel_K = ref_k > 0 && with_k ? e.mse_K * e.pixels / ref_k : 0;
  return e;
}

}  // namespace

std::vector<PullBackStep> pull_back(const Mesh& mesh, const curvature::CurvatureField& object,
                                    const std::vector<ScreenOptions>& estimators, Device* device,
                                    const PullBackOptions& o) {
  const std::size_t nv = mesh.positions.size();
  if (mesh.triangles.empty()) throw Error("pull_back: the mesh has no triangles");
  if (object.H.size() != nv || object.K.size() != nv || object.normals.size() != nv)
    throw Error("pull_back: the curvature field (H, K, normals) does not match the mesh");
  if (o.steps < 1 || !(o.distance_step >= 0))
    throw Error("pull_back: needs at least one step and a distance step >= 0");
  const Camera fit = fit_camera_to_points(framing_points(mesh), o.view, double(o.width) / o.height);
  std::vector<PullBackStep> steps;
  for (int k = 0; k < o.steps; ++k) {
    PullBackStep step;
    step.distance = 1 + k * o.distance_step;
    const ViewFrame frame = view_frame(pulled_back(fit, step.distance), o.width, o.height);
    RasterHits hits;
    const GBuffer g = rasterise(mesh, object.normals, frame, &hits);
    step.coverage = double(g.valid_count()) / double(g.pixels());
    const std::vector<float> H = interpolate(mesh, hits, object.H),
                             K = interpolate(mesh, hits, object.K);
    for (const ScreenOptions& so : estimators) {
      const ScreenCurvature c = device ? estimate(g, *device, so) : estimate_reference(g, so);
      step.errors.push_back(compare(c, H, K, so.estimator == ScreenEstimator::prantl));
    }
    steps.push_back(std::move(step));
  }
  return steps;
}

}  // namespace isocurv::screen
