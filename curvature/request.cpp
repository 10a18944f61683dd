#include "curvature/request.h"

#include <cmath>

#include "core/mesh_measures.h"
#include "curvature/face_average_normals.h"

namespace isocurv::curvature {

namespace {

struct NormalsNaming {
  NormalsSource source;
  const char* name;
};

constexpr NormalsNaming kNormalsNames[] = {{NormalsSource::volume, "volume"},
                                           {NormalsSource::mesh, "mesh"},
                                           {NormalsSource::area, "area"},
                                           {NormalsSource::face_average, "face-average"}};

}  // namespace

const char* normals_name(NormalsSource s) {
  for (const NormalsNaming& n : kNormalsNames)
    if (n.source == s) return n.name;
  return "";
}

std::optional<NormalsSource> normals_from_name(const std::string& name) {
  if (name.empty()) return NormalsSource::automatic;
  for (const NormalsNaming& n : kNormalsNames)
    if (name == n.name) return n.source;
  return std::nullopt;
}

std::vector<std::string> normals_names() {
  std::vector<std::string> names;
  for (const NormalsNaming& n : kNormalsNames) names.emplace_back(n.name);
  return names;
}

const char* request_field_name(RequestField f) {
  switch (f) {
    case RequestField::estimator: return "estimator";
    case RequestField::normals: return "normals";
    case RequestField::scale: return "scale";
    case RequestField::iso: return "iso";
    case RequestField::ao_scale: return "ao_scale";
    case RequestField::ao_method: return "ao_method";
    case RequestField::hattori_half: return "hattori_half";
  }
  return "";
}

Estimator default_estimator(const Request& request, bool has_volume) {
  if (request.estimator) return *request.estimator;
  return has_volume && request.normals == NormalsSource::automatic ? Estimator::volume
                                                                   : Estimator::rusinkiewicz;
}

Resolved resolve(const Request& request, bool has_volume, std::optional<float> mesh_isovalue) {
  Resolved r;
  r.estimator = default_estimator(request, has_volume);
  const std::string name = estimator_name(r.estimator);
  auto fail = [&](RequestField field, RequestProblem problem, const std::string& message) {
    return RequestError(field, problem, r.estimator, message);
  };
  const bool mesh_estimator = !needs_volume(r.estimator);
  if (!mesh_estimator && !has_volume)
    throw fail(RequestField::estimator, RequestProblem::estimator_needs_volume,
               "'" + name + "' needs a volume (it reads the volume's derivatives), not a mesh alone");
  if (!mesh_estimator && request.normals != NormalsSource::automatic)
    throw fail(RequestField::normals, RequestProblem::normals_not_for_volume,
               "applies to the mesh estimators; '" + name +
                   "' takes its normals from the volume's gradient at its scale");
  if (mesh_estimator && request.scale_given)
    throw fail(RequestField::scale, RequestProblem::scale_not_for_mesh,
               "applies to the volume estimator only");
  if (!std::isfinite(request.scale))
    throw fail(RequestField::scale, RequestProblem::not_finite, "must be a finite number");
  if (request.scale < 0)
    throw fail(RequestField::scale, RequestProblem::not_positive,
               "must not be negative (world units; 0: auto)");
  r.scale = mesh_estimator ? 0 : request.scale;
  if (mesh_estimator) {
    r.normals = request.normals != NormalsSource::automatic ? request.normals
                : has_volume                               ? NormalsSource::volume
                                                           : NormalsSource::mesh;
    if (r.normals == NormalsSource::volume && !has_volume)
      throw fail(RequestField::normals, RequestProblem::volume_normals_need_volume,
                 "'volume' needs a volume, not a mesh alone");
  }
  if (!mesh_estimator) {
    const std::optional<float> iso = request.iso ? request.iso : mesh_isovalue;
    if (!iso)
      throw fail(RequestField::iso, RequestProblem::needs_isovalue,
                 "'" + name + "' needs the mesh's isovalue");
    if (!std::isfinite(*iso))
      throw fail(RequestField::iso, RequestProblem::not_finite, "must be a finite number");
    r.isovalue = *iso;
  } else if (request.iso) {
    throw fail(RequestField::iso, RequestProblem::iso_not_for_mesh,
               "applies to the volume estimator only");
  }
  check_ao(request, has_volume);
  r.ao_scale = request.ao_scale;
  r.ao_method = request.ao_method.value_or(ao::Method::griffin);
  r.hattori_half = request.hattori_half;
  return r;
}

void check_ao(const Request& request, bool has_volume) {
  auto fail = [&](RequestField field, RequestProblem problem, const std::string& message) {
    return RequestError(field, problem, default_estimator(request, has_volume), message);
  };
  if (request.ao_scale) {
    if (!std::isfinite(*request.ao_scale))
      throw fail(RequestField::ao_scale, RequestProblem::not_finite,
                 "must be a finite number");
    if (!(*request.ao_scale > 0))
      throw fail(RequestField::ao_scale, RequestProblem::not_positive,
                 "must be a positive number (world units)");
  }
  const ao::Method method = request.ao_method.value_or(ao::Method::griffin);
  if (request.hattori_half && method != ao::Method::hattori)
    throw fail(RequestField::hattori_half, RequestProblem::hattori_half_not_hattori,
               "applies to the AO method hattori only");
  if (ao::needs_volume(method) && !has_volume)
    throw fail(RequestField::ao_method, RequestProblem::ao_needs_volume,
               std::string("'") + ao::method_name(method) +
                   "' needs a volume (it casts rays through it), not a mesh alone");
}

volume::MeshNormals host_normals(NormalsSource source, const Mesh& mesh,
                                 const volume::Volume* volume, bool caps) {
  volume::MeshNormals n;
  switch (source) {
    case NormalsSource::volume:
      if (!volume) throw Error("normals: 'volume' needs a volume, not a mesh alone");
      n = volume::gradient_normals_for_mesh(*volume, mesh, caps);
      break;
    case NormalsSource::area: n.normals = area_weighted_normals(mesh); break;
    case NormalsSource::face_average: n.normals = face_average_normals(mesh); break;
    case NormalsSource::automatic:
    case NormalsSource::mesh: break;
  }
  return n;
}

std::string normals_report_name(const Resolved& r) {
  return r.volume_estimator() ? "volume estimator" : normals_name(r.normals);
}

}  // namespace isocurv::curvature
