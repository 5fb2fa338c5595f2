// UseGuard: catches an object used from two threads at once, or re-entered from one of its
// own callbacks, and turns it into an Error that names both calls, in every build.
//
// For objects documented as "used from one thread at a time" (CollisionWorld): each public
// call opens a Scope first and returns the guard's error instead of running. The cost is
// one compare-and-swap per call. What it cannot catch: two calls that do not overlap in
// time (that is allowed: one thread at a time, not always the same thread).
//
//   Result<void> CollisionWorld::submit(...) {
//       auto scope = impl_->guard.enter("CollisionWorld::submit");
//       if (!scope) return scope.error();
//       ...
//   }
#pragma once

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

#include "vkcollide/result.hpp"

namespace vkcollide {

class UseGuard {
public:
    // `object` names the kind of object in errors ("CollisionWorld"); a string literal.
    explicit UseGuard(const char* object) noexcept : object_(object) {}
    UseGuard(const UseGuard&) = delete;
    UseGuard& operator=(const UseGuard&) = delete;

    // Held while one call runs; leaving the scope lets the next call in.
    class [[nodiscard]] Scope {
    public:
        Scope(Scope&& o) noexcept : guard_(std::exchange(o.guard_, nullptr)) {}
        Scope& operator=(Scope&&) = delete;
        Scope(const Scope&) = delete;
        ~Scope() {
            if (guard_) guard_->leave();
        }

    private:
        friend class UseGuard;
        explicit Scope(UseGuard* guard) noexcept : guard_(guard) {}
        UseGuard* guard_;
    };

    // `call` names the call in errors ("CollisionWorld::submit"); a string literal.
    // Errors: InvalidArgument when another call is running, on another thread ("used from
    // two threads at once") or on this one (re-entered, e.g. from a callback).
    Result<Scope> enter(const char* call) {
        const std::thread::id me = std::this_thread::get_id();
        std::thread::id expected{};
        if (owner_.compare_exchange_strong(expected, me, std::memory_order_acquire)) {
            call_.store(call, std::memory_order_relaxed);
            return Scope(this);
        }
        const char* running = call_.load(std::memory_order_relaxed);
        const std::string other = running ? running : "another call";
        if (expected == me)
            return Error(ErrorCode::InvalidArgument, std::string(call) + " was called from inside " + other +
                                                         " on the same thread (a callback re-entered the " + object_ +
                                                         "); a " + object_ + " runs one call at a time");
        return Error(ErrorCode::InvalidArgument, std::string(call) + " was called on thread " + idText(me) + " while " + other +
                                                     " runs on thread " + idText(expected) + ": a " + object_ +
                                                     " is used from one thread at a time (the call was refused, nothing changed)");
    }

    // Whether a call is running now (on any thread).
    bool busy() const noexcept { return owner_.load(std::memory_order_acquire) != std::thread::id{}; }

    // For destructors, which cannot return an error: destroying the object while one of
    // its calls runs would free what that call uses, so this stops the process with a
    // message naming the call instead.
    void requireIdle(const char* what) const noexcept {
        if (!busy()) return;
        const char* running = call_.load(std::memory_order_relaxed);
        std::fprintf(stderr, "vkcollide: %s while %s is running on another thread (a %s is used from one thread at a time)\n",
                     what, running ? running : "a call", object_);
        std::abort();
    }

private:
    void leave() noexcept {
        call_.store(nullptr, std::memory_order_relaxed);
        owner_.store(std::thread::id{}, std::memory_order_release);
    }
    static std::string idText(std::thread::id id) {
        std::ostringstream out;
        out << id;
        return out.str();
    }

    const char* object_;
    std::atomic<std::thread::id> owner_{};
    std::atomic<const char*> call_{nullptr};
};

}  // namespace vkcollide
