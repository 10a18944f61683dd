#include "viz/picture_layout.h"

#include <vtkNew.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace isocurv::viz {
namespace {

constexpr int kTicks = 5;
constexpr const char* kNoDataText = "no data";
constexpr int kMinFontPx = 7;
constexpr int kMaxFontPx = 48;
constexpr double kFontPerPixel = 1.0 / 36;   // font size per pixel of the image's smaller side
constexpr double kTitleFontScale = 1.25;     // the title's font beside the labels'
constexpr double kMaxLegendWidth = 0.40;     // of the image width
constexpr double kBarHeightFraction = 0.65;  // of the height left free for the legend
constexpr double kBarWidthPerFont = 1.1;
constexpr int kDpi = 72;  // vtkTextActor's default: points are pixels

int width_of(const PixelBox& b) { return b.x1 - b.x0; }
int height_of(const PixelBox& b) { return b.y1 - b.y0; }

/// Places `text` at `font_px` so that its ink's left-bottom corner is at (x, y).
PlacedText place(const std::string& text, int font_px, int x, int y) {
  PlacedText t;
  t.text = text;
  t.font_px = font_px;
  const PixelBox m = measure_text(text, font_px);
  t.x = x - m.x0;
  t.y = y - m.y0;
  t.box = {x, y, x + width_of(m), y + height_of(m)};
  return t;
}

std::string more_label(std::size_t n) { return "+" + std::to_string(n) + " more"; }

/// The box around `a` and `b` (either may be empty).
PixelBox united(const PixelBox& a, const PixelBox& b) {
  if (b.empty()) return a;
  if (a.empty()) return b;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

/// layout_picture's legend for a label map: a swatch and its value per label, top to bottom, as
/// many as fit the column's height (the last line then counts the rest).
PictureLayout layout_categories(PictureLayout l, int width, int top, int pad, int font,
                                const std::string& legend_title, int bottom_reserved,
                                bool no_data, const std::vector<double>& categories) {
  for (;; --font) {
    const PixelBox tm = measure_text(legend_title, font);
    const int swatch_w = std::max(4, static_cast<int>(std::lround(kBarWidthPerFont * font)));
    const int title_y = top - pad - height_of(tm);
    const int free_top = legend_title.empty() ? top - pad : title_y - pad;
    const int label_h = height_of(measure_text("0123456789", font));
    const PixelBox nm = no_data ? measure_text(kNoDataText, font) : PixelBox{};
    const int entry_h = std::max(label_h, 4) + pad;
    const int free_bottom = bottom_reserved + pad + (no_data ? entry_h + pad : 0);
    const std::size_t fit = static_cast<std::size_t>(std::max(1, (free_top - free_bottom) / entry_h));
    const std::size_t shown = categories.size() <= fit ? categories.size() : fit - 1;
    std::vector<std::string> texts;
    for (std::size_t i = 0; i < shown; ++i) texts.push_back(category_label(categories[i]));
    if (shown < categories.size()) texts.push_back(more_label(categories.size() - shown));
    int label_w = width_of(nm);
    for (const std::string& t : texts) label_w = std::max(label_w, width_of(measure_text(t, font)));
    const int column = std::max(width_of(tm), swatch_w + pad + label_w) + 2 * pad;
    if (column > kMaxLegendWidth * width && font > kMinFontPx) continue;

    const int x0 = width - column + pad;
    l.legend_title = place(legend_title, font, x0, title_y);
    l.legend = l.legend_title.box;
    auto grow = [&l](const PixelBox& b) { l.legend = united(l.legend, b); };
    l.bar = {};
    l.ticks.clear();
    l.labels.clear();
    l.swatches.clear();
    l.swatch_category.clear();
    for (std::size_t i = 0; i < texts.size(); ++i) {
      const int y1 = free_top - static_cast<int>(i) * entry_h, y0 = y1 - entry_h + pad;
      const PixelBox m = measure_text(texts[i], font);
      if (i < shown) {
        l.swatches.push_back({x0, y0, x0 + swatch_w, y1});
        l.swatch_category.push_back(i);
        grow(l.swatches.back());
      }
      l.labels.push_back(place(texts[i], font, x0 + swatch_w + pad, y0 + (y1 - y0 - height_of(m)) / 2));
      grow(l.labels.back().box);
    }
    l.no_data = {};
    l.no_data_label = {};
    if (no_data) {
      const int y1 = free_top - static_cast<int>(texts.size()) * entry_h - pad, y0 = y1 - entry_h + pad;
      l.no_data = {x0, y0, x0 + swatch_w, y1};
      l.no_data_label = place(kNoDataText, font, l.no_data.x1 + pad, y0 + (y1 - y0 - height_of(nm)) / 2);
      grow(l.no_data);
      grow(l.no_data_label.box);
    }
    l.surface = {0, bottom_reserved, width - column, top};
    return l;
  }
}

}  // namespace

PixelBox measure_text(const std::string& text, int font_px) {
  if (text.empty()) return {};
  vtkNew<vtkTextProperty> p;
  p->SetFontFamilyToArial();
  p->SetFontSize(font_px);
  p->SetJustificationToLeft();
  p->SetVerticalJustificationToBottom();
  p->ItalicOff();
  p->BoldOff();
  p->ShadowOff();
  int bbox[4] = {0, 0, 0, 0};
  vtkTextRenderer* r = vtkTextRenderer::GetInstance();
  if (!r || !r->GetBoundingBox(p, vtkStdString(text), bbox, kDpi)) {
    // no FreeType: a generous estimate (0.65 em per character, 1.2 em per line)
    const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    return {0, 0, static_cast<int>(0.65 * font_px * static_cast<double>(text.size())),
            static_cast<int>(1.2 * font_px * lines)};
  }
  // vtkTextRenderer's bbox is inclusive: [xmin, xmax] x [ymin, ymax]
  return {bbox[0], bbox[2], bbox[1] + 1, bbox[3] + 1};
}

std::string tick_label(double value, double range) {
  if (std::fabs(value) <= 1e-9 * std::fabs(range)) value = 0;
  // Enough significant digits that neighbouring ticks (a quarter of the range apart) differ:
  // one below the step's leading digit, at least 3 ("0.52359" on a range of 2e-5, not "0.524").
  int digits = 3;
  const double step = std::fabs(range) / (kTicks - 1);
  if (value != 0 && step > 0 && std::isfinite(step))
    digits = std::clamp(
        static_cast<int>(std::floor(std::log10(std::fabs(value))) - std::floor(std::log10(step))) +
            1,
        3, 15);
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

int stable_surface_right(int width, int height, const std::string& title,
                         const std::string& legend_title, int bottom_reserved) {
  constexpr const char* kReferenceTitle = "Curvedness\n1/length\u00b2";
  int right = width;
  for (const std::string& t : {legend_title, std::string(kReferenceTitle)})
    right = std::min(right, layout_picture(width, height, title, t, -kWidestLegendValue, kWidestLegendValue,
                                           bottom_reserved)
                                .surface.x1);
  return right;
}

std::string category_label(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

PictureLayout layout_picture(int width, int height, const std::string& title,
                             const std::string& legend_title, double lo, double hi,
                             int bottom_reserved, bool no_data,
                             const std::vector<double>* categories) {
  PictureLayout l;
  l.width = width;
  l.height = height;
  const int small = std::max(1, std::min(width, height));
  const int pad = std::max(3, static_cast<int>(std::lround(0.012 * small)));
  int font = std::clamp(static_cast<int>(std::lround(small * kFontPerPixel)), 9, kMaxFontPx);
  bottom_reserved = std::clamp(bottom_reserved, 0, height / 2);

  // The title: shrink the font, then shorten the text, until it fits.
  int top = height;  // the free part's top edge
  if (!title.empty()) {
    const int avail = width - 2 * pad;
    int tf = static_cast<int>(std::lround(kTitleFontScale * font));
    std::string text = title;
    while (tf > kMinFontPx && width_of(measure_text(text, tf)) > avail) --tf;
    while (text.size() > 4 && width_of(measure_text(text, tf)) > avail)
      text = "..." + text.substr(std::min(text.size(), std::size_t(4)));
    const PixelBox m = measure_text(text, tf);
    l.title = place(text, tf, (width - width_of(m)) / 2, height - pad - height_of(m));
    top = l.title.box.y0 - pad;
  }

  if (categories) return layout_categories(l, width, top, pad, font, legend_title,
                                           bottom_reserved, no_data, *categories);
  // The legend column: shrink its font until it takes at most kMaxLegendWidth of the width.
  for (;; --font) {
    l.ticks.clear();
    for (int i = 0; i < kTicks; ++i) l.ticks.push_back(lo + (hi - lo) * i / (kTicks - 1));
    const PixelBox tm = measure_text(legend_title, font);
    int label_w = 0, label_h = 0;
    for (double t : l.ticks) {
      const PixelBox m = measure_text(tick_label(t, hi - lo), font);
      label_w = std::max(label_w, width_of(m));
      label_h = std::max(label_h, height_of(m));
    }
    const int bar_w = std::max(4, static_cast<int>(std::lround(kBarWidthPerFont * font)));
    const PixelBox nm = no_data ? measure_text(kNoDataText, font) : PixelBox{};
    const int column = std::max({width_of(tm), bar_w + pad + label_w, bar_w + pad + width_of(nm)}) + 2 * pad;
    if (column > kMaxLegendWidth * width && font > kMinFontPx) continue;

    const int x0 = width - column + pad;
    const int title_y = top - pad - height_of(tm);
    l.legend_title = place(legend_title, font, x0, title_y);
    const int free_top = (legend_title.empty() ? top - pad : title_y - pad) - (label_h + 1) / 2;
    // The "no data" entry: a swatch as high as a label, its text beside it, at the bottom.
    const int entry_h = no_data ? std::max(label_h, height_of(nm)) + 2 * pad : 0;
    const int free_bottom = bottom_reserved + pad + (label_h + 1) / 2 + entry_h;
    const int bar_h = std::max(8, static_cast<int>(kBarHeightFraction * (free_top - free_bottom)));
    const int bar_top = std::max(free_bottom + 8, free_top);
    const int bar_bottom = std::max(free_bottom, bar_top - bar_h);
    l.bar = {x0, bar_bottom, x0 + bar_w, bar_top};
    l.labels.clear();
    l.legend = l.legend_title.box.empty() ? l.bar : l.legend_title.box;
    auto grow = [&l](const PixelBox& b) { l.legend = united(l.legend, b); };
    grow(l.bar);
    for (int i = 0; i < kTicks; ++i) {
      const std::string text = tick_label(l.ticks[i], hi - lo);
      const PixelBox m = measure_text(text, font);
      const int yc = bar_bottom + (bar_top - bar_bottom) * i / (kTicks - 1);
      l.labels.push_back(place(text, font, l.bar.x1 + pad, yc - height_of(m) / 2));
      grow(l.labels.back().box);
    }
    l.no_data = {};
    l.no_data_label = {};
    if (no_data) {
      const int h = std::max(label_h, height_of(nm));
      const int y0 = bar_bottom - (label_h + 1) / 2 - 2 * pad - h;
      l.no_data = {x0, y0, x0 + bar_w, y0 + h};
      l.no_data_label = place(kNoDataText, font, l.no_data.x1 + pad, y0 + (h - height_of(nm)) / 2);
      grow(l.no_data);
      grow(l.no_data_label.box);
    }
    l.surface = {0, bottom_reserved, width - column, top};
    break;
  }
  return l;
}

}  // namespace isocurv::viz
