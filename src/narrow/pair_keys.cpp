#include "narrow/pair_keys.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <utility>
#include <vector>

#include "common/config.h"
#include "narrow/radix_sort.hpp"
#include "narrow/workspace.hpp"

namespace vkcollide::narrow {
namespace {


// Sorts keys[first, last) ascending and drops repeats; returns the new end.
std::size_t sortRun(std::uint64_t* keys, std::size_t first, std::size_t last) {
    if (last - first <= kInsertionRun) {
        for (std::size_t i = first + 1; i < last; ++i) {
            const std::uint64_t key = keys[i];
            std::size_t j = i;
            for (; j > first && keys[j - 1] > key; --j) keys[j] = keys[j - 1];
            keys[j] = key;
        }
    } else {
        std::sort(keys + first, keys + last);
    }
    return static_cast<std::size_t>(std::unique(keys + first, keys + last) - keys);
}

// The serial form, O(n) passes over 2n ends of 8 bytes:
//  1. checks, and the ends as (id << 32) | end index (end 2k + side of pair k), with the
//     histograms of every radix digit of the ids counted on the way;
//  2. the ends sorted by id (LSD, digits of the measured width, digits equal in every
//     end skipped);
//  3. slots numbered along the sorted ends;
//  4. the sorted ends read once more: each pair's lower end comes up in slot order, so the
//     keys (lower slot, higher slot) come out sorted by lower slot; each run of one lower
//     slot is sorted and its repeats dropped.
std::optional<std::size_t> serialKeys(std::span<const CandidatePair> in_pairs, std::uint32_t total, NarrowWorkspace::Impl& ws,
                                      PairKeys& out) {
    const std::size_t n = in_pairs.size();
    const std::size_t end_count = 2 * n;
    const int id_bits = keyBits(total == 0 ? 0 : total - 1);
    const int widest = std::clamp(keyBits(end_count), kMinDigitBits, kMaxDigitBits);
    const int digits = (id_bits + widest - 1) / widest;
    const int digit_bits = (id_bits + digits - 1) / digits;
    const std::size_t buckets = std::size_t{1} << digit_bits;
    const std::uint32_t digit_mask = static_cast<std::uint32_t>(buckets - 1);
    std::array<std::uint32_t, kCountCapacity> count_memory;  // digit d's buckets: [d * buckets, (d + 1) * buckets)
    std::fill(count_memory.begin(), count_memory.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(digits) * buckets), 0u);
    const auto counts = [&](int d) { return count_memory.data() + static_cast<std::size_t>(d) * buckets; };

    Buffer<std::uint64_t>& ends = ws.ends;
    ends.resize(end_count);
    for (std::size_t k = 0; k < n; ++k) {
        const CandidatePair p = in_pairs[k];
        if (p.a >= total || p.b >= total || p.a == p.b) return k;
        ends[2 * k] = (std::uint64_t{p.a} << 32) | (2 * k);
        ends[2 * k + 1] = (std::uint64_t{p.b} << 32) | (2 * k + 1);
        for (int d = 0; d < digits; ++d) {
            ++counts(d)[(p.a >> (d * digit_bits)) & digit_mask];
            ++counts(d)[(p.b >> (d * digit_bits)) & digit_mask];
        }
    }
    Buffer<std::uint64_t>& scratch = ws.ends_scratch;
    scratch.resize(end_count);
    for (int d = 0; d < digits && n > 0; ++d) {
        const int shift = 32 + d * digit_bits;
        std::uint32_t* const c = counts(d);
        if (c[(ends[0] >> shift) & digit_mask] == end_count) continue;  // the same digit everywhere
        std::uint32_t sum = 0;
        for (std::size_t b = 0; b < buckets; ++b) sum += std::exchange(c[b], sum);
        for (std::size_t e = 0; e < end_count; ++e) scratch[c[(ends[e] >> shift) & digit_mask]++] = ends[e];
        ends.swap(scratch);
    }

    Buffer<std::uint32_t>& slot_of_end = ws.pair_slots;
    slot_of_end.resize(end_count);
    Buffer<std::uint32_t>& slot_ids = ws.slot_ids;
    slot_ids.resize(end_count);
    std::size_t slots = 0;
    for (std::size_t e = 0; e < end_count; ++e) {
        const auto id = static_cast<std::uint32_t>(ends[e] >> 32);
        if (slots == 0 || slot_ids[slots - 1] != id) slot_ids[slots++] = id;
        slot_of_end[static_cast<std::uint32_t>(ends[e])] = static_cast<std::uint32_t>(slots - 1);
    }
    slot_ids.resize(slots);

    const int slot_bits = keyBits(slots == 0 ? 0 : slots - 1);
    Buffer<std::uint64_t>& keys = ws.pair_keys;
    keys.resize(n);
    std::size_t count = 0, run = 0;
    std::uint32_t run_slot = 0;
    for (std::size_t e = 0; e < end_count; ++e) {
        const auto end = static_cast<std::uint32_t>(ends[e]);
        const std::uint32_t lower = slot_of_end[end], higher = slot_of_end[end ^ 1u];
        if (lower > higher) continue;  // the pair's other end is its lower one (ids differ, so slots do)
        if (lower != run_slot) {
            count = sortRun(keys.data(), run, count);
            run = count;
            run_slot = lower;
        }
        keys[count++] = (std::uint64_t{lower} << slot_bits) | higher;
    }
    count = sortRun(keys.data(), run, count);
    keys.resize(count);
    out = {slots, slot_bits, count};
    return std::nullopt;
}

// The parallel form (the pair path's before this round; see the header's comment).
std::optional<std::size_t> parallelKeys(Executor& ex, std::span<const CandidatePair> in_pairs, std::uint32_t total,
                                        NarrowWorkspace::Impl& ws, PairKeys& out) {
    const std::size_t input = in_pairs.size();
    const int id_bits = keyBits(total == 0 ? 0 : total - 1);

    // Checks.
    Buffer<std::uint64_t>& keys = ws.pair_keys;
    keys.resize(input);
    std::vector<std::size_t> first_bad(taskCount(input, kPairKeyGrain), input);
    ex.parallelFor(input, kPairKeyGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const CandidatePair p = in_pairs[k];
            if (p.a >= total || p.b >= total || p.a == p.b) {
                first_bad[begin / kPairKeyGrain] = k;
                return;
            }
        }
    });
    for (const std::size_t k : first_bad) {
        if (k != input) return k;
    }
    // Slots, the distinct triangles in id order. When ids span a range not much larger
    // than the input, a marker per id and a scan number them; otherwise sorting the ends
    // (id, 2 k + side) does.
    Buffer<std::uint32_t>& slot_of_end = ws.pair_slots;  // [2 k], [2 k + 1]: the slots of input pair k
    slot_of_end.resize(2 * input);
    std::size_t slot_count = 0;
    if (std::size_t{total} <= kDenseIdsPerPair * input + kDenseIdsFree) {
        Buffer<std::uint32_t>& slot_of = ws.responder_of;  // borrowed: free until the responses
        slot_of.resize(total);
        ex.parallelFor(total, kPairKeyGrain, [&](std::size_t begin, std::size_t end) {
            std::fill(slot_of.begin() + begin, slot_of.begin() + end, 0u);
        });
        static_assert(std::atomic_ref<std::uint32_t>::required_alignment <= alignof(std::uint32_t));
        ex.parallelFor(input, kPairKeyGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                std::atomic_ref<std::uint32_t>(slot_of[in_pairs[k].a]).store(1, std::memory_order_relaxed);
                std::atomic_ref<std::uint32_t>(slot_of[in_pairs[k].b]).store(1, std::memory_order_relaxed);
            }
        });
        ws.slot_ids.resize(total);
        slot_count = compact(
            ex, total, [&](std::size_t g) { return slot_of[g] != 0; },
            [&](std::size_t position, std::size_t g) { ws.slot_ids[position] = static_cast<std::uint32_t>(g); });
        ws.slot_ids.resize(slot_count);
        exclusiveScan(ex, slot_of.data(), total);
        ex.parallelFor(input, kPairKeyGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                slot_of_end[2 * k] = slot_of[in_pairs[k].a];
                slot_of_end[2 * k + 1] = slot_of[in_pairs[k].b];
            }
        });
    } else {
        const int end_bits = keyBits(2 * std::uint64_t{input});
        Buffer<std::uint64_t>& ends = ws.ends;
        ends.resize(2 * input);
        ex.parallelFor(input, kPairKeyGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                ends[2 * k] = (std::uint64_t{in_pairs[k].a} << end_bits) | (2 * k);
                ends[2 * k + 1] = (std::uint64_t{in_pairs[k].b} << end_bits) | (2 * k + 1);
            }
        });
        parallelSortKeys(ex, ends, ws.ends_scratch, id_bits + end_bits, end_bits);  // built in end order
        Buffer<std::uint32_t>& slot_begin = ws.responder_begin;  // borrowed: free until the responses
        slot_begin.resize(ends.size() + 1);
        slot_count = compact(
            ex, ends.size(), [&](std::size_t e) { return e == 0 || (ends[e] >> end_bits) != (ends[e - 1] >> end_bits); },
            [&](std::size_t position, std::size_t e) { slot_begin[position] = static_cast<std::uint32_t>(e); });
        slot_begin[slot_count] = static_cast<std::uint32_t>(ends.size());
        ws.slot_ids.resize(slot_count);
        const std::uint64_t end_mask = (std::uint64_t{1} << end_bits) - 1;
        ex.parallelFor(slot_count, kPairKeyGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t s = begin; s < end; ++s) {
                ws.slot_ids[s] = static_cast<std::uint32_t>(ends[slot_begin[s]] >> end_bits);
                for (std::size_t e = slot_begin[s]; e < slot_begin[s + 1]; ++e) {
                    slot_of_end[ends[e] & end_mask] = static_cast<std::uint32_t>(s);
                }
            }
        });
    }

    // The pairs as (lower slot, higher slot) keys, sorted, repeats dropped: the distinct
    // pairs in canonical order (slots follow the ids, ids follow (object, triangle)).
    const int slot_bits = keyBits(slot_count == 0 ? 0 : slot_count - 1);
    ex.parallelFor(input, kPairKeyGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const std::uint32_t sa = slot_of_end[2 * k], sb = slot_of_end[2 * k + 1];
            keys[k] = (std::uint64_t{std::min(sa, sb)} << slot_bits) | std::max(sa, sb);
        }
    });
    parallelSortKeys(ex, keys, ws.pair_scratch, 2 * slot_bits);
    Buffer<std::uint64_t>& distinct = ws.pair_scratch;
    distinct.resize(input);
    const std::size_t pairs = compact(
        ex, input, [&](std::size_t k) { return k == 0 || keys[k] != keys[k - 1]; },
        [&](std::size_t position, std::size_t k) { distinct[position] = keys[k]; });
    distinct.resize(pairs);
    keys.swap(distinct);  // keys: the distinct pairs, ascending
    out = {slot_count, slot_bits, pairs};
    return std::nullopt;
}

}  // namespace

std::optional<std::size_t> buildPairKeys(Executor& executor, std::span<const CandidatePair> in_pairs, std::uint32_t total,
                                         PairKeysForm form, NarrowWorkspace::Impl& io_ws, PairKeys& out) {
    if (form == PairKeysForm::Automatic) form = in_pairs.size() < kSerialPairsBelow ? PairKeysForm::Serial : PairKeysForm::Parallel;
    return form == PairKeysForm::Serial ? serialKeys(in_pairs, total, io_ws, out) : parallelKeys(executor, in_pairs, total, io_ws, out);
}

}  // namespace vkcollide::narrow
