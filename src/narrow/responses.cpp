#include "narrow/responses.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/config.h"
#include "narrow/radix_sort.hpp"

namespace vkcollide::narrow {
namespace {


Vec3d unitNormal(const Vertex3& v) {
    const double ux = double(v[1].x) - v[0].x, uy = double(v[1].y) - v[0].y, uz = double(v[1].z) - v[0].z;
    const double vx = double(v[2].x) - v[0].x, vy = double(v[2].y) - v[0].y, vz = double(v[2].z) - v[0].z;
    const Vec3d n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(length > 0) || !std::isfinite(length)) return {};  // zero-area (or overflowing) triangle: no normal
    return {n.x / length, n.y / length, n.z / length};
}

// Fills one response: self's object and triangle, its partner count and the direction of
// the summed terms. The sum is first scaled by a power of two (exact) that brings its
// largest component into [0.5, 1): a direction made of tiny differences of unit normals
// (down to about 2^-650) would otherwise square to nothing. The device responses
// (spirv/cells/device_responses.comp.glsl) make the same operations in the same order.
void setResponse(TriangleResponse& response, const SlotData& slots, std::uint32_t self, std::size_t partners, const Vec3d& sum) {
    response = {};
    response.object = slots.object[self];
    response.triangle = slots.triangle[self];
    response.partner_count = static_cast<std::uint32_t>(partners);
    const double largest = std::max({std::abs(sum.x), std::abs(sum.y), std::abs(sum.z)});
    if (!(largest > 0)) return;
    int exponent = 0;
    std::frexp(largest, &exponent);
    const double scale = std::ldexp(1.0, -exponent);
    const Vec3d s{sum.x * scale, sum.y * scale, sum.z * scale};
    const double length = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
    response.direction = {static_cast<float>(s.x / length), static_cast<float>(s.y / length), static_cast<float>(s.z / length)};
}

// The responses on the calling thread (the Serial form). As in the Grouped form below,
// a slot's pairs in pair order are those where it is the higher end, then its run as the
// lower end in the sorted pairs: a counting sort of the higher ends over the slots (a
// stable scatter of pair indices) lists the first, a cursor walking the pairs alongside
// the slots reads the second. The terms are summed in pair order, so the result is the
// same to the bit as every other form's. No parallel loop: a few thousand hits cost tens
// of microseconds here, where a parallel form's loops cost more than that in hand-outs
// and cache-line traffic on 16 threads. It walks every slot, so it is used only when the
// slots are not many more than the ends.
void respondSerial(const Buffer<std::uint64_t>& colliding, const SlotData& slots, std::size_t slot_count,
                   NarrowWorkspace::Impl& ws, NarrowResult& out) {
    const std::size_t pairs = colliding.size();
    // Counted one place up, scattered through first[s + 1]: afterwards slot s's higher-end
    // pairs are pair_of[first[s], first[s + 1]).
    Buffer<std::uint32_t>& first = ws.responder_begin;
    first.resize(slot_count + 2);
    std::fill(first.begin(), first.end(), 0u);
    // Slot s's run as the lower end ends at run_end[s] (0: no run), so it is
    // [max(previous runs' end), run_end[s]): no search.
    Buffer<std::uint32_t>& run_end = ws.responder_of;
    run_end.resize(slot_count);
    std::fill(run_end.begin(), run_end.end(), 0u);
    for (std::size_t k = 0; k < pairs; ++k) {
        ++first[(colliding[k] & 0xffffffffu) + 2];
        run_end[colliding[k] >> 32] = static_cast<std::uint32_t>(k + 1);
    }
    for (std::size_t slot = 0; slot < slot_count; ++slot) first[slot + 2] += first[slot + 1];
    Buffer<std::uint32_t>& pair_of = ws.responders;
    pair_of.resize(pairs);
    for (std::size_t k = 0; k < pairs; ++k) pair_of[first[(colliding[k] & 0xffffffffu) + 1]++] = static_cast<std::uint32_t>(k);
    // Responders and their normals (read only for slots in a pair).
    Buffer<Vec3d>& normal = ws.slot_normals;
    normal.resize(slot_count);
    std::size_t responders = 0;
    for (std::size_t slot = 0; slot < slot_count; ++slot) {
        if (run_end[slot] == 0 && first[slot + 1] == first[slot]) continue;
        normal[slot] = unitNormal(slots.v[slot]);
        ++responders;
    }
    out.responses.resize(responders);
    std::size_t r = 0;
    for (std::size_t slot = 0, k = 0; slot < slot_count; ++slot) {
        const std::size_t run_first = k;
        k = std::max<std::size_t>(k, run_end[slot]);
        if (k == run_first && first[slot + 1] == first[slot]) continue;
        const Vec3d& n = normal[slot];
        Vec3d sum;
        for (std::size_t e = first[slot]; e < first[slot + 1]; ++e) {
            const Vec3d& m = normal[colliding[pair_of[e]] >> 32];
            sum.x += m.x - n.x;
            sum.y += m.y - n.y;
            sum.z += m.z - n.z;
        }
        for (std::size_t q = run_first; q < k; ++q) {
            const Vec3d& m = normal[colliding[q] & 0xffffffffu];
            sum.x += m.x - n.x;
            sum.y += m.y - n.y;
            sum.z += m.z - n.z;
        }
        setResponse(out.responses[r++], slots, static_cast<std::uint32_t>(slot), first[slot + 1] - first[slot] + (k - run_first), sum);
    }
}

// The Sorted form: the (slot, pair index) keys of both ends of every pair, sorted, list
// each responder's pairs in pair order, so responders are summed in parallel with the
// serial result. Needs no per-slot array: the form for slots much sparser than the ends.
void respondSorted(const Buffer<std::uint64_t>& colliding, const SlotData& slots, std::size_t slot_count, Executor& ex,
                   NarrowWorkspace::Impl& ws, NarrowResult& out) {
    const std::size_t pairs = colliding.size();
    Buffer<std::uint64_t>& ends = ws.contributions;
    ends.resize(2 * pairs);
    ex.parallelFor(pairs, kResultGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            ends[2 * k] = keyOf(static_cast<std::uint32_t>(colliding[k] >> 32), static_cast<std::uint32_t>(k));
            ends[2 * k + 1] = keyOf(static_cast<std::uint32_t>(colliding[k]), static_cast<std::uint32_t>(k));
        }
    });
    parallelRadixSort(ex, ends, ws.contribution_scratch, 32 + keyBits(slot_count), 32);  // built in pair order
    // Responders: where the slot changes in the sorted keys.
    Buffer<std::uint32_t>& begin_of = ws.responder_begin;
    begin_of.resize(ends.size() + 1);
    const std::size_t responders = compact(
        ex, ends.size(), [&](std::size_t i) { return i == 0 || (ends[i] >> 32) != (ends[i - 1] >> 32); },
        [&](std::size_t out_position, std::size_t i) { begin_of[out_position] = static_cast<std::uint32_t>(i); });
    begin_of[responders] = static_cast<std::uint32_t>(ends.size());
    Buffer<std::uint32_t>& responder_of = ws.responder_of;  // slot -> responder; read only where written this call
    responder_of.resize(slot_count);
    std::vector<Vec3d> normal(responders);
    ex.parallelFor(responders, kResultGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            const auto slot = static_cast<std::uint32_t>(ends[begin_of[r]] >> 32);
            responder_of[slot] = static_cast<std::uint32_t>(r);
            normal[r] = unitNormal(slots.v[slot]);
        }
    });
    resizeFresh(out.responses, responders, ex);
    ex.parallelFor(responders, kResultGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            const auto self = static_cast<std::uint32_t>(ends[begin_of[r]] >> 32);
            const Vec3d& n = normal[r];
            Vec3d sum;
            for (std::size_t e = begin_of[r]; e < begin_of[r + 1]; ++e) {
                const std::uint64_t pair = colliding[ends[e] & 0xffffffffu];
                const auto a = static_cast<std::uint32_t>(pair >> 32), b = static_cast<std::uint32_t>(pair);
                const Vec3d& m = normal[responder_of[a == self ? b : a]];
                sum.x += m.x - n.x;
                sum.y += m.y - n.y;
                sum.z += m.z - n.z;
            }
            setResponse(out.responses[r], slots, self, begin_of[r + 1] - begin_of[r], sum);
        }
    });
}

// The Grouped form. The pairs ascend by (lower slot, higher slot), so slot s's pairs in
// pair order are those where s is the higher end (their lower slots are below s), then
// the one run where s is the lower end. Only the higher ends need grouping: a stable sort
// of (higher slot, pair index) over the pairs, half the ends of the Sorted form and, by
// parallelSortKeys, two passes over the whole array instead of one per byte. Each slot's
// two ranges are found where the slot changes, the responders by a compaction over the
// slots, and every responder sums the same terms in the same order as respondSerial.
void respondGrouped(const Buffer<std::uint64_t>& colliding, const SlotData& slots, std::size_t slot_count, Executor& ex,
                    NarrowWorkspace::Impl& ws, NarrowResult& out) {
    const std::size_t pairs = colliding.size();
    Buffer<std::uint64_t>& higher = ws.contributions;  // (higher slot, pair index), grouped by slot in pair order
    higher.resize(pairs);
    ex.parallelFor(pairs, kResultGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) higher[k] = keyOf(static_cast<std::uint32_t>(colliding[k]), static_cast<std::uint32_t>(k));
    });
    parallelSortKeys(ex, higher, ws.contribution_scratch, 32 + keyBits(slot_count), 32);  // built in pair order
    Buffer<std::uint64_t>& lower_run = ws.lower_runs;        // slot s's pairs as the lower end: colliding[first, first + count)
    Buffer<std::uint64_t>& higher_group = ws.higher_groups;  // ... as the higher end: higher[first, first + count)
    lower_run.resize(slot_count);
    higher_group.resize(slot_count);
    ex.parallelFor(slot_count, kSlotGrain, [&](std::size_t begin, std::size_t end) {
        std::fill(lower_run.begin() + begin, lower_run.begin() + end, std::uint64_t{0});
        std::fill(higher_group.begin() + begin, higher_group.begin() + end, std::uint64_t{0});
    });
    // Where a run starts (in this task or not), its slot's entry is written, once.
    const auto runs = [pairs](const std::uint64_t* keys, std::uint64_t* run_of, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const std::uint64_t slot = keys[k] >> 32;
            if (k > 0 && (keys[k - 1] >> 32) == slot) continue;
            std::size_t last = k + 1;
            while (last < pairs && (keys[last] >> 32) == slot) ++last;
            run_of[slot] = keyOf(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(last - k));
        }
    };
    ex.parallelFor(pairs, kResultGrain, [&](std::size_t begin, std::size_t end) {
        runs(colliding.data(), lower_run.data(), begin, end);
        runs(higher.data(), higher_group.data(), begin, end);
    });
    Buffer<std::uint32_t>& responder_slot = ws.responders;
    responder_slot.resize(slot_count);
    Buffer<Vec3d>& normal = ws.slot_normals;  // read only for responders
    normal.resize(slot_count);
    const std::size_t responders = compact(
        ex, slot_count, [&](std::size_t s) { return (lower_run[s] | higher_group[s]) != 0; },
        [&](std::size_t position, std::size_t s) {
            responder_slot[position] = static_cast<std::uint32_t>(s);
            normal[s] = unitNormal(slots.v[s]);
        });
    resizeFresh(out.responses, responders, ex);
    ex.parallelFor(responders, kResultGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            const std::uint32_t self = responder_slot[r];
            const Vec3d& n = normal[self];
            Vec3d sum;
            const std::uint64_t group = higher_group[self], run = lower_run[self];
            const std::size_t group_first = group >> 32, group_count = group & 0xffffffffu;
            const std::size_t run_first = run >> 32, run_count = run & 0xffffffffu;
            for (std::size_t e = group_first; e < group_first + group_count; ++e) {
                const Vec3d& m = normal[colliding[higher[e] & 0xffffffffu] >> 32];
                sum.x += m.x - n.x;
                sum.y += m.y - n.y;
                sum.z += m.z - n.z;
            }
            for (std::size_t k = run_first; k < run_first + run_count; ++k) {
                const Vec3d& m = normal[colliding[k] & 0xffffffffu];
                sum.x += m.x - n.x;
                sum.y += m.y - n.y;
                sum.z += m.z - n.z;
            }
            setResponse(out.responses[r], slots, self, group_count + run_count, sum);
        }
    });
}

}  // namespace

void respond(const Buffer<std::uint64_t>& colliding, const SlotData& slots, std::size_t slot_count, ResponseForm form,
             Executor& ex, NarrowWorkspace::Impl& ws, NarrowResult& out) {
    const std::size_t pairs = colliding.size();
    if (form == ResponseForm::Automatic) {
        if (slot_count > kSlotsPerEnd * 2 * pairs + kSlotsFree) {
            form = ResponseForm::Sorted;
        } else {
            form = pairs < kSerialResponsesBelow || ex.threadCount() < kGroupedFromThreads ? ResponseForm::Serial : ResponseForm::Grouped;
        }
    }
    switch (form) {
    case ResponseForm::Serial: respondSerial(colliding, slots, slot_count, ws, out); return;
    case ResponseForm::Grouped: respondGrouped(colliding, slots, slot_count, ex, ws, out); return;
    default: respondSorted(colliding, slots, slot_count, ex, ws, out); return;
    }
}

}  // namespace vkcollide::narrow
