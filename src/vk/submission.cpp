// Submission: see the state diagram in submission.hpp.
#include "vk/submission.hpp"

#include <string>
#include <vector>

#include "vk/debug_names.hpp"

namespace vkcollide::vk {
namespace {

// The problem with one list of SubmitSync, or empty.
std::string syncProblem(std::span<const SemaphoreSubmit> list, const char* which) {
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string who = std::string("SubmitSync::") + which + "[" + std::to_string(i) + "]";
        if (list[i].semaphore == VK_NULL_HANDLE) return who + ": semaphore is VK_NULL_HANDLE";
        if (list[i].stages == 0) return who + ": stages is 0 (use VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT for all of the work)";
    }
    return {};
}

void appendInfos(std::span<const SemaphoreSubmit> list, std::vector<VkSemaphoreSubmitInfo>& out) {
    for (const SemaphoreSubmit& s : list) {
        VkSemaphoreSubmitInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        info.semaphore = s.semaphore;
        info.value = s.value;  // ignored for binary semaphores
        info.stageMask = s.stages;
        out.push_back(info);
    }
}

}  // namespace

Result<Submission> Submission::create(Device& device, std::string_view name) {
    Submission s;
    s.device_ = device.ref();
    const auto& f = device.fns;
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pi.queueFamilyIndex = device.queue_family;
    VkResult r = f.vkCreateCommandPool(device.device, &pi, device.allocator(), &s.pool_);
    if (r != VK_SUCCESS) {
        s.pool_ = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateCommandPool");
    }
    nameObject(device, s.pool_, name, " pool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = s.pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    r = f.vkAllocateCommandBuffers(device.device, &ai, &s.cmd_);
    if (r != VK_SUCCESS) return vulkanError(r, "vkAllocateCommandBuffers");
    nameObject(device, s.cmd_, name);
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    r = f.vkCreateFence(device.device, &fi, device.allocator(), &s.fence_);
    if (r != VK_SUCCESS) {
        s.fence_ = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateFence");
    }
    nameObject(device, s.fence_, name, " fence");
    return s;
}

Submission& Submission::operator=(Submission&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::move(o.device_);
        o.device_.reset();
        pool_ = std::exchange(o.pool_, VK_NULL_HANDLE);
        cmd_ = std::exchange(o.cmd_, VK_NULL_HANDLE);
        fence_ = std::exchange(o.fence_, VK_NULL_HANDLE);
        state_ = std::exchange(o.state_, State::Idle);
        reusable_ = std::exchange(o.reusable_, false);
        begun_reusable_ = std::exchange(o.begun_reusable_, false);
        engine_ = std::exchange(o.engine_, EngineCommandBuffer{});
    }
    return *this;
}

Error Submission::lose(VkResult result, const char* what) {
    if (result == VK_ERROR_DEVICE_LOST) state_ = State::Lost;
    return vulkanError(result, what);
}

Result<void> Submission::waitBeforeRecording() {
    if (!valid()) return Error(ErrorCode::InvalidArgument, "the Submission was not created (or was reset)");
    if (state_ == State::Lost) return Error(ErrorCode::DeviceLost, "the device was lost during an earlier submission",
                                            static_cast<std::int32_t>(VK_ERROR_DEVICE_LOST));
    if (state_ == State::Pending) return wait();
    return {};
}

Result<VkCommandBuffer> Submission::begin(Reuse reuse) {
    if (auto ok = waitBeforeRecording(); !ok) return ok.error();
    const auto& f = device_->fns;
    engine_ = EngineCommandBuffer{};
    state_ = State::Idle;
    reusable_ = false;
    VkResult r = f.vkResetCommandPool(device_->device, pool_, 0);
    if (r != VK_SUCCESS) return lose(r, "vkResetCommandPool");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = reuse == Reuse::Once ? VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT : 0;
    r = f.vkBeginCommandBuffer(cmd_, &bi);
    if (r != VK_SUCCESS) return lose(r, "vkBeginCommandBuffer");
    state_ = State::Recording;
    begun_reusable_ = reuse == Reuse::Again;
    return cmd_;
}

Result<VkCommandBuffer> Submission::beginIn(const EngineCommandBuffer& target) {
    if (!target.command_buffer) return Error(ErrorCode::InvalidArgument, "EngineCommandBuffer::command_buffer is VK_NULL_HANDLE");
    if (!target.timeline) return Error(ErrorCode::InvalidArgument, "EngineCommandBuffer::timeline is VK_NULL_HANDLE");
    if (!device_ || !device_->timeline_semaphore)
        return Error(ErrorCode::UnsupportedFeature, "EngineCommandBuffer needs the timelineSemaphore feature, which the device has not enabled");
    if (target.value == 0)
        return Error(ErrorCode::InvalidArgument, "EngineCommandBuffer::value is 0: a timeline starts there, so the work would look finished before it ran");
    if (auto ok = waitBeforeRecording(); !ok) return ok.error();
    std::uint64_t now = 0;
    VkResult r = device_->fns.vkGetSemaphoreCounterValue(device_->device, target.timeline, &now);
    if (r != VK_SUCCESS) return lose(r, "vkGetSemaphoreCounterValue (EngineCommandBuffer::timeline)");
    if (now >= target.value)
        return Error(ErrorCode::InvalidArgument, "EngineCommandBuffer::value " + std::to_string(target.value) +
                                                     " is already reached (the timeline is at " + std::to_string(now) +
                                                     "): the work would look finished before it ran");
    engine_ = target;
    state_ = State::Recording;
    return target.command_buffer;
}

Result<void> Submission::submit(const SubmitSync& sync) {
    if (state_ != State::Recording)
        return Error(ErrorCode::InvalidArgument, state_ == State::Lost ? "submit after the device was lost"
                                                                       : "submit without a recording: begin() first");
    if (engine_.command_buffer) {
        if (!sync.wait.empty() || !sync.signal.empty())
            return Error(ErrorCode::InvalidArgument, "SubmitSync given for work recorded into the engine's command buffer: the "
                                                     "engine orders its own submission (leave SubmitSync empty)");
        state_ = State::Pending;  // done when the engine's timeline reaches engine_.value
        return {};
    }
    if (std::string p = syncProblem(sync.wait, "wait"); !p.empty()) return Error(ErrorCode::InvalidArgument, p);
    if (std::string p = syncProblem(sync.signal, "signal"); !p.empty()) return Error(ErrorCode::InvalidArgument, p);

    // From here on a failure leaves nothing submitted: Idle, or Lost.
    state_ = State::Idle;
    VkResult r = device_->fns.vkEndCommandBuffer(cmd_);
    if (r != VK_SUCCESS) return lose(r, "vkEndCommandBuffer");
    auto queued = queue(cmd_, sync);
    reusable_ = queued && begun_reusable_;
    return queued;
}

Result<void> Submission::resubmit(const SubmitSync& sync) {
    if (!canResubmit())
        return Error(ErrorCode::InvalidArgument, state_ == State::Lost ? "resubmit after the device was lost"
                                                                       : "resubmit without a recording begun with Reuse::Again and submitted since");
    if (std::string p = syncProblem(sync.wait, "wait"); !p.empty()) return Error(ErrorCode::InvalidArgument, p);
    if (std::string p = syncProblem(sync.signal, "signal"); !p.empty()) return Error(ErrorCode::InvalidArgument, p);
    if (auto ok = waitBeforeRecording(); !ok) return ok.error();
    engine_ = EngineCommandBuffer{};
    state_ = State::Idle;
    return queue(cmd_, sync);
}

Result<void> Submission::submitSyncOnly(const SubmitSync& sync) {
    if (state_ == State::Recording)
        return Error(ErrorCode::InvalidArgument, "submitSyncOnly while recording: submit the recording (or begin again) first");
    if (std::string p = syncProblem(sync.wait, "wait"); !p.empty()) return Error(ErrorCode::InvalidArgument, p);
    if (std::string p = syncProblem(sync.signal, "signal"); !p.empty()) return Error(ErrorCode::InvalidArgument, p);
    if (auto ok = waitBeforeRecording(); !ok) return ok.error();
    engine_ = EngineCommandBuffer{};
    state_ = State::Idle;
    return queue(VK_NULL_HANDLE, sync);
}

// One batch: `cmd` (none when null) between sync's waits and signals, with the fence.
Result<void> Submission::queue(VkCommandBuffer cmd, const SubmitSync& sync) {
    VkResult r = device_->fns.vkResetFences(device_->device, 1, &fence_);
    if (r != VK_SUCCESS) return lose(r, "vkResetFences");
    std::vector<VkSemaphoreSubmitInfo> waits, signals;
    appendInfos(sync.wait, waits);
    appendInfos(sync.signal, signals);
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = cmd;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.waitSemaphoreInfoCount = static_cast<std::uint32_t>(waits.size());
    si.pWaitSemaphoreInfos = waits.data();
    si.commandBufferInfoCount = cmd ? 1 : 0;
    si.pCommandBufferInfos = cmd ? &cbi : nullptr;
    si.signalSemaphoreInfoCount = static_cast<std::uint32_t>(signals.size());
    si.pSignalSemaphoreInfos = signals.data();
    r = device_->queueSubmit(std::span(&si, 1), fence_);
    if (r != VK_SUCCESS) return lose(r, "vkQueueSubmit2");
    state_ = State::Pending;
    return {};
}

Result<Completion> Submission::waitFor(std::uint64_t timeout_ns) {
    if (state_ == State::Lost)
        return Error(ErrorCode::DeviceLost, "the device was lost during this submission", static_cast<std::int32_t>(VK_ERROR_DEVICE_LOST));
    if (state_ != State::Pending) return Completion::Done;
    const auto& f = device_->fns;
    VkResult r;
    if (engine_.command_buffer) {
        if (timeout_ns == 0) {
            std::uint64_t now = 0;
            r = f.vkGetSemaphoreCounterValue(device_->device, engine_.timeline, &now);
            if (r == VK_SUCCESS && now < engine_.value) r = VK_TIMEOUT;
        } else {
            VkSemaphoreWaitInfo wi{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
            wi.semaphoreCount = 1;
            wi.pSemaphores = &engine_.timeline;
            wi.pValues = &engine_.value;
            r = f.vkWaitSemaphores(device_->device, &wi, timeout_ns);
        }
    } else {
        r = timeout_ns == 0 ? f.vkGetFenceStatus(device_->device, fence_)
                            : f.vkWaitForFences(device_->device, 1, &fence_, VK_TRUE, timeout_ns);
    }
    if (r == VK_TIMEOUT || r == VK_NOT_READY) return Completion::NotYet;
    if (r != VK_SUCCESS) return lose(r, engine_.command_buffer ? "waiting for the engine's timeline" : "vkWaitForFences");
    state_ = State::Idle;
    return Completion::Done;
}

Result<Completion> Submission::poll() { return waitFor(0); }

Result<void> Submission::wait(std::uint64_t timeout_ns) {
    auto done = waitFor(timeout_ns);
    if (!done) return done.error();
    if (*done == Completion::NotYet)
        return Error(ErrorCode::VulkanError, "GPU work did not finish within the timeout of " + std::to_string(timeout_ns / 1000000) +
                                                 " ms; it is still pending (wait again, or treat the device as lost)",
                     static_cast<std::int32_t>(VK_TIMEOUT));
    return {};
}

void Submission::reset() {
    if (!device_) return;
    // Never free what the GPU may still use: wait without a limit (a lost device ends the
    // wait). The result does not matter here: the objects go either way.
    if (state_ == State::Pending) (void)waitFor(UINT64_MAX);
    const auto& f = device_->fns;
    if (fence_) f.vkDestroyFence(device_->device, fence_, device_->allocator());
    if (pool_) f.vkDestroyCommandPool(device_->device, pool_, device_->allocator());
    fence_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
    cmd_ = VK_NULL_HANDLE;
    engine_ = EngineCommandBuffer{};
    reusable_ = begun_reusable_ = false;
    if (state_ != State::Lost) state_ = State::Idle;
}

}  // namespace vkcollide::vk
