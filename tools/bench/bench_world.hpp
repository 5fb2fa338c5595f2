// Putting a bench scene into a CollisionWorld the way an engine would: host meshes through
// addMesh, engine meshes (BenchObject::gpu) through addGpuMesh on buffers created here,
// and per frame new transforms (setTransform), new vertices (updateVertices) or a rewrite
// of the engine's vertex buffer. Shared by vkcollide_bench and the recall guard test.
#pragma once

#include <vector>

#include "bench_scenes.hpp"
#include "vk/resources.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::bench {

// Rigid and deforming scenes are measured in world space (transforms baked into the
// vertices, as the peers see them), so that the reference and the GPU start from the same
// floats; moving scenes keep their transforms. Scales typical_edge_length with the transform.
Result<void> bakeTransforms(std::vector<BenchObject>& objects);

// Frame `frame` of `scene` as the bench measures it: transforms baked into the vertices,
// except a moving scene's (it keeps them for setTransform) unless bake_moving.
Result<std::vector<BenchObject>> buildFrame(const SceneSpec& scene, int frame, bool bake_moving = false);

// An engine mesh: positions (stride 12 or 16) and indices (32 or 16 bit) in host-visible
// buffers owned here.
struct EngineMesh {
    vk::Buffer vertices, indices;
    GpuMeshDesc desc;
};

struct SceneInWorld {
    std::vector<ObjectId> ids;         // one per object, in order
    std::vector<EngineMesh> engine;    // one per object (empty buffers for host objects)
};

// Adds every object (each one open when `all_open`); the buffers must outlive the world's use.
Result<SceneInWorld> addToWorld(CollisionWorld& world, Context& context, const std::vector<BenchObject>& objects, bool all_open = false);

// Moves the world to `frame` (same objects, same topology as the ones added).
Result<void> applyFrame(CollisionWorld& world, SceneInWorld& scene, Motion motion, const std::vector<BenchObject>& frame);

}  // namespace vkcollide::bench
