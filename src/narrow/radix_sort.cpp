#include "narrow/radix_sort.hpp"

namespace vkcollide::narrow {
namespace {

constexpr int kTopBits = 11;
constexpr std::size_t kBuckets = std::size_t{1} << kTopBits;

}  // namespace

void parallelSortKeys(Executor& ex, Buffer<std::uint64_t>& io_keys, Buffer<std::uint64_t>& scratch, int key_bits, int first_bit) {
    const std::size_t n = io_keys.size();
    scratch.resize(n);
    if (n < 2 || key_bits <= first_bit) return;
    if (n < kSerialBelow || ex.threadCount() == 1 || key_bits - first_bit <= kTopBits) {
        lsdSortBits(io_keys.begin(), io_keys.end(), scratch.begin(), first_bit, key_bits);
        return;
    }
    const int low_bits = key_bits - kTopBits;
    const auto bucketOf = [&](std::uint64_t key) { return static_cast<std::size_t>(key >> low_bits) & (kBuckets - 1); };
    const std::size_t grain = grainFor(n, ex.threadCount(), 2, 2048, std::size_t(1) << 30);
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
            lsdSortBits(begin, end, io_keys.begin() + bucket_begin[b], first_bit, low_bits);
            std::copy(begin, end, io_keys.begin() + bucket_begin[b]);
        }
    });
}

}  // namespace vkcollide::narrow
