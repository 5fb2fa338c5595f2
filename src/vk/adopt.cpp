// Context::adopt: borrow an engine's device after checking, by name, everything vkcollide
// needs of it (context.hpp lists it). The engine states what it enabled; Vulkan has no
// query for a device's enabled features, so that statement is what is checked.
#include <string>
#include <vector>

#include "vk/debug_names.hpp"
#include "vk/device.hpp"

namespace vkcollide {
using namespace vk;

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

std::string versionText(std::uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version));
}

bool below13(std::uint32_t version) {
    return VK_API_VERSION_MAJOR(version) < 1 || (VK_API_VERSION_MAJOR(version) == 1 && VK_API_VERSION_MINOR(version) < 3);
}

}  // namespace

Result<std::unique_ptr<Context>> Context::adopt(const AdoptedDevice& in, MessageCallback on_message) {
    std::vector<std::string> null_handles;
    if (!in.get_instance_proc_addr) null_handles.emplace_back("get_instance_proc_addr");
    if (!in.instance) null_handles.emplace_back("instance");
    if (!in.physical_device) null_handles.emplace_back("physical_device");
    if (!in.device) null_handles.emplace_back("device");
    if (!in.queue) null_handles.emplace_back("queue");
    if (!null_handles.empty())
        return Error(ErrorCode::InvalidArgument, "AdoptedDevice needs get_instance_proc_addr, instance, physical_device, "
                                                 "device and queue; null: " + joined(null_handles));
    // The engine's statement first: it costs no Vulkan call and names what to fix.
    auto enabled = readEnabledChain(in.enabled_features);
    if (!enabled) return enabled.error();
    if (below13(in.api_version))
        return Error(ErrorCode::UnsupportedFeature, "the adopted instance was created for Vulkan " + versionText(in.api_version) +
                                                        " (AdoptedDevice::api_version); vkcollide needs 1.3");
    if (auto missing = enabled->missingRequired(); !missing.empty())
        return Error(ErrorCode::UnsupportedFeature,
                     "the adopted device was created without these required features: " + joined(missing) +
                         " (enable them in the VkPhysicalDeviceFeatures2 chain of VkDeviceCreateInfo; "
                         "vkcollide::enableRequiredFeatures() sets them)");

    auto d = std::make_shared<Device>();
    d->on_message = std::move(on_message);
    if (static_cast<bool>(in.queue_hooks.lock) != static_cast<bool>(in.queue_hooks.unlock))
        return Error(ErrorCode::InvalidArgument, "AdoptedDevice::queue_hooks: lock and unlock come as a pair (one of them is empty)");
    d->queue_hooks = in.queue_hooks;
    if (auto ok = takeHostHooks(*d, in.allocation_callbacks, in.memory_hooks, "AdoptedDevice"); !ok) return ok.error();
    auto global = loadGlobalFunctions(in.get_instance_proc_addr);
    if (!global) return global.error();
    d->global = *global;
    d->instance = in.instance;
    d->physical = in.physical_device;
    d->device = in.device;
    d->queue = in.queue;
    d->queue_family = in.queue_family;
    auto inst = loadInstanceFunctions(in.get_instance_proc_addr, in.instance);
    if (!inst) return inst.error();
    d->instance_fns = *inst;
    PhysicalDeviceReport physical = describePhysicalDevice(d->instance_fns, d->physical);
    d->info = physical.info;
    if (below13(d->info.api_version))
        return Error(ErrorCode::UnsupportedFeature, "the adopted device " + d->info.name + " supports Vulkan " +
                                                        versionText(d->info.api_version) + "; vkcollide needs 1.3");

    // Optional capabilities: used where the engine enabled them (and the device has them).
    const auto listed = [&](const char* name) { return listsExtension(in.enabled_extensions, name); };
    d->conservative_rasterization = listed(VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME) && d->info.conservative_rasterization;
    d->push_descriptor = listed(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) && d->info.push_descriptor;
    d->statistics_unavailable = "an adopted device: pipeline statistics need a Context that creates its device (ContextCreateInfo)";
    d->shader_float64 = enabled->has(Feature::ShaderFloat64);
    d->robust_buffer_access = enabled->has(Feature::RobustBufferAccess);
    d->robust_buffer_access2 = listed(VK_EXT_ROBUSTNESS_2_EXTENSION_NAME) && enabled->has(Feature::RobustBufferAccess2);
    d->timeline_semaphore = enabled->has(Feature::TimelineSemaphore);

    if (auto ok = finishDevice(*d); !ok) return ok.error();
    std::vector<std::string> queue_lacks;
    if (!(d->queue_flags & VK_QUEUE_GRAPHICS_BIT)) queue_lacks.emplace_back("graphics");
    if (!(d->queue_flags & VK_QUEUE_COMPUTE_BIT)) queue_lacks.emplace_back("compute");
    if (d->timestamp_valid_bits == 0) queue_lacks.emplace_back("timestamps (timestampValidBits = 0)");
    if (!queue_lacks.empty())
        return Error(ErrorCode::UnsupportedFeature, "the adopted queue family " + std::to_string(in.queue_family) +
                                                        " lacks: " + joined(queue_lacks));
    auto dev = loadDeviceFunctions(d->instance_fns, d->device, d->push_descriptor);
    if (!dev) return dev.error();
    d->fns = *dev;
    // Vulkan has no query for an instance's enabled extensions: the engine's list says it.
    d->debug_utils = listsExtension(in.enabled_instance_extensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
                     loadDebugLabelFunctions(in.get_instance_proc_addr, in.instance, d->fns);
    if (auto ok = setUpPipelineCache(*d, in.pipeline_cache, in.pipeline_cache_data); !ok) return ok.error();
    return std::unique_ptr<Context>(new Context(std::move(d)));
}

}  // namespace vkcollide
