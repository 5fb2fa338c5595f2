// The per-file options (ObjectOptions and the tool's own per-file choices): each sets one
// file's FileSlot from the text after "FILES:" (or nothing, for the list-only options).
// Errors say what was expected; options.cpp puts the option and its argument first.
#pragma once

#include <string_view>

#include "cli/options.hpp"

namespace cli {

Result<void> slotName(FileSlot& slot, std::string_view text);       // NAME
Result<void> slotOpen(FileSlot& slot, std::string_view text);       // (list only)
Result<void> slotSelf(FileSlot& slot, std::string_view text);       // (list only)
Result<void> slotGpu(FileSlot& slot, std::string_view text);        // (list only)
Result<void> slotEdge(FileSlot& slot, std::string_view text);       // L > 0
// Transforms, each applied after the file's transform so far (object -> world).
Result<void> slotTransform(FileSlot& slot, std::string_view text);  // 12 numbers, row-major 3x4
Result<void> slotTranslate(FileSlot& slot, std::string_view text);  // x,y,z
Result<void> slotRotate(FileSlot& slot, std::string_view text);     // axis x,y,z, degrees
Result<void> slotScale(FileSlot& slot, std::string_view text);      // s or sx,sy,sz

}  // namespace cli
