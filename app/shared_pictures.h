#pragma once
// --range shared (the default): the pictures of a sweep, a batch or a time series drawn with one
// colour range and one camera, so that they compare side by side and play as an animation.
//
// Each entry's mesh is written as usual; as it goes, a sample of its colour values and framing
// points is kept (at most 65,536 values and 8,192 points a picture). Once every entry is done,
// draw() reads each mesh back and draws its picture with the range taken from all the samples
// (viz::color_range over them, as one picture's would be over its own values) and the camera
// fitted to all the points. Memory does not grow with the meshes; a picture costs one more read.
#include <functional>
#include <string>
#include <vector>

#include "app/render_options_cli.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "lines/polylines.h"
#include "viz/render_options.h"

namespace isocurv::app {

/// One picture to draw at the end.
struct SharedPicture {
  std::string mesh_path;   ///< the mesh written for it (.vtp or .ply: with its curvature arrays)
  std::string png_path;    ///< the picture to write
  viz::RenderOptions opts; ///< its own options (title, colour array resolved, view)
  std::string lines_path;  ///< with lines: the .vtp of the lines drawn (else empty)
  std::size_t tag = 0;     ///< the caller's (e.g. its entry's index), given back with a failure
};

/// A picture draw() could not make: its tag and the problem (naming the file).
struct SharedPictureFailure {
  std::size_t tag = 0;
  std::string message;
};

/// The lines of a picture, for the camera it is drawn with (run --lines in a series).
using SharedLines = std::function<lines::Polylines(const Mesh&, const curvature::CurvatureField&,
                                                   const Camera&)>;

class SharedPictures {
 public:
  /// Shares what `r` leaves free: the range unless --range MIN,MAX fixed it, the camera unless
  /// --camera gave one. Inactive for --range each, or when both are fixed.
  explicit SharedPictures(const RenderCli& r);

  /// True when the pictures are to be drawn at the end (add, then draw) rather than one by one.
  bool active() const { return active_; }

  /// Notes a picture of `mesh` and `field` (sampled now; they need not outlive the call).
  void add(SharedPicture picture, const Mesh& mesh, const curvature::CurvatureField& field);

  /// Draws every picture noted (and its lines file, with `lines`), each written atomically.
  /// Returns the pictures that failed (the others are still drawn). A progress bar on stderr
  /// (core/progress.h) for long runs.
  std::vector<SharedPictureFailure> draw(const SharedLines& lines = {});

  /// The shared colour range and camera points of the pictures noted so far (for reports).
  viz::ColorRange range() const;

 private:
  bool active_ = false, share_range_ = false, share_camera_ = false;
  double clamp_percentile_ = 2;
  std::string quantity_;
  std::vector<SharedPicture> pictures_;
  std::vector<float> values_;
  std::vector<std::array<double, 3>> points_;
};

}  // namespace isocurv::app
