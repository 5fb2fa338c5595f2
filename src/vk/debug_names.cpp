#include "vk/debug_names.hpp"

#include <string>

namespace vkcollide::vk {

bool loadDebugLabelFunctions(PFN_vkGetInstanceProcAddr gipa, VkInstance instance, DeviceFunctions& io_fns) noexcept {
    bool all = true;
#define VKC_LOAD(name)                                                          \
    io_fns.name = reinterpret_cast<PFN_##name>(gipa(instance, #name));          \
    all = all && io_fns.name != nullptr;
    VKC_DEBUG_LABEL_FUNCTIONS(VKC_LOAD)
#undef VKC_LOAD
    if (!all) {
#define VKC_CLEAR(name) io_fns.name = nullptr;
        VKC_DEBUG_LABEL_FUNCTIONS(VKC_CLEAR)
#undef VKC_CLEAR
    }
    return all;
}

void nameObject(const Device& device, VkObjectType type, std::uint64_t handle, std::string_view what, std::string_view suffix) {
    if (!device.debug_utils || handle == 0) return;
    std::string name;
    name.reserve(kDebugPrefix.size() + what.size() + suffix.size());
    name.append(kDebugPrefix).append(what).append(suffix);
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    (void)device.fns.vkSetDebugUtilsObjectNameEXT(device.device, &info);
}

void beginLabel(const Device& device, VkCommandBuffer cmd, std::string_view what) {
    if (!device.debug_utils) return;
    const std::string name = std::string(kDebugPrefix) + std::string(what);
    VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    label.pLabelName = name.c_str();
    device.fns.vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
}

void endLabel(const Device& device, VkCommandBuffer cmd) {
    if (device.debug_utils) device.fns.vkCmdEndDebugUtilsLabelEXT(cmd);
}

}  // namespace vkcollide::vk
