#include "labels/label_surfaces.h"

#include <algorithm>
#include <utility>

#include "core/error.h"
#include "curvature/auto_scale.h"

namespace isocurv::labels {

int scale_margin(const volume::Volume& map, const std::vector<double>& scales) {
  const openvdb::Vec3d s = map.spacing();
  const double smallest = std::min({s[0], s[1], s[2]});
  double sigma_voxels = curvature::kBinaryScaleVoxels;
  for (const double scale : scales)
    if (scale > 0) sigma_voxels = std::max(sigma_voxels, scale / smallest);
  return indicator_margin(sigma_voxels);
}

std::vector<std::int64_t> for_each_label_surface(
    const volume::Volume& map, const std::vector<Label>& picked, const LabelSurfaceSteps& steps,
    const std::function<void(LabelSurface& surface)>& visit) {
  if (!steps.extract) throw Error("for_each_label_surface: no extraction given");
  auto stage = [&](const char* name) {
    if (steps.stage) steps.stage(name);
  };
  std::vector<std::int64_t> empty;
  for (const Label& l : picked) {
    LabelSurface s;
    s.label = l;
    stage("labels");
    s.indicator = label_indicator(map, l, steps.margin);
    stage("extract");
    s.mesh = steps.extract(s.indicator, s.isovalue);
    stage("");
    if (s.mesh.triangles.empty()) {
      empty.push_back(l.value);
      continue;
    }
    if (steps.curvature) s.field = steps.curvature(s.mesh, s.indicator, s.isovalue);
    visit(s);
  }
  return empty;
}

LabelSurfaces label_surfaces(const volume::Volume& map, const std::vector<Label>& picked,
                             const LabelSurfaceSteps& steps) {
  LabelSurfaces out;
  out.empty = for_each_label_surface(map, picked, steps, [&](LabelSurface& s) {
    if (steps.stage) steps.stage("labels");
    append_label(out.merged, s.label.value, s.mesh, s.field ? &*s.field : nullptr);
    if (steps.stage) steps.stage("");
  });
  return out;
}

}  // namespace isocurv::labels
