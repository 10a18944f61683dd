#include "curvature/estimator.h"

#include <cstdio>

#include "core/error.h"
#include "curvature/auto_scale.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "curvature/volume_estimate.h"

namespace isocurv::curvature {

const char* estimator_name(Estimator e) {
  switch (e) {
    case Estimator::rusinkiewicz:
      return "rusinkiewicz";
    case Estimator::volume:
      return "volume";
  }
  return "?";
}

std::optional<Estimator> estimator_from_name(const std::string& name) {
  for (Estimator e : {Estimator::rusinkiewicz, Estimator::volume})
    if (name == estimator_name(e)) return e;
  return std::nullopt;
}

std::vector<std::string> estimator_names() { return {"rusinkiewicz", "volume"}; }

std::vector<std::string> arrays_filled(Estimator e) {
  std::vector<std::string> all = {"Normals",    "Area", "k1",      "k2",    "dir1",
                                  "dir2",       "H",    "K",       "dcurv", "ShapeIndex",
                                  "Curvedness", "AO",   "Boundary"};
  if (e == Estimator::volume) all.push_back("Unreliable");
  return all;
}

bool needs_volume(Estimator e) { return e == Estimator::volume; }

CurvatureField estimate_field(const Mesh& mesh, const VolumeSource& source, Device* device,
                              const Options& options, EstimatorReport* report) {
  EstimatorReport r;
  r.estimator = estimator_name(options.estimator);
  CurvatureField field;
  switch (options.estimator) {
    case Estimator::rusinkiewicz:
      field = device ? estimate(mesh, *device, options) : estimate_reference(mesh, options);
      r.parameters.emplace_back("ao_scale", options.ao_scale);
      break;
    case Estimator::volume: {
      if (!source.volume)
        throw Error(
            "the volume estimator needs a volume (the one the mesh was extracted from), "
            "not a mesh file; use --estimator rusinkiewicz for meshes");
      double scale = options.scale;
      if (scale == 0) {
        const ScaleChoice c = auto_scale(*source.volume, mesh, source.isovalue);
        scale = c.scale;
        r.notes.emplace_back("scale", "auto");
        r.parameters.emplace_back("scale", scale);
        r.parameters.emplace_back("scale_voxels", scale / c.voxel);
        r.parameters.emplace_back("noise", c.noise);
        r.parameters.emplace_back("measured_noise", c.measured_noise);
        r.parameters.emplace_back("quantisation_noise", c.quantisation);
        r.parameters.emplace_back("edge_step", c.edge_step);
        r.parameters.emplace_back("noise_level", c.noise_level);
      } else {
        r.notes.emplace_back("scale", "given");
        r.parameters.emplace_back("scale", scale);
      }
      r.parameters.emplace_back("ao_scale", options.ao_scale);
      VolumeEstimateStats st;
      field = device ? volume_estimate(mesh, *source.volume, source.isovalue, scale,
                                       options.ao_scale, *device, &st)
                     : volume_estimate_reference(mesh, *source.volume, source.isovalue, scale,
                                                 options.ao_scale, &st);
      r.unreliable = st.unreliable;
      break;
    }
  }
  field.metadata.emplace_back("estimator", r.estimator);
  for (const auto& [key, value] : r.parameters) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", value);
    field.metadata.emplace_back(key, text);
  }
  for (const auto& [key, how] : r.notes) field.metadata.emplace_back(key + "_chosen", how);
  if (report) *report = std::move(r);
  return field;
}

}  // namespace isocurv::curvature
