#pragma once
// Fewer first touches of host memory: on virtual machines first touches of small pages are slow
// (about 3 ms per MiB here), of huge pages some 30 times faster. Fresh large arrays backed by
// transparent huge pages, and freed memory kept for reuse.
// Tested through its users: the mesher's output arrays (tests/mc/extract_test.cpp).
#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>
#include <vector>

namespace isocurv {

constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;  ///< x86-64 transparent huge page

/// Advises the kernel to back [data, data + bytes) with huge pages where whole 2 MiB pages fit.
/// Call before the memory is first written. A hint only: no effect where unsupported.
inline void advise_huge_pages(void* data, std::size_t bytes) {
  constexpr std::uintptr_t kHuge = kHugePageBytes;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

/// v.resize(n) for an empty vector, its new storage advised into huge pages before it is filled.
template <typename T, typename A>
void resize_in_huge_pages(std::vector<T, A>& v, std::size_t n) {
  if (v.capacity() < n) {
    v.reserve(n);
    advise_huge_pages(v.data(), n * sizeof(T));
  }
  v.resize(n);
}

/// Keeps freed heap memory in the process (glibc: no trimming, arrays up to 32 MiB from the heap
/// rather than fresh mappings), so repeated work (the explorer's updates, benchmark runs) reuses
/// pages already touched instead of faulting new ones: about 3 ms per MiB on virtual machines.
/// A process-wide setting, for executables to call once at start; libraries leave it alone.
inline void retain_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
}

}  // namespace isocurv
