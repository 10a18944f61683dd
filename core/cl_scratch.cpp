#include "core/cl_scratch.h"

#include <cstdlib>

#include "core/cl_input.h"
#include "core/error.h"
#include "core/huge_pages.h"

namespace isocurv {
namespace {

constexpr std::size_t kSmallPageBytes = 4096;
// Below this a buffer's first touches cost less in small pages than one huge page's zeroing:
// measured on this project's virtual machines, 0.3 us per KiB against about 50 us a huge page.
constexpr std::size_t kSmallScratchBytes = std::size_t(128) << 10;

}  // namespace

ScratchBuffers::~ScratchBuffers() {
  for (Slot& s : slots_) {
    s.buffer = cl::Buffer();
    std::free(s.host);
  }
}

cl::Buffer& ScratchBuffers::get(std::size_t slot, std::size_t bytes) {
  if (slot >= slots_.size()) throw Error("scratch slot " + std::to_string(slot) + " out of range");
  Slot& s = slots_[slot];
  if (bytes <= s.bytes && s.bytes > 0) return s.buffer;
  std::size_t want = std::max<std::size_t>(bytes + bytes / 2, 4096);
  // Queued commands may still use the old buffer (and its host memory): let them finish first.
  if (s.bytes > 0) device_.queue().finish();
  s.buffer = cl::Buffer();
  std::free(s.host);
  s.host = nullptr;
  s.bytes = 0;
  if (works_in_host_memory(device_)) {
    // Host memory the CPU device works in directly. Huge pages make first touches of large
    // buffers cheap; a small buffer in a huge page of its own would cost that page's zeroing
    // (kSmallScratchBytes: where the two cost the same here), so small ones take small pages.
    const bool huge = want >= kSmallScratchBytes;
    const std::size_t page = huge ? kHugePageBytes : kSmallPageBytes;
    want = (want + page - 1) / page * page;
    s.host = std::aligned_alloc(page, want);
    if (!s.host) throw Error("out of memory allocating " + std::to_string(want >> 20) + " MiB of device scratch");
    if (huge) advise_huge_pages(s.host, want);
    s.buffer = cl::Buffer(device_.context(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, want, s.host);
  } else {
    s.buffer = cl::Buffer(device_.context(), CL_MEM_READ_WRITE, want);
  }
  s.bytes = want;
  return s.buffer;
}

}  // namespace isocurv
