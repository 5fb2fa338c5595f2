// The words of a CommandTape (graph/command_tape.hpp): each command is an opcode word
// followed by its fields, one 64-bit word each, or two 32-bit fields packed into one
// (pack()); arrays follow their count. Recording (command_tape.cpp) writes them, replay
// (command_tape_replay.cpp) reads them back.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <type_traits>

#include <vulkan/vulkan_core.h>

namespace vkcollide::graph::tape {

enum Op : std::uint64_t {
    kBindPipeline = 1,
    kPushConstants,
    kPushDescriptorSet,
    kDispatch,
    kDispatchIndirect,
    kDraw,
    kFillBuffer,
    kCopyBuffer,
    kPipelineBarrier,
    kBeginRendering,
    kEndRendering,
    kSetViewport,
    kSetScissor,
    kWriteTimestamp,
    kBeginLabel,
    kEndLabel,
    kSignalHost,
};

template <class H>
std::uint64_t bits(H h) {
    if constexpr (std::is_pointer_v<H>) return reinterpret_cast<std::uintptr_t>(h);
    else return static_cast<std::uint64_t>(h);
}

template <class H>
H handle(std::uint64_t word) {
    if constexpr (std::is_pointer_v<H>) return reinterpret_cast<H>(static_cast<std::uintptr_t>(word));
    else return static_cast<H>(word);
}

inline std::uint64_t pack(std::uint32_t lo, std::uint32_t hi) { return std::uint64_t{lo} | std::uint64_t{hi} << 32; }
inline std::uint32_t lo(std::uint64_t w) { return static_cast<std::uint32_t>(w); }
inline std::uint32_t hi(std::uint64_t w) { return static_cast<std::uint32_t>(w >> 32); }
inline std::uint64_t packFloats(float a, float b) { return pack(std::bit_cast<std::uint32_t>(a), std::bit_cast<std::uint32_t>(b)); }

inline std::size_t wordsFor(std::size_t bytes) { return (bytes + 7) / 8; }

enum class DescriptorKind { Buffer, Image, Texel };

inline DescriptorKind kindOf(VkDescriptorType type) {
    switch (type) {
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC:
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC: return DescriptorKind::Buffer;
        case VK_DESCRIPTOR_TYPE_SAMPLER:
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT: return DescriptorKind::Image;
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: return DescriptorKind::Texel;
        default: std::abort();  // inline uniforms and acceleration structures come in a pNext
    }
}

// Reads a tape's words in order.
struct Reader {
    const std::uint64_t* p;
    std::uint64_t next() { return *p++; }
    template <class H>
    H nextHandle() { return handle<H>(*p++); }
};

}  // namespace vkcollide::graph::tape
