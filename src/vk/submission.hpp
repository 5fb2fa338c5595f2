// One submission in flight: a command pool, one primary command buffer and a fence, or the
// engine's command buffer and timeline (EngineCommandBuffer in context.hpp). Every queue
// submission vkcollide makes goes through Submission::submit (and from there through
// Device::queueSubmit: the Context's lock and the engine's QueueHooks).
//
// States and what moves between them:
//
//   Idle --begin()/beginIn()--> Recording --submit()--> Pending --poll()/wait*() Done--> Idle
//                                   |  ^                  |
//                                   |  '--submit() refused (bad SubmitSync): still Recording
//                                   '--submit() failed: Idle (nothing was submitted)
//   Idle --submitSyncOnly()--> Pending (a batch of waits and signals only)
//   Idle --resubmit()--> Pending (the last recording begun with Reuse::Again, submitted again)
//   Pending --waitFor() NotYet / wait() timeout--> Pending (wait again, or give the device up)
//   any --VK_ERROR_DEVICE_LOST--> Lost (every later call fails with DeviceLost)
//
// A timeout is never an error state: the work stays Pending and every resource it uses must
// stay alive. reset() (and the destructor) waits for Pending work without a time limit:
// Vulkan guarantees that such waits return once the device is lost, so a hung GPU ends as
// Lost, never as freed memory the GPU still writes.
#pragma once

#include <cstdint>
#include <string_view>

#include "vk/device.hpp"

namespace vkcollide::vk {

enum class Completion {
    Done,   // nothing of it is pending any more (or nothing was submitted)
    NotYet  // still running
};

class Submission {
public:
    enum class State { Idle, Recording, Pending, Lost };
    // How long wait() waits by default: long enough for any detection on a CPU driver.
    static constexpr std::uint64_t kDefaultTimeoutNs = 60ull * 1000 * 1000 * 1000;
    // Whether a recording may be submitted more than once (resubmit()). Once: recorded with
    // VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, which lets a driver free as it goes.
    enum class Reuse { Once, Again };

    Submission() = default;
    // `name` names its command pool, command buffer and fence (vk/debug_names.hpp).
    static Result<Submission> create(Device& device, std::string_view name = "submission");
    ~Submission() { reset(); }
    Submission(Submission&& o) noexcept { *this = std::move(o); }
    Submission& operator=(Submission&& o) noexcept;

    // Starts recording into the Submission's own command buffer. Pending: waits for it
    // first (kDefaultTimeoutNs; a timeout is returned as wait()'s error and the state stays
    // Pending). Recording (a recording abandoned after an error): starts over.
    // Errors: DeviceLost (state Lost), VulkanError / OutOfMemory. Ends what resubmit()
    // could submit (the pool is reset).
    Result<VkCommandBuffer> begin(Reuse reuse = Reuse::Once);
    // Starts recording into the engine's command buffer (context.hpp, EngineCommandBuffer);
    // returns target.command_buffer. submit() then submits nothing: the work is Pending
    // until the engine's timeline reaches target.value. Pending: as begin().
    // Errors: InvalidArgument (null command buffer or timeline; value 0 or a value the
    // timeline has already reached: the work would look finished before it ran),
    // UnsupportedFeature (the device has not enabled timelineSemaphore), DeviceLost.
    Result<VkCommandBuffer> beginIn(const EngineCommandBuffer& target);

    // Ends the recording and submits it with sync's waits and signals (one batch).
    // Errors: InvalidArgument when not Recording, when a semaphore is VK_NULL_HANDLE or a
    // stage mask is 0 (named by list and index), or when sync is not empty after beginIn()
    // (the engine orders its own command buffer): the state stays Recording, so the caller
    // may submit again with a fixed sync. VulkanError / OutOfMemory from ending or
    // submitting: state Idle, nothing was submitted (Vulkan leaves semaphores untouched on
    // a failed vkQueueSubmit2). DeviceLost: state Lost.
    Result<void> submit(const SubmitSync& sync = {});
    // Submits a batch without commands that only waits and signals: what a caller uses when
    // its work failed after (or before) it promised the engine a signal, so that neither the
    // engine's GPU nor a binary wait is left hanging. Idle, or Pending (waited for first, as
    // begin()); Recording is refused (submit or abandon the recording first). Errors: as
    // submit(); on success the state is Pending.
    Result<void> submitSyncOnly(const SubmitSync& sync);
    // Submits the Submission's own command buffer again, as the last submit() after a
    // begin(Reuse::Again) ended it, with sync's waits and signals: what a caller does when
    // it would record exactly the same commands, all of whose objects are still alive (the
    // caller's to know). Pending: waited for first, as begin(). Errors: InvalidArgument
    // when nothing can be resubmitted (canResubmit() false) or as submit() for sync;
    // otherwise as submit().
    Result<void> resubmit(const SubmitSync& sync = {});
    // Whether resubmit() has a recording to submit: begun with Reuse::Again, ended and
    // queued by submit(), and not begun again (or reset) since. beginIn() keeps it.
    bool canResubmit() const noexcept { return reusable_ && state_ != State::Lost && state_ != State::Recording; }
    // The Submission's own command buffer (VK_NULL_HANDLE before create()), whatever state it is in.
    VkCommandBuffer commandBuffer() const noexcept { return cmd_; }

    // Non-blocking: Done once the submitted work has finished (state Idle), NotYet while it
    // runs. Idle or Recording: Done. Errors: DeviceLost (state Lost); VulkanError /
    // OutOfMemory from the status query leave it Pending.
    Result<Completion> poll();
    // Waits up to timeout_ns (0: poll). NotYet after the timeout: still Pending.
    Result<Completion> waitFor(std::uint64_t timeout_ns);
    // waitFor(), with NotYet reported as Error(VulkanError, VK_TIMEOUT, "GPU work did not
    // finish within the timeout ...") and the state still Pending.
    Result<void> wait(std::uint64_t timeout_ns = kDefaultTimeoutNs);

    State state() const noexcept { return state_; }
    bool pending() const noexcept { return state_ == State::Pending; }
    bool lost() const noexcept { return state_ == State::Lost; }
    bool valid() const noexcept { return pool_ != VK_NULL_HANDLE; }
    // Waits for Pending work without a time limit, then destroys the pool and fence. Keeps
    // the DeviceRef until the destructor (see resources.hpp).
    void reset();

private:
    Result<void> waitBeforeRecording();
    Result<void> queue(VkCommandBuffer cmd, const SubmitSync& sync);
    Error lose(VkResult result, const char* what);

    DeviceRef device_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    State state_ = State::Idle;
    bool reusable_ = false;       // see canResubmit()
    bool begun_reusable_ = false; // the recording in progress was begun with Reuse::Again
    // Set by beginIn(): the recording goes into the engine's command buffer, and
    // completion is read from its timeline instead of the fence.
    EngineCommandBuffer engine_{};
};

}  // namespace vkcollide::vk
