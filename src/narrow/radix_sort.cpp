#include "narrow/radix_sort.hpp"

namespace vkcollide::narrow {
namespace {

constexpr int kTopBits = 11;
constexpr std::size_t kBuckets = std::size_t{1} << kTopBits;

// LSD by byte digits of the low `bits` bits of [first, last), using tmp (same size);
// the result ends in [first, last). Digits that are equal in every key are skipped.
void lsdSort(std::uint64_t* first, std::uint64_t* last, std::uint64_t* tmp, int bits) {
    const std::size_t n = static_cast<std::size_t>(last - first);
    if (n < 2 || bits <= 0) return;
    if (n <= 32) {  // insertion sort
        for (std::size_t i = 1; i < n; ++i) {
            const std::uint64_t key = first[i];
            std::size_t j = i;
            for (; j > 0 && first[j - 1] > key; --j) first[j] = first[j - 1];
            first[j] = key;
        }
        return;
    }
    std::uint64_t varying = 0;
    for (std::size_t i = 1; i < n; ++i) varying |= first[i] ^ first[0];
    std::uint64_t* from = first;
    std::uint64_t* to = tmp;
    for (int shift = 0; shift < bits; shift += 8) {
        if (((varying >> shift) & 0xff) == 0) continue;
        std::size_t count[256] = {};
        for (std::size_t i = 0; i < n; ++i) ++count[(from[i] >> shift) & 0xff];
        std::size_t total = 0;
        for (std::size_t& c : count) {
            const std::size_t here = c;
            c = total;
            total += here;
        }
        for (std::size_t i = 0; i < n; ++i) to[count[(from[i] >> shift) & 0xff]++] = from[i];
        std::swap(from, to);
    }
    if (from != first) std::copy(from, from + n, first);
}

}  // namespace

void parallelSortKeys(Executor& ex, Buffer<std::uint64_t>& io_keys, Buffer<std::uint64_t>& scratch, int key_bits) {
    const std::size_t n = io_keys.size();
    scratch.resize(n);
    if (n < 2) return;
    if (n < kSerialBelow || ex.threadCount() == 1 || key_bits <= kTopBits) {
        lsdSort(io_keys.begin(), io_keys.end(), scratch.begin(), key_bits);
        return;
    }
    const int low_bits = key_bits - kTopBits;
    const auto bucketOf = [&](std::uint64_t key) { return static_cast<std::size_t>(key >> low_bits) & (kBuckets - 1); };
    const std::size_t grain = grainFor(n, ex.threadCount(), 2, 16384, std::size_t(1) << 30);
    const std::size_t tasks = taskCount(n, grain);
    std::vector<std::size_t> counts(tasks * kBuckets);
    ex.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        std::size_t* count = &counts[(begin / grain) * kBuckets];
        std::fill(count, count + kBuckets, std::size_t{0});
        for (std::size_t i = begin; i < end; ++i) ++count[bucketOf(io_keys[i])];
    });
    std::vector<std::size_t> bucket_begin(kBuckets + 1);
    std::size_t total = 0;
    for (std::size_t b = 0; b < kBuckets; ++b) {
        bucket_begin[b] = total;
        for (std::size_t t = 0; t < tasks; ++t) {
            const std::size_t here = counts[t * kBuckets + b];
            counts[t * kBuckets + b] = total;
            total += here;
        }
    }
    bucket_begin[kBuckets] = total;
    ex.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
        std::size_t* next = &counts[(begin / grain) * kBuckets];
        for (std::size_t i = begin; i < end; ++i) scratch[next[bucketOf(io_keys[i])]++] = io_keys[i];
    });
    // Each bucket from scratch back into io_keys, sorted by the low bits.
    ex.parallelFor(kBuckets, 16, [&](std::size_t first, std::size_t last) {
        for (std::size_t b = first; b < last; ++b) {
            std::uint64_t* begin = scratch.begin() + bucket_begin[b];
            std::uint64_t* end = scratch.begin() + bucket_begin[b + 1];
            lsdSort(begin, end, io_keys.begin() + bucket_begin[b], low_bits);
            std::copy(begin, end, io_keys.begin() + bucket_begin[b]);
        }
    });
}

}  // namespace vkcollide::narrow
