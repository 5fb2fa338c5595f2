#include "vk/device.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace vkcollide::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasExtension(const std::vector<VkExtensionProperties>& exts, const char* name) {
    return std::any_of(exts.begin(), exts.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* device = static_cast<Device*>(user);
    MessageSeverity s = MessageSeverity::Info;
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) s = MessageSeverity::Error;
    else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) s = MessageSeverity::Warning;
    if (s != MessageSeverity::Info) device->validation_messages.fetch_add(1, std::memory_order_relaxed);
    device->message(s, data && data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;
}

// The features vkcollide turns on; also used to check what a device has.
struct FeatureChain {
    VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    FeatureChain() {
        core.pNext = &v12;
        v12.pNext = &v13;
    }
    FeatureChain(const FeatureChain&) = delete;
    FeatureChain& operator=(const FeatureChain&) = delete;

    void requireAll() {
        core.features.shaderInt64 = VK_TRUE;
        core.features.fragmentStoresAndAtomics = VK_TRUE;
        core.features.vertexPipelineStoresAndAtomics = VK_FALSE;
        v12.bufferDeviceAddress = VK_TRUE;
        v12.scalarBlockLayout = VK_TRUE;
        v12.shaderBufferInt64Atomics = VK_TRUE;
        v12.hostQueryReset = VK_TRUE;
        v13.dynamicRendering = VK_TRUE;
        v13.synchronization2 = VK_TRUE;
        v13.maintenance4 = VK_TRUE;
    }

    std::vector<std::string> missing() const {
        std::vector<std::string> out;
        if (!core.features.shaderInt64) out.push_back("shaderInt64");
        if (!core.features.fragmentStoresAndAtomics) out.push_back("fragmentStoresAndAtomics");
        if (!v12.bufferDeviceAddress) out.push_back("bufferDeviceAddress");
        if (!v12.scalarBlockLayout) out.push_back("scalarBlockLayout");
        if (!v12.shaderBufferInt64Atomics) out.push_back("shaderBufferInt64Atomics");
        if (!v12.hostQueryReset) out.push_back("hostQueryReset");
        if (!v13.dynamicRendering) out.push_back("dynamicRendering");
        if (!v13.synchronization2) out.push_back("synchronization2");
        if (!v13.maintenance4) out.push_back("maintenance4");
        return out;
    }
};

}  // namespace

Device::~Device() {
    if (device && owns_device) {
        fns.vkDeviceWaitIdle(device);
        fns.vkDestroyDevice(device, nullptr);
    }
    if (messenger) instance_fns.vkDestroyDebugUtilsMessengerEXT(instance, messenger, nullptr);
    if (instance && owns_instance) instance_fns.vkDestroyInstance(instance, nullptr);
}

std::optional<std::uint32_t> Device::findMemoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                                    VkMemoryPropertyFlags preferred) const {
    std::optional<std::uint32_t> fallback;
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if (!(type_bits & (1u << i))) continue;
        VkMemoryPropertyFlags flags = memory.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (!fallback) fallback = i;
    }
    return fallback;
}

void Device::message(MessageSeverity severity, std::string_view text) const {
    if (on_message) {
        on_message(severity, text);
        return;
    }
    if (severity == MessageSeverity::Info) return;
    std::fprintf(stderr, "vkcollide %s: %.*s\n", severity == MessageSeverity::Error ? "error" : "warning",
                 static_cast<int>(text.size()), text.data());
}

DeviceInfo describePhysicalDevice(const InstanceFunctions& fns, VkPhysicalDevice physical,
                                  std::optional<std::uint32_t>* out_queue_family) {
    DeviceInfo info;
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    subgroup.pNext = &driver;
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &subgroup;
    fns.vkGetPhysicalDeviceProperties2(physical, &props);
    info.name = props.properties.deviceName;
    info.type = props.properties.deviceType;
    info.api_version = props.properties.apiVersion;
    info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    info.timestamp_period_ns = props.properties.limits.timestampPeriod;
    info.subgroup_size = subgroup.subgroupSize;

    if (VK_API_VERSION_MAJOR(info.api_version) == 1 && VK_API_VERSION_MINOR(info.api_version) < 3) {
        info.missing.push_back("Vulkan 1.3 (device reports " + std::to_string(VK_API_VERSION_MAJOR(info.api_version)) +
                               "." + std::to_string(VK_API_VERSION_MINOR(info.api_version)) + ")");
        return info;  // 1.3 feature structs cannot be queried
    }

    std::uint32_t ext_count = 0;
    fns.vkEnumerateDeviceExtensionProperties(physical, nullptr, &ext_count, nullptr);
    std::vector<VkExtensionProperties> exts(ext_count);
    fns.vkEnumerateDeviceExtensionProperties(physical, nullptr, &ext_count, exts.data());
    if (!hasExtension(exts, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) info.missing.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    info.conservative_rasterization = hasExtension(exts, VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);

    FeatureChain features;
    fns.vkGetPhysicalDeviceFeatures2(physical, &features.core);
    for (auto& m : features.missing()) info.missing.push_back(m);

    std::uint32_t family_count = 0;
    fns.vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    fns.vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, families.data());
    std::optional<std::uint32_t> chosen;
    for (std::uint32_t i = 0; i < family_count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0) {
            chosen = i;
            break;
        }
    }
    if (!chosen) info.missing.push_back("a graphics+compute queue with timestamp queries");
    if (out_queue_family) *out_queue_family = chosen;
    return info;
}

namespace {

Result<void> finishDevice(Device& d) {
    d.instance_fns.vkGetPhysicalDeviceProperties(d.physical, &d.properties);
    d.instance_fns.vkGetPhysicalDeviceMemoryProperties(d.physical, &d.memory);
    std::uint32_t family_count = 0;
    d.instance_fns.vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    d.instance_fns.vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &family_count, families.data());
    if (d.queue_family >= family_count)
        return Error(ErrorCode::InvalidArgument, "queue family " + std::to_string(d.queue_family) +
                                                     " does not exist (the device has " + std::to_string(family_count) + ")");
    d.timestamp_valid_bits = families[d.queue_family].timestampValidBits;
    VkPhysicalDeviceVulkan13Properties p13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
    VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
    p11.pNext = &p13;
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &p11;
    d.instance_fns.vkGetPhysicalDeviceProperties2(d.physical, &props);
    if (p13.maxBufferSize) d.max_buffer_size = p13.maxBufferSize;
    if (p11.maxMemoryAllocationSize) d.max_allocation_size = p11.maxMemoryAllocationSize;
    return {};
}

}  // namespace

}  // namespace vkcollide::vk

namespace vkcollide {
using namespace vk;

const char* toString(VkPhysicalDeviceType type) noexcept {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
        default: return "other";
    }
}

Context::Context(std::unique_ptr<vk::Device> device) : device_(std::move(device)) {}
Context::~Context() = default;
const DeviceInfo& Context::deviceInfo() const noexcept { return device_->info; }
bool Context::ownsDevice() const noexcept { return device_->owns_device; }
std::uint64_t Context::validationMessageCount() const noexcept { return device_->validation_messages.load(); }

Result<std::vector<DeviceInfo>> Context::listDevices() {
    auto lib = LoaderLibrary::open();
    if (!lib) return lib.error();
    auto global = loadGlobalFunctions((*lib)->getInstanceProcAddr());
    if (!global) return global.error();
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vkcollide";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = global->vkCreateInstance(&ci, nullptr, &instance);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateInstance");
    auto fns = loadInstanceFunctions((*lib)->getInstanceProcAddr(), instance);
    if (!fns) return fns.error();
    std::uint32_t count = 0;
    fns->vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> physicals(count);
    fns->vkEnumeratePhysicalDevices(instance, &count, physicals.data());
    std::vector<DeviceInfo> out;
    for (VkPhysicalDevice p : physicals) out.push_back(describePhysicalDevice(*fns, p));
    fns->vkDestroyInstance(instance, nullptr);
    return out;
}

Result<std::unique_ptr<Context>> Context::create(const ContextCreateInfo& info) {
    auto d = std::make_unique<Device>();
    d->on_message = info.on_message;
    auto lib = LoaderLibrary::open();
    if (!lib) return lib.error();
    d->library = *lib;
    auto global = loadGlobalFunctions(d->library->getInstanceProcAddr());
    if (!global) return global.error();
    d->global = *global;

    std::uint32_t loader_version = VK_API_VERSION_1_0;
    if (d->global.vkEnumerateInstanceVersion) d->global.vkEnumerateInstanceVersion(&loader_version);
    if (VK_API_VERSION_MINOR(loader_version) < 3 && VK_API_VERSION_MAJOR(loader_version) == 1)
        return Error(ErrorCode::NoSuitableDevice, "the Vulkan loader supports only " +
                                                      std::to_string(VK_API_VERSION_MAJOR(loader_version)) + "." +
                                                      std::to_string(VK_API_VERSION_MINOR(loader_version)) + "; vkcollide needs 1.3");

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    VkValidationFeatureEnableEXT sync_validation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT validation_features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    validation_features.enabledValidationFeatureCount = 1;
    validation_features.pEnabledValidationFeatures = &sync_validation;
    VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = onDebugMessage;
    messenger_info.pUserData = d.get();
    if (info.validation) {
        std::uint32_t count = 0;
        d->global.vkEnumerateInstanceLayerProperties(&count, nullptr);
        std::vector<VkLayerProperties> props(count);
        d->global.vkEnumerateInstanceLayerProperties(&count, props.data());
        bool found = std::any_of(props.begin(), props.end(),
                                 [](const VkLayerProperties& p) { return std::strcmp(p.layerName, kValidationLayer) == 0; });
        if (!found)
            return Error(ErrorCode::UnsupportedFeature,
                         "validation was requested but VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        validation_features.pNext = &messenger_info;
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vkcollide";
    app.pEngineName = "vkcollide";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pNext = info.validation ? &validation_features : nullptr;
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    VkResult r = d->global.vkCreateInstance(&ci, nullptr, &d->instance);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateInstance");
    d->owns_instance = true;
    auto inst = loadInstanceFunctions(d->library->getInstanceProcAddr(), d->instance);
    if (!inst) return inst.error();
    d->instance_fns = *inst;
    if (info.validation) {
        r = d->instance_fns.vkCreateDebugUtilsMessengerEXT(d->instance, &messenger_info, nullptr, &d->messenger);
        if (r != VK_SUCCESS) return vulkanError(r, "vkCreateDebugUtilsMessengerEXT");
    }

    // Pick the device: by name if asked, else by type preference among suitable ones.
    std::uint32_t count = 0;
    d->instance_fns.vkEnumeratePhysicalDevices(d->instance, &count, nullptr);
    std::vector<VkPhysicalDevice> physicals(count);
    d->instance_fns.vkEnumeratePhysicalDevices(d->instance, &count, physicals.data());
    if (physicals.empty()) return Error(ErrorCode::NoSuitableDevice, "the Vulkan loader found no physical device (is a driver such as mesa-vulkan-drivers installed?)");

    std::string wanted = info.device_name;
    if (wanted.empty()) {
        if (const char* env = std::getenv("VKCOLLIDE_DEVICE")) wanted = env;
    }
    int best_rank = 1 << 30;
    std::string report;
    for (VkPhysicalDevice p : physicals) {
        std::optional<std::uint32_t> family;
        DeviceInfo di = describePhysicalDevice(d->instance_fns, p, &family);
        report += "\n  " + di.name + " (" + toString(di.type) + ")";
        if (!wanted.empty() && lower(di.name).find(lower(wanted)) == std::string::npos) continue;
        if (!di.missing.empty()) {
            report += ": lacks";
            for (auto& m : di.missing) report += " " + m;
            continue;
        }
        int rank = typeRank(di.type);
        if (rank < best_rank) {
            best_rank = rank;
            d->physical = p;
            d->queue_family = *family;
            d->info = di;
        }
    }
    if (!d->physical) {
        std::string why = wanted.empty() ? "no device meets vkcollide's requirements"
                                         : "no suitable device matches the name '" + wanted + "'";
        return Error(ErrorCode::NoSuitableDevice, why + "; devices:" + report);
    }

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = d->queue_family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    FeatureChain features;
    features.requireAll();
    // Optional: conservative rasterisation, only where the device has it (coverage setting).
    std::vector<const char*> device_exts = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (d->info.conservative_rasterization) device_exts.push_back(VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = &features.core;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &queue_info;
    dci.enabledExtensionCount = static_cast<std::uint32_t>(device_exts.size());
    dci.ppEnabledExtensionNames = device_exts.data();
    r = d->instance_fns.vkCreateDevice(d->physical, &dci, nullptr, &d->device);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateDevice on " + d->info.name);
    d->owns_device = true;
    d->conservative_rasterization = d->info.conservative_rasterization;
    auto dev = loadDeviceFunctions(d->instance_fns, d->device);
    if (!dev) return dev.error();
    d->fns = *dev;
    d->fns.vkGetDeviceQueue(d->device, d->queue_family, 0, &d->queue);
    if (auto ok = finishDevice(*d); !ok) return ok.error();
    return std::unique_ptr<Context>(new Context(std::move(d)));
}

Result<std::unique_ptr<Context>> Context::adopt(const AdoptedDevice& in, MessageCallback on_message) {
    if (!in.get_instance_proc_addr || !in.instance || !in.physical_device || !in.device || !in.queue)
        return Error(ErrorCode::InvalidArgument,
                     "AdoptedDevice needs get_instance_proc_addr, instance, physical_device, device and queue (one is null)");
    auto d = std::make_unique<Device>();
    d->on_message = std::move(on_message);
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
    d->info = describePhysicalDevice(d->instance_fns, d->physical);
    if (VK_API_VERSION_MINOR(in.api_version) < 3 && VK_API_VERSION_MAJOR(in.api_version) == 1)
        d->info.missing.push_back("an instance created for Vulkan 1.3 (AdoptedDevice::api_version is lower)");
    if (!d->info.missing.empty()) {
        std::string what;
        for (auto& m : d->info.missing) what += " " + m;
        return Error(ErrorCode::UnsupportedFeature, "the adopted device " + d->info.name + " lacks:" + what);
    }
    auto dev = loadDeviceFunctions(d->instance_fns, d->device);
    if (!dev) return dev.error();
    d->fns = *dev;
    // The engine says whether it enabled the extension; vkcollide cannot see that itself.
    d->conservative_rasterization = in.conservative_rasterization && d->info.conservative_rasterization;
    if (auto ok = finishDevice(*d); !ok) return ok.error();
    if (d->timestamp_valid_bits == 0)
        return Error(ErrorCode::UnsupportedFeature, "the adopted queue family " + std::to_string(in.queue_family) +
                                                        " has no timestamp support (timestampValidBits = 0)");
    return std::unique_ptr<Context>(new Context(std::move(d)));
}

}  // namespace vkcollide
