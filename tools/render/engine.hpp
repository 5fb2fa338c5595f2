// A stand-in for a game engine, shared by the samples and the command-line tool (its
// --png and --gpu-mesh): it creates its own Vulkan instance, device and queue, allocates
// buffers, records and submits work, and lends the device to vkcollide with
// Context::adopt (see adoptedDevice()). This is the integration an engine does.
//
// Vulkan failures inside these helpers are fatal (message and exit): the users are
// programs, and their own Vulkan plumbing is not what they are meant to show. vkcollide's
// calls are checked by each program with their Result.
#pragma once

#include "render/vk.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "vkcollide/context.hpp"
#include "vkcollide/result.hpp"

namespace render {

// The name die() and the messages print (the program's name).
void setProgramName(const char* name);
// Prints "<program>: <what>" to stderr and exits with status 1.
[[noreturn]] void die(const std::string& what);
// Dies with the call's name when `result` is not VK_SUCCESS.
void check(VkResult result, const char* call);

// Prints a vkcollide error ("<program>: <message>") and returns 1, for `return fail(...)`.
int fail(const vkcollide::Error& error);

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    VkDeviceAddress address = 0;  // for shaders (buffer_reference) and GpuMeshDesc users
    void* mapped = nullptr;       // host-visible buffers: persistently mapped, coherent
};

enum class Memory {
    Device,  // device-local; written by the GPU or by Engine::upload
    Host,    // host-visible and coherent, mapped; the CPU writes it every frame
};

struct EngineOptions {
    // VK_LAYER_KHRONOS_validation with synchronization validation; every warning or
    // error is printed and counted (validationMessages()).
    bool validation = false;
    // Substring of the device name (case-insensitive); empty: VKCOLLIDE_DEVICE, else the
    // first discrete GPU, integrated GPU, virtual GPU, then CPU driver (lavapipe).
    std::string device_name;
};

class Engine {
public:
    static std::unique_ptr<Engine> create(const EngineOptions& options);
    ~Engine();
    Engine(const Engine&) = delete;
    Engine& operator=(const Engine&) = delete;

    // What Context::adopt needs. The device was created with every feature vkcollide
    // requires (context.hpp), and the engine submits only from this thread, so the queue
    // can be shared.
    vkcollide::AdoptedDevice adoptedDevice() const;
    // Library diagnostics for Context::adopt: printed and counted like validation messages.
    vkcollide::MessageCallback messageCallback();

    VkDevice device() const { return device_; }
    const std::string& deviceName() const { return device_name_; }
    std::uint64_t validationMessages() const { return *messages_; }

    Buffer createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, Memory memory);
    void destroy(Buffer& buffer);
    // Memory for an image or buffer: device-local, or host-visible and coherent.
    VkDeviceMemory allocate(const VkMemoryRequirements& requirements, Memory memory, bool device_address = false);
    // Copies bytes into a device-local buffer through a staging buffer (waits).
    void upload(const Buffer& destination, const void* data, VkDeviceSize size);

    // Records with `record`, submits to the shared queue and waits for completion.
    // Every command buffer starts with a full memory barrier, so work is ordered with
    // whatever was submitted before (vkcollide's detections included).
    void submit(const std::function<void(VkCommandBuffer)>& record);

    VkShaderModule createShaderModule(std::span<const std::uint32_t> spirv);

    // A compute pipeline whose only input is `push_size` bytes of push constants (the
    // shaders reach their buffers through device addresses).
    struct ComputePipeline {
        VkPipeline pipeline = VK_NULL_HANDLE;
        VkPipelineLayout layout = VK_NULL_HANDLE;
    };
    ComputePipeline createComputePipeline(std::span<const std::uint32_t> spirv, std::uint32_t push_size);
    void destroy(ComputePipeline& pipeline);

private:
    Engine() = default;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queue_family_ = 0;
    // The feature chain and extensions the device was created with (adopt reads them).
    struct EnabledFeatures {
        VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    };
    std::unique_ptr<EnabledFeatures> features_;
    std::vector<const char*> extensions_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory_{};
    std::string device_name_;
    std::shared_ptr<std::uint64_t> messages_ = std::make_shared<std::uint64_t>(0);
};

// The program's exit status: 0, or 3 when the validation layer or vkcollide reported a
// warning or an error during the run (the smoke tests fail on it).
int exitStatus(const Engine& engine);

}  // namespace render
