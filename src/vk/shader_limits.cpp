#include "vk/shader_limits.hpp"

#include <algorithm>
#include <array>
#include <unordered_map>

namespace vkcollide::vk {
namespace {

// SPIR-V 1.x numbers used here (the SPIR-V specification, section 3).
constexpr std::uint32_t kMagic = 0x07230203;
constexpr std::uint32_t kOpExecutionMode = 16, kOpExecutionModeId = 331;
constexpr std::uint32_t kModeLocalSize = 17, kModeLocalSizeId = 38;
constexpr std::uint32_t kOpTypeBool = 20, kOpTypeInt = 21, kOpTypeFloat = 22, kOpTypeVector = 23, kOpTypeMatrix = 24;
constexpr std::uint32_t kOpTypeArray = 28, kOpTypeStruct = 30, kOpTypePointer = 32;
constexpr std::uint32_t kOpConstant = 43, kOpSpecConstant = 50, kOpVariable = 59;
constexpr std::uint32_t kStorageWorkgroup = 4;

struct Layout {
    std::uint64_t size = 0, align = 1;
};

std::uint64_t alignUp(std::uint64_t x, std::uint64_t a) { return (x + a - 1) / a * a; }

}  // namespace

Result<ComputeNeeds> readComputeNeeds(std::span<const std::uint32_t> spirv) {
    if (spirv.size() < 5 || spirv[0] != kMagic) return Error(ErrorCode::InvalidArgument, "not SPIR-V (no magic number)");
    ComputeNeeds needs;
    std::unordered_map<std::uint32_t, Layout> types;
    std::unordered_map<std::uint32_t, std::uint32_t> pointee;    // pointer type id -> pointed-to type, Workgroup pointers only
    std::unordered_map<std::uint32_t, std::uint64_t> constants;  // scalar integer constants (array lengths)
    std::optional<std::array<std::uint32_t, 3>> size_ids;         // LocalSizeId's operands
    for (std::size_t at = 5; at < spirv.size();) {
        const std::uint32_t words = spirv[at] >> 16, op = spirv[at] & 0xffffu;
        if (words == 0 || at + words > spirv.size())
            return Error(ErrorCode::InvalidArgument, "SPIR-V instruction at word " + std::to_string(at) + " runs past the end");
        const std::uint32_t* w = &spirv[at];
        auto known = [&](std::uint32_t id) -> const Layout* {
            auto it = types.find(id);
            return it == types.end() ? nullptr : &it->second;
        };
        switch (op) {
            case kOpExecutionMode:
                if (words >= 6 && w[2] == kModeLocalSize) {
                    needs.local_size[0] = w[3], needs.local_size[1] = w[4], needs.local_size[2] = w[5];
                    needs.local_size_known = true;
                }
                break;
            case kOpExecutionModeId:  // constants' ids, resolved once the constants are read
                if (words >= 6 && w[2] == kModeLocalSizeId) size_ids = {w[3], w[4], w[5]};
                break;
            case kOpTypeBool:
                if (words >= 2) types[w[1]] = {4, 4};
                break;
            case kOpTypeInt:
            case kOpTypeFloat:
                if (words >= 3) types[w[1]] = {w[2] / 8u, w[2] / 8u};
                break;
            case kOpTypeVector:
                if (const Layout* e = words >= 4 ? known(w[2]) : nullptr) types[w[1]] = {e->size * w[3], e->align};
                break;
            case kOpTypeMatrix:  // columns of the column vector type
                if (const Layout* e = words >= 4 ? known(w[2]) : nullptr) types[w[1]] = {e->size * w[3], e->align};
                break;
            case kOpTypeArray:
                if (const Layout* e = words >= 4 ? known(w[2]) : nullptr) {
                    auto length = constants.find(w[3]);
                    if (length == constants.end())
                        return Error(ErrorCode::InvalidArgument, "SPIR-V array type %" + std::to_string(w[1]) + " has a length that is not a constant");
                    types[w[1]] = {alignUp(e->size, e->align) * length->second, e->align};
                }
                break;
            case kOpTypeStruct: {
                Layout s;
                bool all = true;
                for (std::uint32_t m = 2; m < words; ++m) {
                    const Layout* e = known(w[m]);
                    if (!e) {
                        all = false;
                        break;
                    }
                    s.size = alignUp(s.size, e->align) + e->size;
                    s.align = std::max(s.align, e->align);
                }
                if (all) types[w[1]] = {alignUp(s.size, s.align), s.align};
                break;
            }
            case kOpTypePointer:
                if (words >= 4 && w[2] == kStorageWorkgroup) pointee[w[1]] = w[3];
                break;
            case kOpConstant:
            case kOpSpecConstant:  // the default value: what the pipeline gets without specialisation
                if (words >= 4) constants[w[2]] = words >= 5 ? (std::uint64_t{w[4]} << 32) | w[3] : w[3];
                break;
            case kOpVariable:
                if (words >= 4 && w[3] == kStorageWorkgroup) {
                    auto p = pointee.find(w[1]);
                    const Layout* t = p == pointee.end() ? nullptr : known(p->second);
                    if (!t)
                        return Error(ErrorCode::InvalidArgument,
                                     "SPIR-V workgroup variable %" + std::to_string(w[2]) + " has a type whose size is not read here");
                    needs.shared_bytes = alignUp(needs.shared_bytes, t->align) + t->size;
                }
                break;
            default:
                break;
        }
        at += words;
    }
    if (size_ids) {
        needs.local_size_known = true;
        for (int a = 0; a < 3; ++a) {
            auto c = constants.find((*size_ids)[a]);
            if (c == constants.end()) {  // a specialisation constant's id without a default read here
                needs.local_size_known = false;
                break;
            }
            needs.local_size[a] = static_cast<std::uint32_t>(c->second);
        }
    }
    return needs;
}

std::optional<std::string> exceededComputeLimit(const ComputeNeeds& needs, const VkPhysicalDeviceLimits& limits,
                                                const std::string& name) {
    const std::string who = "compute pipeline '" + name + "' ";
    if (needs.shared_bytes > limits.maxComputeSharedMemorySize)
        return who + "needs " + std::to_string(needs.shared_bytes) + " bytes of shared memory; the device offers " +
               std::to_string(limits.maxComputeSharedMemorySize) + " (maxComputeSharedMemorySize)";
    if (!needs.local_size_known) return std::nullopt;
    static const char* const kAxis[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a)
        if (needs.local_size[a] > limits.maxComputeWorkGroupSize[a])
            return who + "has a workgroup size " + std::to_string(needs.local_size[a]) + " in " + kAxis[a] + "; the device allows " +
                   std::to_string(limits.maxComputeWorkGroupSize[a]) + " (maxComputeWorkGroupSize)";
    const std::uint64_t invocations = std::uint64_t{needs.local_size[0]} * needs.local_size[1] * needs.local_size[2];
    if (invocations > limits.maxComputeWorkGroupInvocations)
        return who + "has " + std::to_string(invocations) + " invocations per workgroup; the device allows " +
               std::to_string(limits.maxComputeWorkGroupInvocations) + " (maxComputeWorkGroupInvocations)";
    return std::nullopt;
}

}  // namespace vkcollide::vk
