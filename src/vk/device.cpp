#include "vk/device.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "vk/debug_names.hpp"

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

bool loaderOffers(const GlobalFunctions& global, const char* extension) {
    std::uint32_t count = 0;
    if (global.vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> exts(count);
    if (global.vkEnumerateInstanceExtensionProperties(nullptr, &count, exts.data()) < 0) return false;
    exts.resize(count);
    return hasExtension(exts, extension);
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

}  // namespace

Device::~Device() {
    // Runs when the Context and the last resource made on it are gone (see device.hpp):
    // nothing of vkcollide's is left on the device, and every Submission has waited.
    if (pipeline_cache && owns_pipeline_cache) fns.vkDestroyPipelineCache(device, pipeline_cache, allocator());
    if (device && owns_device) {
        waitIdle();
        fns.vkDestroyDevice(device, allocator());
    }
    if (messenger) instance_fns.vkDestroyDebugUtilsMessengerEXT(instance, messenger, allocator());
    if (instance && owns_instance) instance_fns.vkDestroyInstance(instance, allocator());
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

bool listsExtension(std::span<const char* const> names, const char* name) noexcept {
    return std::any_of(names.begin(), names.end(), [&](const char* n) { return n && std::strcmp(n, name) == 0; });
}

PhysicalDeviceReport describePhysicalDevice(const InstanceFunctions& fns, VkPhysicalDevice physical) {
    PhysicalDeviceReport report;
    DeviceInfo& info = report.info;
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
    // gallivm's loop limiter (LP_MAX_TGSI_LOOP_ITERATIONS), shared by every loop of a shader.
    if (driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE) info.loop_iteration_limit = 65535;

    if (VK_API_VERSION_MAJOR(info.api_version) == 1 && VK_API_VERSION_MINOR(info.api_version) < 3) {
        info.missing.push_back("Vulkan 1.3 (device reports " + std::to_string(VK_API_VERSION_MAJOR(info.api_version)) +
                               "." + std::to_string(VK_API_VERSION_MINOR(info.api_version)) + ")");
        return report;  // 1.3 feature structs cannot be queried
    }

    std::uint32_t ext_count = 0;
    fns.vkEnumerateDeviceExtensionProperties(physical, nullptr, &ext_count, nullptr);
    std::vector<VkExtensionProperties> exts(ext_count);
    fns.vkEnumerateDeviceExtensionProperties(physical, nullptr, &ext_count, exts.data());
    exts.resize(ext_count);
    info.conservative_rasterization = hasExtension(exts, VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
    info.push_descriptor = hasExtension(exts, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    const bool robustness2_extension = hasExtension(exts, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME);
    report.executable_properties = hasExtension(exts, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);

    report.supported = querySupported(fns, physical, robustness2_extension);
    for (auto& m : report.supported.missingRequired()) info.missing.push_back(m);
    info.shader_float64 = report.supported.has(Feature::ShaderFloat64);
    info.timeline_semaphore = report.supported.has(Feature::TimelineSemaphore);
    info.robustness2 = robustness2_extension && report.supported.has(Feature::RobustBufferAccess2);

    std::uint32_t family_count = 0;
    fns.vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    fns.vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, families.data());
    for (std::uint32_t i = 0; i < family_count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0) {
            report.queue_family = i;
            break;
        }
    }
    if (!report.queue_family) info.missing.push_back("a graphics+compute queue with timestamp queries");
    return report;
}

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
    d.queue_flags = families[d.queue_family].queueFlags;
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

std::string loopLimitPhrase(const Device& device, std::string_view does) {
    return device.info.name + " " + std::string(does) + " in one shader invocation (it ends loops past " +
           std::to_string(device.info.loop_iteration_limit) + " iterations without an error)";
}

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

Context::Context(std::shared_ptr<vk::Device> device) : device_(std::move(device)) {
    std::lock_guard lock(device_->pipelines_mutex);
    device_->keep_pipelines = true;
}

Context::~Context() {
    std::vector<std::shared_ptr<const vk::PipelineHandles>> kept;
    {
        std::lock_guard lock(device_->pipelines_mutex);
        device_->keep_pipelines = false;
        kept.swap(device_->kept_pipelines);
    }
    // Released outside the lock: the last release of a pipeline destroys it (and may be the
    // last DeviceRef, destroying the device and its mutex).
    kept.clear();
}
const DeviceInfo& Context::deviceInfo() const noexcept { return device_->info; }
bool Context::ownsDevice() const noexcept { return device_->owns_device; }
std::uint64_t Context::validationMessageCount() const noexcept { return device_->validation_messages.load(); }
std::uint64_t Context::deviceMemoryInUse() const noexcept { return device_->memory_in_use.load(); }

Result<std::vector<DeviceInfo>> Context::listDevices(PFN_vkGetInstanceProcAddr get_instance_proc_addr) {
    std::shared_ptr<LoaderLibrary> library;
    if (!get_instance_proc_addr) {
        auto lib = LoaderLibrary::open();
        if (!lib) return lib.error();
        library = *lib;
        get_instance_proc_addr = library->getInstanceProcAddr();
    }
    auto global = loadGlobalFunctions(get_instance_proc_addr);
    if (!global) return global.error();
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vkcollide";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = global->vkCreateInstance(&ci, nullptr, &instance);
    if (r != VK_SUCCESS) return vulkanError(r, "vkCreateInstance");
    auto fns = loadInstanceFunctions(get_instance_proc_addr, instance);
    if (!fns) {
        // The instance must go even though its table is incomplete.
        if (auto destroy = reinterpret_cast<PFN_vkDestroyInstance>(get_instance_proc_addr(instance, "vkDestroyInstance")))
            destroy(instance, nullptr);
        return fns.error();
    }
    std::uint32_t count = 0;
    fns->vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> physicals(count);
    fns->vkEnumeratePhysicalDevices(instance, &count, physicals.data());
    physicals.resize(count);
    std::vector<DeviceInfo> out;
    for (VkPhysicalDevice p : physicals) out.push_back(describePhysicalDevice(*fns, p).info);
    fns->vkDestroyInstance(instance, nullptr);
    return out;
}

Result<std::unique_ptr<Context>> Context::create(const ContextCreateInfo& info) {
    auto d = std::make_shared<Device>();
    d->on_message = info.on_message;
    if (auto ok = takeHostHooks(*d, info.allocation_callbacks, info.memory_hooks, "ContextCreateInfo"); !ok) return ok.error();
    PFN_vkGetInstanceProcAddr gipa = info.get_instance_proc_addr;
    if (!gipa) {
        auto lib = LoaderLibrary::open();
        if (!lib) return lib.error();
        d->library = *lib;
        gipa = d->library->getInstanceProcAddr();
    }
    auto global = loadGlobalFunctions(gipa);
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
        props.resize(count);
        bool found = std::any_of(props.begin(), props.end(),
                                 [](const VkLayerProperties& p) { return std::strcmp(p.layerName, kValidationLayer) == 0; });
        if (!found)
            return Error(ErrorCode::UnsupportedFeature,
                         "validation was requested but VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        validation_features.pNext = &messenger_info;
    } else if (info.debug_names && loaderOffers(d->global, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
        // Names and labels cost a few calls at creation and two per recorded pass (none for a
        // command buffer submitted again), and make a capture of the application readable
        // without a rebuild: on wherever the loader has the extension.
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    const bool debug_utils_enabled = listsExtension(extensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

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
    VkResult r = d->global.vkCreateInstance(&ci, d->allocator(), &d->instance);
    if (r != VK_SUCCESS) {
        d->instance = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateInstance");
    }
    auto inst = loadInstanceFunctions(gipa, d->instance);
    if (!inst) {
        // ~Device cannot destroy an instance without its table: do it here.
        if (auto destroy = reinterpret_cast<PFN_vkDestroyInstance>(gipa(d->instance, "vkDestroyInstance")))
            destroy(d->instance, d->allocator());
        d->instance = VK_NULL_HANDLE;
        return inst.error();
    }
    d->instance_fns = *inst;
    d->owns_instance = true;
    if (info.validation) {
        r = d->instance_fns.vkCreateDebugUtilsMessengerEXT(d->instance, &messenger_info, d->allocator(), &d->messenger);
        if (r != VK_SUCCESS) return vulkanError(r, "vkCreateDebugUtilsMessengerEXT");
    }

    // Pick the device: by name if asked, else by type preference among suitable ones.
    std::uint32_t count = 0;
    r = d->instance_fns.vkEnumeratePhysicalDevices(d->instance, &count, nullptr);
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) return vulkanError(r, "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> physicals(count);
    d->instance_fns.vkEnumeratePhysicalDevices(d->instance, &count, physicals.data());
    physicals.resize(count);
    if (physicals.empty()) return Error(ErrorCode::NoSuitableDevice, "the Vulkan loader found no physical device (is a driver such as mesa-vulkan-drivers installed?)");

    std::string wanted = info.device_name;
    if (wanted.empty()) {
        if (const char* env = std::getenv("VKCOLLIDE_DEVICE")) wanted = env;
    }
    int best_rank = 1 << 30;
    std::string report;
    FeatureSet supported;
    bool executable_properties = false;
    for (VkPhysicalDevice p : physicals) {
        PhysicalDeviceReport pd = describePhysicalDevice(d->instance_fns, p);
        report += "\n  " + pd.info.name + " (" + toString(pd.info.type) + ")";
        if (!wanted.empty() && lower(pd.info.name).find(lower(wanted)) == std::string::npos) continue;
        if (!pd.info.missing.empty()) {
            report += ": lacks";
            for (auto& m : pd.info.missing) report += " " + m;
            continue;
        }
        int rank = typeRank(pd.info.type);
        if (rank < best_rank) {
            best_rank = rank;
            d->physical = p;
            d->queue_family = *pd.queue_family;
            d->info = pd.info;
            supported = pd.supported;
            executable_properties = pd.executable_properties;
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
    // Every required feature, and the optional ones the device has: shaderFloat64 for the
    // double-precision filters; robust buffer access as a second line of defence behind
    // the passes' own checks (it covers descriptor accesses only, not device addresses).
    FeatureSet enable;
    for (std::size_t i = 0; i < kFeatureCount; ++i)
        if (isRequired(static_cast<Feature>(i))) enable.set(static_cast<Feature>(i));
    d->shader_float64 = supported.has(Feature::ShaderFloat64);
    d->robust_buffer_access = info.robust_buffer_access && supported.has(Feature::RobustBufferAccess);
    d->robust_buffer_access2 = d->robust_buffer_access && d->info.robustness2;
    enable.set(Feature::ShaderFloat64, d->shader_float64);
    enable.set(Feature::RobustBufferAccess, d->robust_buffer_access);
    enable.set(Feature::RobustBufferAccess2, d->robust_buffer_access2);
    d->timeline_semaphore = supported.has(Feature::TimelineSemaphore);
    enable.set(Feature::TimelineSemaphore, d->timeline_semaphore);
    const DeviceCreateChain features(enable, d->robust_buffer_access2);
    std::vector<const char*> device_exts;
    d->conservative_rasterization = d->info.conservative_rasterization;
    d->push_descriptor = d->info.push_descriptor;
    if (d->conservative_rasterization) device_exts.push_back(VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
    if (d->push_descriptor) device_exts.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    if (d->robust_buffer_access2) device_exts.push_back(VK_EXT_ROBUSTNESS_2_EXTENSION_NAME);
    // Pipeline statistics (tuning only): the feature goes in front of the chain.
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executable_info{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
    executable_info.pNext = const_cast<VkPhysicalDeviceFeatures2*>(features.head());
    executable_info.pipelineExecutableInfo = VK_TRUE;
    const bool statistics = info.pipeline_statistics && executable_properties;
    if (statistics) device_exts.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = statistics ? static_cast<const void*>(&executable_info) : static_cast<const void*>(features.head());
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &queue_info;
    dci.enabledExtensionCount = static_cast<std::uint32_t>(device_exts.size());
    dci.ppEnabledExtensionNames = device_exts.data();
    r = d->instance_fns.vkCreateDevice(d->physical, &dci, d->allocator(), &d->device);
    if (r != VK_SUCCESS) {
        d->device = VK_NULL_HANDLE;
        return vulkanError(r, "vkCreateDevice on " + d->info.name);
    }
    auto dev = loadDeviceFunctions(d->instance_fns, d->device, d->push_descriptor);
    if (!dev) {
        if (auto destroy = reinterpret_cast<PFN_vkDestroyDevice>(d->instance_fns.vkGetDeviceProcAddr(d->device, "vkDestroyDevice")))
            destroy(d->device, d->allocator());
        d->device = VK_NULL_HANDLE;
        return dev.error();
    }
    d->fns = *dev;
    d->owns_device = true;
    d->debug_utils = info.debug_names && debug_utils_enabled && loadDebugLabelFunctions(gipa, d->instance, d->fns);
    d->fns.vkGetDeviceQueue(d->device, d->queue_family, 0, &d->queue);
    if (info.pipeline_statistics) {
        d->get_executable_properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
            d->instance_fns.vkGetDeviceProcAddr(d->device, "vkGetPipelineExecutablePropertiesKHR"));
        d->get_executable_statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
            d->instance_fns.vkGetDeviceProcAddr(d->device, "vkGetPipelineExecutableStatisticsKHR"));
        d->capture_statistics = statistics && d->get_executable_properties && d->get_executable_statistics;
        d->statistics_unavailable = d->capture_statistics ? ""
                                    : d->info.name + "'s driver (" + d->info.driver +
                                          ") does not offer VK_KHR_pipeline_executable_properties";
    }
    if (auto ok = finishDevice(*d); !ok) return ok.error();
    if (auto ok = setUpPipelineCache(*d, VK_NULL_HANDLE, info.pipeline_cache_data); !ok) return ok.error();
    return std::unique_ptr<Context>(new Context(std::move(d)));
}

}  // namespace vkcollide
