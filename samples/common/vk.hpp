// The samples call Vulkan directly, as an engine does: they link the loader
// (Vulkan::Vulkan) and use its prototypes. Include this header before any other Vulkan
// or vkcollide header.
#pragma once

// Workaround: the library exports VK_NO_PROTOTYPES as a PUBLIC compile definition,
// which hides the prototypes from every consumer. The fix (the definition becomes
// private to the library) is on the `engine` branch; this block goes when it lands.
#ifdef VK_NO_PROTOTYPES
#ifdef VULKAN_CORE_H_
#error "samples/common/vk.hpp must come before any other Vulkan or vkcollide header"
#endif
#undef VK_NO_PROTOTYPES
#endif

#include <vulkan/vulkan.h>
