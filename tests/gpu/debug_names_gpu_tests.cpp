// Names and labels on the device, validation on: a loader wrapper between vkcollide and the
// real loader sees every object vkcollide creates and every name and label it sets, while
// detections run (both methods, a command buffer submitted again, a record() into the
// engine's command buffer). With debug utils every object gets a "vkcollide: " name and
// every command buffer's labels are balanced; with names off there is no call at all.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "support/engine_commands.hpp"
#include "support/gpu_fixture.hpp"
#include "support/test_scenes.hpp"
#include "support/world_fixture.hpp"
#include "vk/loader.hpp"
#include "vk/semaphore.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

// What the wrapper saw. vkGetInstanceProcAddr has no user pointer: one wrapper at a time.
struct Spy {
    std::shared_ptr<vk::LoaderLibrary> loader;
    PFN_vkGetInstanceProcAddr real_gipa = nullptr;
    PFN_vkGetDeviceProcAddr real_gdpa = nullptr;
    bool tracking = true;                          // false: the test plays the engine
    std::map<std::uint64_t, std::string> unnamed;  // handle -> the call that created it, until named
    std::vector<std::string> problems;
    std::vector<std::string> labels;               // every label begun
    std::map<VkCommandBuffer, std::vector<std::string>> open;  // labels open per command buffer
    int debug_calls = 0;
#define SPY_PFN(name) PFN_##name name = nullptr;
#define SPY_CREATES(X)                                                                                                   \
    X(vkCreateBuffer, VkBufferCreateInfo, VkBuffer) X(vkAllocateMemory, VkMemoryAllocateInfo, VkDeviceMemory)            \
    X(vkCreateImage, VkImageCreateInfo, VkImage) X(vkCreateImageView, VkImageViewCreateInfo, VkImageView)                \
    X(vkCreateShaderModule, VkShaderModuleCreateInfo, VkShaderModule)                                                    \
    X(vkCreateDescriptorSetLayout, VkDescriptorSetLayoutCreateInfo, VkDescriptorSetLayout)                               \
    X(vkCreatePipelineLayout, VkPipelineLayoutCreateInfo, VkPipelineLayout)                                              \
    X(vkCreatePipelineCache, VkPipelineCacheCreateInfo, VkPipelineCache)                                                 \
    X(vkCreateCommandPool, VkCommandPoolCreateInfo, VkCommandPool) X(vkCreateFence, VkFenceCreateInfo, VkFence)          \
    X(vkCreateSemaphore, VkSemaphoreCreateInfo, VkSemaphore) X(vkCreateQueryPool, VkQueryPoolCreateInfo, VkQueryPool)
#define SPY_CREATE_PFN(name, info, handle) SPY_PFN(name)
    SPY_CREATES(SPY_CREATE_PFN)
    SPY_PFN(vkCreateComputePipelines)
    SPY_PFN(vkCreateGraphicsPipelines)
    SPY_PFN(vkAllocateCommandBuffers)
    SPY_PFN(vkBeginCommandBuffer)
    SPY_PFN(vkEndCommandBuffer)
    SPY_PFN(vkSetDebugUtilsObjectNameEXT)
    SPY_PFN(vkCmdBeginDebugUtilsLabelEXT)
    SPY_PFN(vkCmdEndDebugUtilsLabelEXT)
    SPY_PFN(vkCmdInsertDebugUtilsLabelEXT)
};
Spy* g_spy = nullptr;

template <class H>
std::uint64_t bits(H h) {
    if constexpr (std::is_pointer_v<H>) return reinterpret_cast<std::uintptr_t>(h);
    else return static_cast<std::uint64_t>(h);
}

void made(const char* call, std::uint64_t handle) {
    if (g_spy->tracking) g_spy->unnamed[handle] = call;
}

bool prefixed(const char* text) { return text && std::string_view(text).rfind("vkcollide: ", 0) == 0; }

template <auto Real, class Info, class Handle>
VKAPI_ATTR VkResult VKAPI_CALL create(VkDevice d, const Info* info, const VkAllocationCallbacks* a, Handle* out) {
    const VkResult r = (g_spy->*Real)(d, info, a, out);
    if (r == VK_SUCCESS) made("create", bits(*out));
    return r;
}

template <auto Real, class Info>
VKAPI_ATTR VkResult VKAPI_CALL createPipelines(VkDevice d, VkPipelineCache cache, std::uint32_t n, const Info* infos,
                                               const VkAllocationCallbacks* a, VkPipeline* out) {
    const VkResult r = (g_spy->*Real)(d, cache, n, infos, a, out);
    if (r == VK_SUCCESS)
        for (std::uint32_t i = 0; i < n; ++i) made("pipeline", bits(out[i]));
    return r;
}

VKAPI_ATTR VkResult VKAPI_CALL allocateCommandBuffers(VkDevice d, const VkCommandBufferAllocateInfo* info, VkCommandBuffer* out) {
    const VkResult r = g_spy->vkAllocateCommandBuffers(d, info, out);
    if (r == VK_SUCCESS)
        for (std::uint32_t i = 0; i < info->commandBufferCount; ++i) made("command buffer", bits(out[i]));
    return r;
}

VKAPI_ATTR VkResult VKAPI_CALL beginCommandBuffer(VkCommandBuffer cmd, const VkCommandBufferBeginInfo* info) {
    g_spy->open[cmd].clear();
    return g_spy->vkBeginCommandBuffer(cmd, info);
}

VKAPI_ATTR VkResult VKAPI_CALL endCommandBuffer(VkCommandBuffer cmd) {
    for (const std::string& label : g_spy->open[cmd]) g_spy->problems.push_back("label '" + label + "' open at vkEndCommandBuffer");
    return g_spy->vkEndCommandBuffer(cmd);
}

VKAPI_ATTR VkResult VKAPI_CALL setObjectName(VkDevice d, const VkDebugUtilsObjectNameInfoEXT* info) {
    ++g_spy->debug_calls;
    if (!prefixed(info->pObjectName)) g_spy->problems.push_back(std::string("name without the prefix: ") + info->pObjectName);
    g_spy->unnamed.erase(info->objectHandle);
    return g_spy->vkSetDebugUtilsObjectNameEXT(d, info);
}

VKAPI_ATTR void VKAPI_CALL beginLabel(VkCommandBuffer cmd, const VkDebugUtilsLabelEXT* label) {
    ++g_spy->debug_calls;
    if (!prefixed(label->pLabelName)) g_spy->problems.push_back(std::string("label without the prefix: ") + label->pLabelName);
    g_spy->labels.emplace_back(label->pLabelName);
    g_spy->open[cmd].emplace_back(label->pLabelName);
    g_spy->vkCmdBeginDebugUtilsLabelEXT(cmd, label);
}

VKAPI_ATTR void VKAPI_CALL endLabel(VkCommandBuffer cmd) {
    ++g_spy->debug_calls;
    if (g_spy->open[cmd].empty()) g_spy->problems.emplace_back("vkCmdEndDebugUtilsLabelEXT without a label open");
    else g_spy->open[cmd].pop_back();
    g_spy->vkCmdEndDebugUtilsLabelEXT(cmd);
}

VKAPI_ATTR void VKAPI_CALL insertLabel(VkCommandBuffer cmd, const VkDebugUtilsLabelEXT* label) {
    ++g_spy->debug_calls;
    g_spy->vkCmdInsertDebugUtilsLabelEXT(cmd, label);
}

PFN_vkVoidFunction wrap(std::string_view name, PFN_vkVoidFunction real) {
#define SPY_WRAP(fn, wrapper)                                              \
    if (name == #fn) {                                                     \
        g_spy->fn = reinterpret_cast<PFN_##fn>(real);                      \
        return reinterpret_cast<PFN_vkVoidFunction>(wrapper);              \
    }
#define SPY_WRAP_CREATE(fn, info, handle) SPY_WRAP(fn, (create<&Spy::fn, info, handle>))
    SPY_CREATES(SPY_WRAP_CREATE)
    SPY_WRAP(vkCreateComputePipelines, (createPipelines<&Spy::vkCreateComputePipelines, VkComputePipelineCreateInfo>))
    SPY_WRAP(vkCreateGraphicsPipelines, (createPipelines<&Spy::vkCreateGraphicsPipelines, VkGraphicsPipelineCreateInfo>))
    SPY_WRAP(vkAllocateCommandBuffers, allocateCommandBuffers)
    SPY_WRAP(vkBeginCommandBuffer, beginCommandBuffer)
    SPY_WRAP(vkEndCommandBuffer, endCommandBuffer)
    SPY_WRAP(vkSetDebugUtilsObjectNameEXT, setObjectName)
    SPY_WRAP(vkCmdBeginDebugUtilsLabelEXT, beginLabel)
    SPY_WRAP(vkCmdEndDebugUtilsLabelEXT, endLabel)
    SPY_WRAP(vkCmdInsertDebugUtilsLabelEXT, insertLabel)
    return real;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL spyDeviceProcAddr(VkDevice device, const char* name) {
    PFN_vkVoidFunction real = g_spy->real_gdpa(device, name);
    return real ? wrap(name, real) : nullptr;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL spyInstanceProcAddr(VkInstance instance, const char* name) {
    const std::string_view n = name;
    if (n == "vkGetInstanceProcAddr") return reinterpret_cast<PFN_vkVoidFunction>(spyInstanceProcAddr);
    PFN_vkVoidFunction real = g_spy->real_gipa(instance, name);
    if (!real) return nullptr;
    if (n == "vkGetDeviceProcAddr") {
        g_spy->real_gdpa = reinterpret_cast<PFN_vkGetDeviceProcAddr>(real);
        return reinterpret_cast<PFN_vkVoidFunction>(spyDeviceProcAddr);
    }
    return wrap(n, real);
}

// Installs a Spy over the real loader for its lifetime.
struct SpyScope {
    Spy spy;
    SpyScope() {
        auto loader = vk::LoaderLibrary::open();
        REQUIRE(loader);
        spy.loader = *loader;
        spy.real_gipa = spy.loader->getInstanceProcAddr();
        g_spy = &spy;
    }
    ~SpyScope() { g_spy = nullptr; }
    SpyScope(const SpyScope&) = delete;
    SpyScope& operator=(const SpyScope&) = delete;
};

DetectSettings withMethod(DetectMethod method) {
    DetectSettings s;
    s.method = method;
    s.resolution = method == DetectMethod::Reliable ? 64u : 128u;
    s.direction = std::array<float, 3>{0.15f, -0.2f, 1.0f};
    return s;
}

// Detections as an engine runs them: each method twice (the second submits its command
// buffers again), then one recorded into the engine's command buffer.
void runDetections(ValidatedContext& ctx, Spy& spy) {
    auto world = makeWorld(ctx);
    auto scene = overlappingSpheres();
    REQUIRE(scene);
    addScene(*world, *scene);
    for (DetectMethod method : {DetectMethod::Reliable, DetectMethod::Peeling})
        for (int k = 0; k < 2; ++k) REQUIRE(world->detect(withMethod(method)));
    spy.tracking = false;  // the engine's pool and command buffer are not vkcollide's to name
    auto timeline = vk::Semaphore::createTimeline(ctx.device(), 0, "engine-timeline");
    REQUIRE(timeline);
    EngineCommands engine(ctx.device());
    spy.tracking = true;
    REQUIRE(world->record({engine.cmd, timeline->handle(), 1}, withMethod(DetectMethod::Reliable)));
    CHECK(spy.open[engine.cmd].empty());
    engine.submit(timeline->handle(), 1);
    REQUIRE(world->collect());
}

}  // namespace

TEST_CASE("with debug utils every object vkcollide creates is named, every pass labelled, labels balanced per command buffer",
          "[vk][gpu][debug-names]") {
    SpyScope scope;
    Spy& spy = scope.spy;
    ValidatedContext ctx(spyInstanceProcAddr);
    REQUIRE(ctx.device().debug_utils);
    runDetections(ctx, spy);
    for (const std::string& p : spy.problems) UNSCOPED_INFO(p);
    CHECK(spy.problems.empty());
    for (const auto& [handle, call] : spy.unnamed) UNSCOPED_INFO("unnamed: " << call << " " << handle);
    CHECK(spy.unnamed.empty());
    const auto has = [&](const std::string& label) { return std::find(spy.labels.begin(), spy.labels.end(), label) != spy.labels.end(); };
    CHECK(has("vkcollide: detect"));
    CHECK(has("vkcollide: cells-sweep"));  // a pass of the cell method
    CHECK(has("vkcollide: merge"));        // a pass of the peeling method
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("with names turned off vkcollide makes no debug-utils call, though validation enabled the extension",
          "[vk][gpu][debug-names]") {
    SpyScope scope;
    Spy& spy = scope.spy;
    ValidatedContext ctx(spyInstanceProcAddr, false);
    CHECK_FALSE(ctx.device().debug_utils);
    runDetections(ctx, spy);
    CHECK(spy.debug_calls == 0);
    CHECK(spy.labels.empty());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
