#pragma once
// A per-pixel curvature image as the explorer's screen-space mode shows it (plain data, filled by
// the caller from screen::estimate; viz does not depend on screen/).
// Tested in tests/viz/test_explorer_screen.cpp (through its users).
#include <cstdint>
#include <string>
#include <vector>

namespace isocurv::viz {

/// width x height pixels, row-major (index x + width * y), y up from the bottom row (VTK display
/// order, as screen::GBuffer).
struct ScreenImage {
  int width = 0, height = 0;
  std::vector<float> H;  ///< mean curvature (outward normals: a sphere has +1/R)
  std::vector<float> K;  ///< Gaussian curvature; empty when the estimator gives none (Mellado)
  /// Shading factor in [0, 1] the colour is multiplied by (screen::view_shading: a sense of
  /// shape); empty: 1 everywhere.
  std::vector<float> shade;
  std::vector<std::uint8_t> valid;  ///< 1 where estimated; others show the background
  double update_ms = 0;             ///< time the callback spent (the explorer measures it when 0)
  std::string detail;               ///< extra status-line text ("cast 80 ms, estimate 12 ms")

  std::size_t pixels() const { return std::size_t(width) * std::size_t(height); }
  std::size_t valid_count() const {
    std::size_t n = 0;
    for (std::uint8_t v : valid) n += v != 0;
    return n;
  }
};

}  // namespace isocurv::viz
