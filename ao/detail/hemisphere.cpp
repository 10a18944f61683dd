#include "ao/detail/hemisphere.h"

#include <cmath>

namespace isocurv::ao::detail {

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

namespace {
/// A uniform double in [0, 1) from the stream's next state.
double next_unit(std::uint64_t& state) {
  state = mix64(state);
  return double(state >> 11) * (1.0 / 9007199254740992.0);
}
}  // namespace

void hemisphere_directions(const Dir& n, int g, bool cosine, std::uint64_t seed,
                           std::vector<Dir>& out) {
  // Tangent frame (t, b, n) from the normal alone (Duff et al. 2017).
  const double sign = std::copysign(1.0, n[2]);
  const double a = -1.0 / (sign + n[2]), c = n[0] * n[1] * a;
  const Dir t = {1 + sign * n[0] * n[0] * a, sign * c, -sign * n[0]};
  const Dir b = {c, sign + n[1] * n[1] * a, -n[1]};
  std::uint64_t state = mix64(seed);
  const double rotation = 2 * M_PI * next_unit(state);
  out.resize(std::size_t(g) * g);
  std::size_t k = 0;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j, ++k) {
      const double u = (i + next_unit(state)) / g, v = (j + next_unit(state)) / g;
      const double ct = cosine ? std::sqrt(u) : u, st = std::sqrt(std::max(0.0, 1 - ct * ct));
      const double phi = 2 * M_PI * v + rotation, x = st * std::cos(phi), y = st * std::sin(phi);
      for (int d = 0; d < 3; ++d) out[k][d] = x * t[d] + y * b[d] + ct * n[d];
    }
}

}  // namespace isocurv::ao::detail
