// The explorer's camera: named views ('v'), resetting ('r') and saving it ('k').
#include "viz/detail/explorer.h"

#include <array>
#include <iostream>

#include "core/error.h"
#include "viz/camera_file.h"

namespace isocurv::viz::detail {

void Explorer::reset_camera() {
  RenderOptions o = scene_.options();
  o.view.view = view_;
  o.camera.reset();
  try_options(o);
  frame_camera();
}

void Explorer::frame_camera() {
  std::array<double, 6> b{};
  if (current_.mesh.positions.empty() && screen_on_ && setup_.screen.bounds &&
      setup_.screen.bounds(iso_, b))
    scene_.frame_camera(&b);
  else
    scene_.frame_camera();
}

void Explorer::save_camera_file() {
  try {
    save_camera(setup_.camera_path, scene_.current_camera());
    message_ = "saved the camera to " + setup_.camera_path + " (isocurv render --camera)";
    std::cout << "saved camera: " << setup_.camera_path << std::endl;
  } catch (const Error& e) {
    message_ = e.what();
  }
}

}  // namespace isocurv::viz::detail
