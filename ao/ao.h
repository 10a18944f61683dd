#pragma once
// ao::compute: the per-vertex "AO" array of a CurvatureField by one of the ambient-occlusion
// methods (ao/method.h). The curvature stage's last step (curvature::Options::ao_method,
// curvature::apply_ao): the formulas read the field's k1, k2 or H, the ray casts read the volume
// the mesh came from.
// Tested in tests/ao/test_ao.cpp.
#include <string>

#include "ao/method.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/estimator.h"

namespace isocurv::ao {

struct Options {
  Method method = Method::griffin;
  /// rho: the hemisphere's radius, world units (curvature::Options::ao_scale; the command line's
  /// --ao-scale, by default 4 mean edge lengths). > 0 and finite.
  double radius = 1;
  /// Ray casts: strata x strata rays per vertex (16: 256 rays).
  int strata = 16;
  /// Hattori: the umbilic mean rho (k1 + k2) / 2 instead of the printed rho (k1 + k2).
  bool hattori_half = false;
  /// Prantl: the flat value a, and H_ref (0: the 98th percentile of |H| over the vertices with a
  /// finite H that are not flagged Unreliable, but at least 1 / (4 rho), so that on a nearly flat
  /// surface the noise in H is not stretched over the whole range).
  double prantl_a = 0.9;
  double prantl_href = 0;
};

/// Replaces field.ao with options.method's AO, one value in [0, 1] per vertex (1 = open), and
/// records the method in field.metadata: "ao" (method_name), "ao_radius", and for prantl
/// "ao_href", for hattori "ao_hattori" ("printed" or "half"), for the ray casts "ao_rays"
/// (replacing earlier "ao*" entries). Griffin's polynomial is the curvature stage's own AO
/// (curvature/derived.h) recomputed from k1, k2: the same values the estimators give.
/// Per-method inputs: griffin, griffin-exact, hattori: field.k1, field.k2; prantl: field.H;
/// raycast, raycast-cos: field.normals (unit, outward), mesh.positions and source.volume at
/// source.isovalue. Vertices without a finite curvature get 1.
/// @throw Error for a radius that is not positive and finite, a ray cast without a volume
/// ("needs the volume"), or field arrays missing or not of the mesh's size.
/// Threading: parallel over vertices (TBB) for the ray casts; deterministic.
void compute(const Mesh& mesh, curvature::CurvatureField& field,
             const curvature::VolumeSource& source, const Options& options);

}  // namespace isocurv::ao
