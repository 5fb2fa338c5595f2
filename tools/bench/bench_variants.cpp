#include "bench_variants.hpp"

#include <algorithm>
#include <sstream>

namespace vkcollide::bench {

std::vector<Variant> allVariants(const std::vector<std::uint32_t>& resolutions) {
    using S = DetectSettings;
    std::vector<Variant> v = {
        // name            group          what changes
        {"default", "default", [](S&) {}},
        {"axes3", "mitigations", [](S& s) { s.axes = 3; }},
        {"best", "mitigations", [](S& s) { s.coverage = Coverage::Best; }},
        {"axes3-best", "mitigations", [](S& s) { s.axes = 3, s.coverage = Coverage::Best; }},
        {"dual", "mitigations", [](S& s) { s.dual = true; }},
        {"raster", "backends", [](S& s) { s.backend = SamplingBackend::Raster; }},
        {"compute", "backends", [](S& s) { s.backend = SamplingBackend::Compute; }},
        {"cap2", "paper", [](S& s) { s.layer_cap = 2; }},
        {"cap4", "paper", [](S& s) { s.layer_cap = 4; }},
        {"paper-packing", "paper", [](S& s) { s.packing = PackingMethod::Paper; }},
        {"open", "paper", [](S&) {}, true},
        {"async", "paper", [](S&) {}, false, true},
        {"depth-sep", "modes", [](S& s) { s.depth_aware = true; }},  // depth-aware separation on
        {"paper-sep", "modes", [](S& s) { s.depth_aware = false; }},  // the paper's separation
        // Issue 12's new settings join here when their DetectSettings fields land, e.g.
        // {"reliable", "modes", [](S& s) { s.broad_phase = BroadPhase::Reliable; }},
    };
    for (std::uint32_t r : resolutions)
        v.push_back({"res-" + std::to_string(r), "resolutions", [r](S& s) { s.resolution = r; }});
    return v;
}

Result<std::vector<Variant>> selectVariants(const std::vector<Variant>& all, const std::string& selection) {
    std::vector<std::string> names;
    std::stringstream ss(selection);
    for (std::string item; std::getline(ss, item, ',');)
        if (!item.empty()) names.push_back(item);
    std::vector<Variant> out;
    for (const std::string& n : names) {
        const bool known = n == "all" || std::any_of(all.begin(), all.end(), [&](const Variant& v) { return v.name == n || v.group == n; });
        if (!known) return Error(ErrorCode::InvalidArgument, "unknown variant or group '" + n + "' (--list)");
    }
    for (const Variant& v : all)
        if (std::any_of(names.begin(), names.end(), [&](const std::string& n) { return n == "all" || n == v.name || n == v.group; }))
            out.push_back(v);
    return out;
}

}  // namespace vkcollide::bench
