// Compute shaders' workgroup needs read from their SPIR-V, and a device below them refused
// by name when the pipeline is made (not through a validation message at a dispatch).
#include <catch2/catch.hpp>

#include "cells/cells.h"
#include "common/broadphase.h"
#include "shaders/all.hpp"
#include "support/error_text.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/pipeline.hpp"
#include "vk/shader_limits.hpp"

using namespace vkcollide;

namespace {

using test::mentions;

}  // namespace

TEST_CASE("compute needs: the cell stage's deep sweep, counted from its declarations", "[vk][limits]") {
    auto needs = vk::readComputeNeeds(shaders::cells_deep_comp);
    REQUIRE(needs);
    CHECK(needs->local_size_known);
    CHECK(needs->local_size[0] == gpu::kCellsGroupSize);
    CHECK(needs->local_size[1] == 1u);
    CHECK(needs->local_size[2] == 1u);
    // s_zlo, s_key, s_order (4 bytes each), s_runs (k + 1 uints), s_index (uvec3), and the
    // workgroup helpers' kGroupSize uints (workgroup.glsl.inc).
    const std::uint64_t k = gpu::kCellsDeepShared;
    CHECK(needs->shared_bytes == 3 * 4 * k + 4 * (k + 1) + 12 * k + 4 * gpu::kGroupSize);
    // Above Vulkan's guaranteed 16 KB, below the 32 KB every desktop driver offers.
    CHECK(needs->shared_bytes > 16384u);
    CHECK(needs->shared_bytes <= 32768u);
}

TEST_CASE("compute needs: limits name what they exceed", "[vk][limits]") {
    vk::ComputeNeeds needs;
    needs.local_size[0] = 256;
    needs.local_size_known = true;
    needs.shared_bytes = 20000;
    VkPhysicalDeviceLimits limits{};
    limits.maxComputeSharedMemorySize = 32768;
    limits.maxComputeWorkGroupInvocations = 256;
    limits.maxComputeWorkGroupSize[0] = limits.maxComputeWorkGroupSize[1] = 256;
    limits.maxComputeWorkGroupSize[2] = 64;
    CHECK_FALSE(vk::exceededComputeLimit(needs, limits, "p").has_value());
    limits.maxComputeSharedMemorySize = 16384;  // Vulkan's minimum
    auto shared = vk::exceededComputeLimit(needs, limits, "p");
    REQUIRE(shared);
    CHECK(shared->find("20000 bytes of shared memory") != std::string::npos);
    CHECK(shared->find("maxComputeSharedMemorySize") != std::string::npos);
    limits.maxComputeSharedMemorySize = 32768;
    limits.maxComputeWorkGroupInvocations = 128;  // Vulkan's minimum
    auto invocations = vk::exceededComputeLimit(needs, limits, "p");
    REQUIRE(invocations);
    CHECK(invocations->find("maxComputeWorkGroupInvocations") != std::string::npos);
    limits.maxComputeWorkGroupInvocations = 256;
    limits.maxComputeWorkGroupSize[0] = 128;
    auto size = vk::exceededComputeLimit(needs, limits, "p");
    REQUIRE(size);
    CHECK(size->find("workgroup size 256 in x") != std::string::npos);
    // Not SPIR-V at all.
    const std::uint32_t junk[6] = {1, 2, 3, 4, 5, 6};
    CHECK_FALSE(vk::readComputeNeeds(junk));
}

TEST_CASE("a device with Vulkan's minimum shared memory refuses the deep sweep by name", "[gpu][vk][limits]") {
    test::ValidatedContext ctx;
    vk::Device& dev = ctx.device();
    const std::span<const vk::Pipeline::Binding> none;
    REQUIRE(vk::Pipeline::createCompute(dev, shaders::cells_deep_comp, none, sizeof(gpu::Push), "cells-deep"));
    const VkPhysicalDeviceLimits real = dev.properties.limits;
    dev.properties.limits.maxComputeSharedMemorySize = 16384;
    auto refused = vk::Pipeline::createCompute(dev, shaders::cells_deep_comp, none, sizeof(gpu::Push), "cells-deep");
    dev.properties.limits = real;
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code() == ErrorCode::UnsupportedFeature);
    CHECK(mentions(refused.error(), "'cells-deep'"));
    CHECK(mentions(refused.error(), "maxComputeSharedMemorySize"));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}
