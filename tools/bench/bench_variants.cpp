#include "bench_variants.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace vkcollide::bench {

std::vector<Variant> allVariants(const std::vector<std::uint32_t>& resolutions) {
    using S = DetectSettings;
    // The paper's method, explicitly: its mitigations, backends and knobs only mean
    // something there (the default is the reliable method since it landed).
    const auto paper = [](std::function<void(S&)> more) {
        return [more = std::move(more)](S& s) {
            s.method = DetectMethod::Peeling;
            more(s);
        };
    };
    // A fixed direction (the reliable method's default is the automatic one).
    const auto along = [](float x, float y, float z) { return [=](S& s) { s.direction = std::array<float, 3>{x, y, z}; }; };
    std::vector<Variant> v = {
        // name            group          what changes
        {"default", "default", [](S&) {}},
        {"reliable", "modes", [](S& s) { s.method = DetectMethod::Reliable; }},
        {"peeling", "modes", paper([](S&) {})},  // the default before the reliable method
        {"axes3", "mitigations", paper([](S& s) { s.peeling.axes = 3; })},
        {"best", "mitigations", paper([](S& s) { s.peeling.coverage = Coverage::Best; })},
        {"axes3-best", "mitigations", paper([](S& s) { s.peeling.axes = 3, s.peeling.coverage = Coverage::Best; })},
        {"dual", "mitigations", paper([](S& s) { s.peeling.dual = true; })},
        {"raster", "backends", paper([](S& s) { s.peeling.backend = SamplingBackend::Raster; })},
        {"compute", "backends", paper([](S& s) { s.peeling.backend = SamplingBackend::Compute; })},
        {"cap2", "paper", paper([](S& s) { s.peeling.layer_cap = 2; })},
        {"cap4", "paper", paper([](S& s) { s.peeling.layer_cap = 4; })},
        {"paper-packing", "paper", paper([](S& s) { s.peeling.packing = PackingMethod::Paper; })},
        {"open", "paper", paper([](S&) {}), true},
        {"async", "paper", paper([](S&) {}), false, true},
        {"reliable-async", "modes", [](S& s) { s.method = DetectMethod::Reliable; }, false, true},
        // The reliable method with the exact decision on the CPU (the reference path): its
        // difference to "default" is what deciding on the GPU saves (docs/exact_gpu.md).
        {"exact-cpu", "modes", [](S& s) { s.reliable.exact = ExactDecision::Cpu; }},
        // The GPU's exact decision inside the pair pass, or in a pass of its own, always (the
        // default, ExactPass::Auto, chooses from the last detection's canonical candidates).
        {"exact-inline", "modes", [](S& s) { s.reliable.exact_pass = ExactPass::Inline; }},
        {"exact-queued", "modes", [](S& s) { s.reliable.exact_pass = ExactPass::Queued; }},
        // The host result's pairs sorted on the GPU always, or on the CPU always (the default,
        // PairSort::Auto, sorts on the GPU from kGpuPairSortFrom pairs).
        {"sort-gpu", "modes", [](S& s) { s.reliable.pair_sort = PairSort::Gpu; }},
        {"sort-cpu", "modes", [](S& s) { s.reliable.pair_sort = PairSort::Cpu; }},
        // Where the pairs are sorted on the GPU, the host result's responses from the narrow
        // phase (the reference path) instead of the GPU (the default, ResponseSource::Auto).
        {"responses-cpu", "modes", [](S& s) { s.reliable.responses = ResponseSource::Cpu; }},
        // The pairs named after the fence only (PairNaming::AfterFence), not while the GPU
        // computes the responses: its difference to "default" is what the overlap saves.
        {"after-fence", "modes", [](S& s) { s.reliable.pair_naming = PairNaming::AfterFence; }},
        // The automatic grid fixed at kCellsPerEdge (the default on a GPU tunes it per scene,
        // docs/reliable.md "The grid per scene"): its difference to "default" is the tuning's.
        {"grid-fixed", "modes", [](S& s) { s.reliable.grid_tuning = GridTuning::Off; }},
        {"grid-tuned", "modes", [](S& s) { s.reliable.grid_tuning = GridTuning::On; }},
        // The pairs also sorted on the GPU (DetectSettings::reliable.device_pairs): its cost is
        // sorting_ms, the difference to "default".
        {"device-pairs", "modes", [](S& s) { s.reliable.device_pairs = true; }},
        // The pairs left on the GPU only (host_pairs off): a frame as a GPU solver sees it,
        // nothing read back, no host narrow phase. Its recall is the pairs' count against
        // the reference's (tests/api/device_pairs_tests.cpp compares the content).
        {"device-only", "modes", [](S& s) { s.reliable.device_pairs = true, s.reliable.host_pairs = false; }},
        // The same with every colliding triangle's response left there too (device_responses).
        {"device-responses", "modes",
         [](S& s) { s.reliable.device_pairs = true, s.reliable.host_pairs = false, s.reliable.device_responses = true; }},
        {"depth-sep", "modes", paper([](S& s) { s.peeling.depth_aware = true; })},  // peeling, depth-aware separation on
        {"paper-sep", "modes", paper([](S& s) { s.peeling.depth_aware = false; })},  // peeling, the paper's separation (the old default)
        // The reliable method along a fixed direction instead of the automatic one (the axis most
        // triangle area faces): the main diagonal, a direction oblique to every axis, and one 20
        // degrees off z (a flat scene still seen almost face-on) but oblique to the other axes.
        {"dir-diagonal", "directions", along(1, 1, 1)},
        {"dir-oblique", "directions", along(0.31f, 0.52f, 0.8f)},
        {"dir-tilt", "directions", along(0.21f, 0.27f, 0.94f)},
        // Object-level contacts on (docs/contacts.md): their cost is the difference to "default".
        {"contacts", "contacts", [](S& s) { s.contacts.objects = true; }},
        {"contacts-256", "contacts", [](S& s) { s.contacts.objects = true, s.contacts.resolution = 256u; }},
        // Contact geometry of the intersecting pairs (DetectSettings::contacts.geometry): its
        // cost is the difference to "default" (DetectStats::contacts.geometry_ms).
        {"contact-geometry", "contacts", [](S& s) { s.contacts.geometry = true; }},
    };
    Variant into{"into", "modes", [](S&) {}};  // the default through detectInto(), one result kept
    into.into = true;
    v.push_back(into);
    Variant dropped{"dropped", "modes", [](S&) {}};  // the default, each frame's result released before the next
    dropped.drop = true;
    v.push_back(dropped);
    Variant geometry_into{"contact-geometry-into", "contacts", [](S& s) { s.contacts.geometry = true; }};  // and its memory kept
    geometry_into.into = true;
    v.push_back(std::move(geometry_into));
    Variant pipelined{"pipelined", "modes", [](S&) {}, false, true};  // the default, one frame late, back to back
    pipelined.pipelined = true;
    v.push_back(pipelined);
    Variant slack = pipelined;  // the same with 5 ms of the engine's own work between steps
    slack.name = "pipelined-slack";
    slack.slack_ms = 5;
    v.push_back(std::move(slack));
    for (std::uint32_t r : resolutions)
        v.push_back({"res-" + std::to_string(r), "resolutions", paper([r](S& s) { s.resolution = r; })});
    // The reliable method at a multiple of its automatic grid: how its cost and the choice
    // of kCellsPerEdge depend on the cell size.
    for (double f : {0.5, 0.7, 1.4, 2.0}) {
        char name[32];
        std::snprintf(name, sizeof name, "cells-x%g", f);
        Variant scaled{name, "cell-scales", [](S&) {}};
        scaled.resolution_scale = f;
        v.push_back(std::move(scaled));
    }
    for (std::uint32_t r : resolutions)  // the reliable method at a fixed grid (its automatic one is the default)
        v.push_back({"cells-" + std::to_string(r), "cell-resolutions", [r](S& s) { s.resolution = r; }});
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
