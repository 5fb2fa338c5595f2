// The push constants of the graph test shaders (tests/shaders/graph_test_*.glsl), as the
// C++ side writes them: one definition for every test that draws or sums with them.
#pragma once

#include <vulkan/vulkan_core.h>

namespace vkcollide::test {

// graph_test_draw.vert/.frag: the rectangle to cover and the framebuffer size in pixels,
// and the counter the fragment shader adds to.
struct DrawPush {
    float rect[4];
    float extent[2];
    VkDeviceAddress counter;
};
// graph_test_sum.comp: the counter the covered pixels are added to.
struct SumPush {
    VkDeviceAddress sum;
};

}  // namespace vkcollide::test
