#include "broad/cells/reliable_method.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vkcollide::passes {

Result<std::unique_ptr<BroadPhaseMethod>> ReliableMethod::create(vk::Device& device, BufferTable& table, const CoreBuffers& core) {
    auto cells = CellStage::create(device, &table);  // its buffers: rows of the broad phase's table
    if (!cells) return cells.error();
    return std::unique_ptr<BroadPhaseMethod>(new ReliableMethod(device, table, core, std::move(*cells)));
}

namespace {

// The cell stage's settings of a run with `s` (the proximity pad aside: prepareStage).
CellStageSettings cellSettings(const BroadPhaseSettings& s) {
    CellStageSettings settings;
    settings.max_candidate_pairs = s.max_candidate_pairs;
    settings.exact = s.exact_on_gpu;
    settings.exact_pass = s.exact_pass;
    settings.pair_chunk = s.pair_chunk;
    settings.sweep_work = s.sweep_work;
    settings.repeat_checks = static_cast<CellStageSettings::RepeatChecks>(std::min(s.repeat_checks, 2u));
    return settings;
}

}  // namespace

// Every stage a run with `s` may create on first use, created now, and every form of the
// cell stage's passes: their pipelines stay with the device's Context (vk::Pipeline).
Result<void> ReliableMethod::preparePipelines(const BroadPhaseSettings& s) {
    if (auto ok = cells_->makeEveryPipeline(cellSettings(s)); !ok) return ok;
    // Sorting on the GPU needs the exact decision there (prepareStage).
    const bool exact = s.exact_on_gpu && cells_->filterSupported();
    const bool sorts = exact && (s.device_pairs || s.sort_on_gpu);
    return makeStages(s.proximity_distance > 0, sorts, sorts && (s.device_responses || s.responses_on_gpu), exact && s.small_sort);
}

// The stages after the cell stage that a run uses, each created on first use (its buffers:
// rows of the table).
Result<void> ReliableMethod::makeStages(bool proximity, bool sorting, bool responding, bool small) {
    if (proximity && !proximity_) {
        auto made = proximity::ProximityStage::create(*device_, *table_);
        if (!made) return made.error();
        proximity_ = std::move(*made);
    }
    if (sorting && !device_pairs_) {
        auto made = DevicePairStage::create(*device_, *table_);
        if (!made) return made.error();
        device_pairs_ = std::move(*made);
    }
    if (responding && !device_responses_) {
        auto made = DeviceResponseStage::create(*device_, *table_);
        if (!made) return made.error();
        device_responses_ = std::move(*made);
    }
    if (small && !small_sort_) {
        auto made = SmallSortStage::create(*device_, *table_);
        if (!made) return made.error();
        small_sort_ = std::move(*made);
    }
    return {};
}

// The stage's input from the run: the objects as uploaded, the projection the front's fit
// writes (or the caller's region, uploaded there), per-object flags and the pair mask.
Result<void> ReliableMethod::prepareStage(const RunView& run) {
    fault_.reset();
    again_ = Step::Cells;
    cells_done_ = cells_resubmitted_ = proximity_stale_ = proximity_done_ = host_sort_grown_ = false;
    const std::size_t n = run.meshes.size();
    CellStageInput& in = input_;
    in.objects = run.objects;
    in.projection.reset();
    in.projection_address = table_->buffer(core_.projection).address();
    in.resolution = run.settings.resolution;
    in.self_collision.resize(n);
    download_.resize(n);
    bool any_self = false, any_download = false;
    for (std::size_t i = 0; i < n; ++i) {
        in.self_collision[i] = run.meshes[i].self_collision ? 1 : 0;
        download_[i] = run.meshes[i].check_on_gpu ? 1 : 0;
        any_self = any_self || run.meshes[i].self_collision;
        any_download = any_download || run.meshes[i].check_on_gpu;
    }
    if (!any_self) in.self_collision.clear();  // keeps its capacity
    in.download = any_download ? std::span<const std::uint8_t>(download_) : std::span<const std::uint8_t>();
    in.pair_mask = run.settings.pair_mask ? std::span<const std::uint32_t>(run.settings.pair_mask->bits) : std::span<const std::uint32_t>();
    CellStageSettings settings = cellSettings(run.settings);
    // Device pairs: only where the exact decision runs on the GPU (the API refuses the rest).
    device_pairs_on_ = run.settings.device_pairs && run.settings.exact_on_gpu && cells_->filterSupported();
    pairs_on_device_only_ = device_pairs_on_ && !run.settings.host_pairs;
    device_responses_on_ = device_pairs_on_ && run.settings.device_responses;
    // The host result sorted on the GPU: not with device pairs (their buffers are the
    // engine's), nor with meshes checked on the GPU (their faults mark the sort incomplete).
    sorted_for_host_ = !device_pairs_on_ && run.settings.sort_on_gpu && run.settings.exact_on_gpu && cells_->filterSupported() &&
                       !run.any_gpu_check;
    host_responses_on_ = sorted_for_host_ && run.settings.responses_on_gpu;
    // Few pairs in one pass: beside the host's path (the survivors still read back), so only
    // where no device-pairs pass sorts them.
    small_sort_on_ = run.settings.small_sort && !device_pairs_on_ && !sorted_for_host_ && run.settings.exact_on_gpu &&
                     cells_->filterSupported() && !run.any_gpu_check;
    early_pairs_on_ = host_responses_on_ && static_cast<bool>(run.settings.on_sorted_pairs);
    on_sorted_pairs_ = early_pairs_on_ ? run.settings.on_sorted_pairs : nullptr;
    early_piece_pairs_ = run.settings.early_piece_pairs;
    settings.survivors_on_device = pairs_on_device_only_ || sorted_for_host_;
    // Proximity: every triangle grown by half the distance (rounded up to a float).
    proximity_on_ = run.settings.proximity_distance > 0;
    if (proximity_on_) {
        const double half = run.settings.proximity_distance * 0.5;
        float pad = static_cast<float>(half);
        if (double(pad) < half) pad = std::nextafter(pad, 3.0e38f);
        settings.proximity_pad = pad;
    }
    if (auto ok = cells_->prepare(in, settings); !ok) return ok;
    if (auto ok = makeStages(proximity_on_, sorting(), responding(), small_sort_on_); !ok) return ok;
    if (proximity_on_)
        if (auto ok = proximity_->prepare(*cells_, run.meshes, run.settings.proximity_distance, run.settings.proximity_capacity); !ok)
            return ok;
    if (small_sort_on_)
        if (auto ok = small_sort_->prepare(*cells_, last_small_pairs_, last_small_responses_); !ok) return ok;
    if (!sorting()) return {};
    device_pairs_->retire();
    object_tags_.resize(n);
    // Objects as the API names them for the engine, as run indices for the host's result.
    for (std::size_t i = 0; i < n; ++i) object_tags_[i] = sorted_for_host_ ? static_cast<std::uint32_t>(i) : run.meshes[i].tag;
    device_pair_capacity_ = run.settings.device_pair_capacity;
    if (sorted_for_host_) device_pair_capacity_ = hostSortCapacity(run.settings.sorted_pairs_expected);
    if (host_responses_on_) host_response_capacity_ = hostCopyCapacity(last_responses_);
    fault_header_ = run.any_gpu_check ? table_->buffer(core_.header).address() : 0;
    return prepareSort();
}

Result<void> ReliableMethod::prepareSort() {
    // With device responses the header comes back too: DetectStats says how many there are,
    // and a bucket past a loop limit is named.
    const bool header_to_host = pairs_on_device_only_ || sorted_for_host_ || device_responses_on_;
    early_pairs_seen_ = false;  // a new sort: what the callback took is not its pairs
    early_pairs_count_ = early_pairs_taken_ = 0;
    if (auto ok = device_pairs_->prepare(*cells_, object_tags_, device_pair_capacity_, fault_header_, header_to_host, sorted_for_host_,
                                         responding() ? DeviceResponseStage::responseCapacity(*cells_) : 0,
                                         early_pairs_on_ ? (early_piece_pairs_ ? early_piece_pairs_ : DevicePairStage::kMinEarlyChunkPairs) : 0);
        !ok)
        return ok;
    if (!responding()) return {};
    return device_responses_->prepare(*cells_, *device_pairs_, host_responses_on_ ? host_response_capacity_ : 0);
}

void ReliableMethod::recordSort(graph::Graph& g, const CellStage::Resources& cells, graph::ResourceId fault_header) const {
    const DevicePairStage::Resources sorted = device_pairs_->record(g, cells, fault_header);
    device_pairs_->recordEarlyCopies(g, sorted);  // prepared early: the pairs to the host, then the event
    if (responding()) device_responses_->record(g, cells, sorted);
    device_pairs_->recordCopies(g, sorted);
}

void ReliableMethod::record(Phase phase, graph::Graph& g, const RunView&, const GraphBuffers& buffers) const {
    if (phase == Phase::Measure) return;
    // The one pass of few pairs ends every submission that may complete the stage: it reads
    // the survivors only where the run is complete (else it writes Skipped).
    if (phase == Phase::Again && again_ == Step::PairChunk) {
        const CellStage::Resources cells = cells_->recordPairChunk(g);
        if (small_sort_on_) small_sort_->record(g, cells);
        return;
    }
    if (phase == Phase::Again && again_ == Step::SweepChunk) {
        const CellStage::Resources cells = cells_->recordSweepChunk(g);
        if (small_sort_on_) small_sort_->record(g, cells);
        return;
    }
    if (phase == Phase::Main || again_ == Step::Cells) {
        // The projection the front wrote stays in its buffer for a rerun.
        const CellStage::Resources cells = cells_->record(g, buffers[core_.projection]);
        if (phase == Phase::Again) {  // the stage alone: the passes after it run once it completes
            if (small_sort_on_) small_sort_->record(g, cells);
            return;
        }
        if (proximity_on_) proximity_->record(g, cells);
        if (sorting()) recordSort(g, cells, fault_header_ ? buffers[core_.header] : graph::ResourceId{});
        if (small_sort_on_) small_sort_->record(g, cells);
        return;
    }
    const CellStage::Resources cells = cells_->importOutputs(g);
    if (again_ == Step::Sort) recordSort(g, cells, {});
    if (again_ == Step::Proximity) proximity_->record(g, cells);
}

// A host copy's capacity for `expected` records: a quarter more, at least 4096.
std::uint32_t ReliableMethod::hostCopyCapacity(std::uint64_t expected) {
    return static_cast<std::uint32_t>(std::min<std::uint64_t>(std::max<std::uint64_t>(expected + expected / 4, 4096), UINT32_MAX));
}

// The same for the pairs, at most the survivor capacity (which holds every distinct pair of a
// complete run); the responses' copy is clamped to the run's triangles (DeviceResponseStage).
std::uint32_t ReliableMethod::hostSortCapacity(std::uint64_t expected) const {
    return std::min(hostCopyCapacity(expected), std::max(cells_->capacity().survivors, 1u));
}

// Each step ends in the result or asks for its passes again (the broad phase records
// Phase::Again and calls collect() once more): the cell stage until it completes, then
// the device pairs and the proximity pass, whose first run saw the stage fail, once more
// each, then their own overflows.
Result<Collected> ReliableMethod::collect(const RunView& run, const gpu::Header&, BroadPhaseResult& result) {
    if (!cells_done_)
        if (auto step = collectCells(run, result); !step || *step == Collected::Again) return step;
    if (proximity_on_ && !proximity_done_)
        if (auto step = collectProximity(result); !step || *step == Collected::Again) return step;
    result.has_pairs = true;
    if (sorted_for_host_) return collectSorted(result);
    if (pairs_on_device_only_) {
        const gpu::DevicePairsHeader h = device_pairs_->header();
        if (h.flags & gpu::kDevicePairsLoopLimit) return loopLimitError("device pairs");
        result.device_header = BroadPhaseResult::DeviceHeader{h.count, h.needed, h.flags, h.capacity};
        result.device_responses = h.responses;
        return Collected::Done;
    }
    if (device_responses_on_) {
        const gpu::DevicePairsHeader h = device_pairs_->header();
        if (h.flags & gpu::kDevicePairsLoopLimit) return loopLimitError("device responses");
        result.device_responses = h.responses;
    }
    result.pairs = cells_->survivors();
    result.gpu_triangles = cells_->gpuTriangles();
    // The one pass ran in the submission that completed the stage (record()).
    if (small_sort_on_) {
        const SmallSortStage::Output out = small_sort_->result();
        last_small_pairs_ = out.pairs;
        last_small_responses_ = out.responses;
        if (out.done) {
            result.has_sorted_pairs = result.has_sorted_responses = result.sorted_in_one_pass = true;
            result.sorted_pairs = out.sorted;
            result.sorted_responses = out.sorted_responses;
        }
    }
    return Collected::Done;
}

Result<Collected> ReliableMethod::collectCells(const RunView& run, BroadPhaseResult& result) {
    auto outcome = cells_->finish(result.cells);
    if (!outcome) {
        // Bad input only this stage checks (magnitudes of 2^62 and more): named as a fault
        // of the object, so the detection's BadObjectPolicy applies to it.
        if (const auto& bad = cells_->badInput(); bad && bad->object < run.meshes.size()) {
            const bool index = (bad->flags & gpu::kCellsBadIndex) != 0;
            fault_ = ObjectFault{bad->object, index ? ObjectFault::Kind::IndexOutOfRange : ObjectFault::Kind::OutOfRange,
                                 bad->triangle, 1, run.meshes[bad->object].vertex_count};
        }
        return outcome.error();
    }
    cells_->noteSweepTime(result.passes);  // the next chunk's or run's size
    if (*outcome == CellStage::Outcome::Rerun) {
        if (cells_->runs() >= CellStageSettings{}.max_runs)
            return Error(ErrorCode::OutOfMemory, "cell stage: buffers still overflowed after " + std::to_string(cells_->runs()) +
                                                     " runs (entries " + std::to_string(cells_->capacity().entries) +
                                                     ", candidates " + std::to_string(cells_->capacity().candidates) + ")");
        // An overflow: the stage alone again, its buffers grown; the projection stays.
        cells_resubmitted_ = true;
        return again(Step::Cells);
    }
    if (*outcome == CellStage::Outcome::MoreSweep) {
        // The sweep's next chunk, in a submission of its own (CellStageSettings::sweep_work).
        cells_resubmitted_ = true;
        return again(Step::SweepChunk);
    }
    if (*outcome == CellStage::Outcome::MorePairs) {
        // The pair pass's next chunk, in a submission of its own (CellStageSettings::pair_chunk).
        cells_resubmitted_ = true;
        return again(Step::PairChunk);
    }
    cells_done_ = true;
    cells_->notePairPassTime(result.passes, result.cells.candidates);
    // The passes after the stage in the first submission saw it incomplete: again, once.
    proximity_stale_ = proximity_on_ && cells_resubmitted_;
    if (sorting() && cells_resubmitted_) {
        // The device pairs of the first run say Incomplete: sort the final run's survivors
        // (the stage's buffers may have grown, so size for them first).
        if (auto ok = prepareSort(); !ok) return ok.error();
        return again(Step::Sort);
    }
    return Collected::Done;
}

Result<Collected> ReliableMethod::collectProximity(BroadPhaseResult& result) {
    if (proximity_stale_) {
        // The pass of the first run saw the stage fail: once more after it completed.
        proximity_stale_ = false;
        proximity_->refresh(*cells_);
        return again(Step::Proximity);
    }
    auto outcome = proximity_->finish();
    if (!outcome) return outcome.error();
    if (*outcome == proximity::ProximityStage::Outcome::Rerun) {
        if (proximity_->runs() >= CellStageSettings{}.max_runs)
            return Error(ErrorCode::OutOfMemory, "proximity: the record buffer still overflowed after " + std::to_string(proximity_->runs()) + " runs");
        proximity_->refresh(*cells_);
        return again(Step::Proximity);
    }
    proximity_done_ = true;
    result.has_proximity = true;
    const std::span<const gpu::ProximityRecord> records = proximity_->records();
    // The public record is the GPU's (static_asserts in proximity_stage.cpp).
    result.proximity = {reinterpret_cast<const ProximityPair*>(records.data()), records.size()};
    const gpu::ProximityHeader& h = proximity_->header();
    result.proximity_counts = {h.pairs_tested, h.distances, h.neighbours, h.capacity};
    result.proximity_runs = proximity_->runs();
    result.proximity_device = proximity_->view();
    return Collected::Done;
}

// A triangle with so many partners that one shader invocation cannot sort them on a device
// that ends long loops silently (DeviceInfo::loop_iteration_limit): named, never misordered.
Error ReliableMethod::loopLimitError(const char* what) const {
    return Error(ErrorCode::LimitExceeded,
                 std::string(what) + ": a triangle has more partners than " + vk::loopLimitPhrase(*device_, "sorts") +
                     ": sort on the host (DetectSettings::reliable.pair_sort Cpu, no device_pairs), "
                     "or detect on a GPU");
}

// A piece of the pairs is in host memory, the responses are not yet: a complete sort's
// pieces go to the callback in order (an incomplete or overflowing sort is collectSorted's
// to sort again); a piece it refuses ends the early naming for this sort.
void ReliableMethod::pairsReady(std::size_t piece) {
    if (piece == 0) {
        const gpu::DevicePairsHeader h = device_pairs_->earlyHeader();
        early_pairs_seen_ = false;
        early_pairs_taken_ = 0;
        early_pairs_count_ = h.flags == 0 && h.count == h.needed && on_sorted_pairs_ ? h.count : 0;
        if (early_pairs_count_ == 0) return;
    } else if (early_pairs_count_ == 0 || early_pairs_taken_ != std::min<std::uint64_t>(std::uint64_t(piece) * device_pairs_->earlyChunkPairs(), early_pairs_count_)) {
        return;  // refused or skipped before
    }
    const std::uint32_t end =
        static_cast<std::uint32_t>(std::min<std::uint64_t>(std::uint64_t(piece + 1) * device_pairs_->earlyChunkPairs(), early_pairs_count_));
    if (!on_sorted_pairs_(device_pairs_->hostPairs(early_pairs_count_), early_pairs_taken_, end)) {
        early_pairs_count_ = 0;
        return;
    }
    early_pairs_taken_ = end;
    early_pairs_seen_ = early_pairs_taken_ == early_pairs_count_;
}

Result<Collected> ReliableMethod::collectSorted(BroadPhaseResult& result) {
    gpu::DevicePairsHeader h = device_pairs_->header();
    if (h.flags & gpu::kDevicePairsLoopLimit) return loopLimitError("sorted pairs");
    const bool responses_short = host_responses_on_ && h.responses > device_responses_->hostCapacity();
    if ((h.flags == gpu::kDevicePairsOverflow || (h.flags == 0 && responses_short)) && !host_sort_grown_) {
        // More pairs (or responses) than expected: sort again into copies that hold them all.
        host_sort_grown_ = true;
        device_pair_capacity_ = hostSortCapacity(h.needed);
        if (host_responses_on_) host_response_capacity_ = hostCopyCapacity(h.responses);
        if (auto ok = prepareSort(); !ok) return ok.error();
        return again(Step::Sort);
    }
    if (h.flags != 0 || h.count != h.needed)
        return Error(ErrorCode::VulkanError, "sorted pairs: the GPU's sort ended with flags " + std::to_string(h.flags) + ", " +
                                                 std::to_string(h.count) + " of " + std::to_string(h.needed) + " pairs (internal error)");
    result.has_sorted_pairs = true;
    result.sorted_pairs = device_pairs_->hostPairs(h.count);
    result.sorted_pairs_seen = early_pairs_seen_ && early_pairs_count_ == h.count;
    if (host_responses_on_) {
        if (h.responses > device_responses_->hostCapacity())
            return Error(ErrorCode::VulkanError, "sorted responses: " + std::to_string(h.responses) + " found, the copy holds " +
                                                     std::to_string(device_responses_->hostCapacity()) + " after growing (internal error)");
        last_responses_ = h.responses;
        result.has_sorted_responses = true;
        result.sorted_responses = device_responses_->hostResponses(h.responses);
    }
    result.gpu_triangles = cells_->gpuTriangles();
    return Collected::Done;
}

}  // namespace vkcollide::passes
