// One detection through the API: settings resolved and checked, the GPU part run by
// passes::Detection, its findings named, the narrow phase on its candidates, the statistics.
#include <algorithm>
#include <exception>
#include <optional>
#include <string>
#include <type_traits>

#include "api/collision_rays.hpp"
#include "api/mesh_checks.hpp"
#include "api/validation.hpp"
#include "api/world_impl.hpp"
#include "narrow/calling_thread_executor.hpp"
#include "narrow/exact_stage.hpp"
#include "narrow/pair_narrow_phase.hpp"
#include "narrow/parallel.hpp"
#include "narrow/sorted_pairs.hpp"
#include "proximity/ownership.hpp"
#include "proximity/proximity_results.hpp"
#include "vk/device.hpp"

namespace vkcollide {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// A result made in memory prepared for the last one (prepareResultMemory) keeps at most twice
// what it holds: a frame whose pairs fell from millions to a few does not carry tens of MB.
// The copy moves what remains, under half of the memory. detectInto's memory is the caller's.
template <typename T>
void releaseSlack(std::vector<T>& v) {
    constexpr std::size_t kFromBytes = std::size_t{1} << 20;
    if (v.capacity() * sizeof(T) >= kFromBytes && v.size() < v.capacity() / 2) v.shrink_to_fit();
}

}  // namespace

// An error of the detection, with the objects the GPU check named (indices in the run's
// meshes) named by id: the only place the API words those findings.
Error CollisionWorld::Impl::describeFailure(const Run& run, const Error& e) const {
    const passes::Detection::Failure& f = run.detection->failure();
    if (f.faults.empty()) return e;
    const passes::ObjectFault& first = f.faults.front();
    const ObjectId id = run.ids.at(first.object);
    const std::string named_fault = registry.who(id, registry.objects.at(id).name) + ": " + passes::describe(first);
    return Error(e.code(), f.none_left ? "no object left to test: " + named_fault : named_fault, e.vkResult());
}

// Proximity: each live object's owned primitives (computed once per host mesh), named
// refusals for objects without host indices.
Result<void> CollisionWorld::Impl::prepareProximity(Run& run) {
    const bool on = run.settings.proximity.distance > 0;
    for (std::size_t i = 0; i < run.meshes.size(); ++i) {
        run.meshes[i].proximity_owned = {};
        if (!on) continue;
        const ObjectId id = run.ids[i];
        Object& o = registry.objects[id];
        if (!o.host)
            return registry.named(id, Error(ErrorCode::UnsupportedFeature,
                                            "proximity needs the object's indices on the host to tell neighbouring primitives apart; "
                                            "engine meshes (addGpuMesh) are not supported yet"));
        if (o.proximity_owned.size() != o.host_indices.size() / 3)
            o.proximity_owned = proximity::ownedPrimitives(o.host_indices, static_cast<std::uint32_t>(o.host_positions.size()));
        run.meshes[i].proximity_owned = o.proximity_owned;
    }
    return {};
}

// Auto sorts on the host where the device ends long loops (llvmpipe): a triangle with
// thousands of partners would fail the GPU's sort there.
bool CollisionWorld::Impl::sortsOnGpu(const DetectSettings& s, std::size_t last_pairs) const {
    const bool auto_gpu_sort = last_pairs >= kGpuPairSortFrom && device().info.loop_iteration_limit == 0;
    return s.reliable.pair_sort == PairSort::Gpu || s.reliable.responses == ResponseSource::Gpu ||
           (s.reliable.pair_sort == PairSort::Auto && auto_gpu_sort);
}

// What decides which passes and stages a method runs (and so which pipelines it needs:
// preparePipelines asks for the same); start() adds the rest of the run's settings.
passes::BroadPhaseSettings CollisionWorld::Impl::methodSettings(const DetectSettings& s, bool sort_on_gpu) const {
    passes::BroadPhaseSettings b;
    b.backend = s.peeling.backend;
    b.exact_on_gpu = s.reliable.exact != ExactDecision::Cpu;  // Gpu was checked against the device
    b.exact_pass = s.reliable.exact_pass;
    b.device_pairs = s.reliable.device_pairs;
    b.device_responses = s.reliable.device_responses;
    b.sort_on_gpu = sort_on_gpu;
    b.responses_on_gpu = sort_on_gpu && s.reliable.responses != ResponseSource::Cpu;
    // Few pairs in one GPU pass: where Auto leaves the sort and the responses to the host
    // (the method turns it off where the GPU sorts or does not decide).
    b.small_sort = s.reliable.pair_sort == PairSort::Auto && s.reliable.responses == ResponseSource::Auto;
    b.proximity_distance = s.proximity.distance;
    return b;
}

Result<void> CollisionWorld::Impl::start(Run& run, const DetectSettings& settings, bool measure, graph::SubmitTarget* target) {
    run.start = Clock::now();
    std::vector<passes::GpuMesh>& meshes = run.meshes;  // kept: no allocation per detection
    registry.liveMeshes(meshes, run.ids);
    run.positions.clear();
    for (ObjectId id : run.ids) run.positions.push_back(registry.objects[id].host_positions);  // GPU meshes: empty
    run.settings = resolve(settings, &run.note, &run.grid);
    for (auto ok : {validation::checkScene(meshes), validation::checkSettings(run.settings, device())})
        if (!ok) return ok.error();
    const DetectSettings& s = run.settings;
    if (s.method == DetectMethod::Reliable)
        for (ObjectId id : run.ids)
            if (auto ok = validation::checkReliableObject(registry.objects[id].options.transform, registry.objects[id].max_abs); !ok)
                return registry.named(id, ok.error());
    passes::DetectionSettings d;
    d.method = DetectionsInFlight::methodFactory(s.method);
    auto mask = registry.pairMask(run.ids);
    if (!mask) return mask.error();
    const bool filter_on_host_only = registry.pair_filter && !*mask;
    for (auto ok :
         {validation::checkSortedOnGpuFilter("reliable.device_pairs", s.reliable.device_pairs, filter_on_host_only, run.ids.size()),
          validation::checkSortedOnGpuFilter("reliable.pair_sort Gpu", s.reliable.pair_sort == PairSort::Gpu, filter_on_host_only,
                                             run.ids.size()),
          validation::checkSortedOnGpuFilter("reliable.responses Gpu", s.reliable.responses == ResponseSource::Gpu, filter_on_host_only,
                                             run.ids.size())})
        if (!ok) return ok.error();
    d.broad = methodSettings(s, !filter_on_host_only && sortsOnGpu(s, last_narrow_pairs));
    d.broad.pair_mask = *mask;
    // Not with a filter only the host applies, nor after a detection of kGpuPairSortFrom pairs
    // or more, whose successor would not fit the pass (a device that ends long loops sorts
    // those on the host: then the pass would only fail to fit).
    d.broad.small_sort = d.broad.small_sort && !filter_on_host_only && last_narrow_pairs < kGpuPairSortFrom;
    d.broad.device_pair_capacity = s.reliable.device_pair_capacity;
    d.broad.host_pairs = s.reliable.host_pairs;
    d.broad.sorted_pairs_expected = static_cast<std::uint32_t>(std::min<std::size_t>(last_narrow_pairs, UINT32_MAX));
    run.sorts_on_gpu = s.method == DetectMethod::Reliable && d.broad.sort_on_gpu && s.reliable.host_pairs;
    // The pairs named while the GPU computes their responses (finish() then names none).
    if (run.sorts_on_gpu && d.broad.responses_on_gpu && s.reliable.pair_naming == PairNaming::Auto &&
        last_narrow_pairs >= kNameDuringGpuFrom)
        d.broad.on_sorted_pairs = [this, &run](std::span<const CandidatePair> sorted, std::size_t begin, std::size_t end) {
            return nameEarly(run, sorted, begin, end);
        };
    for (std::size_t i = 0; i < meshes.size(); ++i) meshes[i].tag = run.ids[i];  // the ids device pairs carry
    if (auto ok = prepareProximity(run); !ok) return ok.error();
    if (s.contacts.geometry)
        for (ObjectId id : run.ids)
            if (!registry.objects[id].host)
                return registry.named(id, Error(ErrorCode::UnsupportedFeature,
                                                "contacts.geometry reads the triangles' vertices on the host; "
                                                "engine meshes (addGpuMesh) are not supported"));
    if (s.proximity.distance > 0 && registry.pair_filter && !*mask)
        return Error(ErrorCode::InvalidArgument, "proximity with a pair filter over " + std::to_string(run.ids.size()) +
                                                     " objects: the filter is applied on the host only beyond " +
                                                     std::to_string(gpu::kMaxFilterMaskObjects) +
                                                     " objects, the proximity pass needs it on the GPU");
    d.broad.proximity_capacity = s.proximity.capacity;
    d.broad.resolution = *s.resolution;
    d.broad.direction = *s.direction;
    d.broad.layer_cap = s.peeling.layer_cap;
    d.broad.dual = s.peeling.dual;
    d.broad.packing = s.peeling.packing;
    d.broad.open_epsilon = *s.peeling.open_epsilon;
    d.broad.closed_epsilon = s.peeling.closed_epsilon;
    // resolve() turned Best into Conservative or Dilate. The reliable method samples no
    // rays and ignores coverage (checkSettings does not check it then): Centre, so that a
    // Conservative it was given on a device without conservative rasterisation does not
    // break the broad phase's precondition.
    d.broad.coverage = s.method == DetectMethod::Reliable ? Coverage::Centre : s.peeling.coverage;
    d.broad.region = s.region;
    // One clock for the whole detection: every submission, rerun and wait ends by it.
    d.broad.timeout_ns = std::uint64_t{s.limits.timeout_ms} * 1000000;
    run.deadline = run.start + std::chrono::milliseconds(s.limits.timeout_ms);
    d.broad.deadline = run.deadline;
    d.broad.poll_ns = std::uint64_t{s.limits.wait_poll_us} * 1000;
    // While the wait polls, keep the narrow phase's workers awake as many as a detection
    // like the last one will use: they then take its first loops at once instead of
    // 0.1-0.2 ms later, when the kernel has woken the last of them (docs/narrow_phase.md).
    if (const unsigned wake = last_narrow_one_pass ? 0 : narrow::threadsToWake(last_narrow_pairs, executor->threadCount(), last_narrow_decided))
        d.broad.poll_hook = [ex = executor, wake] { ex->prepare(wake); };
    d.broad.depth_aware = s.peeling.depth_aware;
    d.broad.keep_ray_image = s.peeling.collision_rays;  // peeling only (validation)
    d.broad.max_candidate_pairs = s.limits.max_candidate_pairs;  // the reliable method's GPU budget
    d.axes = s.peeling.axes;
    d.bad_objects = s.bad_objects;
    run.settings_ms = msSince(run.start);
    if (auto ok = run.detection->start(meshes, d, measure, target); !ok) return noted(describeFailure(run, ok.error()));
    run.in_flight = true;
    run.start_ms = msSince(run.start);
    return {};
}

// A result's first writes into new memory fault its pages in: on the H100's host 1.5-2 ms for
// the 27 MB of 1.7M pairs with 16 threads touching them (run 33), and about 2 us a page on
// one thread (the responses of 32K pairs, 0.9 MB, took 0.48 ms to copy into fresh memory
// after the GPU's wait, 0.02 ms into warm memory: run 44). A result kept by the caller does
// not come back to the allocator, so the next one's memory is new pages from the kernel
// (above the allocator's mmap threshold, from 128 KB, every time). So where the GPU sorts
// the pairs, before the wait, vectors the size of the last result's (and an eighth more) are
// made ready, their pages touched, while the GPU works; the narrow phase then writes the
// pairs and responses into them. resize() writes no pair (TrianglePair's constructor leaves
// the ids unset: a one-thread zeroing of those 27 MB took 2.8 ms more); the responses'
// resize() still zeroes, beside the pairs' pages. Under a megabyte the calling thread
// touches them (a few hundred pages at most), so the executor's workers are not woken for
// it. The host's pair path (under kGpuPairSortFrom pairs) gets none: made ready there, its
// few kilobytes cost its narrow phase more than their faults (run 48: spheres-8x10K +0.19
// ms, 2,882 pairs).
static_assert(!std::is_trivially_default_constructible_v<TrianglePair> && std::is_trivially_copyable_v<TrianglePair>,
              "resize() must make a result's pairs without writing them");
void CollisionWorld::Impl::prepareResultMemory() {
    constexpr std::size_t kFromBytes = std::size_t{16} << 10;
    const auto wanted = [](const auto& v, std::size_t last) -> std::size_t {
        const std::size_t n = last + last / 8;
        return n * sizeof(v[0]) < kFromBytes ? v.size() : std::max(n, v.size());  // never shrunk here
    };
    const std::size_t pairs = wanted(ready_pairs, last_result_pairs), responses = wanted(ready_responses, last_responses);
    const std::size_t bytes = pairs * sizeof(TrianglePair) + responses * sizeof(TriangleResponse);
    narrow::CallingThreadExecutor calling_thread;
    Executor& ex = bytes < narrow::fresh::kTouchBytes ? static_cast<Executor&>(calling_thread) : *executor;
    narrow::resizeFresh(ready_pairs, pairs, ready_responses, responses, ex, kFromBytes);
}

// Inside collect()'s wait, as each piece of a complete sort's pairs reaches host memory (the
// broad phase calls it in order and stops at a refused piece, and says in
// BroadPhaseResult::sorted_pairs_seen whether every piece of the final sort was taken): it
// is named into the result's memory, checked on the way, while the GPU copies the next piece
// and computes the responses. The objects are named as finish() names them when the run's
// objects are all live (finish uses this naming only then). Never throws (the executor's
// callback must not).
bool CollisionWorld::Impl::nameEarly(Run& run, std::span<const CandidatePair> sorted, std::size_t begin, std::size_t end) {
    const auto t0 = Clock::now();
    if (begin == 0) {  // a sort's first piece: the source and the memory for all of them
        run.early_name_ms = 0;
        if (!run.early_into || sorted.size() > run.settings.limits.max_pairs) return false;
        try {
            if (!registry.syncSource(run.ids)) return false;
        } catch (...) {  // host memory ran out: finish() says so
            return false;
        }
        if (!narrow::prepareSortedNames(*run.early_into, sorted.size(), *executor)) return false;
    }
    const bool ok = narrow::nameSortedPairs(sorted, begin, end, registry.source, *executor, *run.early_into);
    run.early_name_ms += msSince(t0);
    return ok;
}

Result<DetectResult> CollisionWorld::Impl::collect(Run& run, bool restart_clock, DetectResult* reuse) {
    run.in_flight = false;
    const auto t0 = Clock::now();
    if (restart_clock) {
        run.deadline = t0 + std::chrono::milliseconds(run.settings.limits.timeout_ms);
        run.detection->setDeadline(run.deadline);
    }
    run.prepare_ms = 0;
    if (!reuse && run.sorts_on_gpu) {
        prepareResultMemory();
        run.prepare_ms = msSince(t0);
    }
    run.early_into = reuse ? &reuse->pairs : &ready_pairs;
    run.early_name_ms = 0;
    auto r = run.detection->collect();
    run.early_into = nullptr;
    run.wait_ms = msSince(t0);
    if (!r) return noted(describeFailure(run, r.error()));
    return finish(run, std::move(*r), reuse);
}

Result<DetectResult> CollisionWorld::Impl::finish(Run& run, passes::DetectionResult detected, DetectResult* reuse) {
    const std::vector<ObjectId>& run_ids = run.ids;
    const DetectSettings& run_settings = run.settings;
    const std::vector<passes::BroadPhaseResult>& broad = detected.axes;
    // Broad-phase object index -> ObjectId.
    std::vector<ObjectId>& ids = finish_ids;
    ids.clear();
    for (std::uint32_t i : detected.objects) ids.push_back(run_ids[i]);
    DetectResult out;
    // The caller's memory for the largest arrays (detectInto): sizes kept, so that what is
    // overwritten in place needs neither fresh pages nor zeroing.
    std::vector<TrianglePair> pair_memory;
    std::vector<TriangleResponse> response_memory;
    if (reuse) {
        pair_memory = std::move(reuse->pairs);
        response_memory = std::move(reuse->responses);
        out.pair_contacts = std::move(reuse->pair_contacts);  // overwritten (or cleared) below
    }
    for (const passes::ObjectFault& f : detected.excluded) {
        const ObjectId id = run_ids[f.object];
        out.excluded.push_back({id, registry.named(id, Error(ErrorCode::InvalidMesh, passes::describe(f)))});
    }
    DetectStats& st = out.stats;
    st.objects = static_cast<std::uint32_t>(ids.size());
    st.method = run_settings.method;
    st.resolution = *run_settings.resolution;
    st.direction = detected.directions[0];
    st.peeling.dual = run_settings.peeling.dual;
    st.peeling.axes = static_cast<std::uint32_t>(broad.size());
    st.peeling.coverage = run_settings.peeling.coverage;
    st.settings_note = run.note;
    for (std::size_t i = 0; i < run_ids.size(); ++i)
        if (const Object& o = registry.objects[run_ids[i]]; o.host && !o.options.open) {
            const bool inside_out = o.boundary_edges == 0 && o.volume6 * mesh_checks::determinant(run.meshes[i].transform) < 0;
            if (inside_out || o.boundary_edges > 0)
                st.mesh_warnings.push_back({run_ids[i], inside_out, o.boundary_edges,
                                            registry.who(run_ids[i], o.name) + ": " + mesh_checks::describe(inside_out, o.boundary_edges)});
        }
    st.peeling.backend = broad[0].backend;
    st.peeling.backend_reason = broad[0].backend_reason;
    for (std::uint32_t k = 1; k < broad.size(); ++k)
        if (broad[k].backend != broad[0].backend)
            st.peeling.backend_reason +=
                "; axis " + std::to_string(k) + ": " + toString(broad[k].backend) + " (" + broad[k].backend_reason + ")";
    const std::uint32_t cap = run_settings.peeling.layer_cap;
    for (std::uint32_t k = 0; k < broad.size(); ++k) {
        const passes::BroadPhaseResult& b = broad[k];
        st.triangles = b.triangles;
        st.collision_rays += b.collision_rays;
        st.triangles_downloaded += b.records.size();
        st.peeling.depth_complexity = std::max(st.peeling.depth_complexity, b.depth_complexity);
        st.peeling.layers = std::max(st.peeling.layers, b.layers);
        st.peeling.peel_passes += b.peel_steps;
        st.peeling.peel_submissions += b.peel_submissions;
        st.peeling.deep_rays += b.deep_rays;
        st.peeling.layers_short =
            st.peeling.layers_short || (b.depth_complexity > b.layers && (cap == 0 || b.layers < cap)) || b.deep_rays > 0;
        const std::string prefix = broad.size() > 1 ? "axis " + std::to_string(k) + ": " : "";
        for (const auto& p : b.passes) st.gpu_passes.push_back({prefix + p.name, p.gpu_ms});
        st.sampling_ms += b.sampling_ms;
        st.peeling.merging_ms += b.merging_ms;
        st.peeling.separation_ms += b.separation_ms;
        st.peeling.packing_ms += b.packing_ms;
        st.reliable.footprints_ms += b.footprints_ms;
        st.reliable.pairing_ms += b.pairing_ms;
        st.reliable.filtering_ms += b.filtering_ms;
        st.reliable.sorting_ms += b.sorting_ms;
        st.readback_ms += b.readback_ms;
        st.host.upload_ms += b.host.upload_ms;
        st.host.declare_ms += b.host.declare_ms;
        st.host.compile_ms += b.host.compile_ms;
        st.host.record_ms += b.host.record_ms;
        st.host.submit_ms += b.host.submit_ms;
        st.host.wait_ms += b.host.wait_ms;
        st.host.milestone_ms += b.host.milestone_ms;  // every piece's callback, named or refused
        st.gpu_span_ms += b.host.gpu_span_ms;
        st.host.launch_wake_ms += b.host.launch_wake_ms;
        st.submissions += b.host.submissions;
        st.host.reused_submissions += b.host.reused;
    }
    if (run_settings.peeling.collision_rays) out.collision_rays = collisionRays(broad, st.resolution);
    if (detected.hasPairs()) {
        const passes::CellStageStats& c = broad[0].cells;
        st.cells = {c.entries,   c.max_cell,      c.deep_cells, c.candidate_cells, c.candidates,       c.duplicates, c.filtered,
                    c.survivors, c.gpu_triangles, c.runs,       c.filter_ran,      c.exact_ran,        c.exact_tests, c.exact_neighbours,
                    c.repeats,   c.sweep_chunks,  c.pair_chunks,  c.huge_cells,      c.comparisons,      c.exact_queued};
        st.collision_rays = c.candidate_cells;
        st.peeling.backend_reason = "none: the reliable method samples no rays";
    }

    NarrowOptions& options = narrow_options;
    options.self_collision.clear();
    options.may_collide = {};
    // As the objects were at start() (they may have moved since: pipelining).
    for (std::uint32_t i : detected.objects) options.self_collision.push_back(run.meshes[i].self_collision);
    options.max_pairs = run_settings.limits.max_pairs;
    options.max_box_pairs = run_settings.limits.max_candidate_pairs;
    options.pairs_decided = detected.hasPairs() && broad[0].cells.exact_ran;
    last_narrow_decided = options.pairs_decided;
    last_narrow_one_pass = false;
    // The filter's kept answers (indices of the live objects the mask was built over), or
    // the filter itself beyond the mask's object limit. The filter must not throw
    // (world.hpp); if it does, the exception stops here, the narrow phase sees "may not
    // collide" from then on, and the detection fails naming it.
    std::optional<Error> filter_threw;
    const passes::ObjectPairMask* mask =
        registry.pair_filter && registry.pair_mask.objects == run_ids.size() && !registry.pair_mask_dirty ? &registry.pair_mask : nullptr;
    const std::vector<std::uint32_t>& live = detected.objects;
    if (mask) {
        options.may_collide = [mask, &live](std::uint32_t a, std::uint32_t b) { return mask->allows(live[a], live[b]); };
    } else if (registry.pair_filter) {
        options.may_collide = [this, &ids, &filter_threw](std::uint32_t a, std::uint32_t b) {
            if (filter_threw) return false;
            auto answer = registry.callPairFilter(ids[a], ids[b]);
            if (answer) return *answer;
            filter_threw = answer.error();
            return false;
        };
    }
    const auto t0 = Clock::now();
    Result<NarrowResult> narrow = Error(ErrorCode::InvalidArgument, "no narrow phase ran");
    bool calling_thread_only = false;  // few decided pairs: the pair path ran without the executor
    if (detected.hasPairs() && broad[0].device_header) {
        // The pairs stay on the GPU (host_pairs off): nothing to read, test or respond to.
        narrow = NarrowResult{};
        st.reliable.device_pairs_found = broad[0].device_header->needed;
        st.reliable.device_pairs_written = broad[0].device_header->count;
        last_narrow_pairs = 0;
    } else if (detected.hasPairs()) {
        // Reliable: the pairs sorted on the GPU (runSortedPairs), or the survivors straight
        // from the GPU's memory (deduplicated and sorted in parallel by the narrow phase);
        // host meshes from the world's source, engine meshes' triangles from the download.
        if (auto ok = registry.syncSource(ids); !ok) return ok.error();
        // As the objects were at start(): transforms, and the positions (updateVertices may
        // have made another copy current since: pipelining).
        for (std::uint32_t i : detected.objects)
            if (const Object& o = registry.objects[run_ids[i]]; o.host && o.source_index != kNoSource) {
                if (auto ok = registry.source.setTransform(o.source_index, run.meshes[i].transform); !ok)
                    return registry.named(run_ids[i], ok.error());
                if (registry.source.objects()[o.source_index].positions.data() != run.positions[i].data())
                    if (auto ok = registry.source.setHostGeometry(o.source_index, run.positions[i], o.host_indices); !ok)
                        return registry.named(run_ids[i], ok.error());
            }
        registry.source.setGpuTriangles(broad[0].gpu_triangles);
        if (broad[0].has_sorted_pairs) {
            if (!reuse) {  // the memory made ready during the wait (prepareResultMemory), or none
                pair_memory = std::move(ready_pairs);
                response_memory = std::move(ready_responses);
            }
            // Named during the wait (nameEarly) over these pairs, with the same objects.
            const bool named = broad[0].sorted_pairs_seen && std::ranges::equal(ids, run.ids);
            // Sorted in one pass: at most kSmallSortPairs, checked and copied on this thread.
            narrow::CallingThreadExecutor calling_thread;
            calling_thread_only = broad[0].sorted_in_one_pass;
            narrow = narrow::runSortedPairs(broad[0].sorted_pairs, registry.source, options,
                                            calling_thread_only ? static_cast<Executor&>(calling_thread) : *executor, narrow_workspace,
                                            std::move(pair_memory), std::move(response_memory), broad[0].sorted_responses, named);
            st.reliable.pairs_named_during_gpu = named && narrow && narrow->pairs_left_out == 0;
            if (named && narrow) narrow->timings.validate_ms = run.early_name_ms;
            last_narrow_pairs = broad[0].sorted_pairs.size();
            last_narrow_one_pass = calling_thread_only;
            st.reliable.pairs_sorted_on_gpu = true;
            st.reliable.responses_on_gpu = broad[0].has_sorted_responses && narrow && narrow->pairs_left_out == 0;
            st.reliable.pairs_sorted_in_one_pass = broad[0].sorted_in_one_pass;
        } else {
            // detectInto's memory; detect() makes none ready for this path (its results have
            // fewer than kGpuPairSortFrom pairs): run 48, `experiments/session62_old_prepare.diff`.
            narrow = narrow::runPairNarrowPhaseInto(broad[0].pairs, registry.source, options, *executor, narrow_workspace,
                                                    std::move(pair_memory), std::move(response_memory));
            last_narrow_pairs = broad[0].pairs.size();
            calling_thread_only = narrow::runsOnCallingThread(last_narrow_pairs, options.pairs_decided);
        }
        registry.source.setGpuTriangles({});  // the download is overwritten by the next run
    } else {
        narrow = runNarrowPhase(detected.candidates(), options, *executor, narrow_workspace);
        last_narrow_pairs = 0;  // the record path prepares no threads of its own
    }
    st.narrow_ms = msSince(t0);
    if (detected.hasPairs()) st.reliable.device_responses_written = broad[0].device_responses;
    options.may_collide = {};  // it refers to this call's objects
    if (filter_threw) return *filter_threw;
    if (!narrow) return narrow.error();
    if (narrow->pairs_left_out > 0) {
        out.pairs_left_out = narrow->pairs_left_out;
        out.incomplete =
            Error(ErrorCode::LimitExceeded,
                  "found " + std::to_string(narrow->pairs.size() + narrow->pairs_left_out) +
                      " intersecting pairs, more than DetectSettings::limits.max_pairs (" + std::to_string(run_settings.limits.max_pairs) +
                      "): kept " + std::to_string(narrow->pairs.size()) + ", left out " + std::to_string(narrow->pairs_left_out));
    }
    st.host.narrow_threads = calling_thread_only ? 1 : executor->threadCount();
    st.narrow = narrow->stats;
    st.narrow_timings = narrow->timings;
    st.potentially_colliding_triangles = narrow->stats.potentially_colliding_triangles;
    st.cpu_exact_tests = narrow->stats.triangle_tests;
    st.gpu_exact_tests = detected.hasPairs() ? broad[0].cells.exact_tests : 0;
    st.triangle_tests = st.cpu_exact_tests + st.gpu_exact_tests;
    st.positive_tests = narrow->stats.positive_tests;
    if (detected.hasPairs()) st.triangles_downloaded = narrow->stats.candidates;  // distinct triangles in the pairs
    // Run indices grow with ids, so the sorted order survives the mapping; a world whose
    // ids are its run indices (none removed, none left out) needs none.
    out.pairs = std::move(narrow->pairs);
    out.responses = std::move(narrow->responses);
    last_result_pairs = out.pairs.size();
    last_responses = out.responses.size();
    if (!reuse) {
        releaseSlack(out.pairs);
        releaseSlack(out.responses);
    }
    bool renumber = false;
    for (std::size_t i = 0; i < ids.size(); ++i) renumber = renumber || ids[i] != i;
    if (renumber) {
        constexpr std::size_t kGrain = 1 << 15;
        executor->parallelFor(out.pairs.size(), kGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k)
                out.pairs[k].object_a = ids[out.pairs[k].object_a], out.pairs[k].object_b = ids[out.pairs[k].object_b];
        });
        executor->parallelFor(out.responses.size(), kGrain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) out.responses[k].object = ids[out.responses[k].object];
        });
    }
    if (broad[0].scene_box) auto_settings.measured_box = broad[0].scene_box;
    // The tuned grid's time: the GPU span of a detection whose cell stage ran once (a run
    // that grew a buffer is not comparable).
    if (run.grid && broad.size() == 1 && broad[0].cells.runs == 1) auto_settings.grid.report(run.grid->scene, run.grid->step, st.gpu_span_ms);
    if (run.settings.contacts.objects)
        if (auto ok = addContacts(run, detected, ids, out); !ok) return ok.error();
    if (run.settings.contacts.geometry) {
        if (auto ok = addPairContacts(run, detected, ids, out); !ok) return ok.error();
    } else {
        out.pair_contacts.clear();
    }
    if (detected.hasPairs() && broad[0].has_proximity) {
        const auto p0 = Clock::now();
        proximity::sortedPairs(broad[0].proximity, out.proximity, st.proximity);
        const auto& counts = broad[0].proximity_counts;
        st.proximity.triangle_pairs = counts.triangle_pairs;
        st.proximity.distances = counts.distances;
        st.proximity.neighbours = counts.neighbours;
        st.proximity.capacity = counts.capacity;
        out.device_proximity = broad[0].proximity_device;
        st.proximity.ran = true;
        st.proximity.distance = run_settings.proximity.distance;
        st.proximity.runs = broad[0].proximity_runs;
        st.proximity.gpu_ms = broad[0].proximity_ms;
        st.proximity.host_ms = msSince(p0);
    }
    if (auto view = run.detection->devicePairs()) {
        out.device = detections.devicePairsOf(*view, run);
        // collect() may have grown the buffers (a repeated run): devicePairs() names them now.
        if (detections.last_device_pairs && detections.last_device_pairs->slot == out.device->slot)
            detections.last_device_pairs = out.device;
    }
    // Everything the world holds: both slots' broad phases (their tables, with every method's,
    // stage's and the contact stage's rows, and the graph's cached transients) and the
    // uploaded meshes, in Context::deviceMemoryInUse's unit.
    for (const Run& r : detections.runs) st.gpu_memory_bytes += r.detection ? r.detection->memoryBytes() : 0;
    for (const Object& o : registry.objects) {
        st.gpu_memory_bytes += o.vertices.memoryBytes() + o.indices.memoryBytes();
        for (const Object::VertexCopy& c : o.copies) st.gpu_memory_bytes += c.upload.memoryBytes();
    }
    st.total_ms = msSince(run.start);
    st.host.start_ms = run.start_ms;
    st.host.collect_ms = run.wait_ms;
    st.host.prepare_ms = run.prepare_ms;
    st.host.settings_ms = run.settings_ms;
    return out;
}

}  // namespace vkcollide
