#include "screen/image_files.h"

#include <vtkColorTransferFunction.h>
#include <vtkErrorCode.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cmath>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/vtk_errors.h"
#include "viz/curvature_scene.h"
#include "viz/headless_display.h"
#include "viz/legend.h"
#include "viz/quantity.h"

namespace isocurv::screen {
namespace {

const std::vector<float>& values_of(const ScreenCurvature& c, const std::string& q) {
  if (q == "H") return c.H;
  if (q == "K") return c.K;
  throw Error("screen: --color takes H or K, not " + q);
}

std::string legend_title(const PictureOptions& o) {
  const std::string q = viz::canonical_quantity(o.quantity);
  const std::string unit = viz::quantity_unit(q, o.length_unit);
  return unit.empty() ? q : q + "\n" + unit;
}

}  // namespace

viz::PictureLayout screen_layout(int width, int height, const PictureOptions& o,
                                 const viz::ColorRange& range, bool no_data) {
  viz::PictureLayout l =
      viz::layout_picture(width, height, o.title, legend_title(o), range.lo, range.hi, 0, no_data);
  // As render frames it (viz::stable_surface_right): the values do not move the camera.
  l.surface.x1 = std::min(l.surface.x1, viz::stable_surface_right(width, height, o.title, legend_title(o)));
  return l;
}

bool has_unestimated(const GBuffer& g, const ScreenCurvature& c) {
  if (g.valid.size() != c.valid.size()) return false;
  for (std::size_t i = 0; i < c.valid.size(); ++i)
    if (g.valid[i] && !c.valid[i]) return true;
  return false;
}

viz::ColorRange screen_range(const ScreenCurvature& c, const PictureOptions& o) {
  const std::vector<float>& v = values_of(c, o.quantity);
  std::vector<float> valid;
  valid.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    if (c.valid[i]) valid.push_back(v[i]);
  if (valid.empty()) return o.range ? *o.range : viz::ColorRange{-1, 1};
  return viz::color_range(valid, viz::canonical_quantity(o.quantity), o.clamp_percentile, o.range);
}

void write_picture(const std::string& path, const GBuffer& g, const ScreenCurvature& c,
                   const viz::PictureLayout& layout, const PictureOptions& o,
                   const viz::ColorRange& range) {
  const viz::PixelBox& box = layout.surface;
  if (box.x1 - box.x0 != c.width || box.y1 - box.y0 != c.height || g.width() != c.width ||
      g.height() != c.height)
    throw Error(path, "the screen image does not fit the picture's surface box");
  const std::string q = viz::canonical_quantity(o.quantity);
  const std::string cmap = viz::resolve_color_map(o.cmap, q);
  const std::vector<float>& values = values_of(c, o.quantity);

  viz::ensure_display();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(layout.width, layout.height);
  viz::check_opengl(window);
  vtkNew<vtkRenderer> overlay;
  overlay->GradientBackgroundOn();
  overlay->SetBackground(viz::kBackgroundBottom[0], viz::kBackgroundBottom[1],
                         viz::kBackgroundBottom[2]);
  overlay->SetBackground2(viz::kBackgroundTop[0], viz::kBackgroundTop[1], viz::kBackgroundTop[2]);
  window->AddRenderer(overlay);
  viz::Legend legend(overlay);
  legend.update(layout, cmap, range, true);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  {
    io::VtkErrorCapture errors(grab);
    grab->Update();
    if (errors.failed()) throw Error(path, "cannot read the rendered image: " + errors.message());
  }
  vtkImageData* img = grab->GetOutput();
  auto* rgb = static_cast<unsigned char*>(img->GetScalarPointer());
  const int w = layout.width;
  const std::vector<float> shade = o.shade ? view_shading(g) : std::vector<float>{};
  auto colors = viz::vertex_colors(values, range, viz::make_color_map(range, cmap),
                                   o.shade ? &shade : nullptr);
  const unsigned char* col = colors->GetPointer(0);
  const std::array<double, 3> none = viz::no_data_color(cmap);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const std::size_t i = std::size_t(x) + std::size_t(c.width) * y;
      unsigned char* px = rgb + 3 * (std::size_t(box.x0 + x) + std::size_t(w) * (box.y0 + y));
      if (c.valid[i] && std::isfinite(values[i])) {
        for (int k = 0; k < 3; ++k) px[k] = col[3 * i + k];
      } else if (g.valid[i]) {  // the surface, without an estimate: "no data"
        const double s = o.shade ? shade[i] : 1.0;
        for (int k = 0; k < 3; ++k)
          px[k] = static_cast<unsigned char>(std::clamp(255.0 * none[k] * s + 0.5, 0.0, 255.0));
      }
    }
  img->Modified();
  write_atomically(path, [&](const std::string& tmp) {
    vtkNew<vtkPNGWriter> writer;
    io::VtkErrorCapture errors(writer);
    writer->SetInputData(img);
    writer->SetFileName(tmp.c_str());
    writer->Write();
    if (errors.failed() || writer->GetErrorCode() != vtkErrorCode::NoError)
      throw Error(path,
                  "cannot write PNG" + (errors.failed() ? ": " + errors.message() : std::string()));
  });
  window->Finalize();
}

viz::ScreenImage explorer_image(const GBuffer& g, ScreenCurvature&& c, bool with_k) {
  viz::ScreenImage img;
  img.width = c.width, img.height = c.height;
  img.H = std::move(c.H);
  if (with_k) img.K = std::move(c.K);
  img.valid = std::move(c.valid);
  img.shade = view_shading(g);
  return img;
}

void write_raw(const std::string& path, const ScreenCurvature& c,
               const viz::PictureLayout* layout) {
  const int W = layout ? layout->width : c.width, Hh = layout ? layout->height : c.height;
  const int x0 = layout ? layout->surface.x0 : 0, y0 = layout ? layout->surface.y0 : 0;
  if (layout && (layout->surface.x1 - x0 != c.width || layout->surface.y1 - y0 != c.height))
    throw Error(path, "the screen image does not fit the picture's surface box");
  vtkNew<vtkImageData> img;
  img->SetDimensions(W, Hh, 1);
  img->SetSpacing(1, 1, 1);
  img->SetOrigin(0, 0, 0);
  const std::size_t n = std::size_t(W) * std::size_t(Hh);
  // The index in c of the picture's point p, or -1 outside the surface box.
  auto in_c = [&](std::size_t p) -> long {
    const int x = int(p % std::size_t(W)) - x0, y = int(p / std::size_t(W)) - y0;
    if (x < 0 || y < 0 || x >= c.width || y >= c.height) return -1;
    return long(x) + long(c.width) * y;
  };
  auto add = [&](const char* name, auto&& value) {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfTuples(static_cast<vtkIdType>(n));
    for (std::size_t p = 0; p < n; ++p) {
      const long i = in_c(p);
      a->SetValue(static_cast<vtkIdType>(p), i < 0 ? 0.0f : value(std::size_t(i)));
    }
    img->GetPointData()->AddArray(a);
  };
  add("H", [&](std::size_t i) { return c.valid[i] ? c.H[i] : 0.0f; });
  add("K", [&](std::size_t i) { return c.valid[i] ? c.K[i] : 0.0f; });
  add("Valid", [&](std::size_t i) { return c.valid[i] ? 1.0f : 0.0f; });
  write_atomically(path, [&](const std::string& tmp) {
    vtkNew<vtkXMLImageDataWriter> writer;
    io::VtkErrorCapture errors(writer);
    writer->SetInputData(img);
    writer->SetFileName(tmp.c_str());
    if (!writer->Write() || errors.failed())
      throw Error(path, "cannot write VTK image data" +
                            (errors.failed() ? ": " + errors.message() : std::string()));
  });
}

}  // namespace isocurv::screen
