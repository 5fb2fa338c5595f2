#include "vkcollide/result.hpp"

namespace vkcollide {

const char* toString(ErrorCode code) noexcept {
    switch (code) {
        case ErrorCode::InvalidArgument: return "invalid argument";
        case ErrorCode::InvalidMesh: return "invalid mesh";
        case ErrorCode::BufferTooSmall: return "buffer too small";
        case ErrorCode::ParseError: return "parse error";
        case ErrorCode::IoError: return "I/O error";
        case ErrorCode::LoaderUnavailable: return "Vulkan loader unavailable";
        case ErrorCode::NoSuitableDevice: return "no suitable device";
        case ErrorCode::UnsupportedFeature: return "unsupported feature";
        case ErrorCode::VulkanError: return "Vulkan error";
        case ErrorCode::DeviceLost: return "device lost";
        case ErrorCode::OutOfMemory: return "out of memory";
        case ErrorCode::GraphError: return "render graph error";
        case ErrorCode::Timeout: return "timeout";
        case ErrorCode::LimitExceeded: return "limit exceeded";
    }
    return "unknown error";
}

}  // namespace vkcollide
