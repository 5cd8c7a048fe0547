#pragma once
//! \file huge_pages.h
//! Growth's large arrays in 2 MiB pages. At 10^7 particles nearly every read that misses the
//! caches also misses the TLB (4 KiB pages). Where Linux's transparent huge pages are in
//! `madvise` mode an array is in huge pages only when asked, and in any mode only where a
//! whole 2 MiB-aligned page lies within it. docs/dev/performance-notes.md has the measurements.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace dla {

inline constexpr std::size_t kHugePageBytes = std::size_t{1} << 21;

//! Asks for huge pages on the whole 2 MiB pages within [data, data + bytes); a no-op elsewhere
//! and on systems without transparent huge pages.
inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(MADV_HUGEPAGE)
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t begin = (first + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t end = (first + bytes) & ~(kHugePageBytes - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data, (void)bytes;
#endif
}

//! Bytes now held by HugePageAllocator's own mappings. glibc's heap statistics (mallinfo2) do
//! not see them, so a measure of heap use adds this.
inline std::atomic<std::size_t>& huge_page_bytes() {
  static std::atomic<std::size_t> bytes{0};
  return bytes;
}

//! Gives an allocation of 2 MiB or more its own mapping that starts on a 2 MiB boundary, with
//! huge pages advised: glibc starts a large block 16 bytes past a 4 KiB page, which leaves an
//! array of 2-4 MiB without a single huge page. Smaller allocations come from the heap.
template <class T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > max_size()) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) return std::allocator<T>().allocate(n);
#if defined(__linux__)
    // Map a huge page more than asked, then give back what lies before the first 2 MiB
    // boundary and after the array's last page.
    const std::size_t mapped = mapped_bytes(bytes);
    void* const area = mmap(nullptr, mapped + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (area == MAP_FAILED) throw std::bad_alloc();
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(area);
    const std::uintptr_t aligned = (start + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
    if (aligned > start) munmap(area, aligned - start);
    if (const std::size_t after = start + kHugePageBytes - aligned; after > 0)
      munmap(reinterpret_cast<void*>(aligned + mapped), after);
    advise_huge_pages(reinterpret_cast<void*>(aligned), mapped);
    huge_page_bytes() += mapped;
    return reinterpret_cast<T*>(aligned);
#else
    return std::allocator<T>().allocate(n);
#endif
  }

  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) return std::allocator<T>().deallocate(p, n);
#if defined(__linux__)
    const std::size_t mapped = mapped_bytes(bytes);
    munmap(p, mapped);
    huge_page_bytes() -= mapped;
#else
    std::allocator<T>().deallocate(p, n);
#endif
  }

  static constexpr std::size_t max_size() noexcept { return (std::size_t{1} << 62) / sizeof(T); }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept { return false; }

 private:
  // The array rounded up to whole pages of the system's size.
  static std::size_t mapped_bytes(std::size_t bytes) {
#if defined(__linux__)
    static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    return (bytes + page - 1) / page * page;
#else
    return bytes;
#endif
  }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace dla
