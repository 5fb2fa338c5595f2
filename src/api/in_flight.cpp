// The detections in flight: which slot a new one starts in, and what the calls that
// change objects ask of the ones in flight.
#include "api/in_flight.hpp"

#include <algorithm>
#include <new>

#include "broad/cells/reliable_method.hpp"
#include "broad/peeling/peeling_method.hpp"
#include "vk/device.hpp"

namespace vkcollide {

passes::MethodFactory DetectionsInFlight::methodFactory(DetectMethod method) {
    return method == DetectMethod::Reliable ? passes::ReliableMethod::create : passes::PeelingMethod::create;
}

// The slot the next detection goes into: slot 0 when none is in flight (a world that never
// pipelines never allocates the second), else the other one (created on first use; it
// predicts from the first's measured depth).
Result<DetectionsInFlight::Run*> DetectionsInFlight::freeRun(vk::Device& device) {
    if (inFlight() == runs.size())
        return Error(ErrorCode::InvalidArgument, "submit while " + std::to_string(runs.size()) +
                                                     " detections are in flight (CollisionWorld::kMaxInFlight): collect() one first");
    if (inFlight() == 0) oldest = 0;
    const std::uint32_t k = runs[oldest].in_flight ? 1 - oldest : oldest;
    Run& run = runs[k];
    if (!run.detection) {
        Result<std::unique_ptr<passes::Detection>> created = Error(ErrorCode::OutOfMemory, "host memory ran out creating the second slot");
        try {
            created = passes::Detection::create(device, methodFactory(DetectSettings{}.method));
        } catch (const std::bad_alloc&) {
        }
        if (!created) return created.error();
        run.detection = std::move(*created);
        run.detection->shareDepth(*runs[1 - k].detection);
    }
    return &run;
}

bool DetectionsInFlight::reads(ObjectId id, VkDeviceAddress upload, const Float3* positions) const {
    for (const Run& r : runs) {
        if (!r.in_flight) continue;
        const auto it = std::lower_bound(r.ids.begin(), r.ids.end(), id);  // ids ascend (liveMeshes)
        if (it == r.ids.end() || *it != id) continue;
        const auto k = static_cast<std::size_t>(it - r.ids.begin());
        if (r.meshes[k].vertices == upload || r.positions[k].data() == positions) return true;
    }
    return false;
}

Result<void> DetectionsInFlight::notPending(const char* what) const {
    if (pending())
        return Error(ErrorCode::InvalidArgument, std::string(what) + " while a detection is in flight (it reads what " + what +
                                                     " changes): collect() it first");
    return {};
}

Result<void> DetectionsInFlight::notBusy(const char* what) const {
    if (settling())
        return Error(ErrorCode::Timeout, std::string(what) + " while the GPU work of a detection that timed out still runs " +
                                             "(state() is Busy until it ends): try again later");
    return {};
}

}  // namespace vkcollide
