#include "viz/legend.h"

#include <vtkActor2D.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkColorTransferFunction.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty2D.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <vector>

namespace isocurv::viz {
namespace {

constexpr int kBarSteps = 256;
constexpr double kTextGrey = 0.95;
constexpr double kFrameGrey = 0.75;

vtkSmartPointer<vtkTextActor> make_text(vtkRenderer* r) {
  auto t = vtkSmartPointer<vtkTextActor>::New();
  vtkTextProperty* p = t->GetTextProperty();
  p->SetFontFamilyToArial();  // as measure_text
  p->SetJustificationToLeft();
  p->SetVerticalJustificationToBottom();
  p->SetColor(kTextGrey, kTextGrey, kTextGrey);
  p->ItalicOff();
  p->BoldOff();
  p->ShadowOff();
  t->VisibilityOff();
  r->AddViewProp(t);
  return t;
}

void show(vtkTextActor* a, const PlacedText& t, bool visible) {
  a->SetInput(t.text.c_str());
  a->GetTextProperty()->SetFontSize(t.font_px);
  a->SetPosition(t.x, t.y);
  a->SetVisibility(visible && !t.text.empty());
}

/// Appends `box` to `points` and `cells` as one quad.
void add_box(vtkPoints* points, vtkCellArray* cells, const PixelBox& box) {
  const vtkIdType first = points->GetNumberOfPoints();
  points->InsertNextPoint(box.x0, box.y0, 0);
  points->InsertNextPoint(box.x1, box.y0, 0);
  points->InsertNextPoint(box.x1, box.y1, 0);
  points->InsertNextPoint(box.x0, box.y1, 0);
  const vtkIdType q[4] = {first, first + 1, first + 2, first + 3};
  cells->InsertNextCell(4, q);
}

/// Appends the colour `rgb` (components in [0, 1]) to `colors` as bytes.
void add_color(vtkUnsignedCharArray* colors, const double rgb[3]) {
  const unsigned char c[3] = {static_cast<unsigned char>(255 * rgb[0] + 0.5),
                              static_cast<unsigned char>(255 * rgb[1] + 0.5),
                              static_cast<unsigned char>(255 * rgb[2] + 0.5)};
  colors->InsertNextTypedTuple(c);
}

}  // namespace

struct Legend::Impl {
  vtkRenderer* renderer;
  vtkSmartPointer<vtkTextActor> title, legend_title;
  std::vector<vtkSmartPointer<vtkTextActor>> labels;
  vtkSmartPointer<vtkPolyData> bar = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkActor2D> bar_actor = vtkSmartPointer<vtkActor2D>::New();
  vtkSmartPointer<vtkTextActor> no_data_label;
  vtkSmartPointer<vtkPolyData> swatch = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkActor2D> swatch_actor = vtkSmartPointer<vtkActor2D>::New();
  vtkSmartPointer<vtkPolyData> frame = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkActor2D> frame_actor = vtkSmartPointer<vtkActor2D>::New();
  vtkSmartPointer<vtkPolyData> categories = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkActor2D> categories_actor = vtkSmartPointer<vtkActor2D>::New();

  explicit Impl(vtkRenderer* r) : renderer(r) {
    title = make_text(r);
    legend_title = make_text(r);
    no_data_label = make_text(r);
    auto swatch_mapper = vtkSmartPointer<vtkPolyDataMapper2D>::New();
    swatch_mapper->SetInputData(swatch);
    swatch_mapper->ScalarVisibilityOff();
    swatch_actor->SetMapper(swatch_mapper);
    r->AddViewProp(swatch_actor);
    auto bar_mapper = vtkSmartPointer<vtkPolyDataMapper2D>::New();
    bar_mapper->SetInputData(bar);
    bar_mapper->SetScalarModeToUseCellData();
    bar_mapper->SetColorModeToDirectScalars();
    bar_actor->SetMapper(bar_mapper);
    r->AddViewProp(bar_actor);
    auto frame_mapper = vtkSmartPointer<vtkPolyDataMapper2D>::New();
    frame_mapper->SetInputData(frame);
    frame_mapper->ScalarVisibilityOff();
    frame_actor->SetMapper(frame_mapper);
    frame_actor->GetProperty()->SetColor(kFrameGrey, kFrameGrey, kFrameGrey);
    r->AddViewProp(frame_actor);
    auto categories_mapper = vtkSmartPointer<vtkPolyDataMapper2D>::New();
    categories_mapper->SetInputData(categories);
    categories_mapper->SetScalarModeToUseCellData();
    categories_mapper->SetColorModeToDirectScalars();
    categories_actor->SetMapper(categories_mapper);
    categories_actor->VisibilityOff();
    r->AddViewProp(categories_actor);
  }
};

Legend::Legend(vtkRenderer* renderer) : impl_(std::make_unique<Impl>(renderer)) {}
Legend::~Legend() = default;

void Legend::update(const PictureLayout& layout, const std::string& cmap, const ColorRange& range,
                    bool show_bar) {
  Impl& s = *impl_;
  show(s.title, layout.title, true);
  show(s.legend_title, layout.legend_title, show_bar);
  while (s.labels.size() < layout.labels.size()) s.labels.push_back(make_text(s.renderer));
  for (std::size_t i = 0; i < s.labels.size(); ++i)
    if (i < layout.labels.size())
      show(s.labels[i], layout.labels[i], show_bar);
    else
      s.labels[i]->VisibilityOff();

  // The bar: kBarSteps quads, each the map's colour at its middle value.
  const PixelBox& b = layout.bar;
  auto map = make_color_map(range, cmap);
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto quads = vtkSmartPointer<vtkCellArray>::New();
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetNumberOfComponents(3);
  for (int i = 0; i <= kBarSteps; ++i) {
    const double y = b.y0 + (b.y1 - b.y0) * double(i) / kBarSteps;
    points->InsertNextPoint(b.x0, y, 0);
    points->InsertNextPoint(b.x1, y, 0);
  }
  for (int i = 0; i < kBarSteps; ++i) {
    const vtkIdType ids[4] = {2 * i, 2 * i + 1, 2 * i + 3, 2 * i + 2};
    quads->InsertNextCell(4, ids);
    double rgb[3];
    map->GetColor(range.lo + (range.hi - range.lo) * (i + 0.5) / kBarSteps, rgb);
    add_color(colors, rgb);
  }
  s.bar->SetPoints(points);
  s.bar->SetPolys(quads);
  s.bar->GetCellData()->SetScalars(colors);
  s.bar->Modified();

  auto fpoints = vtkSmartPointer<vtkPoints>::New();
  fpoints->InsertNextPoint(b.x0 - 1, b.y0 - 1, 0);
  fpoints->InsertNextPoint(b.x1, b.y0 - 1, 0);
  fpoints->InsertNextPoint(b.x1, b.y1, 0);
  fpoints->InsertNextPoint(b.x0 - 1, b.y1, 0);
  auto loop = vtkSmartPointer<vtkCellArray>::New();
  const vtkIdType ids[5] = {0, 1, 2, 3, 0};
  loop->InsertNextCell(5, ids);
  s.frame->SetPoints(fpoints);
  s.frame->SetLines(loop);
  s.frame->Modified();
  // A label map's legend: a swatch per label shown, in its category's colour, for the bar.
  const bool listed = !layout.swatches.empty();
  s.bar_actor->SetVisibility(show_bar && !listed);
  s.frame_actor->SetVisibility(show_bar && !listed);
  s.categories_actor->SetVisibility(show_bar && listed);
  if (listed) {
    auto cpoints = vtkSmartPointer<vtkPoints>::New();
    auto cquads = vtkSmartPointer<vtkCellArray>::New();
    auto ccolors = vtkSmartPointer<vtkUnsignedCharArray>::New();
    ccolors->SetNumberOfComponents(3);
    for (std::size_t i = 0; i < layout.swatches.size(); ++i) {
      add_box(cpoints, cquads, layout.swatches[i]);
      add_color(ccolors, categorical_color(layout.swatch_category[i]).data());
    }
    s.categories->SetPoints(cpoints);
    s.categories->SetPolys(cquads);
    s.categories->GetCellData()->SetScalars(ccolors);
    s.categories->Modified();
  }

  // The "no data" swatch: a square of that colour with a frame like the bar's.
  const PixelBox& n = layout.no_data;
  const bool swatch_on = show_bar && !n.empty();
  show(s.no_data_label, layout.no_data_label, swatch_on);
  if (swatch_on) {
    auto sp = vtkSmartPointer<vtkPoints>::New();
    auto quad = vtkSmartPointer<vtkCellArray>::New();
    add_box(sp, quad, n);
    s.swatch->SetPoints(sp);
    s.swatch->SetPolys(quad);
    s.swatch->Modified();
    const std::array<double, 3> c = no_data_color(cmap);
    s.swatch_actor->GetProperty()->SetColor(c[0], c[1], c[2]);
  }
  s.swatch_actor->SetVisibility(swatch_on);
}

}  // namespace isocurv::viz
