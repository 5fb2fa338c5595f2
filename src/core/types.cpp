#include "vkcollide/types.hpp"

namespace vkcollide {

const char* toString(PackingMethod method) noexcept {
    switch (method) {
        case PackingMethod::Scan: return "scan";
        case PackingMethod::Paper: return "paper";
    }
    return "?";
}

const char* toString(DetectMethod method) noexcept {
    switch (method) {
        case DetectMethod::Reliable: return "reliable";
        case DetectMethod::Peeling: return "peeling";
    }
    return "?";
}

const char* toString(Coverage coverage) noexcept {
    switch (coverage) {
        case Coverage::Centre: return "centre";
        case Coverage::Dilate: return "dilate";
        case Coverage::Conservative: return "conservative";
        case Coverage::Best: return "best";
    }
    return "?";
}

const char* toString(SamplingBackend backend) noexcept {
    switch (backend) {
        case SamplingBackend::Auto: return "auto";
        case SamplingBackend::Raster: return "raster";
        case SamplingBackend::Compute: return "compute";
    }
    return "?";
}

const char* toString(ExactDecision exact) noexcept {
    switch (exact) {
        case ExactDecision::Auto: return "auto";
        case ExactDecision::Gpu: return "gpu";
        case ExactDecision::Cpu: return "cpu";
    }
    return "?";
}

const char* toString(ResponseSource source) noexcept {
    switch (source) {
        case ResponseSource::Auto: return "auto";
        case ResponseSource::Gpu: return "gpu";
        case ResponseSource::Cpu: return "cpu";
    }
    return "?";
}

const char* toString(GridTuning tuning) noexcept {
    switch (tuning) {
        case GridTuning::Auto: return "auto";
        case GridTuning::On: return "on";
        case GridTuning::Off: return "off";
    }
    return "?";
}

const char* toString(ExactPass pass) noexcept {
    switch (pass) {
        case ExactPass::Auto: return "auto";
        case ExactPass::Inline: return "inline";
        case ExactPass::Queued: return "queued";
    }
    return "?";
}

const char* toString(PairNaming naming) noexcept {
    switch (naming) {
        case PairNaming::Auto: return "auto";
        case PairNaming::AfterFence: return "after-fence";
    }
    return "?";
}

const char* toString(PairSort sort) noexcept {
    switch (sort) {
        case PairSort::Auto: return "auto";
        case PairSort::Gpu: return "gpu";
        case PairSort::Cpu: return "cpu";
    }
    return "?";
}

}  // namespace vkcollide
