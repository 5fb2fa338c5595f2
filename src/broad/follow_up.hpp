// A stage that runs after a detection's broad phase was collected, on what that run left:
// its objects as uploaded, its executor, its buffer table and its deadline. Object-level
// contacts (contacts/contact_stage.hpp) are one. It goes through the same path as a
// method's Again passes (BroadPhase::runFollowUp): each submission recorded by the broad
// phase's one recording path, submitted on its executor, waited for within what is left
// of the run's deadline, then collected: Done, or Again for one more submission (a next
// step after a host step, or a buffer grown after the GPU counted an overflow).
//
// Its buffers are owner-sized rows of the broad phase's table (BufferTable::addOwned),
// added once by its factory: the table's memory check covers them, and they live as long
// as the broad phase. A timed-out submission leaves the broad phase busy, like a timed-out
// run: the next run settles it first.
#pragma once

#include <memory>

#include "broad/buffer_table.hpp"
#include "broad/method.hpp"
#include "broad/run_view.hpp"
#include "graph/executor.hpp"

namespace vkcollide::passes {

class FollowUpStage {
public:
    virtual ~FollowUpStage() = default;
    // For errors: "the contact stage".
    virtual const char* name() const noexcept = 0;
    // Before its first submission, after the broad phase's run was collected: sizes its
    // rows and uploads its inputs. Done: nothing to run; Again: record and run.
    [[nodiscard]] virtual Result<Collected> begin(const RunView& run) = 0;
    // The passes of its next submission; it imports its own rows into `g`.
    virtual void record(graph::Graph& g, const RunView& run) = 0;
    // After that submission ended: Done, or Again (record and run once more).
    [[nodiscard]] virtual Result<Collected> collect(const RunView& run, const graph::ExecutionReport& report) = 0;
};

// Makes a follow-up stage on `device`, adding its rows to `io_table`.
using FollowUpFactory = Result<std::unique_ptr<FollowUpStage>> (*)(vk::Device& device, BufferTable& io_table);

}  // namespace vkcollide::passes
