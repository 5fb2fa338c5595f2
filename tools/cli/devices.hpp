// The Vulkan devices `vkcollide detect` uses. Without --gpu-mesh: vkcollide's own device
// (Context::create, with --device, --no-robust-access and --validation), and for --png a
// second device, the renderer's engine, on the same GPU. With --gpu-mesh the tool plays an
// engine: its device holds those objects' vertex and index buffers, is lent to vkcollide
// (Context::adopt) and renders --png from the very buffers vkcollide read.
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <cstdint>
#include <memory>
#include <vector>

#include "cli/options.hpp"
#include "render/engine.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/gpu_mesh.hpp"

namespace cli {

struct Devices {
    std::unique_ptr<render::Engine> engine;  // with --gpu-mesh or --png
    std::unique_ptr<vkcollide::Context> context;
    std::shared_ptr<std::uint64_t> context_messages = std::make_shared<std::uint64_t>(0);
    // Validation (and library) warnings and errors seen on either device.
    std::uint64_t messages() const { return *context_messages + (engine ? engine->validationMessages() : 0); }
};

// Vulkan failures of the engine end the program with a message (render/engine.hpp);
// vkcollide's are returned.
vkcollide::Result<Devices> openDevices(const CommandLine& line, bool gpu_meshes, bool picture);

// The engine-owned buffers of the --gpu-mesh objects, host-visible so that a --sequence
// frame writes its positions straight into them.
class EngineMeshes {
public:
    explicit EngineMeshes(render::Engine& engine) : engine_(engine) {}
    ~EngineMeshes();
    EngineMeshes(const EngineMeshes&) = delete;
    EngineMeshes& operator=(const EngineMeshes&) = delete;

    // Uploads a mesh and describes its buffers for CollisionWorld::addGpuMesh.
    vkcollide::GpuMeshDesc add(const vkcollide::HostMesh& mesh);
    // New positions of mesh k (same count).
    void update(std::size_t k, const std::vector<vkcollide::Float3>& positions);
    const render::Buffer& vertices(std::size_t k) const { return meshes_[k].vertices; }
    const render::Buffer& indices(std::size_t k) const { return meshes_[k].indices; }

private:
    struct Mesh {
        render::Buffer vertices, indices;
    };
    render::Engine& engine_;
    std::vector<Mesh> meshes_;
};

}  // namespace cli
