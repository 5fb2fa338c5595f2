// vkcollide: the small types and enums shared by every public header and by every layer
// below the API (the broad phase takes the same enums the settings hold).
//
// Thread safety: plain values; toString returns a static string.
#pragma once

#include <array>
#include <cstdint>

#include "vkcollide/export.hpp"

namespace vkcollide {

// Stable handle of an object in a CollisionWorld (never reused after removeObject).
using ObjectId = std::uint32_t;

// A position or direction in object or world units.
struct Float3 {
    float x = 0, y = 0, z = 0;
};

// An affine object-to-world transform, row-major 3x4: rows x, y, z of [R | t], so a point
// p maps to (row_r[0] p.x + row_r[1] p.y + row_r[2] p.z + row_r[3]) for r = x, y, z.
using Transform3x4 = std::array<float, 12>;
inline constexpr Transform3x4 kIdentity3x4{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

// How the broad phase compacts the kept triangles before the readback: a prefix-sum scan
// (default), or the paper's count / shift / move over a packing texture. Same records.
enum class PackingMethod { Scan, Paper };

// How sampling treats thin triangles: those whose projected inradius is below half a
// pixel diagonal (sub-pixel triangles, slivers, zero-area and edge-on triangles). They may
// cover no pixel centre, so the rays cannot see what they intersect (docs/stability.md).
enum class Coverage {
    Centre,        // the paper: the hardware rule, pixel centres only
    Dilate,        // thin triangles are grown by half a pixel diagonal in the vertex shader,
                   // and every ray they touch is a collision ray (any device)
    Conservative,  // the same through VK_EXT_conservative_rasterization: fails with
                   // UnsupportedFeature where the Context has not enabled it
    Best,          // settings only: Conservative where the Context has it, else Dilate
};

// What a detection does when the GPU check of an engine-owned mesh (addGpuMesh) finds an
// index out of range or a NaN or infinite position.
enum class BadObjectPolicy {
    Exclude,  // detect the other objects as if it were absent (one extra GPU run per bad
              // object, that frame); DetectResult::excluded names it and the problem
    Fail,     // the whole detection fails with that error
};

// How object sampling (paper §4) runs: depth peeling on the graphics pipeline, or the
// same rays and keys computed by compute shaders (edge functions with the rasterizer's
// coverage rule). Auto (settings only) chooses per device and scene; DetectStats::peeling
// says which ran and why.
enum class SamplingBackend { Auto, Raster, Compute };

// How a detection's broad phase finds what the exact decision decides (DetectSettings::
// method; detect_settings.hpp says what each guarantees and costs).
enum class DetectMethod {
    Reliable,  // cells on a grid, candidate pairs formed and filtered on the GPU: every
               // intersecting pair, touching included, at any resolution (docs/reliable.md)
    Peeling,   // the paper: depth peeling along rays, the kept triangles read back
};

// Where the reliable method's exact triangle-triangle decision runs
// (DetectSettings::reliable.exact). Both give the same pairs: the GPU's test is the CPU's,
// predicate for predicate, in exact arithmetic (docs/exact_gpu.md).
enum class ExactDecision {
    Auto,  // on the GPU where the device has shaderFloat64, else on the CPU
    Gpu,  // on the GPU; a device without shaderFloat64 is refused (UnsupportedFeature)
    Cpu,  // on the CPU: every pair the GPU filter keeps is read back and tested there
};

// How the GPU's exact decision runs (DetectSettings::reliable.exact_pass). The pairs are the
// same either way; only the time changes (docs/exact_gpu.md, "Two passes").
enum class ExactPass {
    Auto,    // Queued where the world's last detection had at least 65,536 candidates in
             // their canonical cells (CellStats: candidates - duplicates), Inline below
             // 32,768, else as the last one (Inline at first)
    Inline,  // inside the pair pass: no pass of its own, but each subgroup of candidates
             // waits for its lanes that take the exact path
    Queued,  // the pair pass queues the candidates its filter cannot decide and an exact pass
             // of its own decides them in full subgroups
};

// Where the host result's pairs are put in order (DetectSettings::reliable.pair_sort) when the exact
// decision ran on the GPU. Both give the same pairs and responses to the bit.
enum class PairSort {
    Auto,  // on the GPU when the world's last detection had at least kGpuPairSortFrom pairs
           // (not where the device ends long loops, DeviceInfo::loop_iteration_limit: llvmpipe);
           // below that one GPU pass sorts them and computes their responses where its 4,096
           // survivors hold them (DetectStats::reliable.pairs_sorted_in_one_pass), else the CPU
    Gpu,   // on the GPU: the pairs come back sorted and the CPU only computes the responses
    Cpu,   // on the CPU: the GPU's unsorted pairs are read back, sorted and deduplicated there
};

// Where the host result's responses are computed (DetectSettings::reliable.responses) when
// its pairs are sorted on the GPU (PairSort). Both give the same responses to the bit
// (docs/exact_gpu.md, "Responses on the GPU").
enum class ResponseSource {
    Auto,  // on the GPU wherever the host result's pairs are sorted there
    Gpu,   // on the GPU, with the pairs sorted there (as PairSort::Gpu): both come back ready
    Cpu,   // the narrow phase's, on the host's threads (the reference path)
};

// When the host names the pairs the GPU sorted (DetectSettings::reliable.pair_naming), where
// the GPU also computes their responses (ResponseSource). The same result either way
// (docs/exact_gpu.md, "The pairs named while the GPU computes the responses").
enum class PairNaming {
    Auto,        // during the responses' passes, from kNameDuringGpuFrom pairs in the world's last
                 // detection: the host polls a VkEvent the GPU sets after each piece of the copy
    AfterFence,  // only after the submission's fence: the host synchronisation Vulkan specifies
};

// How the reliable method's automatic grid is chosen (DetectSettings::reliable.grid_tuning).
// The pairs are the same at any grid (the method is exact at every resolution): only the time
// changes.
enum class GridTuning {
    // The library's choice: On on a GPU (as fast or faster on every bench scene on the
    // H200), Off on a CPU implementation such as lavapipe (docs/reliable.md, "The grid per
    // scene").
    Auto,
    // Per scene, from the detections' own GPU times: kCellsPerEdge scaled by steps of
    // sqrt(2) from 1/4 to 2, the fastest of its neighbours kept (docs/reliable.md, "The grid
    // per scene").
    On,
    // kCellsPerEdge (2) cells per typical edge, whatever the scene.
    Off,
};

// Lower-case names as the command-line options spell them: "scan", "paper"; "centre",
// "dilate", "conservative", "best"; "auto", "raster", "compute"; "reliable", "peeling";
// "auto", "gpu", "cpu" (three times); "auto", "on", "off"; "auto", "after-fence".
VKCOLLIDE_API const char* toString(PackingMethod method) noexcept;
VKCOLLIDE_API const char* toString(DetectMethod method) noexcept;
VKCOLLIDE_API const char* toString(Coverage coverage) noexcept;
VKCOLLIDE_API const char* toString(SamplingBackend backend) noexcept;
VKCOLLIDE_API const char* toString(ExactDecision exact) noexcept;
VKCOLLIDE_API const char* toString(PairSort sort) noexcept;
VKCOLLIDE_API const char* toString(ResponseSource source) noexcept;
VKCOLLIDE_API const char* toString(ExactPass pass) noexcept;
VKCOLLIDE_API const char* toString(GridTuning tuning) noexcept;
VKCOLLIDE_API const char* toString(PairNaming naming) noexcept;

}  // namespace vkcollide
