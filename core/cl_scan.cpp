#include "core/cl_scan.h"

#include <algorithm>

#include "core/cl_scratch.h"

namespace isocurv {
namespace kernels {
extern const char* const scan_cl;
}

std::uint32_t exclusive_scan(Device& dev, const cl::Buffer& in, const cl::Buffer& out, std::uint32_t n) {
  if (n == 0) return 0;
  cl::Program& prog = dev.program("scan", kernels::scan_cl);
  // Enough chunks to feed every compute unit, few enough for the serial middle pass.
  const std::uint32_t p = std::clamp<std::uint32_t>(n / 512, 1, 4096);
  const std::uint32_t chunk = (n + p - 1) / p;
  cl::Buffer& totals = dev.scratch().get(kScanTotals, sizeof(std::uint32_t) * (p + 1));
  cl::Kernel k1(prog, "scan_chunk_totals"), k2(prog, "scan_totals"), k3(prog, "scan_chunks");
  k1.setArg(0, in); k1.setArg(1, n); k1.setArg(2, chunk); k1.setArg(3, totals);
  k2.setArg(0, totals); k2.setArg(1, p);
  k3.setArg(0, in); k3.setArg(1, out); k3.setArg(2, n); k3.setArg(3, chunk); k3.setArg(4, totals);
  auto& q = dev.queue();
  q.enqueueNDRangeKernel(k1, cl::NullRange, cl::NDRange(p));
  q.enqueueNDRangeKernel(k2, cl::NullRange, cl::NDRange(1));
  q.enqueueNDRangeKernel(k3, cl::NullRange, cl::NDRange(p));
  std::uint32_t total = 0;
  q.enqueueReadBuffer(totals, CL_TRUE, sizeof(std::uint32_t) * p, sizeof(std::uint32_t), &total);
  return total;
}

}  // namespace isocurv
