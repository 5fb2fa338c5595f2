#include "cli/scene.hpp"

#include <algorithm>
#include <limits>

#include "vkcollide/io.hpp"

namespace cli {
namespace {

using vkcollide::Error;
using vkcollide::ErrorCode;
using vkcollide::HostMesh;

Error mismatch(const CommandLine& line, std::size_t frame, std::size_t slot, const std::string& what) {
    return Error(ErrorCode::InvalidArgument, "--sequence: frame " + std::to_string(frame) + " (" + line.frameFiles(frame)[slot] +
                                                 ") does not have frame 0's topology (" + line.frameFiles(0)[slot] + "): " + what);
}

}  // namespace

std::vector<std::string> Scene::names() const {
    std::vector<std::string> out;
    for (const SceneObject& o : objects) out.push_back(o.options.name);
    return out;
}

std::array<float, 6> Scene::worldBounds() const {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    std::array<float, 6> b{kInf, kInf, kInf, -kInf, -kInf, -kInf};
    for (const SceneObject& o : objects) {
        const vkcollide::Transform3x4& t = o.options.transform;
        for (const vkcollide::Float3& p : o.mesh.positions) {
            for (int r = 0; r < 3; ++r) {
                const float w = t[r * 4] * p.x + t[r * 4 + 1] * p.y + t[r * 4 + 2] * p.z + t[r * 4 + 3];
                b[r] = std::min(b[r], w);
                b[r + 3] = std::max(b[r + 3], w);
            }
        }
    }
    return b;
}

vkcollide::Result<Scene> readScene(const CommandLine& line) {
    Scene scene;
    const auto files = line.frameFiles(0);
    for (std::size_t slot = 0; slot < files.size(); ++slot) {
        auto meshes = vkcollide::readMeshFile(files[slot]);
        if (!meshes) return meshes.error();
        const FileSlot& s = line.slots[slot];
        for (HostMesh& m : *meshes) {
            SceneObject o;
            o.options = s.options;
            // --name: one object takes the name, several keep theirs after it.
            if (!s.options.name.empty()) o.options.name = meshes->size() == 1 ? s.options.name : s.options.name + "/" + m.name;
            else o.options.name = m.name;
            o.slot = slot;
            o.gpu_mesh = s.gpu_mesh;
            o.first_triangle = scene.triangles;
            scene.triangles += m.triangleCount();
            o.mesh = std::move(m);
            scene.objects.push_back(std::move(o));
        }
    }
    return scene;
}

vkcollide::Result<void> readFrame(const CommandLine& line, std::size_t frame, Scene& io_scene) {
    const auto files = line.frameFiles(frame);
    std::size_t next = 0;  // the scene's object the file's first one must match
    for (std::size_t slot = 0; slot < files.size(); ++slot) {
        auto meshes = vkcollide::readMeshFile(files[slot]);
        if (!meshes) return meshes.error();
        const std::size_t first = next;
        while (next < io_scene.objects.size() && io_scene.objects[next].slot == slot) ++next;
        if (meshes->size() != next - first)
            return mismatch(line, frame, slot,
                            std::to_string(meshes->size()) + " objects instead of " + std::to_string(next - first));
        for (std::size_t k = 0; k < meshes->size(); ++k) {
            HostMesh& m = (*meshes)[k];
            SceneObject& o = io_scene.objects[first + k];
            const std::string who = "object " + std::to_string(first + k) + " ('" + o.options.name + "')";
            if (m.positions.size() != o.mesh.positions.size())
                return mismatch(line, frame, slot,
                                who + " has " + std::to_string(m.positions.size()) + " vertices instead of " + std::to_string(o.mesh.positions.size()));
            if (m.indices.size() != o.mesh.indices.size())
                return mismatch(line, frame, slot,
                                who + " has " + std::to_string(m.triangleCount()) + " triangles instead of " + std::to_string(o.mesh.triangleCount()));
            const auto differs = std::mismatch(m.indices.begin(), m.indices.end(), o.mesh.indices.begin());
            if (differs.first != m.indices.end())
                return mismatch(line, frame, slot,
                                who + ": triangle " + std::to_string((differs.first - m.indices.begin()) / 3) + " has other vertex indices");
        }
        for (std::size_t k = 0; k < meshes->size(); ++k) io_scene.objects[first + k].mesh.positions = std::move((*meshes)[k].positions);
    }
    return {};
}

}  // namespace cli
