// runPairNarrowPhase (include/vkcollide/narrow.hpp) with memory for its result: the
// caller's, lent by detectInto / collectInto.
#pragma once

#include <span>
#include <vector>

#include "vkcollide/narrow.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {

// `pair_memory`, `response_memory`: vectors whose memory the result's pairs and responses
// reuse (their sizes and contents are discarded). Otherwise runPairNarrowPhase.
Result<NarrowResult> runPairNarrowPhaseInto(std::span<const CandidatePair> in_pairs, const TriangleSource& source,
                                            const NarrowOptions& options, Executor& executor, NarrowWorkspace& workspace,
                                            std::vector<TrianglePair> pair_memory, std::vector<TriangleResponse> response_memory);

}  // namespace vkcollide::narrow
