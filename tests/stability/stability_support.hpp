// Helpers the stability tests share (one executable): error text checks, engine-owned
// copies of meshes, the exact-pairs check and a world holding a pathological case.
#pragma once

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "support/error_text.hpp"
#include "support/gpu_fixture.hpp"
#include "support/pathological_scenes.hpp"
#include "support/world_fixture.hpp"
#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::test {


// An engine-owned copy of a mesh: packed positions, 32-bit indices, host-visible.
struct EngineMesh {
    vk::Buffer vertices, indices;
    GpuMeshDesc desc;
    float* positions() { return static_cast<float*>(vertices.mapped()); }
    std::uint32_t* index() { return static_cast<std::uint32_t*>(indices.mapped()); }
    void flush() { vertices.flush(), indices.flush(); }
};

inline EngineMesh engineCopy(vk::Device& dev, const HostMesh& m) {
    EngineMesh e;
    auto vb = vk::Buffer::create(dev, m.positions.size() * 12, 0, vk::MemoryKind::Upload, "engine-vertices");
    auto ib = vk::Buffer::create(dev, m.indices.size() * 4, 0, vk::MemoryKind::Upload, "engine-indices");
    REQUIRE(vb);
    REQUIRE(ib);
    std::memcpy(vb->mapped(), m.positions.data(), m.positions.size() * 12);
    std::memcpy(ib->mapped(), m.indices.data(), m.indices.size() * 4);
    e.desc.vertex_buffer = vb->handle();
    e.desc.vertex_buffer_size = vb->size();
    e.desc.vertex_count = static_cast<std::uint32_t>(m.positions.size());
    e.desc.index_buffer = ib->handle();
    e.desc.index_buffer_size = ib->size();
    e.desc.index_count = static_cast<std::uint32_t>(m.indices.size());
    e.vertices = std::move(*vb);
    e.indices = std::move(*ib);
    e.flush();
    return e;
}

// The pairs against the reference, reported as counts (pair lists are long).
inline void checkExact(const std::vector<TrianglePair>& found, const std::vector<TrianglePair>& reference) {
    const PairComparison cmp = comparePairs(found, reference);
    INFO("found " << found.size() << ", reference " << reference.size() << ", missed " << cmp.false_negatives << ", spurious "
                  << cmp.false_positives);
    CHECK(cmp.false_negatives == 0);
    CHECK(cmp.false_positives == 0);
    CHECK(found.size() == reference.size());
}

// A world (2 threads) holding the case's objects as host meshes or, with `engine`, as
// engine buffers kept there.
inline std::unique_ptr<CollisionWorld> worldOf(ValidatedContext& ctx, const PathologicalCase& c,
                                               std::vector<EngineMesh>* engine = nullptr) {
    auto w = makeWorld(ctx);
    for (const SceneObject& o : c.scene.objects) {
        if (engine) {
            engine->push_back(engineCopy(ctx.device(), o.mesh));
            REQUIRE(w->addGpuMesh(engine->back().desc, o.options));
        } else {
            REQUIRE(w->addMesh(o.mesh, o.options));
        }
    }
    return w;
}

}  // namespace vkcollide::test
