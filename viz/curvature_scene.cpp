#include "viz/curvature_scene.h"

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataObject.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageMapper.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkShaderProperty.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/framing_points.h"
#include "core/mesh_measures.h"
#include "curvature/field_stats.h"
#include "io/field_arrays.h"
#include "io/polydata.h"
#include "viz/color_map.h"
#include "viz/direction_glyphs.h"
#include "viz/legend.h"
#include "viz/quantity.h"
#include "viz/range_values.h"

namespace isocurv::viz {
namespace {

// Lighting (VTK's headlight): ambient + diffuse + a little specular. With AO on the ambient term
// the ambient weight is raised so that occlusion shows (Griffin et al. weigh it similarly).
constexpr double kAmbient = 0.15, kDiffuse = 0.85;
constexpr double kAmbientWithAo = 0.45, kDiffuseWithAo = 0.55;
constexpr double kSpecular = 0.15, kSpecularPower = 20;
constexpr const char* kAoAttribute = "isocurvAO";  // the vertex shader's input for "AO"

/// Shader replacements that multiply the ambient term of VTK's lighting by the per-vertex AO
/// (a vertex attribute, interpolated across triangles): ambientColor is VTK's ambient term,
/// declared in //VTK::Color::Impl before //VTK::Light::Impl uses it.
void set_ambient_ao(vtkActor* actor, vtkPolyDataMapper* mapper, bool on) {
  vtkShaderProperty* sp = actor->GetShaderProperty();
  sp->ClearAllShaderReplacements();
  mapper->RemoveAllVertexAttributeMappings();
  if (!on) return;
  mapper->MapDataArrayToVertexAttribute(kAoAttribute, "AO", vtkDataObject::FIELD_ASSOCIATION_POINTS,
                                        -1);
  sp->AddVertexShaderReplacement(
      "//VTK::Normal::Dec", true,
      "//VTK::Normal::Dec\nin float isocurvAO;\nout float isocurvAOVS;\n", false);
  sp->AddVertexShaderReplacement("//VTK::Normal::Impl", true,
                                 "//VTK::Normal::Impl\n  isocurvAOVS = isocurvAO;\n", false);
  sp->AddFragmentShaderReplacement("//VTK::Normal::Dec", true,
                                   "//VTK::Normal::Dec\nin float isocurvAOVS;\n", false);
  sp->AddFragmentShaderReplacement(
      "//VTK::Light::Impl", true,
      "  ambientColor *= clamp(isocurvAOVS, 0.0, 1.0);\n//VTK::Light::Impl\n", false);
}

}  // namespace

struct CurvatureScene::Impl {
  vtkSmartPointer<vtkRenderer> overlay = vtkSmartPointer<vtkRenderer>::New();
  vtkSmartPointer<vtkRenderer> renderer = vtkSmartPointer<vtkRenderer>::New();
  vtkSmartPointer<vtkPolyData> surface = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkPolyDataMapper> surface_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkSmartPointer<vtkActor> surface_actor = vtkSmartPointer<vtkActor>::New();
  vtkSmartPointer<vtkPolyDataMapper> halo_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkSmartPointer<vtkActor> halo_actor = vtkSmartPointer<vtkActor>::New();
  vtkSmartPointer<vtkPolyDataMapper> glyph_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  vtkSmartPointer<vtkActor> glyph_actor = vtkSmartPointer<vtkActor>::New();
  vtkSmartPointer<vtkPolyData> glyphs;
  Legend legend{overlay};
  Mesh mesh;
  curvature::CurvatureField field;
  RenderOptions options;
  ColorRange range;
  std::string cmap = "diverging";
  PictureLayout layout;
  int bottom_reserved = 0;
  bool no_data_shown = false;  // some vertex shown is unmeasured (its legend entry is drawn)
  std::vector<double> categories;  // a label map's labels, when Label is shown
  bool glyphs_stale = true;  // the glyphs are built when first needed after a change
  // Screen-space mode: the image, drawn as RGBA pixels by a 2D actor in the overlay.
  bool image_on = false;
  ScreenImage image;
  int image_scale = 1;
  vtkSmartPointer<vtkImageData> image_data = vtkSmartPointer<vtkImageData>::New();
  vtkSmartPointer<vtkImageMapper> image_mapper = vtkSmartPointer<vtkImageMapper>::New();
  vtkSmartPointer<vtkActor2D> image_actor = vtkSmartPointer<vtkActor2D>::New();

  Impl() {
    overlay->SetLayer(0);
    overlay->GradientBackgroundOn();
    overlay->SetBackground(kBackgroundBottom[0], kBackgroundBottom[1], kBackgroundBottom[2]);
    overlay->SetBackground2(kBackgroundTop[0], kBackgroundTop[1], kBackgroundTop[2]);
    overlay->InteractiveOff();
    renderer->SetLayer(1);  // transparent: draws over the overlay's background

    surface_mapper->SetInputData(surface);
    surface_mapper->SetScalarModeToUsePointFieldData();
    surface_mapper->SelectColorArray("Colors");
    surface_mapper->SetColorModeToDirectScalars();
    surface_mapper->ScalarVisibilityOn();
    surface_actor->SetMapper(surface_mapper);
    vtkProperty* p = surface_actor->GetProperty();
    p->SetSpecular(kSpecular);
    p->SetSpecularPower(kSpecularPower);
    renderer->AddActor(surface_actor);

    for (auto [mapper, actor, array] :
         {std::tuple{halo_mapper.Get(), halo_actor.Get(), "Halo"},
          std::tuple{glyph_mapper.Get(), glyph_actor.Get(), "Colors"}}) {
      mapper->SetScalarModeToUseCellFieldData();
      mapper->SelectColorArray(array);
      mapper->SetColorModeToDirectScalars();
      actor->SetMapper(mapper);
      actor->GetProperty()->LightingOff();
      actor->VisibilityOff();
      renderer->AddActor(actor);
    }
    glyph_mapper->SetRelativeCoincidentTopologyLineOffsetParameters(0, -2);  // over the halo

    image_mapper->SetInputData(image_data);
    image_mapper->SetColorWindow(255);  // RGBA bytes drawn as they are
    image_mapper->SetColorLevel(127.5);
    image_actor->SetMapper(image_mapper);
    image_actor->VisibilityOff();
    overlay->AddActor2D(image_actor);
  }

  const std::vector<float>& image_values(const std::string& q) const {
    return q == "K" ? image.K : image.H;
  }

  /// Checks that `o` can be shown with the current field; throws Error otherwise.
  void check(const RenderOptions& o) const {
    resolve_color_map(o.cmap, o.color);
    if (o.range) color_range({}, o.color, 0, o.range);
    if (image_on) {  // the mesh's arrays do not matter
      check_image_quantity(o.color, image);
      return;
    }
    if (mesh.positions.empty()) return;
    resolve_quantity(field, o.color);
    if (uses_ao(o.shading) && field.ao.empty())
      throw Error("AO shading requested but the curvature field has no AO values");
  }

  static void check_image_quantity(const std::string& color, const ScreenImage& img) {
    const std::string q = canonical_quantity(color);
    if (q != "H" && q != "K") throw Error("screen-space mode shows H or K, not " + q);
    if (q == "K" && img.pixels() > 0 && img.K.empty())
      throw Error("this screen-space estimator gives no K (mean curvature only)");
  }

  void relayout() {
    const std::string q = canonical_quantity(options.color);
    const std::string unit = quantity_unit(q, options.length_unit);
    const std::string label = quantity_label(q);
    const std::string legend_title = unit.empty() ? label : label + "\n" + unit;
    const bool listed = !image_on && quantity_kind(q) == QuantityKind::label && !categories.empty();
    layout = layout_picture(options.width, options.height, options.title, legend_title, range.lo,
                            range.hi, bottom_reserved, no_data_shown && !image_on,
                            listed ? &categories : nullptr);
    // The surface's box no wider than for the widest values, under this legend's title or a
    // reference one, so that neither the values (a screen-space image's) nor the coloured array
    // move the camera.
    layout.surface.x1 = std::min(layout.surface.x1,
                                 stable_surface_right(options.width, options.height, options.title,
                                                      legend_title, bottom_reserved));
    const PixelBox& s = layout.surface;
    const double w = std::max(1, options.width), h = std::max(1, options.height);
    renderer->SetViewport(s.x0 / w, s.y0 / h, s.x1 / w, s.y1 / h);
    legend.update(layout, cmap, range, image_on ? image.pixels() > 0 : !mesh.positions.empty());
    if (image_on) fill_image();
    // Lines a little wider in big pictures; the halo two pixels wider than the line.
    const double line = std::max(1.0, std::round(std::min(w, h) / 400.0));
    glyph_actor->GetProperty()->SetLineWidth(static_cast<float>(line));
    halo_actor->GetProperty()->SetLineWidth(static_cast<float>(line + 2));
  }

  void build_glyphs() {
    if (!glyphs_stale && glyphs) return;
    glyphs = direction_glyphs(mesh, field, glyph_options(options));
    glyph_mapper->SetInputData(glyphs);
    halo_mapper->SetInputData(glyphs);
    glyphs_stale = false;
  }

  /// The image's pixels coloured into image_data, which covers layout.surface; invalid pixels
  /// (and the box beyond the image) are transparent, so the background shows.
  void fill_image() {
    const PixelBox& box = layout.surface;
    const int bw = std::max(1, box.x1 - box.x0), bh = std::max(1, box.y1 - box.y0);
    image_data->SetDimensions(bw, bh, 1);
    image_data->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
    auto* rgba = static_cast<unsigned char*>(image_data->GetScalarPointer());
    std::fill(rgba, rgba + 4 * std::size_t(bw) * bh, static_cast<unsigned char>(0));
    const std::string q = canonical_quantity(options.color);
    const std::vector<float>& values = image_values(q);
    if (image.pixels() > 0 && values.size() == image.pixels()) {
      auto colors = vertex_colors(values, range, make_color_map(range, cmap),
                                  image.shade.empty() ? nullptr : &image.shade);
      const unsigned char* c = colors->GetPointer(0);
      for (int y = 0; y < bh; ++y) {
        const int iy = y / image_scale;
        if (iy >= image.height) break;
        for (int x = 0; x < bw; ++x) {
          const int ix = x / image_scale;
          if (ix >= image.width) break;
          const std::size_t i = std::size_t(ix) + std::size_t(image.width) * iy;
          if (!image.valid[i]) continue;
          unsigned char* px = rgba + 4 * (std::size_t(x) + std::size_t(bw) * y);
          px[0] = c[3 * i], px[1] = c[3 * i + 1], px[2] = c[3 * i + 2], px[3] = 255;
        }
      }
    }
    image_data->Modified();
    image_actor->SetPosition(box.x0, box.y0);
    image_actor->SetVisibility(image.pixels() > 0);
  }

  void recolor_image() {
    const std::string q = canonical_quantity(options.color);
    cmap = resolve_color_map(options.cmap, q);
    const std::vector<float>& values = image_values(q);
    std::vector<float> shown;
    if (values.size() == image.pixels()) {
      shown.reserve(values.size());
      for (std::size_t i = 0; i < values.size(); ++i)
        if (image.valid[i]) shown.push_back(values[i]);
    }
    range = shown.empty() ? (options.range ? *options.range : ColorRange{})
                          : color_range(shown, q, options.clamp_percentile, options.range);
    relayout();  // fills the image
  }

  void recolor() {
    const std::string q = canonical_quantity(options.color);
    cmap = resolve_color_map(options.cmap, q);
    surface_actor->SetVisibility(!image_on);
    if (image_on) {
      glyph_actor->VisibilityOff();
      halo_actor->VisibilityOff();
      recolor_image();
      return;
    }
    image_actor->VisibilityOff();
    const bool shown = !mesh.positions.empty();
    glyph_actor->SetVisibility(options.dirs && shown);
    halo_actor->SetVisibility(options.dirs && shown);
    if (options.dirs && shown) build_glyphs();
    if (!shown) {
      range = options.range ? *options.range : ColorRange{};
      relayout();
      return;
    }
    const std::vector<float> values = quantity_values(field, q);
    // The range comes from the vertices the statistics count (curvature::field_stats: measured,
    // finite, not a spike the mesh cannot resolve), less the open-boundary ones (a surface cut
    // by the volume's box), whose one-sided curvature is an artefact that would otherwise set
    // the scale. The unmeasured vertices (flagged Unreliable) take the "no data" colour.
    const std::vector<std::uint8_t>* unmeasured =
        field.unreliable.size() == values.size() && quantity_kind(q) != QuantityKind::flag ? &field.unreliable
                                                                                           : nullptr;
    no_data_shown = unmeasured && std::any_of(unmeasured->begin(), unmeasured->end(), [](std::uint8_t u) { return u; });
    range = options.range ? color_range({}, q, options.clamp_percentile, options.range)
                          : color_range(range_values(mesh, field, q), q, options.clamp_percentile);
    vtkPointData* pd = surface->GetPointData();
    pd->RemoveArray("Colors");
    const std::vector<float>* shade = options.shading == Shading::both ? &field.ao : nullptr;
    categories.clear();
    if (quantity_kind(q) == QuantityKind::label) {  // a label map: a colour per label
      categories = categories_of(values);
      pd->AddArray(categorical_vertex_colors(values, categories, shade, unmeasured, no_data_color(cmap)));
    } else {
      pd->AddArray(vertex_colors(values, range, make_color_map(range, cmap), shade, unmeasured,
                                 no_data_color(cmap)));
    }
    pd->RemoveArray("AO");
    const bool ambient_ao = options.shading == Shading::ambient_ao;
    if (ambient_ao) {
      auto ao = vtkSmartPointer<vtkFloatArray>::New();
      ao->SetName("AO");
      ao->SetNumberOfTuples(static_cast<vtkIdType>(field.ao.size()));
      for (std::size_t i = 0; i < field.ao.size(); ++i)
        ao->SetValue(static_cast<vtkIdType>(i), std::isfinite(field.ao[i]) ? field.ao[i] : 1.f);
      pd->AddArray(ao);
    }
    set_ambient_ao(surface_actor, surface_mapper, ambient_ao);
    vtkProperty* p = surface_actor->GetProperty();
    p->SetAmbient(ambient_ao ? kAmbientWithAo : kAmbient);
    p->SetDiffuse(ambient_ao ? kDiffuseWithAo : kDiffuse);
    surface->Modified();
    relayout();
  }
};

CurvatureScene::CurvatureScene() : impl_(std::make_unique<Impl>()) { impl_->recolor(); }
CurvatureScene::~CurvatureScene() = default;

vtkRenderer* CurvatureScene::renderer() const { return impl_->renderer; }
vtkRenderer* CurvatureScene::overlay() const { return impl_->overlay; }

void CurvatureScene::attach(vtkRenderWindow* window) {
  window->SetNumberOfLayers(2);
  window->AddRenderer(impl_->overlay);
  window->AddRenderer(impl_->renderer);
}

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
  curvature::CurvatureField
      shading;  // the surface polydata carries normals (for lighting) and colours
  shading.normals = s.field.normals;
  s.surface = io::to_polydata(s.mesh, &shading);
  s.surface_mapper->SetInputData(s.surface);
  s.glyphs_stale = true;
  s.recolor();
}

void CurvatureScene::set_options(const RenderOptions& options) {
  impl_->check(options);
  const RenderOptions& old = impl_->options;
  if (options.dirs_count != old.dirs_count || options.dirs_length != old.dirs_length ||
      options.width != old.width || options.height != old.height)
    impl_->glyphs_stale = true;
  impl_->options = options;
  impl_->recolor();
}

const RenderOptions& CurvatureScene::options() const { return impl_->options; }

void CurvatureScene::set_size(int width, int height) {
  if (width == impl_->options.width && height == impl_->options.height) return;
  impl_->options.width = width;
  impl_->options.height = height;
  impl_->relayout();
}

void CurvatureScene::set_bottom_reserved(int pixels) {
  impl_->bottom_reserved = pixels;
  impl_->relayout();
}

void CurvatureScene::set_image_mode(bool on) {
  Impl& s = *impl_;
  if (on == s.image_on) return;
  if (on) Impl::check_image_quantity(s.options.color, s.image);
  s.image_on = on;
  s.recolor();
}

bool CurvatureScene::image_mode() const { return impl_->image_on; }

void CurvatureScene::set_image(const ScreenImage& image, int scale) {
  const std::size_t n = image.pixels();
  if (image.width < 0 || image.height < 0 || image.H.size() != n || image.valid.size() != n ||
      (!image.K.empty() && image.K.size() != n) ||
      (!image.shade.empty() && image.shade.size() != n))
    throw Error("screen-space image: arrays do not match its " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " pixels");
  if (scale < 1) throw Error("screen-space image: scale must be at least 1");
  Impl& s = *impl_;
  if (s.image_on) Impl::check_image_quantity(s.options.color, image);
  s.image = image;
  s.image_scale = scale;
  if (s.image_on) s.recolor();
}

const PictureLayout& CurvatureScene::layout() const { return impl_->layout; }
double CurvatureScene::range_lo() const { return impl_->range.lo; }
double CurvatureScene::range_hi() const { return impl_->range.hi; }
const std::string& CurvatureScene::color_map() const { return impl_->cmap; }

vtkPolyData* CurvatureScene::glyphs() {
  impl_->build_glyphs();
  return impl_->glyphs;
}

Camera CurvatureScene::frame_camera(const std::array<double, 6>* bounds) {
  const RenderOptions& o = impl_->options;
  if (o.camera) {
    apply_camera(impl_->renderer, *o.camera);
    return *o.camera;
  }
  const PixelBox& s = impl_->layout.surface;
  const double aspect =
      s.empty() ? double(o.width) / double(o.height) : double(s.x1 - s.x0) / double(s.y1 - s.y0);
  const Camera cam = bounds                      ? fit_camera(*bounds, o.view, aspect)
                     : !o.frame_points.empty() ? fit_camera_to_points(o.frame_points, o.view, aspect)
                                               : fit_camera_to_points(framing_points(impl_->mesh), o.view, aspect);
  apply_camera(impl_->renderer, cam);
  return cam;
}

Camera CurvatureScene::current_camera() const {
  vtkCamera* c = impl_->renderer->GetActiveCamera();
  Camera cam;
  c->GetPosition(cam.position.data());
  c->GetFocalPoint(cam.focal_point.data());
  c->GetViewUp(cam.view_up.data());
  cam.ortho = c->GetParallelProjection() != 0;
  cam.view_angle_deg = c->GetViewAngle();
  cam.parallel_scale = c->GetParallelScale();
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
