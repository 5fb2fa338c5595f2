// The host result from pairs the GPU decided exactly and sorted (DetectSettings::reliable.pair_sort):
// they are already final — distinct, in DetectResult::pairs' order, neighbours and the
// object-pair filter applied — so the host neither sorts nor tests. It keeps the first
// max_pairs, numbers the distinct triangles (slots), gathers their world vertices and
// computes the responses as the pair path does (responses.hpp), so responses are the same
// to the bit as runPairNarrowPhase's over the same pairs.
#pragma once

#include <span>

#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {

// `sorted`: each pair as its two global triangle ids of `source` (a < b), strictly ascending
// as (a, b), which is DetectResult::pairs' order: the GPU's 8-byte form (half the bytes of a
// TrianglePair to copy over the bus); the result names (object, triangle) as it copies them.
// A pair that is not (out of range, out of order) fails naming it.
// `pair_memory`, `response_memory`: vectors whose memory the result's pairs and responses
// reuse (their content is overwritten). `gpu_responses`: the responses of all of `sorted`
// computed on the GPU (DetectSettings::reliable.responses), in order: where no pair is left
// out (max_pairs) they are the result's as they are, so no slot is numbered, no vertex
// gathered and nothing computed (NarrowTimings: validate_ms, then the copies as sort_ms).
// `pairs_named`: pair_memory already holds all of `sorted` named by nameSortedPairs (with the
// same source), so with gpu_responses used as they are nothing is read or written again.
Result<NarrowResult> runSortedPairs(std::span<const CandidatePair> sorted, const TriangleSource& source, const NarrowOptions& options,
                                    Executor& executor, NarrowWorkspace& workspace, std::vector<TrianglePair> pair_memory = {},
                                    std::vector<TriangleResponse> response_memory = {},
                                    std::span<const TriangleResponse> gpu_responses = {}, bool pairs_named = false);

// runSortedPairs' naming alone, piece by piece, as a detection does while the GPU still
// copies the rest and computes the responses: prepareSortedNames makes `out` hold `n`
// pairs (reused memory, or fresh pages touched in parallel first; false where host memory
// ran out); nameSortedPairs names and checks pairs [begin, end) of `sorted` into it
// (out.size() == sorted.size(); the pair before `begin`, which it compares with, must be in
// memory). False, with `out` unspecified there, where a pair is out of range or out of
// order (runSortedPairs then names it). Neither throws.
bool prepareSortedNames(std::vector<TrianglePair>& out, std::size_t n, Executor& executor) noexcept;
bool nameSortedPairs(std::span<const CandidatePair> sorted, std::size_t begin, std::size_t end, const TriangleSource& source,
                     Executor& executor, std::vector<TrianglePair>& out) noexcept;

}  // namespace vkcollide::narrow
