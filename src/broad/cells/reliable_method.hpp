// The reliable method on the broad phase's seam (method.hpp): the cell stage
// (cell_stage.hpp, docs/reliable.md) after the front's fit, in one submission.
//
//   front     clear, GPU input checks, bounds, fit       common_stages.hpp (the projection)
//   main      cells-clear ... cells-pairs                 CellStage::record, reading the
//                                                         projection the fit wrote
//   readback  the broad phase's header                    common_stages.hpp
//   (device pairs, BroadPhaseSettings::device_pairs: pairs-clear/args/bucket/sort after
//             the stage's passes, device_pairs.hpp; with device_responses then
//             responses-clear/bucket/sum, device_responses.hpp)
//   (few pairs, BroadPhaseSettings::small_sort: pairs-small and its copy after the stage's
//             passes, small_sort.hpp; the survivors are read back as well)
//   collect   the stage's header; after an overflow Again (the broad phase runs the
//             stage's passes alone, its buffers already grown), while the pair pass has
//             chunks to go Again (its next chunk alone), until complete, then the device
//             pairs and the proximity pass once more (Again each); the survivors
//             and the engine meshes' triangles as views of host-visible memory
//             (BroadPhaseResult::pairs, gpu_triangles), nothing sorted or copied on the host.
//
// No measuring passes (traits().measures is false), any resolution in [1, 16384] (cells
// per side). The run's objects as the broad phase uploaded them; per object its
// self-collision flag and whether its geometry is only on the GPU (check_on_gpu: its
// survivors' triangles are downloaded with their world vertices); which object pairs may
// collide from BroadPhaseSettings::pair_mask. Settings of the paper's method (layers,
// coverage, dual, packing, backend, epsilons) do not apply.
#pragma once

#include <memory>
#include <vector>

#include "broad/cells/cell_stage.hpp"
#include "broad/cells/device_pairs.hpp"
#include "broad/cells/device_responses.hpp"
#include "broad/cells/small_sort.hpp"
#include "broad/method.hpp"
#include "proximity/proximity_stage.hpp"

namespace vkcollide::passes {

class ReliableMethod final : public BroadPhaseMethod {
public:
    static Result<std::unique_ptr<BroadPhaseMethod>> create(vk::Device& device, BufferTable& io_table, const CoreBuffers& core);

    MethodTraits traits() const noexcept override { return {false, false, true}; }
    Result<void> prepare(const BroadPhaseSettings&, const RunShape&, gpu::Frame&) override { return {}; }
    Result<void> preparePipelines(const BroadPhaseSettings& settings) override;
    // Nothing measured, nothing predicted: the stage sizes its buffers from the scene.
    Result<void> begin(const RunView& run, const gpu::Header*, std::span<const graph::PassTiming>, std::uint32_t) override {
        return prepareStage(run);
    }
    void import(graph::Graph&) override {}
    void record(Phase phase, graph::Graph& g, const RunView& run, const GraphBuffers& buffers) const override;
    Result<Collected> collect(const RunView& run, const gpu::Header& header, BroadPhaseResult& io_result) override;
    std::optional<ObjectFault> fault() const override { return fault_; }
    // With BroadPhaseSettings::on_sorted_pairs (the host's sorted result, its responses on
    // the GPU): the device pairs' events, each set once a piece of the pairs is in host
    // memory, before the responses' passes; the callback hands a complete sort's pieces to
    // on_sorted_pairs.
    graph::Executor::Milestone milestone() override {
        if (!early_pairs_on_) return {};
        return {device_pairs_->events(), [this](std::size_t piece) { pairsReady(piece); }};
    }
    std::optional<DevicePairsView> devicePairs() const override {
        if (!device_pairs_on_) return std::nullopt;  // sorted_for_host_'s buffers are the host's
        DevicePairsView view = device_pairs_->view();
        if (device_responses_on_) {
            view.responses = device_responses_->buffer();
            view.responses_address = device_responses_->address();
            view.response_capacity = device_responses_->capacity();
        }
        return view;
    }

private:
    ReliableMethod(vk::Device& device, BufferTable& table, const CoreBuffers& core, std::unique_ptr<CellStage> cells)
        : device_(&device), table_(&table), core_(core), cells_(std::move(cells)) {}
    Result<void> prepareStage(const RunView& run);
    Result<void> makeStages(bool proximity, bool sorting, bool responding, bool small);
    // collect()'s steps, in order; each answers Again after asking for its passes.
    Result<Collected> collectCells(const RunView& run, BroadPhaseResult& io_result);
    Result<Collected> collectProximity(BroadPhaseResult& io_result);
    Result<Collected> collectSorted(BroadPhaseResult& io_result);
    // milestone()'s callback: piece `piece` of the pairs is in host memory.
    void pairsReady(std::size_t piece);
    Error loopLimitError(const char* what) const;
    enum class Step { Cells, SweepChunk, PairChunk, Sort, Proximity };
    Collected again(Step step) {
        again_ = step;
        return Collected::Again;
    }

    vk::Device* device_;
    BufferTable* table_;
    CoreBuffers core_;
    std::unique_ptr<CellStage> cells_;
    // Per run, kept between runs (no allocation in a steady scene).
    CellStageInput input_;
    std::vector<std::uint8_t> download_;
    std::optional<ObjectFault> fault_;
    // Device pairs (BroadPhaseSettings::device_pairs): made on first use.
    std::unique_ptr<DevicePairStage> device_pairs_;
    bool device_pairs_on_ = false;
    bool pairs_on_device_only_ = false;  // device pairs without a host result
    bool sorted_for_host_ = false;       // the host result's pairs sorted on the GPU (sort_on_gpu)
    bool sorting() const { return device_pairs_on_ || sorted_for_host_; }  // the device-pairs passes run
    // Responses on the GPU (BroadPhaseSettings::device_responses with device pairs, or
    // responses_on_gpu for the host result sorted there): made on first use.
    std::unique_ptr<DeviceResponseStage> device_responses_;
    bool device_responses_on_ = false;
    bool host_responses_on_ = false;  // the host result's responses computed on the GPU (with sorted_for_host_)
    bool responding() const { return device_responses_on_ || host_responses_on_; }
    std::uint32_t host_response_capacity_ = 0;
    std::uint32_t last_responses_ = 0;  // the last host result's responses: what its copy holds first
    // The pairs copied early for BroadPhaseSettings::on_sorted_pairs (milestone()): the
    // current sort's count (from the early header, 0 when incomplete), how many of them the
    // callback has taken, and whether it took every piece.
    bool early_pairs_on_ = false;
    std::function<bool(std::span<const CandidatePair>, std::size_t, std::size_t)> on_sorted_pairs_;
    std::uint32_t early_pairs_count_ = 0, early_pairs_taken_ = 0;
    std::uint32_t early_piece_pairs_ = 0;  // BroadPhaseSettings::early_piece_pairs
    bool early_pairs_seen_ = false;
    // The device pairs' passes, then the responses' and the copies to the host.
    void recordSort(graph::Graph& g, const CellStage::Resources& cells, graph::ResourceId fault_header) const;
    std::uint32_t hostSortCapacity(std::uint64_t expected) const;
    static std::uint32_t hostCopyCapacity(std::uint64_t expected);
    // The device-pairs stage sized for this run (capacity, where its header and pairs go);
    // again after a rerun of the cell stage and for a larger host copy.
    [[nodiscard]] Result<void> prepareSort();
    std::uint32_t device_pair_capacity_ = 0;
    std::vector<std::uint32_t> object_tags_;
    VkDeviceAddress fault_header_ = 0;
    // Few pairs sorted in one pass (BroadPhaseSettings::small_sort): made on first use; the
    // last result's counts size its copies (before any: what the pass can write).
    std::unique_ptr<SmallSortStage> small_sort_;
    bool small_sort_on_ = false;
    std::uint32_t last_small_pairs_ = gpu::kSmallSortPairs, last_small_responses_ = 2 * gpu::kSmallSortPairs;
    // Proximity (BroadPhaseSettings::proximity_distance): made on first use.
    std::unique_ptr<proximity::ProximityStage> proximity_;
    bool proximity_on_ = false;
    // Where collect() is in a run: the steps done, what Phase::Again records.
    Step again_ = Step::Cells;
    bool cells_done_ = false, cells_resubmitted_ = false, proximity_stale_ = false, proximity_done_ = false, host_sort_grown_ = false;
};

}  // namespace vkcollide::passes
