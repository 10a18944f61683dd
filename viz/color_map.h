#pragma once
// Colour maps for curvature quantities, the value range they span, and per-vertex colours.
//
// Maps (--cmap): "diverging" (blue - light grey - red, ColorBrewer's colour-blind-safe RdBu run
// from blue to red, neutral #f7f7f7), "viridis" (perceptually uniform sequential, matplotlib's),
// "grey" (black to white) and "bgr" (the papers' blue-green-red, green at the centre). "auto"
// picks diverging for signed quantities (H, K, k1, k2, ShapeIndex and the arrays named after
// them: H_s2, H_ii, SI_ii, ...; viz::QuantityKind), grey for AO and viridis for the others.
// Tested in tests/viz/test_color_map.cpp, tests/viz/test_render.cpp.
#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

class vtkColorTransferFunction;
class vtkUnsignedCharArray;

namespace isocurv::viz {

/// The value range mapped onto a colour map: `lo` gets the map's first colour, `hi` its last.
struct ColorRange {
  double lo = -1, hi = 1;
};

/// The names --cmap accepts, "auto" first.
const std::vector<std::string>& color_map_names();

/// The map "auto" means for quantity `name` (see the file comment); any other map name is checked
/// and returned. @throw Error for an unknown map.
std::string resolve_color_map(const std::string& cmap, const std::string& quantity);

/// True for the maps with a neutral centre (diverging, bgr): over a range that contains zero,
/// the centre colour lands exactly at zero (make_color_map).
bool is_centred_map(const std::string& cmap);

/// The range for `values` of quantity `name` (any array name: its viz::quantity_kind decides),
/// ignoring non-finite values. `fixed`, when given, is returned exactly (--range; it must have
/// lo < hi). Otherwise, with p = clamp_percentile (clamped to [0, 49]) so that a few outliers do
/// not wash the map out:
///  - curvature (H, K, k1, k2, H_s2, H_ii, ...) that takes both signs (the p-th percentile below
///    zero and the (100-p)-th above): symmetric [-r, r], r = the (100-p)-th percentile of
///    |value|; one-signed: [0, the (100-p)-th percentile] or [the p-th percentile, 0];
///  - shape index (ShapeIndex, SI_ii): [-1, 1]; AO and the 0/1 flags: [0, 1];
///  - magnitude (Curvedness, never negative): [0, the (100-p)-th percentile];
///  - Label: [lowest, highest] (every label gets its colour);
///  - other arrays (LBE, NSV, Vr, ...): [the p-th, the (100-p)-th percentile].
/// A degenerate range (all values equal, or nothing finite) is widened so it is never empty
/// (other arrays: by 0.1% of the value each side, at least 1e-6).
/// @throw Error for a fixed range with !(lo < hi).
ColorRange color_range(const std::vector<float>& values, const std::string& name,
                       double clamp_percentile,
                       const std::optional<ColorRange>& fixed = std::nullopt);

/// The map `cmap` (a resolved name, not "auto") over `range` (values outside are clamped to the
/// end colours). For a centred map over a range containing zero, the map is laid out over
/// [-m, m], m = max(|lo|, |hi|), so its neutral sits at zero and a one-signed range shows only
/// its half; over a range without zero the map is spread from lo to hi. @throw Error for an
/// unknown map.
vtkSmartPointer<vtkColorTransferFunction> make_color_map(const ColorRange& range,
                                                         const std::string& cmap = "diverging");

/// The "no data" colour of map `cmap` (resolved), RGB in [0, 1]: one that map never takes, as
/// ParaView's NaN colours (yellow beside diverging, magenta beside bgr, red beside viridis and
/// grey).
std::array<double, 3> no_data_color(const std::string& cmap);

/// RGB colours (unsigned char, 3 components, named "Colors") for `values` through `map` over
/// `range` (1024 steps); when `ao` is non-null each colour is multiplied by the vertex's AO
/// (clamped to [0, 1]; --shading both). Vertices flagged in `no_data` (one entry per value,
/// optional) and non-finite values get `no_data_rgb`.
vtkSmartPointer<vtkUnsignedCharArray> vertex_colors(const std::vector<float>& values,
                                                    const ColorRange& range,
                                                    vtkColorTransferFunction* map,
                                                    const std::vector<float>* ao = nullptr,
                                                    const std::vector<std::uint8_t>* no_data = nullptr,
                                                    const std::array<double, 3>& no_data_rgb = {0.5, 0.5, 0.5});

/// The categorical palette of label maps (Label): kCategoricalColors colours, RGB in [0, 1],
/// neighbours far apart in hue and lightness (Trubetskoy's distinct colours), none of them near
/// the "no data" red of a label map.
inline constexpr std::size_t kCategoricalColors = 18;
const std::array<std::array<double, 3>, kCategoricalColors>& categorical_palette();

/// The distinct finite values of `values`, ascending (a label map's labels).
std::vector<double> categories_of(const std::vector<float>& values);

/// Category `index`'s colour (the palette's, cycling): the i-th smallest label gets colour i, so
/// neighbouring labels differ.
std::array<double, 3> categorical_color(std::size_t index);

/// RGB colours ("Colors") for label values: each value its category's colour (categories as
/// categories_of returns them), the others and the flagged ones `no_data_rgb`; AO as
/// vertex_colors.
vtkSmartPointer<vtkUnsignedCharArray> categorical_vertex_colors(
    const std::vector<float>& values, const std::vector<double>& categories,
    const std::vector<float>* ao = nullptr, const std::vector<std::uint8_t>* no_data = nullptr,
    const std::array<double, 3>& no_data_rgb = {0.5, 0.5, 0.5});

}  // namespace isocurv::viz
