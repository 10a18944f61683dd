#include "core/cl_scan.h"

#include <algorithm>

#include "core/cl_launch.h"
#include "core/cl_scratch.h"

namespace isocurv {
namespace kernels {
extern const char* const scan_cl;
}

namespace {
constexpr std::size_t kScanChunkGroup = 8;  // chunks per work group
}  // namespace

void enqueue_exclusive_scan(Device& dev, const cl::Buffer& in, const cl::Buffer& out, std::uint32_t n,
                            const cl::Buffer* total, std::uint32_t index) {
  auto& q = dev.queue();
  if (n == 0) {
    if (total) q.enqueueFillBuffer(*total, cl_uint(0), sizeof(std::uint32_t) * index, sizeof(std::uint32_t));
    return;
  }
  cl::Program& prog = dev.program("scan", kernels::scan_cl);
  // Enough chunks to feed every compute unit, few enough for the serial middle pass.
  const std::uint32_t p = std::clamp<std::uint32_t>(n / 512, 1, 4096);
  const std::uint32_t chunk = (n + p - 1) / p;
  cl::Buffer& totals = dev.scratch().get(kScanTotals, sizeof(std::uint32_t) * (p + 1));
  cl::Kernel &k1 = dev.kernel(prog, "scan_chunk_totals"), &k2 = dev.kernel(prog, "scan_totals"),
             &k3 = dev.kernel(prog, "scan_chunks");
  set_args(k1, in, n, chunk, p, totals);
  set_args(k2, totals, p, total ? *total : totals, total ? index : p);
  set_args(k3, in, out, n, chunk, p, totals);
  launch(q, k1, p, kScanChunkGroup);
  launch(q, k2, 1, 1);
  launch(q, k3, p, kScanChunkGroup);
}

std::uint32_t exclusive_scan(Device& dev, const cl::Buffer& in, const cl::Buffer& out, std::uint32_t n) {
  cl::Buffer& total_buffer = dev.scratch().get(kScanTotal, sizeof(std::uint32_t));
  enqueue_exclusive_scan(dev, in, out, n, &total_buffer, 0);
  std::uint32_t total = 0;
  dev.queue().enqueueReadBuffer(total_buffer, CL_TRUE, 0, sizeof total, &total);
  return total;
}

}  // namespace isocurv
