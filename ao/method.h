#pragma once
// The ambient-occlusion methods ao::compute offers (ao/ao.h), and their command-line names.
// Tested in tests/ao/test_ao.cpp, tests/app/test_ao_cli.cpp (through its users).
#include <optional>
#include <string>
#include <vector>

namespace isocurv::ao {

/// How the per-vertex "AO" array (the unoccluded fraction of the hemisphere of radius rho above the
/// surface, 1 = open) is computed. The curvature formulas read k1, k2 or H; the ray casts read the
/// volume. Formulas and their sources: ao/formulas.h, ao/griffin_exact.h, ao/raycast.h.
enum class Method {
  griffin,        ///< Griffin et al.'s polynomial in rho (k1 + k2) (today's; 0.7369 on a plane)
  griffin_exact,  ///< Griffin's exact (k1, k2) integral, eq. 10-12 with sqrt(1 + A^2)
  hattori,        ///< Hattori's (2/pi) arccos form of the umbilic horizon angle
  prantl,         ///< Prantl's mapping of H / H_ref (Gaussian on the concave side; 0.9 on a plane)
  raycast,  ///< ray-cast reference from the volume, uniform over the hemisphere (eq. 10's measure)
  raycast_cos,  ///< the same, cosine-weighted (eq. 9's measure)
};

/// "griffin", "griffin-exact", "hattori", "prantl", "raycast", "raycast-cos".
const char* method_name(Method m);
/// The method called `name`, or nothing for an unknown name.
std::optional<Method> method_from_name(const std::string& name);
/// Every method's name, in enum order (help texts, option checks).
std::vector<std::string> method_names();
/// True for the ray casts, which need the volume the mesh came from.
bool needs_volume(Method m);

}  // namespace isocurv::ao
