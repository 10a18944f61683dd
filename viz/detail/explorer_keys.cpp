// The explorer's keys, and typing an isovalue, a mesh file to open or a path to save to.
#include "viz/detail/explorer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

#include <vtkObjectFactory.h>
#include <vtkSliderRepresentation2D.h>

#include "core/error.h"
#include "viz/quantity.h"

namespace isocurv::viz::detail {

vtkStandardNewMacro(ExplorerStyle);

void ExplorerStyle::OnChar() {
  const char key = this->Interactor ? this->Interactor->GetKeyCode() : 0;
  if (explorer && explorer->on_key(key)) return;
  vtkInteractorStyleTrackballCamera::OnChar();  // r, q/e, w, f, ...
}

bool Explorer::on_key(char key) {
  if (entry_ != Entry::none) {
    typed(key);
    refresh_status();
    window_->Render();
    return true;
  }
  RenderOptions o = scene_.options();
  if (screen_on_ && (key == 'a' || key == 'd' || (key == 'l' && setup_.lines))) {
    message_ = std::string("'") + key + "' applies to the mesh: x leaves screen-space mode";
    refresh_status();
    window_->Render();
    return true;
  }
  switch (key) {
    case 'c': {  // every point array of the surface shown: the curvature ones, then its extras
      const std::vector<std::string> q =
          screen_on_ ? std::vector<std::string>{"H", "K"} : field_quantities(current_.field);
      auto it = std::find(q.begin(), q.end(), canonical_quantity(o.color));
      for (std::size_t step = 0; step < q.size(); ++step) {
        it = (it == q.end() || it + 1 == q.end()) ? q.begin() : it + 1;
        o.color = *it;
        if (try_options(o)) break;
      }
      break;
    }
    case 'a':
      o.shading = o.shading == Shading::lambert ? Shading::ambient_ao : Shading::lambert;
      try_options(o);
      break;
    case 'd': o.dirs = !o.dirs; try_options(o); break;
    case 's': screenshot(next_screenshot_name()); break;
    case 'v':
      view_ = static_cast<NamedView>((static_cast<int>(view_) + 1) % kNamedViews);
      reset_camera();
      break;
    case 'r': reset_camera(); break;
    case 'i':
      if (setup_.has_isovalue) start_entry(Entry::isovalue, "");
      else message_ = "no isovalue here: the frames are meshes";
      break;
    case 'o':
      if (setup_.open_mesh) start_entry(Entry::open, "");
      else message_ = "opening meshes is not available here";
      break;
    case 'w':
      if (setup_.save_surface && screen_on_ && mesh_stale_)
        message_ = "no mesh of this isovalue yet: x leaves screen-space mode and extracts it";
      else if (setup_.save_surface)
        start_entry(Entry::save, setup_.surface_path);
      else message_ = "saving the surface is not available here";
      break;
    case 'k': save_camera_file(); break;
    case 'x':
      if (!setup_.screen.image)
        message_ = "screen space is not available here";
      else if (screen_on_)
        leave_screen();
      else
        enter_screen();
      break;
    case ' ':
      if (!has_time()) return false;
      playing_ = !playing_;
      refresh_status();
      window_->Render();
      break;
    case 'l':
      if (!setup_.lines) return false;
      lines_on_ = !lines_on_;
      overlay_.set_visible(lines_on_);
      break;
    default: return false;
  }
  refresh_status();
  window_->Render();
  return true;
}

void Explorer::start_entry(Entry e, const std::string& initial) {
  entry_ = e;
  typed_ = initial;
  message_.clear();
}

void Explorer::typed(char key) {
  if (key == kEscape) {
    entry_ = Entry::none;
    return;
  }
  if (key == kBackSpace || key == kDelete) {
    if (!typed_.empty()) typed_.pop_back();
    return;
  }
  if (key != kEnter && key != '\n') {
    if (key >= 32 && key < 127) typed_.push_back(key);
    return;
  }
  const Entry e = entry_;
  entry_ = Entry::none;
  if (e == Entry::isovalue) {
    char* end = nullptr;
    const double v = std::strtod(typed_.c_str(), &end);
    if (typed_.empty() || *end != '\0' || !std::isfinite(v)) {
      message_ = "not a number: '" + typed_ + "'";
    } else if (v < setup_.min_value || v > setup_.max_value) {
      message_ = "isovalue " + format(v) + " is outside the value range [" + format(setup_.min_value) + ", " +
                 format(setup_.max_value) + "]";
    } else {
      static_cast<vtkSliderRepresentation2D*>(slider_->GetRepresentation())->SetValue(v);
      update(static_cast<float>(v));
    }
  } else if (e == Entry::open) {
    try {
      present(setup_.open_mesh(typed_), typed_);
      image_stale_ = true;  // screen-space mode: the image is now the mesh's
      reset_camera();
    } catch (const Error& err) {
      message_ = err.what();
    }
  } else if (e == Entry::save) {
    try {
      setup_.save_surface(typed_, current_.mesh, current_.field);
      message_ = "saved the surface to " + typed_;
      std::cout << "saved surface: " << typed_ << std::endl;
    } catch (const Error& err) {
      message_ = err.what();
    }
  }
}

}  // namespace isocurv::viz::detail
