// The renderer's users call Vulkan directly, as an engine does: they link the loader
// (Vulkan::Vulkan) and use its prototypes.
#pragma once

#include <vulkan/vulkan.h>
