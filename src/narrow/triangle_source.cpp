#include <cmath>
#include <limits>
#include <string>

#include "vkcollide/narrow.hpp"

namespace vkcollide {
namespace {

constexpr std::uint64_t kMaxTriangles = std::numeric_limits<std::uint32_t>::max();

std::string objectName(std::uint32_t object) { return "TriangleSource: object " + std::to_string(object); }

Result<void> checkTransform(std::uint32_t object, const Transform3x4& m) {
    for (float x : m) {
        if (!std::isfinite(x)) return Error(ErrorCode::InvalidArgument, objectName(object) + ": transform is not finite");
    }
    return {};
}

Result<void> checkIndexCount(std::uint32_t object, std::size_t index_count) {
    if (index_count % 3 != 0) {
        return Error(ErrorCode::InvalidMesh, objectName(object) + ": index count " + std::to_string(index_count) +
                                                 " is not a multiple of 3");
    }
    return {};
}

}  // namespace

Result<std::uint32_t> TriangleSource::addHostMesh(std::span<const Float3> positions, std::span<const std::uint32_t> indices,
                                                  const Transform3x4& object_to_world) {
    const auto id = static_cast<std::uint32_t>(objects_.size());
    if (auto ok = checkIndexCount(id, indices.size()); !ok) return ok.error();
    if (auto ok = checkTransform(id, object_to_world); !ok) return ok.error();
    const std::uint64_t total = std::uint64_t{base_.back()} + indices.size() / 3;
    if (total > kMaxTriangles) {
        return Error(ErrorCode::InvalidArgument, objectName(id) + ": the source would exceed 2^32 - 1 triangles");
    }
    Object o;
    o.positions = positions;
    o.indices = indices;
    o.transform = object_to_world;
    o.identity = object_to_world == kIdentity;
    objects_.push_back(o);
    base_.push_back(static_cast<std::uint32_t>(total));
    return id;
}

Result<std::uint32_t> TriangleSource::addGpuMesh(std::uint32_t triangle_count) {
    const auto id = static_cast<std::uint32_t>(objects_.size());
    const std::uint64_t total = std::uint64_t{base_.back()} + triangle_count;
    if (total > kMaxTriangles) {
        return Error(ErrorCode::InvalidArgument, objectName(id) + ": the source would exceed 2^32 - 1 triangles");
    }
    Object o;
    o.gpu = true;
    objects_.push_back(o);
    base_.push_back(static_cast<std::uint32_t>(total));
    return id;
}

Result<void> TriangleSource::setTransform(std::uint32_t object, const Transform3x4& object_to_world) {
    if (object >= objects_.size() || objects_[object].gpu) {
        return Error(ErrorCode::InvalidArgument, objectName(object) + ": setTransform needs a host mesh of this source");
    }
    if (auto ok = checkTransform(object, object_to_world); !ok) return ok.error();
    objects_[object].transform = object_to_world;
    objects_[object].identity = object_to_world == kIdentity;
    return {};
}

Result<void> TriangleSource::setHostGeometry(std::uint32_t object, std::span<const Float3> positions,
                                             std::span<const std::uint32_t> indices) {
    if (object >= objects_.size() || objects_[object].gpu) {
        return Error(ErrorCode::InvalidArgument, objectName(object) + ": setHostGeometry needs a host mesh of this source");
    }
    if (auto ok = checkIndexCount(object, indices.size()); !ok) return ok.error();
    if (indices.size() / 3 != triangleCount(object)) {
        return Error(ErrorCode::InvalidArgument, objectName(object) + ": setHostGeometry must keep the triangle count (" +
                                                     std::to_string(triangleCount(object)) + ")");
    }
    objects_[object].positions = positions;
    objects_[object].indices = indices;
    return {};
}

void TriangleSource::clear() noexcept {
    objects_.clear();
    base_.assign(1, 0);
    gpu_triangles_ = {};
}

}  // namespace vkcollide
