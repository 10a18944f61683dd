#pragma once
// The separable sum both jets (volume/gaussian_jet.cpp, volume/spline_jet.cpp) take over their
// taps: the index-space derivatives from per-axis derivative weights.
namespace isocurv::volume::detail {

/// d[nx][ny][nz] += sum over the taps of sample(x, y, z) wx[nx] wy[ny] wz[nz], for
/// nx + ny + nz <= order: along x within each row, then y, then z. `W` has `first`, `count` and
/// weights `w[n][t]` (n = 0..3) per axis; `sample(x, y, z)` reads one sample (double).
template <class W, class Sample>
void separable_sum(const W (&w)[3], int order, const Sample& sample, double (&d)[4][4][4]) {
  for (int tz = 0; tz < w[2].count; ++tz) {
    double dxy[4][4] = {};
    for (int ty = 0; ty < w[1].count; ++ty) {
      double dx[4] = {};
      for (int tx = 0; tx < w[0].count; ++tx) {
        const double f = sample(w[0].first + tx, w[1].first + ty, w[2].first + tz);
        for (int nx = 0; nx <= order; ++nx) dx[nx] += f * w[0].w[nx][tx];
      }
      for (int nx = 0; nx <= order; ++nx)
        for (int ny = 0; nx + ny <= order; ++ny) dxy[nx][ny] += dx[nx] * w[1].w[ny][ty];
    }
    for (int nx = 0; nx <= order; ++nx)
      for (int ny = 0; nx + ny <= order; ++ny)
        for (int nz = 0; nx + ny + nz <= order; ++nz) d[nx][ny][nz] += dxy[nx][ny] * w[2].w[nz][tz];
  }
}

}  // namespace isocurv::volume::detail
