#include "app/shared_pictures.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/framing_points.h"
#include "core/progress.h"
#include "io/mesh_file.h"
#include "lines/line_files.h"
#include "viz/color_map.h"
#include "viz/quantity.h"
#include "viz/range_values.h"
#include "viz/render.h"

namespace isocurv::app {
namespace {

constexpr std::size_t kValuesPerPicture = 65536;
constexpr std::size_t kPointsPerPicture = 8192;

/// Every k-th element so that at most `most` remain (all when fewer).
template <class T>
void append_sample(const std::vector<T>& from, std::size_t most, std::vector<T>& to) {
  const std::size_t step = from.size() <= most ? 1 : (from.size() + most - 1) / most;
  for (std::size_t i = 0; i < from.size(); i += step) to.push_back(from[i]);
}

}  // namespace

SharedPictures::SharedPictures(const RenderCli& r) {
  share_range_ = !r.opts.range;
  share_camera_ = r.camera_file.empty();
  active_ = r.range_mode == "shared" && (share_range_ || share_camera_);
  clamp_percentile_ = r.opts.clamp_percentile;
}

void SharedPictures::add(SharedPicture picture, const Mesh& mesh,
                         const curvature::CurvatureField& field) {
  quantity_ = viz::canonical_quantity(picture.opts.color);
  if (share_range_) append_sample(viz::range_values(mesh, field, quantity_), kValuesPerPicture, values_);
  if (share_camera_) append_sample(framing_points(mesh), kPointsPerPicture, points_);
  pictures_.push_back(std::move(picture));
}

viz::ColorRange SharedPictures::range() const {
  return viz::color_range(values_, quantity_, clamp_percentile_);
}

std::vector<SharedPictureFailure> SharedPictures::draw(const SharedLines& lines) {
  std::vector<SharedPictureFailure> failures;
  const viz::ColorRange shared = range();
  Progress bar("pictures (one range and camera)", pictures_.size());
  for (std::size_t i = 0; i < pictures_.size(); ++i) {
    SharedPicture& p = pictures_[i];
    bar.set(i);
    try {
      io::MeshFile m = io::read_mesh(p.mesh_path);
      if (!m.field) throw Error(p.mesh_path, "has no curvature arrays to draw");
      viz::RenderOptions o = p.opts;
      if (share_range_) o.range = shared;
      if (share_camera_) o.frame_points = points_;
      std::optional<lines::Polylines> poly;
      viz::LinesForCamera lines_for;
      if (lines && !p.lines_path.empty())
        lines_for = [&](const Camera& cam) {
          poly = lines(m.mesh, *m.field, cam);
          return *poly;
        };
      AtomicFileSet outputs;  // the picture and its lines together
      outputs.write(p.png_path, [&](const std::string& tmp) {
        viz::render_png(tmp, m.mesh, *m.field, o, lines_for);
      });
      if (poly)
        outputs.write(p.lines_path, [&](const std::string& tmp) { lines::write_vtp(tmp, *poly); });
      outputs.commit();
    } catch (const std::exception& e) {
      failures.push_back({p.tag, e.what()});
    }
  }
  bar.finish();
  return failures;
}

}  // namespace isocurv::app
