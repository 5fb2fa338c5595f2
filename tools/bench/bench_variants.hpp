// Settings variants of the sweep: each is a name, a group and what it changes from the
// defaults. Adding one is one line in bench_variants.cpp; it then shows up in the CSV's
// `variant` column, in summary.sh's table and as its own series in plot.sh's charts.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "vkcollide/world.hpp"

namespace vkcollide::bench {

struct Variant {
    std::string name;   // CSV `variant`
    std::string group;  // selectable as a whole with --variants GROUP
    std::function<void(DetectSettings&)> apply;
    bool open = false;   // every object added as an open surface
    bool async = false;  // submit() + collect() instead of detect()
    // submit() of frame N, then collect() of frame N - 1 (with async): the narrow phase of
    // N - 1 and the update of N + 1 run while N's GPU work runs.
    bool pipelined = false;
    // detectInto() with one DetectResult kept across frames (its memory reused).
    bool into = false;
    // Each frame's result compared and released before the next frame (as an engine that
    // consumes its result and drops it); otherwise every frame's result is kept until the
    // frames are done, and each frame's result memory is new to the process.
    bool drop = false;
    // > 0: untimed busy host work of this many ms before each timed frame (an engine's other
    // work per frame): with `pipelined`, the GPU's part of a step then runs meanwhile and a
    // step shows the detection's cost on the engine's thread alone.
    double slack_ms = 0;
    // > 0: the resolution the world chooses automatically for the scene, times this
    // (applied after `apply`, through CollisionWorld::resolveSettings).
    double resolution_scale = 0;
};

// Every named variant, plus one "res-N" (group "resolutions") per entry of `resolutions`.
std::vector<Variant> allVariants(const std::vector<std::uint32_t>& resolutions);

// The variants named in `selection` (names or group names, comma separated; "all": every one),
// in table order. Unknown names: InvalidArgument naming them.
Result<std::vector<Variant>> selectVariants(const std::vector<Variant>& all, const std::string& selection);

}  // namespace vkcollide::bench
