// The benchmark scene set, shared by vkcollide's sweep, the peers' benchmark and the
// recall guard (tests/scene/recall_guard_tests.cpp), so that every run sees the same
// meshes and frames. docs/results.md lists every scene with its set, triangles and exact
// pairs.
//
// Two sets. "tuning" scenes may be looked at to choose defaults and settings; "held-out"
// scenes must not be: they differ in kind or parameters (other meshes, scales, seeds,
// orientations, motions) and only measure how well choices made on the tuning set carry
// over. Each scene kind has at least one scene in each set.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"
#include "vkcollide/scene.hpp"

namespace vkcollide::bench {

// Rigid: one frame. Deforming: vertices change every frame (updateVertices, or a rewrite
// of the engine buffer for GPU objects). Moving: only object transforms change (setTransform).
enum class Motion { Rigid, Deforming, Moving };
// User: a scene of the user's own files (user_scene.hpp), in no set of the bench.
enum class SceneSet { Tuning, HeldOut, User };

const char* motionName(Motion motion);
const char* setName(SceneSet set);

inline constexpr Transform3x4 kIdentity3x4{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

struct BenchObject {
    HostMesh mesh;                        // object space; named (the name is the object's)
    Transform3x4 transform = kIdentity3x4;  // object -> world
    bool self_collision = true;
    bool open = false;
    // An engine mesh: the bench copies it into buffers it creates and adds it with
    // addGpuMesh, so the world sees no host geometry for it.
    bool gpu = false;
    std::uint32_t gpu_stride = 12;      // 12: R32G32B32, 16: R32G32B32A32 (w ignored)
    bool gpu_index16 = false;           // 16-bit indices (fewer than 65,536 vertices)
    float typical_edge_length = 0;      // what the engine tells the world (0: unknown)
};

struct SceneSpec {
    std::string name;
    Motion motion = Motion::Rigid;
    SceneSet set = SceneSet::Tuning;
    int frames = 1;    // distinct frames of the motion (rigid: 1)
    std::string what;  // one line for --list and the docs
    // Builds frame `frame` in [0, frames); every frame has the same objects and topology.
    std::function<Result<std::vector<BenchObject>>(int frame)> build;
};

// Every scene. `data`: the folder of the CGAL meshes (tools/fetch_cgal_data.sh); scenes
// that need a missing file fail when built, naming it. `scale` multiplies the triangle
// counts (about: tessellations and subdivision levels are rounded; packaged meshes are
// used as they are), so the same set runs on a software rasterizer at 0.01-0.05.
std::vector<SceneSpec> allScenes(const std::string& data, double scale = 1.0);

// World-space copies (transforms applied), for libraries that take one mesh per object.
Result<std::vector<HostMesh>> worldMeshes(const std::vector<BenchObject>& objects);

// Helpers shared by the scene builders.
Transform3x4 rotationTranslation(double axis_x, double axis_y, double axis_z, double angle, Float3 t);
Transform3x4 compose(const Transform3x4& outer, const Transform3x4& inner);  // outer * inner
// A deterministic pseudo-random number in [0, 1) from an integer (no global state).
double hash01(std::uint32_t i);
// n scaled by scale^(1/dims) (a tessellation count along one of `dims` directions), at least `least`.
std::uint32_t scaledCount(std::uint32_t n, double scale, int dims, std::uint32_t least = 3);
// A packaged mesh centred on the origin with its largest extent `size`.
Result<HostMesh> loadMesh(const std::string& data, const std::string& file, float size);

// The scene kinds (scene_kinds.cpp, scene_piles.cpp); each returns the specs
// of its tuning and held-out scenes.
std::vector<SceneSpec> foldScenes(double scale);
std::vector<SceneSpec> drapeScenes(double scale);
std::vector<SceneSpec> twistedScenes(double scale);
std::vector<SceneSpec> pileScenes(const std::string& data, double scale);
std::vector<SceneSpec> deepOverlapScenes(const std::string& data, double scale);
std::vector<SceneSpec> deformingPairScenes(const std::string& data, double scale);
std::vector<SceneSpec> ballClothScenes(double scale);
std::vector<SceneSpec> mixedScenes(double scale);
std::vector<SceneSpec> touchingScenes(double scale);

}  // namespace vkcollide::bench
