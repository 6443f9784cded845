#pragma once
// Large arrays on 2 MiB pages. A unit's factor (≈ 300 MB) is streamed once per solve
// and K's values (≈ 18 MB) are hit at scattered places by every assembly; on 4 KiB pages
// both miss the TLB, and the hardware prefetchers stop at every page boundary. Where the
// kernel offers transparent huge pages only on request (`madvise`, Debian's default),
// these helpers ask for them: `bench unit` measured the Step 1 solve of a 27,780-DOF unit
// ≈ 20 % faster (BENCHMARKS.md, "Large pages").
//
// FE2_LARGE_PAGES=0 in the environment turns the requests off (for comparisons); nothing
// else changes, and a kernel without transparent huge pages ignores the advice.
#include <cstddef>

namespace fe2 {

/// Requests are made only for allocations of at least this many bytes.
constexpr size_t kLargePageBytes = size_t{2} << 20;

/// Whether requests are made (FE2_LARGE_PAGES is not "0"); read once.
bool large_pages_enabled();

/// `bytes` of uninitialized memory, released with std::free. From kLargePageBytes up it
/// starts on a 2 MiB boundary and is advised for huge pages; nullptr when out of memory.
void* large_page_alloc(size_t bytes);

/// Advises the whole 2 MiB pages inside [p, p + bytes) for huge pages, and discards what
/// they hold: call it between allocating an array and filling it.
void advise_large_pages(void* p, size_t bytes);

/// Makes SuiteSparse (CHOLMOD's factors and workspace, UMFPACK's) allocate through
/// large_page_alloc. Once per process, before the first factorization.
void use_large_pages_in_suitesparse();

}  // namespace fe2
