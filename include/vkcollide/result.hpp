// vkcollide: the error type every fallible call returns. No exceptions cross the API.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

#include "vkcollide/export.hpp"

namespace vkcollide {

// What went wrong, coarse enough to branch on; Error::message() says exactly what.
enum class ErrorCode : std::uint32_t {
    InvalidArgument,     // a setting or argument breaks a documented rule
    InvalidMesh,         // NaN/inf vertex, out-of-range index, bad index count, empty mesh
    BufferTooSmall,      // a user buffer is smaller than the range declared for it
    ParseError,          // a mesh file is malformed (message holds file:line)
    IoError,             // a file could not be opened or read
    LoaderUnavailable,   // libvulkan.so.1 or an entry point could not be found
    NoSuitableDevice,    // no physical device, or none with the required features
    UnsupportedFeature,  // the device lacks a required feature, extension or format
    VulkanError,         // a Vulkan call failed; Error::vkResult() holds its VkResult
    DeviceLost,          // the device was lost; create a new Context
    OutOfMemory,         // host or device memory ran out
    GraphError,          // a render graph is malformed (cycle, undeclared resource, ...)
    Timeout,             // GPU work did not finish within the wait allowed (DetectSettings::limits.timeout_ms)
    LimitExceeded,       // a documented limit was reached (DetectSettings::limits.max_pairs, the sampling range)
};

VKCOLLIDE_API const char* toString(ErrorCode code) noexcept;

class VKCOLLIDE_API Error {
public:
    Error(ErrorCode code, std::string message, std::int32_t vk_result = 0)
        : code_(code), vk_result_(vk_result), message_(std::move(message)) {}

    ErrorCode code() const noexcept { return code_; }
    // The raw VkResult when code() == VulkanError/DeviceLost/OutOfMemory/Timeout, else 0.
    std::int32_t vkResult() const noexcept { return vk_result_; }
    const std::string& message() const noexcept { return message_; }

private:
    ErrorCode code_;
    std::int32_t vk_result_;
    std::string message_;
};

// A value or an Error. Test with `if (!r)`, read with `*r` / `r->`, `r.error()`.
template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : v_(std::move(value)) {}
    Result(Error error) : v_(std::move(error)) {}

    explicit operator bool() const noexcept { return v_.index() == 0; }
    bool ok() const noexcept { return v_.index() == 0; }

    T& value() & { return std::get<0>(v_); }
    const T& value() const& { return std::get<0>(v_); }
    T&& value() && { return std::get<0>(std::move(v_)); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T&& operator*() && { return std::move(*this).value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    const Error& error() const { return std::get<1>(v_); }

private:
    std::variant<T, Error> v_;
};

// For calls that return nothing on success.
template <>
class [[nodiscard]] Result<void> {
public:
    Result() = default;
    Result(Error error) : error_(std::move(error)), ok_(false) {}

    explicit operator bool() const noexcept { return ok_; }
    bool ok() const noexcept { return ok_; }
    const Error& error() const { return error_; }

private:
    Error error_{ErrorCode::InvalidArgument, {}};
    bool ok_ = true;
};

}  // namespace vkcollide
