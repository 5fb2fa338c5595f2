// fuzz_world's Vulkan context (world_context.hpp).
#include "fuzz/world_context.hpp"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "fuzz/world_checks.hpp"

namespace vkcollide::fuzz {
namespace {

// Renewed every kInputsPerContext inputs, so that a long run also creates Contexts (and
// their pipelines, which a Context keeps until it goes) and lavapipe's host memory per
// device (about 16 MB for each set of pipelines it compiles) stays within libFuzzer's limit.

constexpr int kInputsPerContext = 32;

struct Validated {
    std::mutex mutex;
    std::vector<std::string> messages;
    std::unique_ptr<Context> context;
    // The device is destroyed here, and the validation layer reports any Vulkan object
    // still alive then.
    ~Validated() {
        context.reset();
        if (!messages.empty()) {
            std::fprintf(stderr, "fuzz_world: validation messages when the device was destroyed:\n");
            for (const std::string& m : messages) std::fprintf(stderr, "  %s\n", m.c_str());
            std::abort();
        }
    }
};

std::unique_ptr<Validated> makeContext() {
    auto out = std::make_unique<Validated>();
    ContextCreateInfo info;
    const char* env = std::getenv("VKCOLLIDE_FUZZ_VALIDATION");
    info.validation = !(env && std::string(env) == "0");
    info.on_message = [raw = out.get()](MessageSeverity severity, std::string_view text) {
        if (severity == MessageSeverity::Info) return;
        std::lock_guard<std::mutex> lock(raw->mutex);
        raw->messages.emplace_back(text);
    };
    auto ctx = Context::create(info);
    if (!ctx) fail("cannot create a Vulkan context: " + ctx.error().message());
    out->context = std::move(*ctx);
    return out;
}

std::unique_ptr<Validated>& sharedSlot() {
    static std::unique_ptr<Validated> v;  // destroyed at exit, checked then
    return v;
}

Validated& shared() {
    std::unique_ptr<Validated>& v = sharedSlot();
    if (!v) v = makeContext();
    return *v;
}

}  // namespace

Context& fuzzContext() { return *shared().context; }

void nextInput() {
    static int inputs = 0;
    if (++inputs % kInputsPerContext == 0) sharedSlot().reset();
}

void requireNoValidationMessages(const char* after) {
    Validated& v = shared();
    std::lock_guard<std::mutex> lock(v.mutex);
    if (v.messages.empty()) return;
    std::string all;
    for (const std::string& m : v.messages) all += "\n  " + m;
    fail(std::string("validation messages after ") + after + ":" + all);
}

}  // namespace vkcollide::fuzz
