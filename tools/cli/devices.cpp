#include "cli/devices.hpp"

#include <cstdio>
#include <cstring>

namespace cli {

vkcollide::Result<Devices> openDevices(const CommandLine& line, bool gpu_meshes, bool picture) {
    Devices d;
    if (gpu_meshes) {
        d.engine = render::Engine::create({.validation = line.validation, .device_name = line.device});
        auto ctx = vkcollide::Context::adopt(d.engine->adoptedDevice(), d.engine->messageCallback());
        if (!ctx) return ctx.error();
        d.context = std::move(*ctx);
        return d;
    }
    vkcollide::ContextCreateInfo ci;
    ci.device_name = line.device;
    ci.robust_buffer_access = line.robust_access;
    ci.validation = line.validation;
    auto count = d.context_messages;
    ci.on_message = [count](vkcollide::MessageSeverity severity, std::string_view text) {
        if (severity == vkcollide::MessageSeverity::Info) return;
        // The first few in full; the rest only counted.
        if (++*count <= 20)
            std::fprintf(stderr, "vkcollide %s: %.*s\n", severity == vkcollide::MessageSeverity::Error ? "error" : "warning",
                         static_cast<int>(text.size()), text.data());
    };
    auto ctx = vkcollide::Context::create(ci);
    if (!ctx) return ctx.error();
    d.context = std::move(*ctx);
    // The renderer on the GPU vkcollide runs on.
    if (picture) d.engine = render::Engine::create({.validation = line.validation, .device_name = d.context->deviceInfo().name});
    return d;
}

EngineMeshes::~EngineMeshes() {
    for (Mesh& m : meshes_) {
        engine_.destroy(m.vertices);
        engine_.destroy(m.indices);
    }
}

vkcollide::GpuMeshDesc EngineMeshes::add(const vkcollide::HostMesh& mesh) {
    constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    Mesh m;
    const VkDeviceSize vbytes = mesh.positions.size() * sizeof(vkcollide::Float3), ibytes = mesh.indices.size() * 4;
    m.vertices = engine_.createBuffer(vbytes, kUsage, render::Memory::Host);
    std::memcpy(m.vertices.mapped, mesh.positions.data(), vbytes);
    m.indices = engine_.createBuffer(ibytes, kUsage, render::Memory::Host);
    std::memcpy(m.indices.mapped, mesh.indices.data(), ibytes);
    vkcollide::GpuMeshDesc desc;
    desc.vertex_buffer = m.vertices.buffer;
    desc.vertex_buffer_size = m.vertices.size;
    desc.vertex_stride = sizeof(vkcollide::Float3);
    desc.vertex_count = static_cast<std::uint32_t>(mesh.positions.size());
    desc.index_buffer = m.indices.buffer;
    desc.index_buffer_size = m.indices.size;
    desc.index_count = static_cast<std::uint32_t>(mesh.indices.size());
    meshes_.push_back(m);
    return desc;
}

void EngineMeshes::update(std::size_t k, const std::vector<vkcollide::Float3>& positions) {
    std::memcpy(meshes_[k].vertices.mapped, positions.data(), positions.size() * sizeof(vkcollide::Float3));
}

}  // namespace cli
