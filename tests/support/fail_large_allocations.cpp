#include "support/fail_large_allocations.hpp"

#include <atomic>
#include <cstdlib>
#include <limits>
#include <new>

namespace {

std::atomic<std::size_t> g_fail_above{std::numeric_limits<std::size_t>::max()};

}  // namespace

namespace vkcollide::test {

FailLargeAllocations::FailLargeAllocations(std::size_t bytes) { g_fail_above.store(bytes); }
FailLargeAllocations::~FailLargeAllocations() { g_fail_above.store(std::numeric_limits<std::size_t>::max()); }

}  // namespace vkcollide::test

// Every replaceable form, so that no allocation is made by one allocator and freed by
// another (AddressSanitizer checks that pairing). GCC 12 at -O1 and above, seeing these
// definitions inlined into each other in a unity build, takes the free() in operator
// delete[] for one of a pointer from operator new[] (-Wmismatched-new-delete): it is this
// file's own pairing, malloc with free.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t bytes) {
    if (bytes > g_fail_above.load(std::memory_order_relaxed)) throw std::bad_alloc();
    if (void* p = std::malloc(bytes ? bytes : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t bytes) { return ::operator new(bytes); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
    if (bytes > g_fail_above.load(std::memory_order_relaxed)) return nullptr;
    return std::malloc(bytes ? bytes : 1);
}
void* operator new[](std::size_t bytes, const std::nothrow_t& tag) noexcept { return ::operator new(bytes, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
