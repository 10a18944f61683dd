#pragma once
// What a curvature request may ask, decided once for the command line (app/pipeline.cpp) and the
// Python module (python/detail/estimate.cpp): the default estimator, the combinations that are
// errors, the vertex normals the mesh estimators use and the ambient occlusion asked for. The
// callers convert their own arguments into a Request and word a RequestError in their own terms
// ("--normals ...", "normals: ...").
// Tested in tests/curvature/request_test.cpp.
#include <optional>
#include <string>
#include <vector>

#include "ao/method.h"
#include "core/error.h"
#include "core/mesh.h"
#include "curvature/estimator.h"
#include "curvature/options.h"
#include "volume/gradient_normals.h"
#include "volume/volume.h"

namespace isocurv::curvature {

/// Where the mesh estimators' vertex normals come from (the CLI's --normals, Python's normals=).
enum class NormalsSource {
  automatic,     ///< not asked: volume with a volume, else mesh
  volume,        ///< the volume's gradient (volume::gradient_normals_for_mesh)
  mesh,          ///< the faces with Max's weights, the estimator's own
  area,          ///< face normals weighted by area (area_weighted_normals)
  face_average,  ///< the plain average of unit face normals (face_average_normals)
};

/// The name of `s` as the command line spells it: "volume", "mesh", "area", "face-average";
/// "" for automatic.
const char* normals_name(NormalsSource s);
/// The source called `name` ("" is automatic), or nothing for an unknown name.
std::optional<NormalsSource> normals_from_name(const std::string& name);
/// The names a request may give, in the order the messages list them: volume, mesh, area,
/// face-average.
std::vector<std::string> normals_names();

/// A curvature request as the user gave it, before the defaults are applied.
struct Request {
  std::optional<Estimator> estimator;  ///< nothing: default_estimator
  double scale = 0;                    ///< the volume estimator's sigma, world units; 0: auto
  bool scale_given = false;            ///< a scale was asked for (an error for mesh estimators)
  NormalsSource normals = NormalsSource::automatic;
  std::optional<float> iso;       ///< the mesh's isovalue for the volume estimator, when given
  std::optional<float> ao_scale;  ///< nothing: 4 mean edge lengths of the mesh
  std::optional<ao::Method> ao_method;  ///< the AO array's method; nothing: griffin
  bool hattori_half = false;            ///< ao_method hattori: the umbilic mean (Options)
};

/// The request with its defaults applied and its combinations checked.
struct Resolved {
  Estimator estimator = Estimator::rusinkiewicz;
  double scale = 0;  ///< 0: auto
  /// The mesh estimators' normals (never automatic); automatic for the volume estimator, which
  /// takes them from the volume's gradient at its scale.
  NormalsSource normals = NormalsSource::automatic;
  float isovalue = 0;  ///< the volume estimator's isovalue (0 for the mesh estimators)
  std::optional<float> ao_scale;  ///< as requested (checked positive and finite)
  ao::Method ao_method = ao::Method::griffin;  ///< for Options::ao_method
  bool hattori_half = false;                   ///< for Options::hattori_half
  bool volume_estimator() const { return needs_volume(estimator); }
};

/// The estimator a request runs: the one asked for, else the volume estimator when there is a
/// volume and no normals were asked for (the most accurate on every class of docs/curvature.md's
/// table; normals only mean something to the mesh estimators), else rusinkiewicz.
Estimator default_estimator(const Request& request, bool has_volume);

/// Which field of a Request a RequestError is about.
enum class RequestField { estimator, normals, scale, iso, ao_scale, ao_method, hattori_half };

/// The name of `f` as the Request and the Python module spell it: "estimator", "normals",
/// "scale", "iso", "ao_scale", "ao_method", "hattori_half".
const char* request_field_name(RequestField f);

/// Which rule a request broke.
enum class RequestProblem {
  estimator_needs_volume,      ///< estimator: the volume estimator without a volume
  normals_not_for_volume,      ///< normals: asked for with the volume estimator
  scale_not_for_mesh,          ///< scale: given with a mesh estimator
  volume_normals_need_volume,  ///< normals: volume without a volume
  iso_not_for_mesh,            ///< iso: given with a mesh estimator
  needs_isovalue,              ///< iso: the volume estimator with neither iso nor the mesh's own
  not_finite,                  ///< iso, scale or ao_scale: NaN or infinite
  not_positive,                ///< scale (negative) or ao_scale (zero or negative)
  ao_needs_volume,             ///< ao_method: a ray cast (ao::needs_volume) without a volume
  hattori_half_not_hattori,    ///< hattori_half: asked for with an ao_method other than hattori
};

/// A request that breaks a rule: which field (`field`), which rule (`problem`) and the estimator
/// the request resolved to, so that each caller words it in its own terms. detail() is the rule
/// in neutral words ("applies to the volume estimator only"); what() is "<field>: <detail>"
/// (request_field_name: "scale: applies to the volume estimator only").
class RequestError : public Error {
 public:
  RequestError(RequestField field, RequestProblem problem, Estimator estimator,
               const std::string& detail)
      : Error(request_field_name(field), detail),
        field(field),
        problem(problem),
        estimator(estimator),
        detail_(detail) {}
  const std::string& detail() const { return detail_; }
  RequestField field;
  RequestProblem problem;
  Estimator estimator;  ///< the estimator asked for, or the default one

 private:
  std::string detail_;
};

/// Applies the defaults to `request` and checks it, for a mesh with a volume (`has_volume`) or
/// without, whose own isovalue (a mesh extracted by isocurv) is `mesh_isovalue`. The volume
/// estimator needs a volume, takes no normals and needs an isovalue (request.iso, else
/// `mesh_isovalue`); the mesh estimators take no scale and no iso; volume normals need a volume.
/// iso, scale and ao_scale must be finite, scale not negative; then check_ao's rules.
/// @throw RequestError for the first broken rule, in that order
Resolved resolve(const Request& request, bool has_volume,
                 std::optional<float> mesh_isovalue = std::nullopt);

/// The ambient-occlusion rules alone (the last of resolve's), also for a field that is not
/// estimated again (a mesh file's own curvature, apply_ao): ao_scale finite and positive,
/// hattori_half only with ao_method hattori, and a ray cast (ao::needs_volume) needs a volume.
/// @throw RequestError for the first broken rule, in that order (its estimator: default_estimator)
void check_ao(const Request& request, bool has_volume);

/// The normals the mesh estimators are to read (Options::vertex_normals) for `source`, computed on
/// the host: the gradient of `volume` (gradient_normals_for_mesh, with its fallback counts; `caps`
/// for a mesh extracted with mc::Options::cap), area_weighted_normals or face_average_normals.
/// Empty (.normals) for mesh and automatic: the estimators' own.
/// @throw Error for volume without a volume (resolve has refused that already)
volume::MeshNormals host_normals(NormalsSource source, const Mesh& mesh,
                                 const volume::Volume* volume, bool caps = false);

/// True for the sources host_normals computes (volume, area, face-average): the estimators are
/// then given them as Options::vertex_normals.
inline bool host_computed(NormalsSource s) {
  return s == NormalsSource::volume || s == NormalsSource::area || s == NormalsSource::face_average;
}

/// The normals a Resolved request used, as the reports name them: normals_name, or "volume
/// estimator" for the volume estimator.
std::string normals_report_name(const Resolved& r);

}  // namespace isocurv::curvature
