#include "viz/render.h"

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include "core/error.h"
#include "viz/curvature_scene.h"
#include "viz/headless_display.h"
#include "viz/line_overlay.h"
#include "viz/screenshot.h"

namespace isocurv::viz {

PictureLayout render_png(const std::string& path, const Mesh& mesh, const curvature::CurvatureField& field,
                         const RenderOptions& options, const LinesForCamera& lines) {
  if (mesh.positions.empty() || mesh.triangles.empty()) throw Error(path, "nothing to render: the mesh is empty");
  if (options.width < 16 || options.height < 16 || options.width > 16384 || options.height > 16384)
    throw Error(path, "image size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                          " out of range (16 to 16384 pixels a side)");
  CurvatureScene scene;
  scene.set_options(options);
  scene.set_surface(mesh, field);
  ensure_display();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(options.width, options.height);
  window->SetMultiSamples(8);
  check_opengl(window);
  scene.attach(window);
  const Camera camera = scene.frame_camera();
  LineOverlay overlay;
  if (lines) {
    overlay.add_to(scene.renderer());
    overlay.set_lines(lines(camera));
  }
  save_png(window, path);
  window->Finalize();
  return scene.layout();
}

}  // namespace isocurv::viz
