// For test programs that make host memory run out at a known point: while a
// FailLargeAllocations guard is alive, every allocation above its size fails (operator new
// throws std::bad_alloc, the nothrow forms return null). The replacement operators live in
// fail_large_allocations.cpp; a program links that file (it replaces the global operator
// new of the whole program, so such a program is its own executable).
#pragma once

#include <cstddef>

namespace vkcollide::test {

class FailLargeAllocations {
public:
    explicit FailLargeAllocations(std::size_t bytes);
    ~FailLargeAllocations();
    FailLargeAllocations(const FailLargeAllocations&) = delete;
    FailLargeAllocations& operator=(const FailLargeAllocations&) = delete;
};

}  // namespace vkcollide::test
