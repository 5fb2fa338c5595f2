#include "narrow/sorted_pairs.hpp"

#include <algorithm>
#include <atomic>
#include <string>

#include "common/config.h"
#include "narrow/exact_stage.hpp"
#include "narrow/guarded_executor.hpp"
#include "narrow/pair_keys.hpp"
#include "narrow/responses.hpp"
#include "narrow/slots.hpp"
#include "narrow/workspace.hpp"

namespace vkcollide::narrow {
namespace {


// `to` = `from`: reused memory, or fresh pages touched in parallel first; the copy runs in
// parallel (the GPU's responses where they are ready; the pairs are copied by the check).
template <typename T>
void copyFresh(std::span<const T> from, std::vector<T>& to, Executor& ex) {
    resizeFresh(to, from.size(), ex);
    ex.parallelFor(from.size(), narrow::kSortedPairGrain, [&](std::size_t begin, std::size_t end) {
        std::copy(from.begin() + static_cast<std::ptrdiff_t>(begin), from.begin() + static_cast<std::ptrdiff_t>(end),
                  to.begin() + static_cast<std::ptrdiff_t>(begin));
    });
}

// Checks the GPU's list over [from, to) (each pair in range, strictly ascending from the one
// before `from`) and names those below `kept` (object, triangle) into out[k] in the same
// read; with `marks`, marks each end's triangle (relaxed byte stores: every writer writes 1).
// Returns the lowest bad pair's index, or sorted.size().
std::size_t checkAndName(std::span<const CandidatePair> sorted, std::size_t from, std::size_t to, std::size_t kept,
                         const TriangleSource& source, Executor& ex, TrianglePair* const out, std::uint8_t* const marks) {
    const std::size_t found = sorted.size();
    const std::uint32_t total = source.totalTriangles();
    std::atomic<std::size_t> bad{found};  // the lowest pair found out of range or out of order
    ex.parallelFor(to - from, narrow::kSortedPairGrain, [&](std::size_t begin, std::size_t end) {
        begin += from;
        end += from;
        // A chunk's first pair is compared with the pair before it too (chunks may start
        // anywhere: an engine's executor chooses them). A bad pair before it is its own
        // chunk's, and lower: it is the one named.
        std::uint64_t previous = begin > 0 ? keyOf(sorted[begin - 1].a, sorted[begin - 1].b) : 0;
        // Each end's object and its ids [first, next): a's only grows, b's mostly repeats.
        struct Named {
            std::uint32_t object = 0, first = 0, next = 0;  // empty: the first id looks it up
        } na, nb;
        const auto name = [&source](Named& n, std::uint32_t id) {
            if (id - n.first < n.next - n.first) return;  // within [first, next)
            n.object = objectOf(source, id);
            n.first = source.triangleBase(n.object);
            n.next = source.triangleBase(n.object + 1);
        };
        for (std::size_t k = begin; k < end; ++k) {
            const CandidatePair p = sorted[k];
            const std::uint64_t key = keyOf(p.a, p.b);
            if (p.b >= total || p.a >= p.b || key <= previous) {
                std::size_t expected = bad.load();
                while (k < expected && !bad.compare_exchange_weak(expected, k)) {}
                return;
            }
            previous = key;
            if (k < kept) {
                name(na, p.a);
                name(nb, p.b);
                out[k] = TrianglePair{na.object, p.a - na.first, nb.object, p.b - nb.first};
            }
            if (!marks) continue;
            std::atomic_ref<std::uint8_t>(marks[p.a]).store(1, std::memory_order_relaxed);
            std::atomic_ref<std::uint8_t>(marks[p.b]).store(1, std::memory_order_relaxed);
        }
    });
    return bad.load();
}

Result<NarrowResult> sortedPhase(std::span<const CandidatePair> sorted, std::span<const TriangleResponse> gpu_responses,
                                 const TriangleSource& source, const NarrowOptions& options, Executor& ex, NarrowWorkspace::Impl& ws,
                                 std::vector<TrianglePair>& pair_memory, std::vector<TriangleResponse>& response_memory,
                                 bool pairs_named) {
    StageClock clock;
    NarrowResult result;
    result.pairs = std::move(pair_memory);
    result.responses = std::move(response_memory);
    const std::size_t found = sorted.size();
    const std::size_t kept = std::min<std::size_t>(found, options.max_pairs);
    // The GPU's responses are every pair's: used where no pair is left out (no pairs: no
    // responses, whoever computed them, and nothing to mark over every triangle).
    const bool ready = (!gpu_responses.empty() || found == 0) && kept == found;
    const std::uint32_t total = source.totalTriangles();
    // Named already (nameSortedPairs, while the GPU computed the responses), and the
    // responses are the GPU's: nothing to read again.
    const bool named = pairs_named && ready && result.pairs.size() == found;
    // Decided pairs, but the naming below is one parallel loop over them: woken as for tests.
    if (!named)
        if (const unsigned wake = threadsToWake(kept, ex.threadCount(), false)) ex.prepare(wake);

    // Checks, each end's object, and a mark on each end's triangle. Over every pair, kept or
    // not: the slots are the distinct triangles of all the pairs found, as the pair path
    // counts them (NarrowStats::candidates).
    Buffer<std::uint8_t>& marks = ws.in_pair;  // not needed when the responses are ready
    marks.resize(ready ? 0 : total);
    std::fill(marks.begin(), marks.end(), std::uint8_t{0});
    // The kept pairs are named (object, triangle) as they are checked, into the result: one
    // read of the GPU's list (reused memory, or fresh pages touched in parallel first).
    std::size_t bad_pair = found;
    if (!named) {
        resizeFresh(result.pairs, kept, ex);
        bad_pair = checkAndName(sorted, 0, found, kept, source, ex, result.pairs.data(), ready ? nullptr : marks.data());
    }
    if (const std::size_t k = bad_pair; k < found) {
        const CandidatePair p = sorted[k];
        return Error(ErrorCode::VulkanError, "sorted pairs: pair " + std::to_string(k) + " (triangles " + std::to_string(p.a) + " and " +
                                                 std::to_string(p.b) + " of " + std::to_string(total) +
                                                 ") is out of range or out of order (internal error)");
    }
    clock.lap(result.timings.validate_ms);
    if (ready) {
        // Slots are the responders: one response per distinct triangle of the pairs.
        NarrowStats& st = result.stats;
        st.input_pairs = st.sap_pairs = st.positive_tests = found;
        st.candidates = st.potentially_colliding_triangles = gpu_responses.size();
        copyFresh(gpu_responses, result.responses, ex);
        clock.lap(result.timings.sort_ms);
        result.timings.total_ms = clock.totalMs();
        return result;
    }

    // Slots: the marked triangles in id order, numbered in blocks (count, scan, assign).
    const std::size_t blocks = (std::size_t{total} + narrow::kSlotMarkBlock - 1) / narrow::kSlotMarkBlock;
    std::vector<std::size_t>& block_first = ws.hit_begin;
    block_first.assign(blocks + 1, 0);
    ex.parallelFor(blocks, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t blk = begin; blk < end; ++blk) {
            const std::size_t from = blk * narrow::kSlotMarkBlock, to = std::min<std::size_t>(total, from + narrow::kSlotMarkBlock);
            std::size_t n = 0;
            for (std::size_t t = from; t < to; ++t) n += marks[t];
            block_first[blk + 1] = n;
        }
    });
    for (std::size_t blk = 0; blk < blocks; ++blk) block_first[blk + 1] += block_first[blk];
    const std::size_t slot_count = block_first[blocks];
    Buffer<std::uint32_t>& slot_of = ws.pair_slots;  // per triangle id: its slot (marked ones)
    slot_of.resize(total);
    Buffer<std::uint32_t>& slot_ids = ws.slot_ids;
    slot_ids.resize(slot_count);
    ex.parallelFor(blocks, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t blk = begin; blk < end; ++blk) {
            const std::size_t from = blk * narrow::kSlotMarkBlock, to = std::min<std::size_t>(total, from + narrow::kSlotMarkBlock);
            auto slot = static_cast<std::uint32_t>(block_first[blk]);
            for (std::size_t t = from; t < to; ++t)
                if (marks[t]) {
                    slot_of[t] = slot;
                    slot_ids[slot++] = static_cast<std::uint32_t>(t);
                }
        }
    });
    // The colliding pairs as slot keys (from the GPU's global ids, read again): slots follow
    // the ids, so they stay sorted.
    Buffer<std::uint64_t>& colliding = ws.colliding;
    colliding.resize(kept);
    ex.parallelFor(kept, narrow::kSortedPairGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) colliding[k] = keyOf(slot_of[sorted[k].a], slot_of[sorted[k].b]);
    });
    NarrowStats& st = result.stats;
    st.input_pairs = found;
    st.candidates = slot_count;
    st.potentially_colliding_triangles = slot_count;
    st.sap_pairs = found;
    st.positive_tests = found;
    result.pairs_left_out = found - kept;
    clock.lap(result.timings.sweep_ms);

    if (std::optional<Error> e = gatherSlots(source, slot_ids, ex, ws.tags, ws.vertices, ws.table_keys, ws.table_scratch, ws.world))
        return Error(e->code(), "sorted pairs: " + e->message());
    const SlotData slots = slotView(ws.tags, ws.vertices);
    clock.lap(result.timings.gather_ms);

    respond(colliding, slots, slot_count, ResponseForm::Automatic, ex, ws, result);
    clock.lap(result.timings.response_ms);
    result.timings.total_ms = clock.totalMs();
    return result;
}

}  // namespace

Result<NarrowResult> runSortedPairs(std::span<const CandidatePair> sorted, const TriangleSource& source, const NarrowOptions& options,
                                    Executor& executor, NarrowWorkspace& workspace, std::vector<TrianglePair> pair_memory,
                                    std::vector<TriangleResponse> response_memory, std::span<const TriangleResponse> gpu_responses,
                                    bool pairs_named) {
    return guardedCall("runSortedPairs", executor, options.max_box_pairs, [&](Executor& guarded) {
        return sortedPhase(sorted, gpu_responses, source, options, guarded, workspace.impl(), pair_memory, response_memory, pairs_named);
    });
}

bool prepareSortedNames(std::vector<TrianglePair>& out, std::size_t n, Executor& executor) noexcept {
    GuardedExecutor guarded(executor);
    try {
        if (const unsigned wake = threadsToWake(n, executor.threadCount(), false)) executor.prepare(wake);
        resizeFresh(out, n, guarded);
        return true;
    } catch (...) {  // host memory ran out (or an array's largest size): runSortedPairs says so
        return false;
    }
}

bool nameSortedPairs(std::span<const CandidatePair> sorted, std::size_t begin, std::size_t end, const TriangleSource& source,
                     Executor& executor, std::vector<TrianglePair>& out) noexcept {
    if (out.size() != sorted.size() || begin > end || end > sorted.size()) return false;
    GuardedExecutor guarded(executor);
    try {
        return checkAndName(sorted, begin, end, end, source, guarded, out.data(), nullptr) == sorted.size();
    } catch (...) {
        return false;
    }
}

}  // namespace vkcollide::narrow
