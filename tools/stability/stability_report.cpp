// Prints recall, precision and cost of every stability case (tests/stability) under the
// paper's method and each mitigation, then the mitigations' cost on the ordinary test
// scenes (the recall guard's), without the validation layer. Each detection runs four
// times on one world; the time is the fastest of the last three (the first creates
// pipelines and buffers; the machine is shared, so single runs are noisy).
// docs/stability.md quotes its output.
//
//   build/tools/vkcollide_stability_report [case-substring]
#include <cstdio>
#include <string>

#include "support/stability_scenes.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

int main(int argc, char** argv) {
    const std::string filter = argc > 1 ? argv[1] : "";
    auto ctx = Context::create();
    if (!ctx) {
        std::fprintf(stderr, "%s\n", ctx.error().message().c_str());
        return 1;
    }
    std::printf("device: %s\n", (*ctx)->deviceInfo().name.c_str());
    auto cases = allStabilityCases();
    if (!cases) {
        std::fprintf(stderr, "%s\n", cases.error().message().c_str());
        return 1;
    }
    auto line = [](const std::string& name, const std::string& variant, const Result<Measured>& m) {
        if (!m) std::printf("%-34s %-10s error: %s\n", name.c_str(), variant.c_str(), m.error().message().c_str());
        else std::printf("%s\n", describe(name, variant, *m).c_str());
    };
    for (const StabilityCase& c : *cases) {
        if (!filter.empty() && c.name.find(filter) == std::string::npos) continue;
        for (const auto& variants : {mitigationVariants(), reliableVariants()})
            for (const Variant& v : variants) {
                DetectSettings s = c.settings;
                v.apply(s, c);
                line(c.name, v.name, measureCase(**ctx, c, s, 4));
            }
    }
    if (!filter.empty()) return 0;
    // What the mitigations cost where nothing goes wrong: the recall guard's scenes and settings.
    auto scenes = allTestScenes();
    if (!scenes) return 1;
    for (const TestScene& scene : *scenes) {
        auto objects = scene.reference();
        auto reference = computeReferencePairs(objects);
        if (!reference) return 1;
        for (std::uint32_t resolution : {64u, 256u}) {
            StabilityCase c{scene.name + " " + std::to_string(resolution), scene, {}, *reference};
            c.settings.method = DetectMethod::Peeling;
            c.settings.resolution = resolution;
            c.settings.direction = std::array<float, 3>{0.15f, -0.2f, 1.0f};
            c.pixel = 3.0f / float(resolution);
            for (const Variant& v : mitigationVariants()) {
                DetectSettings s = c.settings;
                v.apply(s, c);
                line(c.name, v.name, measureCase(**ctx, c, s, 4));
            }
        }
    }
    return 0;
}
