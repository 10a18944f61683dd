#pragma once
// Reading a PNG back and measuring its colours, for the rendering tests.
#include <cmath>
#include <string>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

namespace isocurv::test {

struct PngStats {
  int width = 0, height = 0, components = 0;
  double luminance_mean = 0, luminance_variance = 0;
  double bluish = 0, reddish = 0, white = 0;  ///< fractions of the inspected pixels
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
    }
  s.luminance_mean = sum / count;
  s.luminance_variance = sum2 / count - s.luminance_mean * s.luminance_mean;
  s.bluish /= count;
  s.reddish /= count;
  s.white /= count;
  return s;
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
  if (n == 0 || n != static_cast<long>(ib->GetNumberOfPoints()) * ib->GetNumberOfScalarComponents()) return -1;
  const auto* pa = static_cast<const unsigned char*>(ia->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(ib->GetScalarPointer());
  long differ = 0;
  for (long i = 0; i < n; ++i) differ += pa[i] != pb[i];
  return differ;
}

}  // namespace isocurv::test
