#include "render/engine.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

namespace render {

namespace {
const char* g_program = "sample";
}  // namespace

void setProgramName(const char* name) { g_program = name; }

void die(const std::string& what) {
    std::fprintf(stderr, "\n%s: %s\n", g_program, what.c_str());
    std::exit(1);
}

int fail(const vkcollide::Error& error) {
    std::fprintf(stderr, "\n%s: %s (%s)\n", g_program, error.message().c_str(), vkcollide::toString(error.code()));
    return 1;
}

int exitStatus(const Engine& engine) {
    if (engine.validationMessages() == 0) return 0;
    std::fprintf(stderr, "%s: %llu validation or library messages (see above)\n", g_program,
                 static_cast<unsigned long long>(engine.validationMessages()));
    return 3;
}

void check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) die(std::string(call) + " failed (VkResult " + std::to_string(result) + ")");
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

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

void report(std::uint64_t& count, bool error, const char* text) {
    // The first few in full; the rest only counted (a broken frame loop repeats them).
    if (++count <= 20) std::fprintf(stderr, "\n%s %s: %s\n", g_program, error ? "error" : "warning", text);
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidation(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    report(*static_cast<std::uint64_t*>(user), severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
           data && data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;
}

bool hasExtension(VkPhysicalDevice physical, const char* name) {
    std::uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, exts.data());
    return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// A graphics+compute family with timestamps, if the device meets every requirement.
std::optional<std::uint32_t> suitableFamily(VkPhysicalDevice physical) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(physical, &props);
    if (VK_API_VERSION_MAJOR(props.apiVersion) == 1 && VK_API_VERSION_MINOR(props.apiVersion) < 3) return std::nullopt;
    // Every feature vkcollide requires (context.hpp) must be available.
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &v13};
    VkPhysicalDeviceFeatures2 available{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &v12};
    vkGetPhysicalDeviceFeatures2(physical, &available);
    if (!(available.features.shaderInt64 && available.features.fragmentStoresAndAtomics && v12.bufferDeviceAddress &&
          v12.scalarBlockLayout && v12.shaderBufferInt64Atomics && v12.hostQueryReset && v13.dynamicRendering &&
          v13.synchronization2 && v13.maintenance4))
        return std::nullopt;
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (std::uint32_t i = 0; i < count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0) return i;
    }
    return std::nullopt;
}

}  // namespace

std::unique_ptr<Engine> Engine::create(const EngineOptions& options) {
    std::unique_ptr<Engine> e(new Engine());

    std::vector<const char*> layers, extensions;
    VkValidationFeatureEnableEXT sync_validation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT validation_features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    validation_features.enabledValidationFeatureCount = 1;
    validation_features.pEnabledValidationFeatures = &sync_validation;
    VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger_info.pfnUserCallback = onValidation;
    messenger_info.pUserData = e->messages_.get();
    if (options.validation) {
        std::uint32_t count = 0;
        vkEnumerateInstanceLayerProperties(&count, nullptr);
        std::vector<VkLayerProperties> props(count);
        vkEnumerateInstanceLayerProperties(&count, props.data());
        if (std::none_of(props.begin(), props.end(), [](const VkLayerProperties& p) { return std::strcmp(p.layerName, kValidationLayer) == 0; }))
            die("validation asked for, but VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        validation_features.pNext = &messenger_info;
    }
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = g_program;
    app.pEngineName = "vkcollide tools";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pNext = options.validation ? &validation_features : nullptr;
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    ici.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    check(vkCreateInstance(&ici, nullptr, &e->instance_), "vkCreateInstance");
    if (options.validation) {
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(e->instance_, "vkCreateDebugUtilsMessengerEXT"));
        check(create_messenger(e->instance_, &messenger_info, nullptr, &e->messenger_), "vkCreateDebugUtilsMessengerEXT");
    }

    std::string wanted = options.device_name;
    if (const char* env = std::getenv("VKCOLLIDE_DEVICE"); wanted.empty() && env) wanted = env;
    std::uint32_t count = 0;
    vkEnumeratePhysicalDevices(e->instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> physicals(count);
    vkEnumeratePhysicalDevices(e->instance_, &count, physicals.data());
    int best = 1 << 30;
    std::string seen;
    for (VkPhysicalDevice p : physicals) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(p, &props);
        seen += std::string(" '") + props.deviceName + "'";
        if (!wanted.empty() && lower(props.deviceName).find(lower(wanted)) == std::string::npos) continue;
        auto family = suitableFamily(p);
        if (!family || typeRank(props.deviceType) >= best) continue;
        best = typeRank(props.deviceType);
        e->physical_ = p;
        e->queue_family_ = *family;
        e->device_name_ = props.deviceName;
    }
    if (!e->physical_) die("no Vulkan device meets vkcollide's requirements" + (wanted.empty() ? "" : " and matches '" + wanted + "'") + "; devices:" + seen);

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = e->queue_family_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    // Exactly what vkcollide requires (context.hpp), set by the library's own helper, plus
    // shaderFloat64 where the device has it (vkcollide's GPU filters use it then).
    e->features_ = std::make_unique<EnabledFeatures>();
    EnabledFeatures& f = *e->features_;
    f.core.pNext = &f.v12;
    f.v12.pNext = &f.v13;
    vkcollide::enableRequiredFeatures(f.core, f.v12, f.v13);
    VkPhysicalDeviceFeatures available{};
    vkGetPhysicalDeviceFeatures(e->physical_, &available);
    f.core.features.shaderFloat64 = available.shaderFloat64;
    // Optional: lets DetectSettings::peeling.coverage use the hardware (Coverage::Best).
    if (hasExtension(e->physical_, VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME))
        e->extensions_.push_back(VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = &f.core;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = static_cast<std::uint32_t>(e->extensions_.size());
    dci.ppEnabledExtensionNames = e->extensions_.data();
    check(vkCreateDevice(e->physical_, &dci, nullptr, &e->device_), "vkCreateDevice");
    vkGetDeviceQueue(e->device_, e->queue_family_, 0, &e->queue_);
    vkGetPhysicalDeviceMemoryProperties(e->physical_, &e->memory_);

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = e->queue_family_;
    check(vkCreateCommandPool(e->device_, &pci, nullptr, &e->pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = e->pool_;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(e->device_, &cai, &e->commands_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(e->device_, &fci, nullptr, &e->fence_), "vkCreateFence");
    return e;
}

Engine::~Engine() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        vkDestroyFence(device_, fence_, nullptr);
        vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroy_messenger(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

vkcollide::AdoptedDevice Engine::adoptedDevice() const {
    vkcollide::AdoptedDevice d;
    d.get_instance_proc_addr = vkGetInstanceProcAddr;
    d.instance = instance_;
    d.physical_device = physical_;
    d.device = device_;
    d.queue_family = queue_family_;
    d.queue = queue_;
    d.api_version = VK_API_VERSION_1_3;
    d.enabled_features = &features_->core;  // the chain the device was created with
    d.enabled_extensions = extensions_;
    return d;
}

vkcollide::MessageCallback Engine::messageCallback() {
    auto count = messages_;
    return [count](vkcollide::MessageSeverity severity, std::string_view text) {
        if (severity == vkcollide::MessageSeverity::Info) return;
        report(*count, severity == vkcollide::MessageSeverity::Error, std::string(text).c_str());
    };
}

Buffer Engine::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, Memory memory) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = std::max<VkDeviceSize>(size, 4);
    bci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    check(vkCreateBuffer(device_, &bci, nullptr, &b.buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, b.buffer, &req);
    b.memory = allocate(req, memory, true);
    check(vkBindBufferMemory(device_, b.buffer, b.memory, 0), "vkBindBufferMemory");
    if (memory == Memory::Host) check(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    ai.buffer = b.buffer;
    b.address = vkGetBufferDeviceAddress(device_, &ai);
    return b;
}

VkDeviceMemory Engine::allocate(const VkMemoryRequirements& req, Memory memory, bool device_address) {
    const VkMemoryPropertyFlags need = memory == Memory::Host
                                           ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                           : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    std::uint32_t type = ~0u;
    for (std::uint32_t i = 0; i < memory_.memoryTypeCount && type == ~0u; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & need) == need) type = i;
    if (type == ~0u) die("no memory type for " + std::to_string(req.size) + " bytes");
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.pNext = device_address ? &flags : nullptr;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type;
    VkDeviceMemory out = VK_NULL_HANDLE;
    check(vkAllocateMemory(device_, &mai, nullptr, &out), "vkAllocateMemory");
    return out;
}

void Engine::destroy(Buffer& b) {
    if (b.buffer) vkDestroyBuffer(device_, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(device_, b.memory, nullptr);
    b = {};
}

void Engine::upload(const Buffer& destination, const void* data, VkDeviceSize size) {
    if (size == 0) return;  // an empty mesh: a zero-sized copy is invalid
    Buffer staging = createBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Memory::Host);
    std::memcpy(staging.mapped, data, size);
    submit([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, size};
        vkCmdCopyBuffer(cmd, staging.buffer, destination.buffer, 1, &region);
    });
    destroy(staging);
}

void Engine::submit(const std::function<void(VkCommandBuffer)>& record) {
    check(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
    // Orders this work after everything submitted earlier to the shared queue (vkcollide's
    // detections read the buffers the engine writes here, and the engine reads them back).
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(commands_, &dep);
    record(commands_);
    check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = commands_;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cbi;
    check(vkQueueSubmit2(queue_, 1, &si, fence_), "vkQueueSubmit2");
    check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(device_, 1, &fence_), "vkResetFences");
}

VkShaderModule Engine::createShaderModule(std::span<const std::uint32_t> spirv) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = spirv.size_bytes();
    ci.pCode = spirv.data();
    VkShaderModule m = VK_NULL_HANDLE;
    check(vkCreateShaderModule(device_, &ci, nullptr, &m), "vkCreateShaderModule");
    return m;
}

Engine::ComputePipeline Engine::createComputePipeline(std::span<const std::uint32_t> spirv, std::uint32_t push_size) {
    ComputePipeline out;
    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size};
    VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    lci.pushConstantRangeCount = 1;
    lci.pPushConstantRanges = &push;
    check(vkCreatePipelineLayout(device_, &lci, nullptr, &out.layout), "vkCreatePipelineLayout");
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = createShaderModule(spirv);
    ci.stage.pName = "main";
    ci.layout = out.layout;
    check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &ci, nullptr, &out.pipeline), "vkCreateComputePipelines");
    vkDestroyShaderModule(device_, ci.stage.module, nullptr);
    return out;
}

void Engine::destroy(ComputePipeline& p) {
    if (p.pipeline) vkDestroyPipeline(device_, p.pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(device_, p.layout, nullptr);
    p = {};
}

}  // namespace render
