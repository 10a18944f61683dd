#pragma once
// Stratified hemisphere directions for the ray-cast AO, rotated and jittered per vertex from a
// hash of its index (deterministic, independent of threading).
#include <array>
#include <cstdint>
#include <vector>

namespace isocurv::ao::detail {

using Dir = std::array<double, 3>;

/// splitmix64: a well-mixed 64-bit hash (the per-vertex random stream).
std::uint64_t mix64(std::uint64_t x);

/// g x g directions (g >= 1) over the hemisphere about unit normal n, one per stratum of
/// (u, v) in [0, 1)^2 with its point jittered: cos(theta) = u (uniform in solid angle) or sqrt(u)
/// (cosine-weighted), azimuth 2 pi v plus a per-vertex rotation. Jitter and rotation come from
/// mix64(seed): the same seed gives the same directions. Written to `out` (resized to g^2).
void hemisphere_directions(const Dir& n, int g, bool cosine, std::uint64_t seed,
                           std::vector<Dir>& out);

}  // namespace isocurv::ao::detail
