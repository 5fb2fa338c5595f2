// GPU test support: a Context with the Khronos validation layer (and synchronization
// validation) on, whose messages are collected so a test fails on any of them.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "api/context_access.hpp"
#include "vk/device.hpp"
#include "vkcollide/context.hpp"

namespace vkcollide::test {

class ValidatedContext {
public:
    // get_instance_proc_addr, debug_names: as ContextCreateInfo's (a test's own loader
    // wrapper; names and labels off).
    explicit ValidatedContext(PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr, bool debug_names = true);
    Context& context() { return *context_; }
    vk::Device& device() { return ContextAccess::device(*context_); }
    // Destroys the Context (its messages stay readable); context() and device() are then
    // invalid: for the tests of what outlives a Context.
    void destroyContext() { context_.reset(); }
    // Validation warnings/errors seen so far, joined for a failure message.
    std::vector<std::string> messages() const;

private:
    struct Log {
        mutable std::mutex mutex;
        std::vector<std::string> lines;
    };
    std::shared_ptr<Log> log_ = std::make_shared<Log>();
    std::unique_ptr<Context> context_;
};

}  // namespace vkcollide::test

// Fails the test if the validation layer reported anything.
#define REQUIRE_NO_VALIDATION_MESSAGES(ctx)                           \
    do {                                                              \
        auto vkcollide_msgs_ = (ctx).messages();                      \
        INFO("validation messages: " << vkcollide_msgs_.size());      \
        for (const auto& m_ : vkcollide_msgs_) UNSCOPED_INFO(m_);     \
        REQUIRE(vkcollide_msgs_.empty());                             \
    } while (0)
