#include "curvature/estimator.h"

#include <cstdio>
#include <string>

#include "ao/ao.h"
#include "core/error.h"
#include "core/lap.h"
#include "core/surface_piece.h"
#include "curvature/auto_scale.h"
#include "curvature/field_stats.h"
#include "curvature/estimate.h"
#include "curvature/mesh_estimators.h"
#include "curvature/reference.h"
#include "curvature/volume_estimate.h"

namespace isocurv::curvature {

namespace {

constexpr Estimator kAll[] = {Estimator::rusinkiewicz, Estimator::volume,  Estimator::batagelo,
                              Estimator::prantl3,      Estimator::prantl2, Estimator::quadric,
                              Estimator::cubic,        Estimator::sampling, Estimator::meyer};

/// The mesh_estimators.h entry of a mesh estimator other than Rusinkiewicz's.
std::optional<MeshEstimator> as_mesh_estimator(Estimator e) {
  switch (e) {
    case Estimator::batagelo: return MeshEstimator::batagelo;
    case Estimator::prantl3: return MeshEstimator::prantl3;
    case Estimator::prantl2: return MeshEstimator::prantl2;
    case Estimator::quadric: return MeshEstimator::quadric;
    case Estimator::cubic: return MeshEstimator::cubic;
    case Estimator::sampling: return MeshEstimator::sampling;
    case Estimator::meyer: return MeshEstimator::meyer;
    default: return std::nullopt;
  }
}

}  // namespace

const char* estimator_name(Estimator e) {
  if (e == Estimator::rusinkiewicz) return "rusinkiewicz";
  if (e == Estimator::volume) return "volume";
  if (const auto m = as_mesh_estimator(e)) return mesh_estimator_info(*m).name;
  return "?";
}

std::optional<Estimator> estimator_from_name(const std::string& name) {
  for (Estimator e : kAll)
    if (name == estimator_name(e)) return e;
  return std::nullopt;
}

std::vector<std::string> estimator_names() {
  std::vector<std::string> names;
  for (Estimator e : kAll) names.push_back(estimator_name(e));
  return names;
}

std::vector<std::string> arrays_filled(Estimator e) {
  std::vector<std::string> all = {"Normals",    "Area", "k1",      "k2",    "dir1",
                                  "dir2",       "H",    "K",       "dcurv", "ShapeIndex",
                                  "Curvedness", "AO",   "Boundary"};
  if (e == Estimator::volume) all.push_back("Unreliable");
  if (const auto m = as_mesh_estimator(e)) {
    const MeshEstimatorInfo& info = mesh_estimator_info(*m);
    std::vector<std::string> some;
    for (const std::string& a : all) {
      if (!info.directions && (a == "dir1" || a == "dir2")) continue;
      if (!info.derivative && a == "dcurv") continue;
      some.push_back(a);
    }
    some.push_back("Unreliable");
    return some;
  }
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
    case Estimator::batagelo:
    case Estimator::prantl3:
    case Estimator::prantl2:
    case Estimator::quadric:
    case Estimator::cubic:
    case Estimator::sampling:
    case Estimator::meyer: {
      const MeshEstimator m = *as_mesh_estimator(options.estimator);
      field = estimate_mesh(m, mesh, device, options);
      r.parameters.emplace_back("ao_scale", options.ao_scale);
      if (options.estimator == Estimator::batagelo)
        r.notes.emplace_back("neighbour_weights", options.batagelo_weights == NeighbourWeights::uniform
                                                      ? "uniform"
                                                      : "inverse-square");
      for (std::uint8_t u : field.unreliable) r.unreliable += u;
      break;
    }
    case Estimator::volume: {
      if (!source.volume)
        throw Error(
            "the volume estimator needs a volume (the one the mesh was extracted from), "
            "not a mesh file; use --estimator rusinkiewicz for meshes");
      VolumeOptions vo;
      vo.sigma = options.scale;
      vo.ao_scale = options.ao_scale;
      vo.finer_scales = options.finer_scales;
      vo.piece = options.piece;
      double auto_ms = -1;
      if (vo.sigma == 0) {
        StepClock::time_point t = StepClock::now();
        const ScaleChoice c = auto_scale(*source.volume, mesh, source.isovalue, options.piece);
        auto_ms = lap(t);
        vo.sigma = c.scale;
        vo.adaptive = c.model;
        r.notes.emplace_back("scale", c.binary ? "auto (binary volume)" : "auto");
        // The first pilot scale; each vertex's own is the Scale array (adaptive_scale.h).
        r.parameters.emplace_back("scale", c.scale);
        r.parameters.emplace_back("scale_voxels", c.scale / c.voxel);
        r.parameters.emplace_back("noise", c.noise);
        r.parameters.emplace_back("measured_noise", c.measured_noise);
        r.parameters.emplace_back("quantisation_noise", c.quantisation);
        r.parameters.emplace_back("edge_step", c.edge_step);
        r.parameters.emplace_back("noise_level", c.noise_level);
      } else {
        r.notes.emplace_back("scale", "given");
        r.parameters.emplace_back("scale", vo.sigma);
      }
      r.parameters.emplace_back("ao_scale", options.ao_scale);
      vo.point = resolved_point(options.volume_point, *source.volume);
      r.notes.emplace_back("point", vo.point == VolumePoint::surface ? "surface" : "vertex");
      VolumeEstimateStats st;
      field = device ? volume_estimate(mesh, *source.volume, source.isovalue, vo, *device, &st)
                     : volume_estimate_reference(mesh, *source.volume, source.isovalue, vo, &st);
      if (vo.adaptive) {
        r.parameters.emplace_back("edge_blur", st.blur);
        // The range of the per-vertex scales (the Scale array's 5th and 95th percentiles over the
        // whole surface): what titles quote, the pilot above being no vertex's scale in general.
        // Collective with a piece: an empty piece has no Scale array but takes part all the same.
        std::vector<float> mine;
        if (const std::vector<float>* scale = field.find_extra("Scale"))
          for (std::size_t i = 0; i < scale->size(); ++i)
            if ((*scale)[i] > 0 && owns_vertex(options.piece, i)) mine.push_back((*scale)[i]);
        const std::uint64_t n = total_count(options.piece, mine.size());
        if (n > 0)
          for (const auto& [name, q] : {std::pair{"scale_p5", 0.05}, std::pair{"scale_p95", 0.95}})
            r.parameters.emplace_back(
                name, kth_smallest_positive(options.piece, mine, std::uint64_t(q * double(n - 1))));
      }
      r.pyramid_bricks_kept = st.pyramid_kept;
      r.unreliable = st.unreliable;
      r.finer_scale = st.finer_scale;
      r.outside = st.outside;
      if (device) {
        if (auto_ms >= 0) r.steps_ms.emplace_back("auto_scale", auto_ms);
        r.steps_ms.insert(r.steps_ms.end(), {{"plan", st.steps.plan},
                                             {"gather", st.steps.gather},
                                             {"passes", st.steps.smooth},
                                             {"vertices", st.steps.vertices},
                                             {"host", st.steps.finish}});
      }
      break;
    }
  }
  // One rule for what is unmeasured, in the mesh and the statistics (field_stats.h).
  r.implausible = flag_implausible(mesh, field, options.piece);
  r.unreliable += r.implausible;
  field.metadata.emplace_back("estimator", r.estimator);
  for (const auto& [key, value] : r.parameters) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", value);
    field.metadata.emplace_back(key, text);
  }
  for (const auto& [key, how] : r.notes) field.metadata.emplace_back(key + "_chosen", how);
  field.metadata.emplace_back("ao", "griffin");  // the AO every estimator gives (ao/ao.h: others)
  StepClock::time_point ao_start = StepClock::now();
  if (apply_ao(mesh, field, source, options)) r.ao_ms = lap(ao_start);
  if (report) *report = std::move(r);
  return field;
}

bool apply_ao(const Mesh& mesh, CurvatureField& field, const VolumeSource& source,
              const Options& options) {
  if (options.ao_method == ao::Method::griffin) return false;
  ao::Options ao;
  ao.method = options.ao_method;
  ao.radius = options.ao_scale;
  ao.hattori_half = options.hattori_half;
  ao::compute(mesh, field, source, ao);
  return true;
}

}  // namespace isocurv::curvature
