// CollisionWorld::preparePipelines: a detection's pipelines made ahead of it, on a broad
// phase of their own that is dropped after; the Context keeps the pipelines (vk::Pipeline),
// so the world's own detections, and every other world's, find them made.
#include <chrono>
#include <cstdint>
#include <limits>
#include <mutex>

#include "api/world_impl.hpp"
#include "broad/broad_phase.hpp"
#include "contacts/contact_stage.hpp"
#include "vk/device.hpp"

namespace vkcollide {
namespace {

std::uint64_t pipelinesCreated(vk::Device& device) {
    std::lock_guard lock(device.pipelines_mutex);
    return device.pipelines_created;
}

}  // namespace

Result<PreparedPipelines> CollisionWorld::preparePipelines(const DetectSettings& settings) {
    const auto t0 = std::chrono::steady_clock::now();
    auto resolved = resolveSettings(settings);
    if (!resolved) return resolved.error();
    auto scope = impl_->guard.enter("CollisionWorld::preparePipelines");
    if (!scope) return scope.error();
    const DetectSettings& s = *resolved;
    vk::Device& device = impl_->device();
    const std::uint64_t before = pipelinesCreated(device);
    auto broad = passes::BroadPhase::create(device, DetectionsInFlight::methodFactory(s.method));
    if (!broad) return broad.error();
    // What the settings turn on, and what Auto may turn on in a later detection (the sort on
    // the GPU, after a detection of many pairs).
    const passes::BroadPhaseSettings b = impl_->methodSettings(s, impl_->sortsOnGpu(s, std::numeric_limits<std::size_t>::max()));
    if (auto ok = (*broad)->preparePipelines(b); !ok) return ok.error();
    if (s.contacts.objects)
        if (auto stage = (*broad)->followUp(passes::ContactStage::create); !stage) return stage.error();
    PreparedPipelines out;
    out.created = static_cast<std::uint32_t>(pipelinesCreated(device) - before);
    out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace vkcollide
