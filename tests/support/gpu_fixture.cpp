#include "support/gpu_fixture.hpp"

namespace vkcollide::test {

ValidatedContext::ValidatedContext(PFN_vkGetInstanceProcAddr get_instance_proc_addr, bool debug_names) {
    ContextCreateInfo info;
    info.validation = true;
    info.get_instance_proc_addr = get_instance_proc_addr;
    info.debug_names = debug_names;
    auto log = log_;
    info.on_message = [log](MessageSeverity severity, std::string_view text) {
        if (severity == MessageSeverity::Info) return;
        std::lock_guard<std::mutex> lock(log->mutex);
        log->lines.emplace_back(text);
    };
    auto ctx = Context::create(info);
    if (!ctx) FAIL("cannot create a validated Vulkan context: " << ctx.error().message());
    context_ = std::move(*ctx);
}

std::vector<std::string> ValidatedContext::messages() const {
    std::lock_guard<std::mutex> lock(log_->mutex);
    return log_->lines;
}

}  // namespace vkcollide::test
