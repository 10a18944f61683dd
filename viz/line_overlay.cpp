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
// Lines are pulled towards the camera by this many depth-buffer units (VTK's
// coincident topology offset for lines) and polygons pushed back by their slope
// (the global polygon offset).
constexpr double kLineOffsetUnits = -4.0;
constexpr double kPolygonOffsetFactor = 2.0, kPolygonOffsetUnits = 2.0;

} // namespace

struct LineOverlay::Impl {
  vtkSmartPointer<vtkPolyDataMapper> mapper =
      vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkSmartPointer<vtkActor> actor = vtkSmartPointer<vtkActor>::New();
  vtkRenderer *renderer = nullptr;
};

LineOverlay::LineOverlay() : impl_(std::make_unique<Impl>()) {
  Impl &m = *impl_;
  m.mapper->SetScalarModeToUseCellData();
  m.mapper->SetColorModeToDirectScalars();
  m.mapper->SetRelativeCoincidentTopologyLineOffsetParameters(0,
                                                              kLineOffsetUnits);
  m.actor->SetMapper(m.mapper);
  m.actor->GetProperty()->SetLineWidth(kLineWidth);
  m.actor->GetProperty()->LightingOff();
  m.actor->GetProperty()->SetRenderLinesAsTubes(false);
  m.mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
}

LineOverlay::~LineOverlay() {
  if (impl_->renderer)
    impl_->renderer->RemoveActor(impl_->actor);
}

void LineOverlay::add_to(vtkRenderer *renderer) {
  if (impl_->renderer == renderer)
    return;
  vtkMapper::SetResolveCoincidentTopologyToPolygonOffset();
  vtkMapper::SetResolveCoincidentTopologyPolygonOffsetParameters(
      kPolygonOffsetFactor, kPolygonOffsetUnits);
  renderer->AddActor(impl_->actor);
  impl_->renderer = renderer;
}

void LineOverlay::set_lines(const lines::Polylines &l) {
  vtkSmartPointer<vtkPolyData> poly = lines::to_polydata(l);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colors");
  colours->SetNumberOfComponents(4);
  colours->SetNumberOfTuples(vtkIdType(l.line_count()));
  for (std::size_t i = 0; i < l.line_count(); ++i) {
    const unsigned char *c = kColours[int(l.type[i]) % lines::kLineTypeCount];
    const float a = std::clamp(l.strength[i], 0.0f, 1.0f);
    const unsigned char rgba[4] = {c[0], c[1], c[2],
                                   static_cast<unsigned char>(255 * a + 0.5f)};
    colours->SetTypedTuple(vtkIdType(i), rgba);
  }
  poly->GetCellData()->SetScalars(colours);
  impl_->mapper->SetInputData(poly);
}

void LineOverlay::set_visible(bool v) { impl_->actor->SetVisibility(v); }
bool LineOverlay::visible() const { return impl_->actor->GetVisibility() != 0; }

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
