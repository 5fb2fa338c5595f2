// Transfer-queue probe (session 65): does a copy of device memory to host memory on a queue of
// a transfer-only family run beside compute work on the main queue? Run 33 found that on the
// main queue it does not (a copy and the dispatches after it, no barrier between them, still
// ran one after the other on an H100), so the pairs' copy to the host (0.33-0.42 ms of
// stack-mating's 2.45 ms span) adds to the span. This measures, with no vkcollide code:
//   copy      fill; barrier; copy of `mb` MB to host-cached memory          (main queue)
//   busy      a compute dispatch of about the responses' passes' length   (main queue)
//   same      fill; barrier; copy; busy, no barrier between copy and busy (main queue)
//   transfer  fill -> semaphore; busy (main queue) || copy (transfer queue, waits for the semaphore)
//   queue2    as transfer, the copy on a second queue of the main family (where it has two)
// GPU spans from timestamps (both queues' stamps are on one clock), host wall time from the
// first submit to the last fence; medians of `reps`.
// Build: glslangValidator -V --target-env vulkan1.2 --vn fill_spv -o fill.h
// session65_tq.comp.glsl, the same with -DBUSY --vn busy_spv -o busy.h, then
//   g++ -O2 -std=c++20 session65_transfer_queue_probe.cpp -o tq_probe -l:libvulkan.so.1
// Run: tq_probe [mb=17] [busy_iterations=4000] [reps=25]
#include <vulkan/vulkan.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "fill.h"  // fill_spv: out[i] = i * 2654435761u
#include "busy.h"  // busy_spv: a dependent chain of `iterations` multiply-adds per invocation

using Clock = std::chrono::steady_clock;

#define CHECK(x)                                                                 \
    do {                                                                         \
        VkResult r_ = (x);                                                       \
        if (r_ != VK_SUCCESS) {                                                  \
            std::fprintf(stderr, "%s failed: %d (line %d)\n", #x, r_, __LINE__); \
            std::exit(1);                                                        \
        }                                                                        \
    } while (0)

struct Buf {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
};

static VkPhysicalDeviceMemoryProperties memory_props;

static std::uint32_t memoryType(std::uint32_t bits, VkMemoryPropertyFlags want) {
    for (std::uint32_t i = 0; i < memory_props.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (memory_props.memoryTypes[i].propertyFlags & want) == want) return i;
    std::fprintf(stderr, "no memory type with flags %x\n", want);
    std::exit(1);
}

static Buf makeBuffer(VkDevice dev, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags want,
                      const std::vector<std::uint32_t>& families) {
    Buf b;
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = size;
    bi.usage = usage;
    bi.sharingMode = families.size() > 1 ? VK_SHARING_MODE_CONCURRENT : VK_SHARING_MODE_EXCLUSIVE;
    bi.queueFamilyIndexCount = families.size() > 1 ? static_cast<std::uint32_t>(families.size()) : 0;
    bi.pQueueFamilyIndices = families.size() > 1 ? families.data() : nullptr;
    CHECK(vkCreateBuffer(dev, &bi, nullptr, &b.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, b.buffer, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = memoryType(req.memoryTypeBits, want);
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    if (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) ai.pNext = &flags;
    CHECK(vkAllocateMemory(dev, &ai, nullptr, &b.memory));
    CHECK(vkBindBufferMemory(dev, b.buffer, b.memory, 0));
    if (want & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) CHECK(vkMapMemory(dev, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    return b;
}

static VkPipeline makePipeline(VkDevice dev, VkPipelineLayout layout, const std::uint32_t* code, std::size_t bytes) {
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mi.codeSize = bytes;
    mi.pCode = code;
    VkShaderModule module;
    CHECK(vkCreateShaderModule(dev, &mi, nullptr, &module));
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main", nullptr};
    ci.layout = layout;
    VkPipeline p;
    CHECK(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, nullptr, &p));
    vkDestroyShaderModule(dev, module, nullptr);
    return p;
}

struct Push {
    VkDeviceAddress out;
    std::uint32_t count, iterations;
};

static double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

int main(int argc, char** argv) {
    const std::size_t mb = argc > 1 ? std::stoul(argv[1]) : 17;
    const std::uint32_t iterations = argc > 2 ? std::stoul(argv[2]) : 4000;
    const int reps = argc > 3 ? std::stoi(argv[3]) : 25;
    const VkDeviceSize bytes = VkDeviceSize(mb) << 20;

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ii{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ii.pApplicationInfo = &app;
    VkInstance inst;
    CHECK(vkCreateInstance(&ii, nullptr, &inst));
    std::uint32_t n = 0;
    vkEnumeratePhysicalDevices(inst, &n, nullptr);
    std::vector<VkPhysicalDevice> pds(n);
    vkEnumeratePhysicalDevices(inst, &n, pds.data());
    VkPhysicalDevice pd = pds.at(0);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    vkGetPhysicalDeviceMemoryProperties(pd, &memory_props);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> qf(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, qf.data());
    std::uint32_t main_family = ~0u, transfer_family = ~0u;
    for (std::uint32_t i = 0; i < n; ++i) {
        std::printf("family %u: flags 0x%x, %u queues, timestampValidBits %u\n", i, qf[i].queueFlags, qf[i].queueCount,
                    qf[i].timestampValidBits);
        const bool compute = qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT;
        const bool graphics = qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT;
        if (compute && graphics && main_family == ~0u) main_family = i;
        if ((qf[i].queueFlags & VK_QUEUE_TRANSFER_BIT) && !compute && !graphics && transfer_family == ~0u) transfer_family = i;
    }
    std::printf("device %s, main family %u, transfer-only family %d\n", props.deviceName, main_family,
                transfer_family == ~0u ? -1 : int(transfer_family));
    const bool has_transfer = transfer_family != ~0u;

    const bool has_queue2 = qf[main_family].queueCount > 1;
    float priority[2] = {1, 1};
    VkDeviceQueueCreateInfo qi[2] = {{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, main_family, has_queue2 ? 2u : 1u, priority},
                                     {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, transfer_family, 1, priority}};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.bufferDeviceAddress = VK_TRUE;
    f12.hostQueryReset = VK_TRUE;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.synchronization2 = VK_TRUE;
    f13.pNext = &f12;
    VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    di.pNext = &f13;
    di.queueCreateInfoCount = has_transfer ? 2 : 1;
    di.pQueueCreateInfos = qi;
    VkDevice dev;
    CHECK(vkCreateDevice(pd, &di, nullptr, &dev));
    VkQueue q_main, q_transfer = VK_NULL_HANDLE, q_second = VK_NULL_HANDLE;
    vkGetDeviceQueue(dev, main_family, 0, &q_main);
    if (has_queue2) vkGetDeviceQueue(dev, main_family, 1, &q_second);
    if (has_transfer) vkGetDeviceQueue(dev, transfer_family, 0, &q_transfer);

    std::vector<std::uint32_t> both{main_family};
    if (has_transfer) both.push_back(transfer_family);
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    Buf src = makeBuffer(dev, bytes, storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, both);
    Buf dst = makeBuffer(dev, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, both);
    const std::uint32_t busy_count = 1u << 20;
    Buf work = makeBuffer(dev, busy_count * 4, storage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, {main_family});
    auto address = [&](VkBuffer b) {
        VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, nullptr, b};
        return vkGetBufferDeviceAddress(dev, &ai);
    };

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Push)};
    VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    li.pushConstantRangeCount = 1;
    li.pPushConstantRanges = &range;
    VkPipelineLayout layout;
    CHECK(vkCreatePipelineLayout(dev, &li, nullptr, &layout));
    VkPipeline fill = makePipeline(dev, layout, fill_spv, sizeof(fill_spv));
    VkPipeline busy = makePipeline(dev, layout, busy_spv, sizeof(busy_spv));

    VkQueryPoolCreateInfo qpi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qpi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qpi.queryCount = 8;
    VkQueryPool pool;
    CHECK(vkCreateQueryPool(dev, &qpi, nullptr, &pool));

    auto makeCommands = [&](std::uint32_t family) {
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pi.queueFamilyIndex = family;
        VkCommandPool cp;
        CHECK(vkCreateCommandPool(dev, &pi, nullptr, &cp));
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = cp;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 3;
        std::vector<VkCommandBuffer> cbs(3);
        CHECK(vkAllocateCommandBuffers(dev, &ai, cbs.data()));
        return cbs;
    };
    std::vector<VkCommandBuffer> main_cbs = makeCommands(main_family);
    std::vector<VkCommandBuffer> transfer_cbs = has_transfer ? makeCommands(transfer_family) : std::vector<VkCommandBuffer>{};
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence_main, fence_transfer;
    CHECK(vkCreateFence(dev, &fi, nullptr, &fence_main));
    CHECK(vkCreateFence(dev, &fi, nullptr, &fence_transfer));
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore filled;
    CHECK(vkCreateSemaphore(dev, &si, nullptr, &filled));

    const std::uint32_t words = static_cast<std::uint32_t>(bytes / 4);
    auto begin = [](VkCommandBuffer cb) {
        CHECK(vkResetCommandBuffer(cb, 0));
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        CHECK(vkBeginCommandBuffer(cb, &bi));
    };
    auto dispatch = [&](VkCommandBuffer cb, VkPipeline p, VkDeviceAddress out, std::uint32_t count, std::uint32_t iters) {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, p);
        Push push{out, count, iters};
        vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdDispatch(cb, (count + 255) / 256, 1, 1);
    };
    auto barrier = [](VkCommandBuffer cb, VkPipelineStageFlags2 src, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst,
                      VkAccessFlags2 dst_access) {
        VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, src, src_access, dst, dst_access};
        VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        d.memoryBarrierCount = 1;
        d.pMemoryBarriers = &mb;
        vkCmdPipelineBarrier2(cb, &d);
    };
    auto copy = [&](VkCommandBuffer cb) {
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cb, src.buffer, dst.buffer, 1, &region);
        barrier(cb, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    };
    auto stamp = [&](VkCommandBuffer cb, VkPipelineStageFlags2 stage, std::uint32_t q) { vkCmdWriteTimestamp2(cb, stage, pool, q); };
    auto submit = [&](VkQueue q, VkCommandBuffer cb, VkSemaphore wait, VkSemaphore signal, VkFence fence) {
        VkCommandBufferSubmitInfo ci{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, nullptr, cb, 0};
        VkSemaphoreSubmitInfo w{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, nullptr, wait, 0, VK_PIPELINE_STAGE_2_COPY_BIT, 0};
        VkSemaphoreSubmitInfo s{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, nullptr, signal, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0};
        VkSubmitInfo2 info{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        info.commandBufferInfoCount = 1;
        info.pCommandBufferInfos = &ci;
        info.waitSemaphoreInfoCount = wait ? 1 : 0;
        info.pWaitSemaphoreInfos = &w;
        info.signalSemaphoreInfoCount = signal ? 1 : 0;
        info.pSignalSemaphoreInfos = &s;
        CHECK(vkQueueSubmit2(q, 1, &info, fence));
    };
    const double period_ms = props.limits.timestampPeriod * 1e-6;
    auto stamps = [&](std::uint32_t count) {
        std::vector<std::uint64_t> t(count);
        CHECK(vkGetQueryPoolResults(dev, pool, 0, count, count * 8, t.data(), 8, VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        return t;
    };
    auto waitAll = [&](bool both_fences) {
        VkFence fences[2] = {fence_main, fence_transfer};
        CHECK(vkWaitForFences(dev, both_fences ? 2 : 1, fences, VK_TRUE, UINT64_MAX));
        CHECK(vkResetFences(dev, both_fences ? 2 : 1, fences));
    };
    const VkPipelineStageFlags2 top = VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, bottom = VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT;
    const VkPipelineStageFlags2 cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;

    // Each mode: GPU span (ms) of what follows the fill, host wall (ms) from submit to the last fence.
    struct Mode {
        const char* name;
        std::vector<double> span, wall, part;  // part: copy's own span (transfer) or 0
    };
    std::vector<Mode> modes = {{"copy"}, {"busy"}, {"same"}, {"transfer"}, {"queue2"}};
    const VkDeviceAddress src_address = address(src.buffer), work_address = address(work.buffer);
    for (int rep = -3; rep < reps; ++rep) {
        for (std::size_t m = 0; m < modes.size(); ++m) {
            if ((m == 3 && !has_transfer) || (m == 4 && !has_queue2)) continue;
            vkResetQueryPool(dev, pool, 0, 8);
            VkCommandBuffer cb = main_cbs[0];
            begin(cb);
            dispatch(cb, fill, src_address, words, 0);
            barrier(cb, cs, VK_ACCESS_2_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT | cs,
                    VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_SHADER_READ_BIT);
            stamp(cb, bottom, 0);  // the fill done: the span's start
            const auto t0 = Clock::now();
            double part = 0;
            std::vector<std::uint64_t> t;
            if (m < 3) {
                if (m == 0 || m == 2) copy(cb);
                if (m == 1 || m == 2) dispatch(cb, busy, work_address, busy_count, iterations);
                stamp(cb, bottom, 1);
                CHECK(vkEndCommandBuffer(cb));
                submit(q_main, cb, VK_NULL_HANDLE, VK_NULL_HANDLE, fence_main);
                waitAll(false);
                t = stamps(2);
            } else {
                CHECK(vkEndCommandBuffer(cb));
                submit(q_main, cb, VK_NULL_HANDLE, filled, VK_NULL_HANDLE);
                VkCommandBuffer tcb = m == 3 ? transfer_cbs[0] : main_cbs[2];
                begin(tcb);
                stamp(tcb, top, 2);
                copy(tcb);
                stamp(tcb, bottom, 3);
                CHECK(vkEndCommandBuffer(tcb));
                submit(m == 3 ? q_transfer : q_second, tcb, filled, VK_NULL_HANDLE, fence_transfer);
                VkCommandBuffer bcb = main_cbs[1];
                begin(bcb);
                dispatch(bcb, busy, work_address, busy_count, iterations);
                stamp(bcb, bottom, 1);
                CHECK(vkEndCommandBuffer(bcb));
                submit(q_main, bcb, VK_NULL_HANDLE, VK_NULL_HANDLE, fence_main);
                waitAll(true);
                t = stamps(4);
                part = (t[3] - t[2]) * period_ms;
                t[1] = std::max(t[1], t[3]);
            }
            const double wall = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            if (rep < 0) continue;
            modes[m].span.push_back((t[1] - t[0]) * period_ms);
            modes[m].wall.push_back(wall);
            modes[m].part.push_back(part);
        }
    }
    // The copy arrived: every word as the fill wrote it.
    const auto* words_out = static_cast<const std::uint32_t*>(dst.mapped);
    std::uint32_t bad = 0;
    for (std::uint32_t i = 0; i < words; i += 4099) bad += words_out[i] != i * 2654435761u;
    std::printf("mode,mb,busy_iterations,reps,span_ms_median,span_ms_min,wall_ms_median,copy_on_other_queue_ms\n");
    for (const Mode& m : modes) {
        if (m.span.empty()) continue;
        std::printf("%s,%zu,%u,%d,%.4f,%.4f,%.4f,%.4f\n", m.name, mb, iterations, reps, median(m.span),
                    *std::min_element(m.span.begin(), m.span.end()), median(m.wall), median(m.part));
    }
    std::printf("copied words checked: %s\n", bad == 0 ? "all equal" : "MISMATCH");
    return bad == 0 ? 0 : 2;
}
