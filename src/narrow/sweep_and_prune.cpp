#include "narrow/sweep_and_prune.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {
namespace {

// Strip height in typical (median) box heights. Lower means fewer boxes per strip to
// sweep past but more boxes listed in two strips; 1-4 measure about the same
// (docs/narrow_phase.md), 2 is in the middle.
constexpr double kStripHeight = 2.0;
// At most this many strips (bounds the per-chunk histograms) and at most one per
// kCandidatesPerStrip candidates.
constexpr std::size_t kMaxStrips = 4096;
constexpr std::size_t kCandidatesPerStrip = 4;
// Average strips per box allowed by the estimate (tall boxes are listed many times).
constexpr double kMaxListingsPerBox = 3.0;
// Boxes sampled to choose the strips: enough for a stable median, independent of n.
constexpr std::size_t kSampleSize = 4096;
// Candidates per task while building the strips (histograms of kMaxStrips counters).
constexpr std::size_t kBuildGrain = 16384;

void forChunks(ThreadPool* pool, std::size_t count, std::size_t grain,
               const std::function<void(std::size_t, std::size_t)>& body) {
    if (pool) {
        pool->parallelFor(count, grain, body);
    } else {
        for (std::size_t begin = 0; begin < count; begin += grain) body(begin, std::min(count, begin + grain));
    }
}

// Maps y to a strip: monotone in y (a rounded subtraction, a multiplication by a positive
// constant and a truncation are each monotone), so a box [y0, y1] touches exactly the
// strips strip(y0)..strip(y1), and strip(max(y0a, y0b)) = max(strip(y0a), strip(y0b)).
struct StripMap {
    double origin = 0, scale = 0;
    std::uint32_t last = 0;  // strip count - 1

    std::uint32_t operator()(float y) const {
        const double t = (double(y) - origin) * scale;  // >= 0: origin is the lowest y0
        return t >= double(last) ? last : static_cast<std::uint32_t>(t);
    }
};

StripMap chooseStrips(std::span<const CandidateTriangle> in_candidates, float y_min, float y_max) {
    const std::size_t n = in_candidates.size();
    StripMap map;
    map.origin = y_min;
    const double range = double(y_max) - double(y_min);
    const std::size_t max_strips = std::clamp<std::size_t>(n / kCandidatesPerStrip, 1, kMaxStrips);
    if (!(range > 0) || max_strips == 1) return map;  // one strip

    // Median height of an evenly spaced sample.
    const std::size_t step = std::max<std::size_t>(1, n / kSampleSize);
    std::vector<float> heights;
    heights.reserve(n / step + 1);
    for (std::size_t i = 0; i < n; i += step) heights.push_back(in_candidates[i].box[3] - in_candidates[i].box[1]);
    const auto middle = heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2);
    std::nth_element(heights.begin(), middle, heights.end());
    const double strip_height = kStripHeight * double(*middle);

    double strips = strip_height > 0 ? std::ceil(range / strip_height) : double(max_strips);
    strips = std::clamp(strips, 1.0, double(max_strips));
    // Fewer strips while the sample says boxes would be listed too often.
    for (;;) {
        map.last = static_cast<std::uint32_t>(strips) - 1;
        map.scale = strips / range;
        if (map.last == 0) break;
        double listings = 0;
        std::size_t sampled = 0;
        for (std::size_t i = 0; i < n; i += step, ++sampled) {
            listings += double(map(in_candidates[i].box[3]) - map(in_candidates[i].box[1]) + 1);
        }
        if (listings <= kMaxListingsPerBox * double(sampled)) break;
        strips = std::floor(strips / 2);
    }
    return map;
}

// A float's bits as an unsigned integer with the same order (-0 and +0 both map to +0's).
std::uint32_t orderedBits(float x) {
    x += 0.0f;  // -0 -> +0
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

}  // namespace

void StripSweep::build(std::span<const CandidateTriangle> in_candidates, ThreadPool* pool) {
    const std::size_t n = in_candidates.size();
    entries_.clear();
    strip_begin_.assign(2, 0);
    if (n == 0) return;

    // The y range (per chunk, then combined).
    const std::size_t chunks = (n - 1) / kBuildGrain + 1;
    std::vector<float> chunk_min(chunks), chunk_max(chunks);
    forChunks(pool, n, kBuildGrain, [&](std::size_t begin, std::size_t end) {
        float lo = in_candidates[begin].box[1], hi = in_candidates[begin].box[3];
        for (std::size_t i = begin; i < end; ++i) {
            lo = std::min(lo, in_candidates[i].box[1]);
            hi = std::max(hi, in_candidates[i].box[3]);
        }
        chunk_min[begin / kBuildGrain] = lo;
        chunk_max[begin / kBuildGrain] = hi;
    });
    const float y_min = *std::min_element(chunk_min.begin(), chunk_min.end());
    const float y_max = *std::max_element(chunk_max.begin(), chunk_max.end());
    const StripMap strip_of = chooseStrips(in_candidates, y_min, y_max);
    const std::size_t strips = std::size_t{strip_of.last} + 1;

    // Counting sort into strips, stable and parallel: each chunk counts its listings per
    // strip, a prefix sum (strip-major, chunk-minor) gives each chunk its slots.
    std::vector<std::size_t> slots(chunks * strips, 0);
    forChunks(pool, n, kBuildGrain, [&](std::size_t begin, std::size_t end) {
        std::size_t* count = &slots[(begin / kBuildGrain) * strips];
        for (std::size_t i = begin; i < end; ++i) {
            const std::uint32_t s0 = strip_of(in_candidates[i].box[1]), s1 = strip_of(in_candidates[i].box[3]);
            for (std::uint32_t s = s0; s <= s1; ++s) ++count[s];
        }
    });
    strip_begin_.assign(strips + 1, 0);
    std::size_t total = 0;
    for (std::size_t s = 0; s < strips; ++s) {
        strip_begin_[s] = total;
        for (std::size_t c = 0; c < chunks; ++c) {
            const std::size_t count = slots[c * strips + s];
            slots[c * strips + s] = total;
            total += count;
        }
    }
    strip_begin_[strips] = total;
    // Scatter, remembering each listing's sort key: x0's bits made orderable as an
    // unsigned integer, then the position in the strip (which follows the candidate
    // index), so equal x0 keep index order and the sort needs no tie-break.
    std::vector<Entry> unsorted(total);
    std::vector<std::uint64_t> sort_keys(total);
    forChunks(pool, n, kBuildGrain, [&](std::size_t begin, std::size_t end) {
        std::size_t* next = &slots[(begin / kBuildGrain) * strips];
        for (std::size_t i = begin; i < end; ++i) {
            const CandidateTriangle& c = in_candidates[i];
            const std::uint32_t s0 = strip_of(c.box[1]), s1 = strip_of(c.box[3]);
            const std::uint64_t x_key = std::uint64_t{orderedBits(c.box[0])} << 32;
            for (std::uint32_t s = s0; s <= s1; ++s) {
                const std::size_t slot = next[s]++;
                unsorted[slot] = Entry{c.box[0], c.box[2], c.box[1], c.box[3], c.zmin, c.zmax,
                                       static_cast<std::uint32_t>(i), s == s0 ? 1u : 0u};
                sort_keys[slot] = x_key | (slot - strip_begin_[s]);
            }
        }
    });

    // Sort each strip by (x0, index): plain integer keys, then one gather.
    entries_.resize(total);
    forChunks(pool, strips, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t s = begin; s < end; ++s) {
            const std::size_t first = strip_begin_[s], last = strip_begin_[s + 1];
            std::sort(sort_keys.begin() + static_cast<std::ptrdiff_t>(first), sort_keys.begin() + static_cast<std::ptrdiff_t>(last));
            for (std::size_t k = first; k < last; ++k) entries_[k] = unsorted[first + (sort_keys[k] & 0xffffffffu)];
        }
    });
}

std::vector<IndexPair> sweepAndPrunePairs(std::span<const CandidateTriangle> in_candidates, ThreadPool* pool) {
    StripSweep sweep;
    sweep.build(in_candidates, pool);
    std::vector<IndexPair> pairs;
    sweep.sweepRange(0, sweep.entryCount(), [&](std::uint32_t i, std::uint32_t j) { pairs.push_back({i, j}); });
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace vkcollide::narrow
