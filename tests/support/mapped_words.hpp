// Reading and poisoning host-visible buffers in GPU tests: a word as the GPU left it (the
// range invalidated first), and every byte set to 0xFF before a run, so that a result the
// GPU did not write shows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "vk/resources.hpp"

namespace vkcollide::test {

inline std::uint32_t wordAt(const vk::Buffer& buffer, std::size_t index) {
    buffer.invalidate();
    std::uint32_t v = 0;
    std::memcpy(&v, static_cast<const std::byte*>(buffer.mapped()) + index * 4, 4);
    return v;
}

inline void poison(const vk::Buffer& buffer) {
    std::memset(buffer.mapped(), 0xFF, buffer.size());
    buffer.flush();
}

}  // namespace vkcollide::test
