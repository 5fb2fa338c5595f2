// What NarrowWorkspace keeps from call to call: every large array of every entry, so that
// frame after frame reuses memory instead of asking the system for fresh pages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "narrow/exact_stage.hpp"
#include "narrow/parallel.hpp"
#include "narrow/radix_sort.hpp"
#include "narrow/slots.hpp"
#include "narrow/sweep_and_prune.hpp"
#include "vkcollide/narrow.hpp"

// Everything here is overwritten (or cleared) before it is read in a call; only the
// capacity carries over.
struct vkcollide::NarrowWorkspace::Impl {
    // Record paths.
    narrow::GridSweep sweep;
    narrow::Buffer<narrow::KeyIndex> keys, key_scratch;  // (object, triangle) keys when the input is not in order
    narrow::Buffer<std::uint32_t> record_of;             // slot -> record then
    narrow::Buffer<std::uint8_t> in_pair;                // per slot: in a candidate pair (std::atomic_ref)
    // Gathered slots (lean record path, pair path).
    narrow::Buffer<std::uint32_t> slot_ids;
    narrow::Buffer<narrow::SlotTag> tags;
    narrow::Buffer<narrow::SlotVertices> vertices;
    narrow::Buffer<std::uint64_t> table_keys, table_scratch;
    narrow::Buffer<Float3> world;  // whole meshes in world space
    // Pair path.
    narrow::Buffer<std::uint64_t> pair_keys, pair_scratch, ends, ends_scratch;
    narrow::Buffer<std::uint32_t> pair_slots;  // 2 per distinct pair
    // Back half.
    std::vector<narrow::PairTask> pair_tasks;
    std::vector<std::size_t> test_begin, object_filtered, hit_begin;
    std::vector<std::vector<std::uint64_t>> hits;
    std::vector<std::size_t> found;   // per test task: hits found, stored or not (max_pairs)
    std::vector<std::uint8_t> kept;  // per test task: its hits are stored
    narrow::Buffer<std::uint64_t> colliding, colliding_scratch;
    narrow::Buffer<std::uint64_t> contributions, contribution_scratch;
    narrow::Buffer<std::uint32_t> responders, responder_begin, responder_of;
    narrow::Buffer<narrow::Vec3d> slot_normals;
    narrow::Buffer<std::uint64_t> lower_runs, higher_groups;  // per slot: (first << 32) | count (responses.cpp)
};
