#include "viz/line_overlay.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>

#include "lines/line_files.h"

namespace isocurv::viz {
namespace {

// RGB per LineType, as in the SVG drawing.
constexpr unsigned char kColours[lines::kLineTypeCount][3] = {
    {0, 0, 0}, {64, 64, 64}, {192, 57, 43}, {31, 95, 191}};
constexpr double kLineWidth = 2.0;
// Every line is drawn over a white halo this much wider (a pixel each side), so
// that it stays visible on any colour map: a red ridge on the red end of the
// diverging map, a black contour on the dark end of viridis.
constexpr unsigned char kHalo[3] = {255, 255, 255};
constexpr double kHaloWidth = kLineWidth + 2.0;
// Lines are pulled towards the camera by this many depth-buffer units (VTK's
// coincident topology offset for lines), the halo a little less so that the
// line wins where they overlap, and polygons pushed back by their slope (the
// global polygon offset).
constexpr double kLineOffsetUnits = -4.0, kHaloOffsetUnits = -3.0;
constexpr double kPolygonOffsetFactor = 2.0, kPolygonOffsetUnits = 2.0;

} // namespace

/// One pass of the overlay: the lines (or their halo) as an unlit actor.
struct LinePass {
  vtkSmartPointer<vtkPolyDataMapper> mapper =
      vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkSmartPointer<vtkActor> actor = vtkSmartPointer<vtkActor>::New();
  LinePass(double width, double offset_units) {
    mapper->SetScalarModeToUseCellData();
    mapper->SetColorModeToDirectScalars();
    mapper->SetRelativeCoincidentTopologyLineOffsetParameters(0, offset_units);
    actor->SetMapper(mapper);
    actor->GetProperty()->SetLineWidth(width);
    actor->GetProperty()->LightingOff();
    actor->GetProperty()->SetRenderLinesAsTubes(false);
    mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
  }
};

struct LineOverlay::Impl {
  LinePass halo{kHaloWidth, kHaloOffsetUnits};
  LinePass line{kLineWidth, kLineOffsetUnits};
  vtkRenderer *renderer = nullptr;
};

LineOverlay::LineOverlay() : impl_(std::make_unique<Impl>()) {}

LineOverlay::~LineOverlay() {
  if (impl_->renderer) {
    impl_->renderer->RemoveActor(impl_->line.actor);
    impl_->renderer->RemoveActor(impl_->halo.actor);
  }
}

void LineOverlay::add_to(vtkRenderer *renderer) {
  if (impl_->renderer == renderer)
    return;
  vtkMapper::SetResolveCoincidentTopologyToPolygonOffset();
  vtkMapper::SetResolveCoincidentTopologyPolygonOffsetParameters(
      kPolygonOffsetFactor, kPolygonOffsetUnits);
  renderer->AddActor(impl_->halo.actor);  // first: the line is drawn over it
  renderer->AddActor(impl_->line.actor);
  impl_->renderer = renderer;
}

void LineOverlay::set_lines(const lines::Polylines &l) {
  // Per line: its type's colour (or the halo's), opacity from its strength.
  auto coloured = [&](bool halo) {
    vtkSmartPointer<vtkPolyData> poly = lines::to_polydata(l);
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetName("Colors");
    colours->SetNumberOfComponents(4);
    colours->SetNumberOfTuples(vtkIdType(l.line_count()));
    for (std::size_t i = 0; i < l.line_count(); ++i) {
      const unsigned char *c =
          halo ? kHalo : kColours[int(l.type[i]) % lines::kLineTypeCount];
      const float a = std::clamp(l.strength[i], 0.0f, 1.0f);
      const unsigned char rgba[4] = {
          c[0], c[1], c[2], static_cast<unsigned char>(255 * a + 0.5f)};
      colours->SetTypedTuple(vtkIdType(i), rgba);
    }
    poly->GetCellData()->SetScalars(colours);
    return poly;
  };
  impl_->line.mapper->SetInputData(coloured(false));
  impl_->halo.mapper->SetInputData(coloured(true));
}

void LineOverlay::set_visible(bool v) {
  impl_->line.actor->SetVisibility(v);
  impl_->halo.actor->SetVisibility(v);
}
bool LineOverlay::visible() const {
  return impl_->line.actor->GetVisibility() != 0;
}

Camera camera_of(vtkCamera *c) {
  Camera cam;
  c->GetPosition(cam.position.data());
  c->GetFocalPoint(cam.focal_point.data());
  c->GetViewUp(cam.view_up.data());
  cam.ortho = c->GetParallelProjection() != 0;
  cam.view_angle_deg = c->GetViewAngle();
  cam.parallel_scale = c->GetParallelScale();
  return cam;
}

} // namespace isocurv::viz
