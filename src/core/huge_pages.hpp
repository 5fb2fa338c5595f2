// Transparent huge pages for the large arrays a detection fills anew every frame (its result's
// pairs and responses): where the kernel hands them out on request (Linux's "madvise" mode, the
// default of most distributions), a fresh array's first writes fault in 2 MiB pages instead of
// 4 KiB ones, 512 times fewer faults. 36 MB made fresh: on a two-core Debian VM 118 ms with
// 4 KiB pages and 9.5 ms with 2 MiB ones (one thread); on the H100's host 6.8-9.8 ms and
// 5.9-6.7 ms (16 threads touching, then resize() zeroing on one: results/h200_2026-12-06/).
#pragma once

#include <cstddef>

namespace vkcollide {

// Asks for huge pages over the whole 2 MiB-aligned pages inside [data, data + bytes), before
// they are first written. Only an advice: nothing happens on other systems, under 4 MiB, or
// where the kernel declines (its answer is ignored: the memory works either way).
void adviseHugePages(void* data, std::size_t bytes) noexcept;

}  // namespace vkcollide
