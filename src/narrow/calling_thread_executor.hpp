// An Executor that runs every loop on the calling thread, in order. The pair path uses it
// for small sets of pairs the GPU already decided (exact_stage.hpp, runsOnCallingThread):
// with no tests to share out, waking and feeding a pool's workers costs more than the work.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>

#include "vkcollide/thread_pool.hpp"

namespace vkcollide::narrow {

class CallingThreadExecutor final : public Executor {
public:
    unsigned threadCount() const noexcept override { return 1; }
    void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body) override {
        grain = std::max<std::size_t>(grain, 1);
        for (std::size_t begin = 0; begin < count; begin += grain) body(begin, std::min(count, begin + grain));
    }
};

}  // namespace vkcollide::narrow
