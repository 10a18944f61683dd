#include "ao/method.h"

namespace isocurv::ao {

namespace {
constexpr Method kAll[] = {Method::griffin, Method::griffin_exact, Method::hattori,
                           Method::prantl,  Method::raycast,       Method::raycast_cos};
}

const char* method_name(Method m) {
  switch (m) {
    case Method::griffin:
      return "griffin";
    case Method::griffin_exact:
      return "griffin-exact";
    case Method::hattori:
      return "hattori";
    case Method::prantl:
      return "prantl";
    case Method::raycast:
      return "raycast";
    case Method::raycast_cos:
      return "raycast-cos";
  }
  return "?";
}

std::optional<Method> method_from_name(const std::string& name) {
  for (Method m : kAll)
    if (name == method_name(m)) return m;
  return std::nullopt;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (Method m : kAll) names.push_back(method_name(m));
  return names;
}

bool needs_volume(Method m) { return m == Method::raycast || m == Method::raycast_cos; }

}  // namespace isocurv::ao
