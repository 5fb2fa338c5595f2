// fuzz_world's values (world_values.hpp).
#include "fuzz/world_values.hpp"

#include <array>
#include <cmath>
#include <limits>

namespace vkcollide::fuzz {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kMax = std::numeric_limits<float>::max();

}  // namespace

namespace {

constexpr std::array<float, 32> kSpecialCoordinates = {
    0.3333333f, -0.7071068f, 1e-3f, 1e-30f,      1e-40f, -1e-40f, 1e6f,   -1e6f, 1e19f,   1e30f,   1e38f, -1e38f, kMax,  -kMax, kNaN, kInf,
    -kInf,      2.0f,        -2.0f, 0.50000006f, 4.0f,   100.0f,  3e-39f, 1e15f, 4.6e18f, 9.3e18f, 1e20f, 0.0f,   -0.0f, 0.1f,  0.2f, 0.7f};

}  // namespace

float coordinate(std::uint8_t b) {
    if (b < kFirstSpecialCoordinate) return static_cast<float>(static_cast<int>(b % 32) - 16) / 16.0f;
    return kSpecialCoordinates[b - kFirstSpecialCoordinate];
}

Transform3x4 transformOf(const TransformCode& t) {
    const float c = std::cos(0.7853982f), s = std::sin(0.7853982f);
    switch (t.code) {
        case 0: return kIdentity3x4;
        case 1: return {1, 0, 0, 0.25f, 0, 1, 0, 0, 0, 0, 1, 0};
        case 2: return {1, 0, 0, 0, 0, 1, 0, 0.5f, 0, 0, 1, 0.25f};
        case 3: return {0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0};  // 90 degrees about z
        case 4: return {c, 0, s, 0.125f, 0, 1, 0, 0, -s, 0, c, 0};  // 45 degrees about y
        case 5: return {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0};
        case 6: return {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};  // everything to one point
        case 7: return {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};  // a mirror
        case 8: return {1, 0.5f, 0, 0, 0, 1, 0, 0, 0, 0.25f, 1, 0};  // a shear
        case 9: return {1e20f, 0, 0, 0, 0, 1e20f, 0, 0, 0, 0, 1e20f, 0};
        case 10: return {1e-30f, 0, 0, 0, 0, 1e-30f, 0, 0, 0, 0, 1e-30f, 0};
        case 11: return {1, 0, 0, kNaN, 0, 1, 0, 0, 0, 0, 1, 0};
        case 12: return {kInf, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        case 13: return {1, 0, 0, 1e38f, 0, 1, 0, 0, 0, 0, 1, 0};
        case 14: return {1e30f, 0, 0, 1e30f, 0, 1e30f, 0, 0, 0, 0, 1e30f, 0};
        case 15: return {1, 0, 0, 1e6f, 0, 1, 0, -1e6f, 0, 0, 1, 0};
        default: {
            Transform3x4 m{};
            for (std::size_t i = 0; i < 12; ++i) m[i] = coordinate(t.matrix[i]);
            return m;
        }
    }
}

float typicalEdge(std::uint8_t b) {
    constexpr std::array<float, 8> kEdges = {0, 0, 0.5f, 0.0625f, -1.0f, kNaN, kInf, 1e-30f};
    return kEdges[b % kEdges.size()];
}

DetectSettings decodeSettings(const SettingsBytes& b) {
    constexpr std::array<std::uint32_t, 16> kResolutions = {0, 1, 2, 3, 4, 7, 8, 16, 17, 32, 64, 100, 128, 256, 16385, 0xFFFFFFFFu};
    constexpr std::array<std::array<float, 3>, 10> kDirections = {
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}, {0, 0, 0}, {kNaN, 0, 0}, {kInf, 0, 0}, {1e-30f, 0, 0}, {1e38f, 1e38f, 0}}};
    constexpr std::array<std::uint32_t, 8> kAxes = {1, 1, 1, 1, 3, 3, 0, 2};
    constexpr std::array<std::uint32_t, 6> kLayerCaps = {0, 0, 1, 2, 3, 1000};
    constexpr std::array<float, 6> kEpsilons = {0, 0.01f, 1, -1, kNaN, kInf};
    constexpr std::array<std::array<float, 6>, 6> kRegions = {{{-1, -1, -1, 1, 1, 1},
                                                               {1, 1, 1, -1, -1, -1},
                                                               {0, 0, 0, 1e-30f, 1e-30f, 1e-30f},
                                                               {kNaN, 0, 0, 1, 1, 1},
                                                               {-1e38f, -1e38f, -1e38f, 1e38f, 1e38f, 1e38f},
                                                               {0, 0, 0, 0.5f, 0.5f, 0.5f}}};
    constexpr std::array<std::uint32_t, 5> kContactResolutions = {16, 15, 4097, 32, 0};
    DetectSettings s;
    s.method = (b[0] & 1) ? DetectMethod::Peeling : DetectMethod::Reliable;
    if (b[0] & 2) s.resolution = kResolutions[b[2] % kResolutions.size()];
    if (b[0] & 4) s.direction = kDirections[b[3] % kDirections.size()];
    s.peeling.dual = (b[0] & 8) != 0;
    s.peeling.packing = (b[0] & 16) ? PackingMethod::Paper : PackingMethod::Scan;
    if (b[0] & 32) s.region = kRegions[b[10] % kRegions.size()];
    s.contacts.objects = (b[0] & 64) != 0;
    s.peeling.depth_aware = (b[0] & 128) == 0;
    constexpr std::array<SamplingBackend, 4> kBackends = {SamplingBackend::Auto, SamplingBackend::Raster, SamplingBackend::Compute,
                                                          SamplingBackend::Auto};
    constexpr std::array<Coverage, 4> kCoverages = {Coverage::Centre, Coverage::Dilate, Coverage::Conservative, Coverage::Best};
    s.peeling.backend = kBackends[b[1] & 3];
    s.peeling.coverage = kCoverages[(b[1] >> 2) & 3];
    s.bad_objects = (b[1] & 16) ? BadObjectPolicy::Fail : BadObjectPolicy::Exclude;
    s.peeling.measure_layers = (b[1] & 32) == 0;
    if (b[1] & 64) s.peeling.open_epsilon = kEpsilons[b[9] % kEpsilons.size()];
    s.peeling.closed_epsilon = kEpsilons[(b[9] / 8) % kEpsilons.size()];
    if (b[1] & 128) s.contacts.resolution = kContactResolutions[b[11] % kContactResolutions.size()];
    s.peeling.axes = kAxes[b[4] % kAxes.size()];
    s.peeling.layer_cap = kLayerCaps[b[5] % kLayerCaps.size()];
    switch (b[6] % 16) {
        case 13: s.limits.timeout_ms = 0; break;
        case 14: s.limits.timeout_ms = 1; break;
        case 15: s.limits.timeout_ms = 5; break;
        default: break;  // the default: a minute
    }
    if (b[6] & 16) s.limits.wait_poll_us = (b[6] & 32) ? 0 : 1u << 20;  // sleep only, or poll up to a second
    constexpr std::array<std::uint64_t, 4> kMaxPairs = {std::uint64_t{1} << 24, 0, 1, 3};
    s.limits.max_pairs = kMaxPairs[b[7] % kMaxPairs.size()];
    constexpr std::array<std::uint64_t, 4> kMaxCandidatePairs = {std::uint64_t{1} << 27, 0, 1, 10};
    s.limits.max_candidate_pairs = kMaxCandidatePairs[b[8] % kMaxCandidatePairs.size()];
    return s;
}

std::string describe(const DetectSettings& s) {
    const DetectSettings d;
    std::string out = toString(s.method);
    const auto add = [&](bool differs, const std::string& what) {
        if (differs) out += ", " + what;
    };
    add(s.resolution.has_value(), "resolution " + (s.resolution ? std::to_string(*s.resolution) : std::string()));
    add(s.direction.has_value(), "direction given");
    add(s.peeling.dual, "dual");
    add(s.peeling.packing != d.peeling.packing, std::string("packing ") + toString(s.peeling.packing));
    add(s.region.has_value(), "region given");
    add(s.contacts.objects, "contacts");
    add(!s.peeling.depth_aware, "depth-aware off");
    add(s.peeling.backend != d.peeling.backend, std::string("backend ") + toString(s.peeling.backend));
    add(s.peeling.coverage != d.peeling.coverage, std::string("coverage ") + toString(s.peeling.coverage));
    add(s.bad_objects != d.bad_objects, "bad objects fail");
    add(!s.peeling.measure_layers, "measure_layers off");
    add(s.peeling.open_epsilon.has_value(), "open_epsilon " + (s.peeling.open_epsilon ? std::to_string(*s.peeling.open_epsilon) : std::string()));
    add(s.peeling.closed_epsilon != d.peeling.closed_epsilon, "closed_epsilon " + std::to_string(s.peeling.closed_epsilon));
    add(s.contacts.resolution.has_value(),
        "contacts.resolution " + (s.contacts.resolution ? std::to_string(*s.contacts.resolution) : std::string()));
    add(s.peeling.axes != d.peeling.axes, "axes " + std::to_string(s.peeling.axes));
    add(s.peeling.layer_cap != d.peeling.layer_cap, "layer_cap " + std::to_string(s.peeling.layer_cap));
    add(s.limits.timeout_ms != d.limits.timeout_ms, "timeout_ms " + std::to_string(s.limits.timeout_ms));
    add(s.limits.wait_poll_us != d.limits.wait_poll_us, "wait_poll_us " + std::to_string(s.limits.wait_poll_us));
    add(s.limits.max_pairs != d.limits.max_pairs, "max_pairs " + std::to_string(s.limits.max_pairs));
    add(s.limits.max_candidate_pairs != d.limits.max_candidate_pairs, "max_candidate_pairs " + std::to_string(s.limits.max_candidate_pairs));
    return out;
}

}  // namespace vkcollide::fuzz
