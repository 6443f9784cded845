#include "worker/large_pages.h"

#include <suitesparse/SuiteSparse_config.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <malloc.h>
#include <mutex>

namespace fe2 {

bool large_pages_enabled() {
  static const bool enabled = [] {
    const char* v = std::getenv("FE2_LARGE_PAGES");
    return !(v && std::strcmp(v, "0") == 0);
  }();
  return enabled;
}

void advise_large_pages(void* p, size_t bytes) {
  if (!large_pages_enabled() || bytes < kLargePageBytes) return;
  const auto begin = reinterpret_cast<uintptr_t>(p);
  const uintptr_t first = (begin + kLargePageBytes - 1) & ~(kLargePageBytes - 1);
  const uintptr_t last = (begin + bytes) & ~(kLargePageBytes - 1);
  if (last <= first) return;
  // Advice only: a kernel without transparent huge pages says EINVAL, and the memory
  // works the same on small pages. malloc may hand out heap pages an earlier array
  // touched (glibc raises its mmap threshold after large frees), and touched small pages
  // stay small: they are given back (their contents are undefined yet), so the next
  // touch faults in whole huge pages.
  void* interior = reinterpret_cast<void*>(first);
  if (madvise(interior, last - first, MADV_HUGEPAGE) == 0) (void)madvise(interior, last - first, MADV_DONTNEED);
}

void* large_page_alloc(size_t bytes) {
  if (!large_pages_enabled() || bytes < kLargePageBytes) return std::malloc(bytes);
  const size_t rounded = (bytes + kLargePageBytes - 1) & ~(kLargePageBytes - 1);
  void* p = std::aligned_alloc(kLargePageBytes, rounded);
  if (p) advise_large_pages(p, rounded);
  return p;
}

namespace {
void* suitesparse_malloc(size_t bytes) { return large_page_alloc(bytes); }

void* suitesparse_calloc(size_t count, size_t size) {
  if (size != 0 && count > SIZE_MAX / size) return nullptr;
  const size_t bytes = count * size;
  if (bytes < kLargePageBytes) return std::calloc(count, size);
  void* p = large_page_alloc(bytes);
  if (p) std::memset(p, 0, bytes);
  return p;
}

void* suitesparse_realloc(void* p, size_t bytes) {
  // glibc's realloc keeps the contents but not the 2 MiB alignment; large blocks move
  // to a fresh large allocation instead (SuiteSparse reallocs rarely: growing a pattern).
  if (!p || bytes < kLargePageBytes || !large_pages_enabled()) return std::realloc(p, bytes);
  void* q = large_page_alloc(bytes);
  if (!q) return nullptr;  // p stays valid, as realloc promises
  const size_t old = malloc_usable_size(p);
  std::memcpy(q, p, old < bytes ? old : bytes);
  std::free(p);
  return q;
}
}  // namespace

void use_large_pages_in_suitesparse() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!large_pages_enabled()) return;
    SuiteSparse_config.malloc_func = suitesparse_malloc;
    SuiteSparse_config.calloc_func = suitesparse_calloc;
    SuiteSparse_config.realloc_func = suitesparse_realloc;
    SuiteSparse_config.free_func = std::free;
  });
}

}  // namespace fe2
