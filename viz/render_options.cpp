#include "viz/render_options.h"

#include "core/error.h"

namespace isocurv::viz {

Shading parse_shading(const std::string& name) {
  if (name == "lambert") return Shading::lambert;
  if (name == "ambient-ao") return Shading::ambient_ao;
  if (name == "both") return Shading::both;
  throw Error("unknown shading '" + name + "' (expected lambert, ambient-ao or both)");
}

std::string to_string(Shading s) {
  switch (s) {
    case Shading::lambert:
      return "lambert";
    case Shading::ambient_ao:
      return "ambient-ao";
    case Shading::both:
      return "both";
  }
  return "lambert";
}

}  // namespace isocurv::viz
