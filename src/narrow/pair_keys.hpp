// The pair path's front (docs/narrow_phase.md): every input pair checked, the distinct
// triangles numbered in id order ("slots"), and the distinct pairs as (lower slot, higher
// slot) keys in ascending order. Two forms with the same result to the bit: a parallel
// one for large inputs and one on the calling thread for the few hundred to few thousand
// pairs the reliable method sends each detection, where the parallel form's dozen
// fork-joins cost more than the work.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {

// Below this many input pairs the front runs on the calling thread (PairKeysForm::Automatic).
inline constexpr std::size_t kSerialPairsBelow = std::size_t{1} << 13;

enum class PairKeysForm {
    Automatic,  // Serial below kSerialPairsBelow pairs, else Parallel
    Serial,     // on the calling thread: the ends sorted by id, the keys read off in order
    Parallel,   // parallel loops: a marker per id or a sort of the ends, then a key sort
};

struct PairKeys {
    std::size_t slot_count = 0;  // distinct triangles: ws.slot_ids[0, slot_count), ascending ids
    int slot_bits = 1;           // a key is (lower slot << slot_bits) | higher slot
    std::size_t pairs = 0;       // distinct pairs: ws.pair_keys[0, pairs), ascending
};

// Fills io_ws.slot_ids and io_ws.pair_keys (and uses the pair path's other scratch) from
// in_pairs, whose ids must be below `total`. Returns the index of the first pair that
// names an id not below `total` or one id twice, if any (then `out` is unspecified).
// Every form gives the same result whatever the executor's thread count.
std::optional<std::size_t> buildPairKeys(Executor& executor, std::span<const CandidatePair> in_pairs, std::uint32_t total,
                                         PairKeysForm form, NarrowWorkspace::Impl& io_ws, PairKeys& out);

}  // namespace vkcollide::narrow
