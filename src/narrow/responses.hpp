// The responses (see TriangleResponse): for each responder, a slot in a colliding pair, in
// slot order, the terms n_partner - n_self summed in the order of the sorted pairs. Three
// forms with the same result to the bit; respond() picks one by size and thread count.
#pragma once

#include <cstddef>
#include <cstdint>

#include "narrow/parallel.hpp"
#include "narrow/slots.hpp"
#include "narrow/workspace.hpp"
#include "vkcollide/narrow.hpp"

namespace vkcollide::narrow {

enum class ResponseForm {
    Automatic,  // Serial for few pairs or one thread, else Grouped; Sorted when the slots are sparse
    Serial,     // on the calling thread: a counting sort of both ends of every pair over the slots
    Grouped,    // parallel: only the higher ends grouped (the lower ends already are), per-slot ranges
    Sorted,     // parallel: both ends sorted as (slot, pair index); no per-slot arrays
};

// Fills out.responses from `colliding`: the distinct colliding pairs as (lower slot << 32)
// | higher slot, ascending, all slots below slot_count. Serial and Grouped keep arrays of
// slot_count entries, so Automatic uses them only when the slots are not many more than
// the ends. Every form gives the same responses on any thread count.
void respond(const Buffer<std::uint64_t>& colliding, const SlotData& slots, std::size_t slot_count, ResponseForm form,
             Executor& executor, NarrowWorkspace::Impl& ws, NarrowResult& out);

}  // namespace vkcollide::narrow
