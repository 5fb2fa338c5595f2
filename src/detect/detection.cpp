#include "detect/detection.hpp"

#include <algorithm>

#include "broad/projection.hpp"
#include "detect/axis_union.hpp"

namespace vkcollide::passes {

Result<std::unique_ptr<Detection>> Detection::create(vk::Device& device, MethodFactory method) {
    if (!method) return Error(ErrorCode::InvalidArgument, "Detection::create: no broad-phase method given");
    std::unique_ptr<Detection> d(new Detection(device));
    auto bp = BroadPhase::create(device, method);
    if (!bp) return bp.error();
    d->broads_[0] = std::move(*bp);
    d->broad_methods_[0] = method;
    return d;
}

Detection::~Detection() {
    // Never free buffers the GPU may still read.
    if (pending_) (void)gather();
}

bool Detection::busy() const {
    return std::any_of(broads_.begin(), broads_.end(), [](const auto& bp) { return bp && bp->busy(); });
}

void Detection::abandon() noexcept {
    for (std::uint32_t k = 0; k < broads_.size(); ++k) {
        if (axis_pending_[k] && broads_[k]) broads_[k]->abandon();
        axis_pending_[k] = false;
        ready_[k].reset();
    }
    pending_ = false;
}

std::uint64_t Detection::memoryBytes() const noexcept {
    std::uint64_t n = 0;
    for (const auto& bp : broads_)
        if (bp) n += bp->memoryBytes();
    if (spare_) n += spare_->memoryBytes();
    return n;
}

Result<FollowUpStage*> Detection::followUp(FollowUpFactory factory) {
    if (!broads_[0]) return Error(ErrorCode::InvalidArgument, "no detection ran yet: nothing to follow up");
    return broads_[0]->followUp(factory);
}

Result<void> Detection::runFollowUp(FollowUpStage& stage) {
    if (pending_ || !broads_[0]) return Error(ErrorCode::InvalidArgument, "a follow-up stage runs after a detection was collected");
    return broads_[0]->runFollowUp(stage);
}

// The objects of this run: every one given that this detection has not excluded.
void Detection::selectRunObjects() {
    run_meshes_.clear();
    run_objects_.clear();
    for (std::uint32_t i = 0; i < meshes_.size(); ++i) {
        if (std::any_of(excluded_.begin(), excluded_.end(), [&](const ObjectFault& f) { return f.object == i; })) continue;
        run_meshes_.push_back(meshes_[i]);
        run_objects_.push_back(i);
    }
    // The pair mask follows the objects left in (rebuilt only in frames that leave one out).
    run_pair_mask_ = settings_.broad.pair_mask;
    if (run_pair_mask_ && run_meshes_.size() != meshes_.size()) {
        subset_mask_.subset(*settings_.broad.pair_mask, run_objects_);
        run_pair_mask_ = &subset_mask_;
    }
}

// An error of this detection; the GPU check's findings, if any, go to failure().
Error Detection::failed(Error e) {
    failure_ = {};
    if (e.code() == ErrorCode::InvalidMesh && broads_[failed_axis_])
        for (ObjectFault f : broads_[failed_axis_]->faults())
            if (f.object < run_objects_.size()) {
                f.object = run_objects_[f.object];
                failure_.faults.push_back(f);
            }
    return e;
}

// Starts every axis: measured (two submissions, waited for) or with the layers predicted
// by the last detection (one submission, left in flight). Stops at the first error; the
// axes already started stay for gather() to drain.
Result<void> Detection::startAxes(bool measure, graph::SubmitTarget* target) {
    for (std::uint32_t k = 0; k < axes_; ++k) {
        const bool last = k + 1 == axes_;  // the engine's signals go with the last direction
        failed_axis_ = k;
        if (!broads_[k] || broad_methods_[k] != settings_.method) {
            depth_known_[k] = false;
            if (k == 0 && spare_ && spare_method_ == settings_.method) {
                std::swap(broads_[0], spare_);
                std::swap(broad_methods_[0], spare_method_);
            } else {
                if (k == 0 && broads_[0]) {
                    spare_ = std::move(broads_[0]);
                    spare_method_ = broad_methods_[0];
                }
                broads_[k].reset();
                auto bp = BroadPhase::create(*device_, settings_.method);
                if (!bp) return bp.error();
                broads_[k] = std::move(*bp);
                broad_methods_[k] = settings_.method;
            }
        }
        if (axes_ > 1 && broads_[k]->traits().pairs)
            return Error(ErrorCode::InvalidArgument, "three sampling directions unite triangle records: the method asked for returns "
                                                     "pairs and runs along one direction (axes = 1)");
        BroadPhaseSettings b = settings_.broad;
        b.direction = directions_[k];
        b.pair_mask = run_pair_mask_;
        // A method that measures nothing is never waited for here unless asked (measure).
        if (measure || (!depth_known_[k] && broads_[k]->traits().measures)) {
            if (target && target->engine)
                return Error(ErrorCode::InvalidArgument,
                             "record: the peeling method measures the depth complexity first (the first detection, or after "
                             "objects were added or removed), with a host wait between two submissions; run detect() or "
                             "submit() once, or use the reliable method");
            auto r = broads_[k]->run(run_meshes_, b, target, last);
            if (!r) return r.error();
            ready_[k] = std::move(*r);
        } else {
            if (auto ok = broads_[k]->submit(run_meshes_, b, std::max(last_depth_[k], 1u), target, last); !ok) return ok.error();
            axis_pending_[k] = true;
        }
    }
    return {};
}

// Waits for every axis started; always drains all of them and returns the first error.
Result<std::vector<BroadPhaseResult>> Detection::gather() {
    std::vector<BroadPhaseResult> out;
    std::optional<Error> first;
    for (std::uint32_t k = 0; k < broads_.size(); ++k) {
        if (ready_[k]) {
            out.push_back(std::move(*ready_[k]));
            ready_[k].reset();
        } else if (axis_pending_[k]) {
            axis_pending_[k] = false;
            auto r = broads_[k]->collect();
            if (r) {
                out.push_back(std::move(*r));
            } else if (!first) {
                first = r.error();
                failed_axis_ = k;
            }
        }
    }
    pending_ = false;
    if (first) return *first;
    return out;
}

bool Detection::excludable(const Error& e) const {
    return settings_.bad_objects == BadObjectPolicy::Exclude && e.code() == ErrorCode::InvalidMesh && broads_[failed_axis_] &&
           !broads_[failed_axis_]->faults().empty();
}

// Leaves out the objects the GPU check named, each with its own finding. Why exclude and
// go on rather than fail: a bad engine buffer (a simulation that produced NaN) should not
// blind collision detection for every other object; re-running without it gives the
// others exactly the pairs they would have alone (tests/stability/faults_tests.cpp).
Result<void> Detection::excludeBad() {
    const std::size_t before = excluded_.size();
    for (ObjectFault f : broads_[failed_axis_]->faults())
        if (f.object < run_objects_.size()) {
            f.object = run_objects_[f.object];
            excluded_.push_back(f);
        }
    if (excluded_.size() == before) return Error(ErrorCode::InvalidMesh, "the GPU input check failed without naming an object");
    selectRunObjects();
    if (run_meshes_.empty()) {
        failure_ = {excluded_, true};
        return Error(ErrorCode::InvalidMesh, "no object left to test: object " + std::to_string(excluded_.front().object) + ": " +
                                                 describe(excluded_.front()));
    }
    return {};
}

// Measured runs of every axis, leaving out bad engine meshes until the check passes: one
// more run per bad object (two when two are named at once), only in frames that have one.
Result<std::vector<BroadPhaseResult>> Detection::runExcluding() {
    for (;;) {
        const Result<void> ok = startAxes(true, nullptr);
        const std::uint32_t failed = failed_axis_;
        auto r = gather();  // drains what startAxes started, even after an error
        if (!ok) {
            failed_axis_ = failed;
            r = ok.error();
        }
        if (r || !excludable(r.error())) return r;
        if (auto ex = excludeBad(); !ex) return ex.error();
    }
}

Result<bool> Detection::ready() {
    for (std::uint32_t k = 0; k < broads_.size(); ++k) {
        if (!axis_pending_[k] || !broads_[k]) continue;
        auto done = broads_[k]->poll();
        if (!done) return done.error();
        if (*done == vk::Completion::NotYet) return false;
    }
    return true;
}

Result<void> Detection::start(std::span<const GpuMesh> meshes, const DetectionSettings& s, bool measure, graph::SubmitTarget* target) {
    if (pending_) return Error(ErrorCode::InvalidArgument, "submit while a detection is in flight: collect() it first");
    if (!s.method) return Error(ErrorCode::InvalidArgument, "DetectionSettings::method names no broad-phase method");
    if (target && target->engine && s.axes > 1)
        return Error(ErrorCode::InvalidArgument, "record: three sampling directions make three submissions; an engine's command "
                                                 "buffer takes one (axes = 1)");
    failure_ = {};
    settings_ = s;
    axes_ = s.axes;
    directions_[0] = s.broad.direction;
    if (axes_ == 3) {
        // The other two: the image axes of the first direction (world axes when it is one).
        const ProjectionBasis basis = projectionBasis(s.broad.direction);
        directions_[1] = basis.u;
        directions_[2] = basis.v;
    }
    meshes_.assign(meshes.begin(), meshes.end());
    excluded_.clear();
    selectRunObjects();
    if (measure) {
        auto r = runExcluding();
        if (!r) return failure_.none_left ? r.error() : failed(r.error());
        for (std::uint32_t k = 0; k < r->size(); ++k) ready_[k] = std::move((*r)[k]);
        pending_ = true;
        return {};
    }
    // A bad engine mesh found while measuring here (no depth known yet) fails the call;
    // one found by the submission is left out in collect().
    if (auto ok = startAxes(false, target); !ok) {
        const std::uint32_t failed_at = failed_axis_;
        (void)gather();
        failed_axis_ = failed_at;
        return failed(ok.error());
    }
    pending_ = true;
    return {};
}

void Detection::setDeadline(std::chrono::steady_clock::time_point deadline) {
    settings_.broad.deadline = deadline;
    for (std::uint32_t k = 0; k < broads_.size(); ++k)
        if (broads_[k] && (axis_pending_[k] || !pending_)) broads_[k]->setDeadline(deadline);
}

Result<DetectionResult> Detection::collect() {
    if (!pending_) return Error(ErrorCode::InvalidArgument, "collect without a detection in flight: submit() first");
    failure_ = {};
    auto r = gather();
    if (!r && excludable(r.error())) {
        // Found by the check of this submission: leave the object out and run again now.
        if (auto ex = excludeBad(); !ex) return failure_.none_left ? ex.error() : failed(ex.error());
        r = runExcluding();
    }
    if (!r) return failure_.none_left ? r.error() : failed(r.error());
    DetectionResult out;
    out.axes = std::move(*r);
    out.directions = directions_;
    out.objects = run_objects_;
    out.excluded = std::move(excluded_);
    excluded_.clear();
    for (std::uint32_t k = 0; k < out.axes.size(); ++k) {
        last_depth_[k] = out.axes[k].depth_complexity;
        depth_known_[k] = true;
    }
    if (out.axes.size() > 1) out.united = uniteAxes(out.axes);
    return out;
}

}  // namespace vkcollide::passes
