#include "narrow/slots.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "common/config.h"
#include "narrow/radix_sort.hpp"

namespace vkcollide::narrow {
namespace {

// world_begin of an object transformed per slot.
constexpr std::size_t kNotWhole = std::numeric_limits<std::size_t>::max();

inline void prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    static_cast<void>(p);
#endif
}

std::string triangleName(std::uint32_t object, std::uint32_t triangle) {
    return "object " + std::to_string(object) + " triangle " + std::to_string(triangle);
}

}  // namespace

std::uint32_t objectOf(const TriangleSource& source, std::uint32_t id) {
    // The last object whose first id is at most `id` (empty objects before it share its base).
    std::uint32_t lo = 0, hi = source.objectCount();
    while (hi - lo > 1) {
        const std::uint32_t mid = lo + (hi - lo) / 2;
        if (source.triangleBase(mid) <= id) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

SlotData slotView(const Buffer<SlotTag>& tags, const Buffer<SlotVertices>& vertices) {
    SlotData d;
    if (tags.empty() || vertices.empty()) return d;  // nothing to view (and no array to point into)
    const SlotTag* t = tags.data();
    d.object = {&t->object, sizeof(SlotTag)};
    d.triangle = {&t->triangle, sizeof(SlotTag)};
    d.vertex_index = {&t->vertex_index, sizeof(SlotTag)};
    d.v = {&vertices.data()->v, sizeof(SlotVertices)};
    return d;
}

std::optional<Error> gatherSlots(const TriangleSource& source, const Buffer<std::uint32_t>& ids, Executor& executor,
                                 Buffer<SlotTag>& out_tags, Buffer<SlotVertices>& out_vertices,
                                 Buffer<std::uint64_t>& table_keys, Buffer<std::uint64_t>& scratch, Buffer<Float3>& world) {
    const std::size_t n = ids.size();
    out_tags.resize(n);
    out_vertices.resize(n);
    const std::span<const TriangleSource::Object> objects = source.objects();

    // The GPU table as (id, position) keys sorted by id, when any GPU-only mesh has a slot.
    const std::span<const GpuTriangle> table = source.gpuTriangles();
    bool any_gpu = false;
    for (const TriangleSource::Object& o : objects) any_gpu = any_gpu || o.gpu;
    table_keys.resize(any_gpu ? table.size() : 0);
    if (any_gpu && !table.empty()) {
        if (table.size() > std::numeric_limits<std::uint32_t>::max()) {
            return Error(ErrorCode::InvalidArgument, "GPU triangle table: more than 2^32 - 1 entries");
        }
        executor.parallelFor(table.size(), 1u << 16, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) table_keys[k] = (std::uint64_t{table[k].id} << 32) | k;
        });
        parallelRadixSort(executor, table_keys, scratch, 64, 32);  // low half: k, ascending
        for (std::size_t k = 1; k < table_keys.size(); ++k) {
            if ((table_keys[k] >> 32) == (table_keys[k - 1] >> 32)) {
                return Error(ErrorCode::InvalidArgument,
                             "GPU triangle table: id " + std::to_string(table_keys[k] >> 32) + " appears more than once");
            }
        }
    }

    // Objects transformed whole: world[world_begin[o] + v] is vertex v of object o.
    const std::size_t objects_count = objects.size();
    std::vector<std::size_t> world_begin(objects_count, kNotWhole);
    {
        std::size_t total = 0;
        for (std::uint32_t o = 0; o < objects_count; ++o) {
            const TriangleSource::Object& ob = objects[o];
            if (ob.gpu || ob.identity || ob.positions.empty()) continue;
            const auto first = std::lower_bound(ids.begin(), ids.end(), source.triangleBase(o));
            const auto last = std::lower_bound(first, ids.end(), source.triangleBase(o + 1));
            if (3 * static_cast<std::size_t>(last - first) < ob.positions.size()) continue;
            world_begin[o] = total;
            total += ob.positions.size();
        }
        world.resize(total);
        for (std::uint32_t o = 0; o < objects_count; ++o) {
            if (world_begin[o] == kNotWhole) continue;
            const TriangleSource::Object& ob = objects[o];
            Float3* const out = world.data() + world_begin[o];
            executor.parallelFor(ob.positions.size(), 1u << 14, [&](std::size_t begin, std::size_t end) {
                for (std::size_t v = begin; v < end; ++v) out[v] = toWorld(ob.transform, ob.positions[v]);
            });
        }
    }

    struct TaskError {
        std::size_t slot;
        Error error;
    };
    const std::size_t grain =
        n < 2 * kMinGatherGrain ? std::max<std::size_t>(n, 1) : grainFor(n, executor.threadCount(), 2, kMinGatherGrain, kMaxGatherGrain);
    std::vector<std::optional<TaskError>> errors(taskCount(n, grain));
    executor.parallelFor(n, grain, [&, grain](std::size_t begin, std::size_t end) {
        // The object of the first slot, then walk: slots ascend.
        std::uint32_t object = objectOf(source, ids[begin]);
        std::size_t cursor = 0;  // into table_keys
        bool cursor_set = false;
        const auto fail = [&](std::size_t slot, Error e) { errors[begin / grain] = TaskError{slot, std::move(e)}; };
        for (std::size_t s = begin; s < end; ++s) {
            const std::uint32_t id = ids[s];
            while (id >= source.triangleBase(object + 1)) ++object;
            const std::uint32_t triangle = id - source.triangleBase(object);
            const TriangleSource::Object& o = objects[object];
            if (!o.gpu) {
                // Ahead within this object only (ids ascend, so the test is one compare).
                const std::uint32_t object_end = source.triangleBase(object + 1);
                if (s + kIndicesAhead < end && ids[s + kIndicesAhead] < object_end) {
                    prefetch(&o.indices[3 * std::size_t{ids[s + kIndicesAhead] - source.triangleBase(object)}]);
                }
                if (s + kPositionsAhead < end && ids[s + kPositionsAhead] < object_end) {
                    const std::uint32_t* ahead = &o.indices[3 * std::size_t{ids[s + kPositionsAhead] - source.triangleBase(object)}];
                    for (int k = 0; k < 3; ++k) {
                        if (ahead[k] < o.positions.size()) prefetch(&o.positions[ahead[k]]);
                    }
                }
            }
            SlotTag& tag = out_tags[s];
            SlotVertices& verts = out_vertices[s];
            tag.object = object;
            tag.triangle = triangle;
            if (!o.gpu) {
                const std::size_t vertex_count = o.positions.size();
                for (int k = 0; k < 3; ++k) {
                    const std::uint32_t index = o.indices[3 * std::size_t{triangle} + k];
                    if (index >= vertex_count) {
                        return fail(s, Error(ErrorCode::InvalidMesh, triangleName(object, triangle) + ": vertex index " +
                                                                         std::to_string(index) + " is out of range (" +
                                                                         std::to_string(vertex_count) + " vertices)"));
                    }
                    tag.vertex_index[k] = index;
                    verts.v[k] = o.identity                          ? o.positions[index]
                                 : world_begin[object] != kNotWhole ? world[world_begin[object] + index]
                                                                     : toWorld(o.transform, o.positions[index]);
                }
            } else {
                if (!cursor_set) {
                    cursor = static_cast<std::size_t>(
                        std::lower_bound(table_keys.begin(), table_keys.end(), std::uint64_t{id} << 32) - table_keys.begin());
                    cursor_set = true;
                }
                while (cursor < table_keys.size() && (table_keys[cursor] >> 32) < id) ++cursor;
                if (cursor == table_keys.size() || (table_keys[cursor] >> 32) != id) {
                    return fail(s, Error(ErrorCode::InvalidArgument, triangleName(object, triangle) + " (global id " +
                                                                         std::to_string(id) +
                                                                         ") has no entry in the GPU triangle table"));
                }
                const GpuTriangle& g = table[table_keys[cursor] & 0xffffffffu];
                for (int k = 0; k < 3; ++k) {
                    tag.vertex_index[k] = g.vertex_index[k];
                    verts.v[k] = g.v[k];
                }
            }
            if (!isFinite(verts.v[0]) || !isFinite(verts.v[1]) || !isFinite(verts.v[2])) {
                return fail(s, Error(ErrorCode::InvalidMesh, triangleName(object, triangle) +
                                                                 " has a vertex that is not finite in world space"));
            }
        }
    });
    for (std::optional<TaskError>& e : errors) {
        if (e) return std::move(e->error);  // tasks in slot order: the first is the lowest slot
    }
    return std::nullopt;
}

}  // namespace vkcollide::narrow
