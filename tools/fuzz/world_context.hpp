// fuzz_world's Vulkan context: one for many inputs (creating one costs far more than a
// detection), with the Khronos validation layer on (VKCOLLIDE_FUZZ_VALIDATION=0: off) and
// every message it gives kept, so that any message is a finding.
#pragma once

#include "vkcollide/context.hpp"

namespace vkcollide::fuzz {

// The context (made on first use).
Context& fuzzContext();
// Aborts, naming `after`, if the validation layer said anything since the context was made.
void requireNoValidationMessages(const char* after);
// Called before each input: every kInputsPerContext inputs the context is destroyed (the
// layer then reports any Vulkan object still alive) and a new one made.
void nextInput();

}  // namespace vkcollide::fuzz
