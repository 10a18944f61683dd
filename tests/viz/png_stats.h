#pragma once
// Reading a PNG back and measuring its colours, for the rendering tests.
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <string>

namespace isocurv::test {

struct PngStats {
  int width = 0, height = 0, components = 0;
  double luminance_mean = 0, luminance_variance = 0;
  double bluish = 0, reddish = 0, white = 0;  ///< fractions of the inspected pixels
  double greenish = 0;  ///< green above red and blue: viridis's middle, absent from RdBu and grey
};

/// Reads `path` and measures pixels with x < max_x_fraction * width (to leave out the scalar bar,
/// which shows every colour of the map).
inline PngStats png_stats(const std::string& path, double max_x_fraction = 0.8) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  PngStats s;
  int dims[3];
  image->GetDimensions(dims);
  s.width = dims[0];
  s.height = dims[1];
  s.components = image->GetNumberOfScalarComponents();
  if (s.width == 0 || s.components < 3) return s;
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  const int max_x = static_cast<int>(max_x_fraction * s.width);
  double sum = 0, sum2 = 0, count = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < max_x; ++x) {
      const unsigned char* p = pixels + (static_cast<std::size_t>(y) * s.width + x) * s.components;
      const int r = p[0], g = p[1], b = p[2];
      const double l = 0.299 * r + 0.587 * g + 0.114 * b;
      sum += l;
      sum2 += l * l;
      count += 1;
      if (b > 90 && b > r + 40 && b > g + 30) s.bluish += 1;
      if (r > 90 && r > g + 40 && r > b + 40) s.reddish += 1;
      if (r > 235 && g > 235 && b > 235) s.white += 1;
      if (g > 90 && g > r + 30 && g > b + 10) s.greenish += 1;
    }
  s.luminance_mean = sum / count;
  s.luminance_variance = sum2 / count - s.luminance_mean * s.luminance_mean;
  s.bluish /= count;
  s.reddish /= count;
  s.white /= count;
  s.greenish /= count;
  return s;
}

/// The bounding box (x0, y0, x1, y1; y up from the bottom row, as VTK) of the pixels of `path`
/// that differ from the scene's background gradient (bottom -> top colours, 0..1) by more than
/// `tolerance` in some channel, leaving out the pixels inside `skip` boxes (title, legend).
/// {0, 0, 0, 0} when there are none.
/// A PNG's pixels, read back (rows bottom-up, as VTK).
struct Pixels {
  vtkSmartPointer<vtkImageData> image;  ///< owns the data
  int width = 0, height = 0, components = 0;
  const unsigned char* data = nullptr;
  const unsigned char* at(int x, int y) const {
    return data + (static_cast<std::size_t>(y) * width + x) * components;
  }
};

inline Pixels read_pixels(const std::string& path) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  Pixels p;
  p.image = reader->GetOutput();
  int dims[3];
  p.image->GetDimensions(dims);
  p.width = dims[0];
  p.height = dims[1];
  p.components = p.image->GetNumberOfScalarComponents();
  p.data = static_cast<const unsigned char*>(p.image->GetScalarPointer());
  return p;
}

/// Fraction of the pixels of `path` with x in [x0, x1) (fractions of the width; the legend lies
/// right of 0.8) within `tolerance` of the RGB `c` (0..255) in every channel.
inline double fraction_near(const std::string& path, const int c[3], double x0 = 0, double x1 = 0.8,
                            int tolerance = 40) {
  const Pixels px = read_pixels(path);
  double hits = 0, count = 0;
  for (int y = 0; y < px.height; ++y)
    for (int x = int(x0 * px.width); x < int(x1 * px.width); ++x, count += 1) {
      const unsigned char* p = px.at(x, y);
      if (std::abs(p[0] - c[0]) < tolerance && std::abs(p[1] - c[1]) < tolerance &&
          std::abs(p[2] - c[2]) < tolerance)
        hits += 1;
    }
  return count > 0 ? hits / count : 0;
}

struct Box {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
template <class Boxes>
inline Box foreground_box(const std::string& path, const double bottom[3], const double top[3],
                          const Boxes& skip, int tolerance = 14) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  const int n = image->GetNumberOfScalarComponents();
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  Box b{dims[0], dims[1], 0, 0};
  for (int y = 0; y < dims[1]; ++y) {
    const double t = dims[1] > 1 ? double(y) / (dims[1] - 1) : 0;
    double bg[3];
    for (int c = 0; c < 3; ++c) bg[c] = 255 * (bottom[c] + t * (top[c] - bottom[c]));
    for (int x = 0; x < dims[0]; ++x) {
      bool skipped = false;
      for (const auto& s : skip)
        skipped = skipped || (x >= s.x0 && x < s.x1 && y >= s.y0 && y < s.y1);
      if (skipped) continue;
      const unsigned char* p = pixels + (static_cast<std::size_t>(y) * dims[0] + x) * n;
      bool fg = false;
      for (int c = 0; c < 3; ++c) fg = fg || std::abs(p[c] - bg[c]) > tolerance;
      if (!fg) continue;
      b.x0 = std::min(b.x0, x), b.y0 = std::min(b.y0, y);
      b.x1 = std::max(b.x1, x + 1), b.y1 = std::max(b.y1, y + 1);
    }
  }
  if (b.x1 == 0) return {};
  return b;
}

/// Mean luminance (0..255) and mean |r-g| + |g-b| of a picture's surface pixels.
struct MaskedStats {
  double luminance = 0, chroma = 0;
  long count = 0;
};
/// Statistics of the pixels of `path` inside `box` that differ from the background gradient
/// (as foreground_box), i.e. of the surface's pixels when `box` is the surface's viewport.
inline MaskedStats surface_stats(const std::string& path, const Box& box, const double bottom[3],
                                 const double top[3], int tolerance = 14) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  const int n = image->GetNumberOfScalarComponents();
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  MaskedStats m;
  for (int y = std::max(0, box.y0); y < std::min(dims[1], box.y1); ++y) {
    const double t = dims[1] > 1 ? double(y) / (dims[1] - 1) : 0;
    for (int x = std::max(0, box.x0); x < std::min(dims[0], box.x1); ++x) {
      const unsigned char* p = pixels + (static_cast<std::size_t>(y) * dims[0] + x) * n;
      bool fg = false;
      for (int c = 0; c < 3; ++c)
        fg = fg || std::abs(p[c] - 255 * (bottom[c] + t * (top[c] - bottom[c]))) > tolerance;
      if (!fg) continue;
      m.luminance += 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
      m.chroma += std::abs(p[0] - p[1]) + std::abs(p[1] - p[2]);
      ++m.count;
    }
  }
  if (m.count) m.luminance /= double(m.count), m.chroma /= double(m.count);
  return m;
}

/// The number of bytes in which two files differ (or -1 when one cannot be read).
inline long pixel_difference(const std::string& a, const std::string& b) {
  vtkNew<vtkPNGReader> ra, rb;
  ra->SetFileName(a.c_str());
  rb->SetFileName(b.c_str());
  ra->Update();
  rb->Update();
  vtkImageData* ia = ra->GetOutput();
  vtkImageData* ib = rb->GetOutput();
  const long n = static_cast<long>(ia->GetNumberOfPoints()) * ia->GetNumberOfScalarComponents();
  if (n == 0 || n != static_cast<long>(ib->GetNumberOfPoints()) * ib->GetNumberOfScalarComponents())
    return -1;
  const auto* pa = static_cast<const unsigned char*>(ia->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(ib->GetScalarPointer());
  long differ = 0;
  for (long i = 0; i < n; ++i) differ += pa[i] != pb[i];
  return differ;
}

/// The number of pixels in which the legend columns of two same-sized pictures differ (right of
/// `x0` of the width, 80% by default, above `y0` of the height from the bottom, below the title's
/// top 15%); -1 when the sizes differ. The explorer's legend: x0 0.88 and y0 0.4 leave out its
/// status line and a surface reaching into the legend's column.
inline long legend_difference(const std::string& a, const std::string& b, double x0 = 0.8,
                              double y0 = 0) {
  const Pixels pa = read_pixels(a), pb = read_pixels(b);
  if (pa.width != pb.width || pa.height != pb.height || pa.components < 3 || pb.components < 3)
    return -1;
  long differ = 0;
  for (int y = int(y0 * pa.height); y < int(0.85 * pa.height); ++y)
    for (int x = int(x0 * pa.width); x < pa.width; ++x)
      differ += std::memcmp(pa.at(x, y), pb.at(x, y), 3) != 0;
  return differ;
}

}  // namespace isocurv::test
