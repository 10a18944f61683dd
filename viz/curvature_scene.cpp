#include "viz/curvature_scene.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include "core/error.h"
#include "io/field_arrays.h"
#include "io/polydata.h"
#include "viz/color_map.h"
#include "viz/direction_glyphs.h"
#include "viz/quantity.h"

namespace isocurv::viz {

struct CurvatureScene::Impl {
  vtkSmartPointer<vtkRenderer> renderer = vtkSmartPointer<vtkRenderer>::New();
  vtkSmartPointer<vtkPolyData> surface = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkPolyDataMapper> surface_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkSmartPointer<vtkActor> surface_actor = vtkSmartPointer<vtkActor>::New();
  vtkSmartPointer<vtkPolyDataMapper> glyph_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkSmartPointer<vtkActor> glyph_actor = vtkSmartPointer<vtkActor>::New();
  vtkSmartPointer<vtkScalarBarActor> scalar_bar = vtkSmartPointer<vtkScalarBarActor>::New();
  vtkSmartPointer<vtkTextActor> title = vtkSmartPointer<vtkTextActor>::New();
  Mesh mesh;
  curvature::CurvatureField field;
  RenderOptions options;
  ColorRange range;
  bool glyphs_stale = true;  // the glyphs are built when first shown after a surface change

  Impl() {
    renderer->GradientBackgroundOn();
    renderer->SetBackground(0.08, 0.08, 0.10);
    renderer->SetBackground2(0.30, 0.31, 0.36);

    surface_mapper->SetInputData(surface);
    surface_mapper->SetScalarModeToUsePointFieldData();
    surface_mapper->SelectColorArray("Colors");
    surface_mapper->SetColorModeToDirectScalars();
    surface_mapper->ScalarVisibilityOn();
    surface_actor->SetMapper(surface_mapper);
    vtkProperty* p = surface_actor->GetProperty();
    p->SetAmbient(0.15);
    p->SetDiffuse(0.85);
    p->SetSpecular(0.15);
    p->SetSpecularPower(20);
    renderer->AddActor(surface_actor);

    glyph_mapper->SetScalarModeToUseCellData();
    glyph_mapper->SetColorModeToDirectScalars();
    glyph_actor->SetMapper(glyph_mapper);
    glyph_actor->GetProperty()->SetLineWidth(2);
    glyph_actor->GetProperty()->LightingOff();
    glyph_actor->VisibilityOff();
    renderer->AddActor(glyph_actor);

    scalar_bar->SetNumberOfLabels(5);
    scalar_bar->SetLabelFormat("%-#6.3g");
    scalar_bar->SetMaximumWidthInPixels(110);
    scalar_bar->SetBarRatio(0.25);
    scalar_bar->GetPositionCoordinate()->SetValue(0.88, 0.12);
    scalar_bar->SetWidth(0.11);
    scalar_bar->SetHeight(0.72);
    scalar_bar->UnconstrainedFontSizeOn();
    scalar_bar->GetTitleTextProperty()->SetFontSize(18);
    scalar_bar->GetLabelTextProperty()->SetFontSize(14);
    for (vtkTextProperty* t : {scalar_bar->GetTitleTextProperty(), scalar_bar->GetLabelTextProperty()}) {
      t->SetColor(1, 1, 1);
      t->ItalicOff();
      t->ShadowOff();
    }
    renderer->AddViewProp(scalar_bar);

    title->GetTextProperty()->SetFontSize(20);
    title->GetTextProperty()->SetColor(1, 1, 1);
    title->GetTextProperty()->SetJustificationToCentered();
    title->GetTextProperty()->SetVerticalJustificationToTop();
    title->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    title->GetPositionCoordinate()->SetValue(0.5, 0.97);
    title->VisibilityOff();
    renderer->AddViewProp(title);
  }

  /// Checks that `o` can be shown with the current field; throws Error otherwise.
  void check(const RenderOptions& o) const {
    canonical_quantity(o.color);
    if (mesh.positions.empty()) return;
    quantity_values(field, o.color);
    if (o.ao && field.ao.empty()) throw Error("AO shading requested but the curvature field has no AO values");
  }

  void recolor() {
    const std::string q = canonical_quantity(options.color);
    scalar_bar->SetTitle((options.ao ? q + " (AO)" : q).c_str());
    title->SetInput(options.title.c_str());
    title->SetVisibility(!options.title.empty());
    glyph_actor->SetVisibility(options.dirs && !mesh.positions.empty());
    if (options.dirs && glyphs_stale) {
      glyph_mapper->SetInputData(direction_glyphs(mesh, field));
      glyphs_stale = false;
    }
    if (mesh.positions.empty()) {
      range = {};
      scalar_bar->SetLookupTable(make_color_map(range));
      return;
    }
    const std::vector<float>& values = quantity_values(field, q);
    range = color_range(values, q, options.clamp_percentile);
    auto map = make_color_map(range);
    surface->GetPointData()->RemoveArray("Colors");
    surface->GetPointData()->AddArray(vertex_colors(values, range, map, options.ao ? &field.ao : nullptr));
    surface->Modified();
    scalar_bar->SetLookupTable(map);
  }
};

CurvatureScene::CurvatureScene() : impl_(std::make_unique<Impl>()) { impl_->recolor(); }
CurvatureScene::~CurvatureScene() = default;

vtkRenderer* CurvatureScene::renderer() const { return impl_->renderer; }

void CurvatureScene::set_surface(const Mesh& mesh, const curvature::CurvatureField& field) {
  io::check_field_sizes(field, mesh.positions.size(), "surface");
  Impl& s = *impl_;
  Mesh old_mesh = std::move(s.mesh);
  curvature::CurvatureField old_field = std::move(s.field);
  s.mesh = mesh;
  s.field = field;
  try {
    s.check(s.options);
  } catch (...) {
    s.mesh = std::move(old_mesh);
    s.field = std::move(old_field);
    throw;
  }
  s.mesh.edge_keys.clear();
  curvature::CurvatureField shading;  // the surface polydata carries normals (for lighting) and colours
  shading.normals = s.field.normals;
  s.surface = io::to_polydata(s.mesh, &shading);
  s.surface_mapper->SetInputData(s.surface);
  s.glyphs_stale = true;
  s.recolor();
}

void CurvatureScene::set_options(const RenderOptions& options) {
  impl_->check(options);
  impl_->options = options;
  impl_->recolor();
}

const RenderOptions& CurvatureScene::options() const { return impl_->options; }
double CurvatureScene::range_lo() const { return impl_->range.lo; }
double CurvatureScene::range_hi() const { return impl_->range.hi; }

Camera CurvatureScene::frame_camera() {
  double b[6];
  impl_->surface->GetBounds(b);
  const RenderOptions& o = impl_->options;
  const Camera cam = fit_camera({b[0], b[1], b[2], b[3], b[4], b[5]}, o.view,
                                double(o.width) / double(o.height));
  apply_camera(impl_->renderer, cam);
  return cam;
}

void apply_camera(vtkRenderer* renderer, const Camera& cam) {
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(cam.focal_point.data());
  camera->SetPosition(cam.position.data());
  camera->SetViewUp(cam.view_up.data());
  camera->SetParallelProjection(cam.ortho ? 1 : 0);
  camera->SetViewAngle(cam.view_angle_deg);
  camera->SetParallelScale(cam.parallel_scale);
  renderer->ResetCameraClippingRange();
}

}  // namespace isocurv::viz
