#pragma once
// Principal directions drawn as short line segments on an even subsample of the vertices.
// Tested in tests/viz/test_color_map.cpp.
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

#include "core/mesh.h"
#include "core/mesh_measures.h"
#include "curvature/curvature_field.h"
#include "viz/render_options.h"

namespace isocurv::viz {

/// Colours of the glyphs: dir1 (direction of k1, the larger curvature) white with a black halo,
/// dir2 black with a white halo, so both read on light and dark colours of every map.
constexpr unsigned char kDir1Color[3] = {255, 255, 255};
constexpr unsigned char kDir1Halo[3] = {0, 0, 0};
constexpr unsigned char kDir2Color[3] = {0, 0, 0};
constexpr unsigned char kDir2Halo[3] = {255, 255, 255};

/// How many glyphs and how long.
struct GlyphOptions {
  int count = 0;  ///< about this many glyph sites over the whole surface; 0: from the image size
  double length = 0;  ///< segment length in world units; 0: 0.7 x the spacing of the sites
  int image_width = 1024, image_height = 768;  ///< the picture they are drawn in (for count = 0)
};

/// The glyph options of a picture: options.dirs_count, dirs_length and the image size.
inline GlyphOptions glyph_options(const RenderOptions& o) {
  return {o.dirs_count, o.dirs_length, o.width, o.height};
}

/// The number of glyph sites used for `count = 0`: one per 36x36 pixels of the image (about 600
/// at 1024x768, 70 at 300x300), about half of which face the camera.
int default_glyph_count(int image_width, int image_height);

/// Line segments centred on a spatially even subsample of the vertices: one per grid cell of
/// `spacing` = sqrt(surface area / count) (so about `count` sites), but at least 2.5 mean edge
/// lengths (never denser than the mesh). Two segments per site, along dir1 and along dir2,
/// `length` long, lifted off the surface by 0.15 mean edge along the normal. Cell data:
/// "Colors" (RGB: kDir1Color / kDir2Color), "Halo" (kDir1Halo / kDir2Halo) and "Direction"
/// (1 or 2). Vertices without finite non-zero directions are skipped; empty when the field has
/// no dir1/dir2. Deterministic: the first vertex (by index) in each cell is chosen.
vtkSmartPointer<vtkPolyData> direction_glyphs(const Mesh& mesh,
                                              const curvature::CurvatureField& field,
                                              const GlyphOptions& options = {});

/// Throws Error naming `path` unless it ends in .vtp (the format write_glyphs writes).
void check_glyphs_path(const std::string& path);

/// Writes `glyphs` (from direction_glyphs) as a VTK XML PolyData file (.vtp) of line cells with
/// their cell data, for ParaView; atomically. @throw Error naming `path` when it cannot be written.
void write_glyphs(const std::string& path, vtkPolyData* glyphs);

}  // namespace isocurv::viz
