// Twist and bend: deformers that turn the generators' straight shapes into ones that pass
// through themselves. Both work in double and write the result only when every vertex
// stays finite, so a failure leaves the mesh unchanged.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "vkcollide/scene.hpp"

namespace vkcollide {
namespace {

Result<void> store(HostMesh& io_mesh, const std::vector<double>& xyz, const char* what) {
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    std::vector<Float3> moved(io_mesh.positions.size());
    for (std::size_t i = 0; i < moved.size(); ++i) {
        for (int a = 0; a < 3; ++a)
            if (!(std::fabs(xyz[3 * i + a]) <= kFloatMax))
                return Error(ErrorCode::InvalidArgument, std::string(what) + ": '" + io_mesh.name + "' vertex " +
                                                             std::to_string(i) + " leaves the float range");
        moved[i] = {static_cast<float>(xyz[3 * i]), static_cast<float>(xyz[3 * i + 1]), static_cast<float>(xyz[3 * i + 2])};
    }
    io_mesh.positions = std::move(moved);
    return {};
}

}  // namespace

Result<void> twistMesh(HostMesh& io_mesh, float radians_per_unit) {
    if (!std::isfinite(radians_per_unit)) return Error(ErrorCode::InvalidArgument, "twistMesh: radians_per_unit must be finite");
    std::vector<double> xyz(3 * io_mesh.positions.size());
    for (std::size_t i = 0; i < io_mesh.positions.size(); ++i) {
        const Float3& p = io_mesh.positions[i];
        const double a = double{radians_per_unit} * p.z, c = std::cos(a), s = std::sin(a);
        xyz[3 * i] = c * p.x - s * p.y;
        xyz[3 * i + 1] = s * p.x + c * p.y;
        xyz[3 * i + 2] = p.z;
    }
    return store(io_mesh, xyz, "twistMesh");
}

Result<void> bendMesh(HostMesh& io_mesh, float radius, float pitch) {
    if (!std::isfinite(radius) || !(radius > 0.0f) || !std::isfinite(pitch))
        return Error(ErrorCode::InvalidArgument, "bendMesh: needs a finite radius > 0 and a finite pitch");
    std::vector<double> xyz(3 * io_mesh.positions.size());
    for (std::size_t i = 0; i < io_mesh.positions.size(); ++i) {
        const Float3& p = io_mesh.positions[i];
        const double rho = double{radius} - p.y;
        // rho <= 0 would put the vertex on or across the bend axis: the mapping's Jacobian
        // changes sign there and the surface turns inside out.
        if (!(rho > 0.0))
            return Error(ErrorCode::InvalidArgument, "bendMesh: '" + io_mesh.name + "' vertex " + std::to_string(i) +
                                                         " has y >= radius (" + std::to_string(radius) + ")");
        const double theta = p.x / double{radius};
        xyz[3 * i] = rho * std::sin(theta);
        xyz[3 * i + 1] = double{radius} - rho * std::cos(theta);
        xyz[3 * i + 2] = p.z + double{pitch} * theta / (2.0 * std::numbers::pi);
    }
    return store(io_mesh, xyz, "bendMesh");
}

}  // namespace vkcollide
