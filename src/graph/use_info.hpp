// What each Use of a resource means in synchronization2 terms: the pipeline stages, the
// access, the image layout and the usage flags it needs. compile() derives barriers from it
// (graph/compile.cpp); isWrite() and toString() answer from it (graph/use_info.cpp).
#pragma once

#include <vulkan/vulkan_core.h>

#include "graph/graph.hpp"

namespace vkcollide::graph {

struct UseInfo {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;  // images only
    VkImageUsageFlags image_usage;
    VkBufferUsageFlags buffer_usage;
    bool write;
};

// `use` by a pass of `kind` (shader uses take their stages from the kind).
UseInfo describe(Use use, PassKind kind);

}  // namespace vkcollide::graph
