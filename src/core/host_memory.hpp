// The promise that no exception crosses the API, for host memory, kept in one place: host
// memory running out inside a call (std::bad_alloc, or an array past its largest size) is
// ErrorCode::OutOfMemory named after the call. Used by the world's calls that copy meshes,
// by detections (which also abandon their GPU work first) and by the narrow phase.
#pragma once

#include <new>
#include <stdexcept>
#include <string>

#include "vkcollide/result.hpp"

namespace vkcollide {

// f(), or OutOfMemory ("<what>: host memory ran out") when it throws for lack of host
// memory; `on_failure` runs before the error is returned.
template <typename F, typename OnFailure>
auto hostMemoryGuarded(const std::string& what, F&& f, OnFailure&& on_failure) -> decltype(f()) {
    try {
        return f();
    } catch (const std::bad_alloc&) {
        on_failure();
        return Error(ErrorCode::OutOfMemory, what + ": host memory ran out");
    } catch (const std::length_error&) {
        on_failure();
        return Error(ErrorCode::OutOfMemory, what + ": an array would exceed its largest size");
    }
}

template <typename F>
auto hostMemoryGuarded(const std::string& what, F&& f) -> decltype(f()) {
    return hostMemoryGuarded(what, std::forward<F>(f), [] {});
}

}  // namespace vkcollide
