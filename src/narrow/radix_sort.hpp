// LSD radix sort on 64-bit keys, for the narrow phase's (object, triangle) keys and
// (rank, rank) pair keys. Byte digits; a digit that is the same in every key is skipped,
// so keys that use few bits (small object ids, ranks below 2^16) take few passes.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vkcollide::narrow {

// A key and the index of the item it belongs to.
struct KeyIndex {
    std::uint64_t key;
    std::uint32_t index;
};

inline std::uint64_t radixKey(std::uint64_t key) { return key; }
inline std::uint64_t radixKey(const KeyIndex& item) { return item.key; }

// Sorts by radixKey, stable (equal keys keep their order). The `ignored_low_bytes` low
// bytes of the key are not sorted by (they may carry a payload: a stable sort of input
// ordered by the payload keeps that order among equal keys). Below a few hundred items a
// comparison sort is faster than the histogram passes.
template <typename T>
void radixSort(std::vector<T>& io, int ignored_low_bytes = 0) {
    const std::size_t n = io.size();
    if (n < 2048) {
        const int shift = 8 * ignored_low_bytes;
        std::stable_sort(io.begin(), io.end(), [shift](const T& a, const T& b) {
            return (radixKey(a) >> shift) < (radixKey(b) >> shift);
        });
        return;
    }
    std::array<std::array<std::size_t, 256>, 8> counts{};
    for (const T& item : io) {
        const std::uint64_t key = radixKey(item);
        for (int d = ignored_low_bytes; d < 8; ++d) ++counts[d][(key >> (8 * d)) & 0xff];
    }
    std::vector<T> scratch(n);
    for (int d = ignored_low_bytes; d < 8; ++d) {
        std::array<std::size_t, 256>& count = counts[d];
        if (std::find(count.begin(), count.end(), n) != count.end()) continue;  // one value: nothing to do
        std::size_t total = 0;
        for (std::size_t& c : count) {
            const std::size_t here = c;
            c = total;
            total += here;
        }
        for (const T& item : io) scratch[count[(radixKey(item) >> (8 * d)) & 0xff]++] = item;
        io.swap(scratch);
    }
}

}  // namespace vkcollide::narrow
