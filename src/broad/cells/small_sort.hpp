// Few pairs sorted in one pass (PairSort::Auto below kGpuPairSortFrom, docs/exact_gpu.md
// "Few pairs: one pass"): one workgroup sorts the exact run's survivors and drops repeats,
// then one invocation per responder computes every colliding triangle's response, equal to
// the CPU narrow phase's to the bit (spirv/cells/small_sort*.comp.glsl have the steps),
// where the device-pairs passes
// (device_pairs.hpp, device_responses.hpp) would take some twenty dispatches over every
// triangle and the host about 50 ns a pair.
//
//   pairs-small            the sort (one workgroup of kSmallSortGroupSize): the pairs, their
//                          ends in order, the responders
//   pairs-small-responses  the responses, one invocation per responder (indirect: as many
//                          workgroups as they need, none where the sort skipped)
//   pairs-small-to-host    its header, pairs and responses copied to host memory
//
// It runs beside the host's path, never instead of it: the survivors stay in host memory,
// so where they do not fit kSmallSortPairs, the run took more than one submission, or the
// copies hold fewer pairs or responses than were found, result() says so and the host sorts
// the survivors as before. The copies hold twice the last result's counts (at least
// kMinCopy), at most what the pass can write (all of it before the first result).
//
// Not thread-safe; one per cell stage (ReliableMethod).
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "broad/broad_phase_types.hpp"
#include "broad/cells/cell_stage.hpp"

namespace vkcollide::passes {

class SmallSortStage {
public:
    // Adds its rows to `io_table`.
    static Result<std::unique_ptr<SmallSortStage>> create(vk::Device& device, BufferTable& io_table);

    // After CellStage::prepare(): sizes the host copies for the last result's counts and
    // uploads the parameters.
    [[nodiscard]] Result<void> prepare(const CellStage& cells, std::uint32_t last_pairs, std::uint32_t last_responses);
    // The pass and its copies, after the cell stage's passes.
    void record(graph::Graph& g, const CellStage::Resources& cells);

    // After the GPU work: the pairs (global ids, a < b, ascending) and responses (the run's
    // object indices), or done = false where the host must sort the survivors.
    struct Output {
        bool done = false;
        std::uint32_t pairs = 0, responses = 0;  // found (also when they did not fit the copies)
        std::span<const CandidatePair> sorted;
        std::span<const TriangleResponse> sorted_responses;
    };
    Output result() const;

    static constexpr std::uint32_t kMinCopy = 1024;

private:
    SmallSortStage(vk::Device& device, BufferTable& table) : device_(&device), table_(&table) {}

    vk::Device* device_;
    BufferTable* table_;
    vk::Pipeline pipeline_, respond_pipeline_;
    struct Buffers {
        TableRow params, header, pairs, ends, responders, run_begin, args, normals, responses, host_header, host_pairs, host_responses;
    } buf_;
    std::uint32_t copy_pairs_ = 0, copy_responses_ = 0;
};

}  // namespace vkcollide::passes
