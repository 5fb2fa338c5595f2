// An engine program against the installed package. It links the Vulkan loader and calls
// Vulkan through the ordinary prototypes (vkCreateInstance, ...), which must stay
// declared although vkcollide's own code is built with VK_NO_PROTOTYPES. It creates its
// own instance and device with the features context.hpp lists, lends them to vkcollide
// (Context::adopt), and also lets vkcollide create its own device (Context::create).
// Exits 0 when both find the pairs of two overlapping spheres.
#include <cstdio>
#include <vector>

#include <vulkan/vulkan.h>

#include <vkcollide/context.hpp>
#include <vkcollide/scene.hpp>
#include <vkcollide/world.hpp>

namespace {

int fail(const char* what, const std::string& why) {
    std::fprintf(stderr, "consumer: %s: %s\n", what, why.c_str());
    return 1;
}

// Two overlapping unit spheres; returns the number of intersecting triangle pairs, or -1.
long detectSpheres(vkcollide::Context& ctx, const char* label) {
    auto world = vkcollide::CollisionWorld::create(ctx);
    if (!world) return fail(label, world.error().message()), -1;
    auto a = vkcollide::uvSphere(1.0f, 24, 12);
    auto b = vkcollide::uvSphere(1.0f, 24, 12);
    if (!a || !b) return -1;
    vkcollide::ObjectOptions moved;
    moved.transform[3] = 1.2f;
    if (!(*world)->addMesh(*a) || !(*world)->addMesh(*b, moved)) return -1;
    auto hits = (*world)->detect();
    if (!hits) return fail(label, hits.error().message()), -1;
    std::printf("consumer (%s, %s): %zu pairs\n", label, ctx.deviceInfo().name.c_str(), hits->pairs.size());
    return static_cast<long>(hits->pairs.size());
}

struct EngineVulkan {
    VkInstance instance = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    ~EngineVulkan() {
        if (device) vkDestroyDevice(device, nullptr);
        if (instance) vkDestroyInstance(instance, nullptr);
    }
};

// The engine's own device, made with the loader's prototypes; then vkcollide adopts it.
int engineDevice() {
    EngineVulkan vk;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "consumer";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    if (vkCreateInstance(&ici, nullptr, &vk.instance) != VK_SUCCESS) return fail("engine", "vkCreateInstance failed");
    std::uint32_t count = 0;
    vkEnumeratePhysicalDevices(vk.instance, &count, nullptr);
    std::vector<VkPhysicalDevice> physicals(count);
    vkEnumeratePhysicalDevices(vk.instance, &count, physicals.data());

    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    v12.pNext = &v13;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &v12;
    vkcollide::enableRequiredFeatures(features, v12, v13);

    for (VkPhysicalDevice physical : physicals) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(physical, &props);
        if (VK_API_VERSION_MINOR(props.apiVersion) < 3) continue;
        std::uint32_t family_count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, nullptr);
        std::vector<VkQueueFamilyProperties> families(family_count);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, families.data());
        for (std::uint32_t family = 0; family < family_count; ++family) {
            const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            if ((families[family].queueFlags & need) != need || families[family].timestampValidBits == 0) continue;
            const float priority = 1.0f;
            VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
            queue_info.queueFamilyIndex = family;
            queue_info.queueCount = 1;
            queue_info.pQueuePriorities = &priority;
            VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
            dci.pNext = &features;
            dci.queueCreateInfoCount = 1;
            dci.pQueueCreateInfos = &queue_info;
            if (vkCreateDevice(physical, &dci, nullptr, &vk.device) != VK_SUCCESS) break;  // lacks a feature
            VkQueue queue = VK_NULL_HANDLE;
            vkGetDeviceQueue(vk.device, family, 0, &queue);

            vkcollide::AdoptedDevice lent;
            lent.get_instance_proc_addr = vkGetInstanceProcAddr;
            lent.instance = vk.instance;
            lent.physical_device = physical;
            lent.device = vk.device;
            lent.queue_family = family;
            lent.queue = queue;
            lent.enabled_features = &features;
            long pairs = 0;
            {
                auto ctx = vkcollide::Context::adopt(lent);
                if (!ctx) return fail("adopt", ctx.error().message());
                pairs = detectSpheres(**ctx, "adopted");
            }
            vkDeviceWaitIdle(vk.device);  // the engine's device outlives vkcollide's Context
            return pairs > 0 ? 0 : 1;
        }
    }
    return fail("engine", "no Vulkan 1.3 device with vkcollide's required features");
}

}  // namespace

int main() {
    {
        auto ctx = vkcollide::Context::create();
        if (!ctx) return fail("Context::create", ctx.error().message());
        if (detectSpheres(**ctx, "own device") <= 0) return 1;
    }
    return engineDevice();
}
