// The byte format of fuzz_world's inputs: a program of CollisionWorld calls. The fuzz
// target (fuzz_world.cpp) reads it with ProgramReader; the seed writer
// (write_world_seeds.cpp) writes it with ProgramWriter. Both live here, field by field in
// the same order, so that they cannot drift apart.
//
// An input is a sequence of operations, each one byte (its Op, modulo kOpCount) followed
// by its fields; bytes past the end read as 0, and the program ends when the input does
// (or after kMaxOps operations). Every byte sequence is a valid program: the fuzzer's
// mutations always mean some sequence of calls, right or wrong.
//
// Fields (each one byte unless said otherwise):
//   geometry  [vertices - 1, mod 8] [triangles, mod 7] [flags] 3 x vertices coordinates,
//             3 x triangles indices (each modulo vertices + 1: one past the end is possible)
//             flags: bit 0 self-collision, 1 open, 2 drop the last index (a count that is
//             not a multiple of 3), 3 no name
//   transform [code] and, when code >= kTransformTableSize, 12 coordinates (any matrix)
//   options   transform, [typical edge code]
//   layout    (engine meshes) bit 0 16-bit indices, 1 RGBA32 positions, 2 4 more bytes of
//             stride, 3 a vertex offset of 8 bytes, 4 an index offset of 4 bytes,
//             5 declare one vertex more than the buffer holds, 6 declare a vertex buffer
//             without SHADER_DEVICE_ADDRESS usage, 7 a null index buffer
//   pick      an object: below 240, the (pick mod live count)-th live object by id;
//             240 and above: an id that is not live (a removed one, or one never given)
//   settings  12 bytes: see readSettings
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vkcollide::fuzz {

enum class Op : std::uint8_t {
    AddMesh,  // geometry, options
    AddGpuMesh,  // geometry, options, layout
    SetGpuMeshBuffers,  // pick, layout, geometry (another topology is refused)
    WriteGpuMesh,  // pick, slot, value: the engine rewrites a vertex coordinate or an index
    RemoveObject,  // pick
    SetTransform,  // pick, transform
    SetSelfCollision,  // pick, on (bit 0)
    UpdateVertices,  // pick, count code, 3 x count coordinates
    SetPairFilter,  // kind (PairFilterKind)
    Detect,  // settings
    Submit,  // settings
    Collect,
    TryCollect,
    Ready,
    ResolveSettings,  // settings
    RecreateWorld,  // destroys the world (detections in flight included), makes a new one
    // (at most twice per input: each compiles its pipelines again)
    Count,
};
inline constexpr std::uint8_t kOpCount = static_cast<std::uint8_t>(Op::Count);
inline constexpr std::size_t kMaxOps = 64;
inline constexpr std::uint32_t kMaxVertices = 8;
inline constexpr std::uint32_t kMaxTriangles = 6;
inline constexpr std::uint8_t kTransformTableSize = 16;
inline constexpr std::uint8_t kBogusPick = 240;
inline constexpr std::size_t kSettingsBytes = 12;

enum class PairFilterKind : std::uint8_t { None, SumNotMultipleOf3, Never, Throws, Count };

// Geometry flags and layout bits (see above).
inline constexpr std::uint8_t kSelfCollision = 1, kOpen = 2, kDropIndex = 4, kNoName = 8;
inline constexpr std::uint8_t kIndex16 = 1, kRgba = 2, kWideStride = 4, kVertexOffset = 8, kIndexOffset = 16, kDeclareExtraVertex = 32,
                              kNoAddressUsage = 64, kNullIndexBuffer = 128;

class ProgramReader {
public:
    ProgramReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    bool done() const { return at_ >= size_; }
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
};

class ProgramWriter {
public:
    void byte(std::uint8_t b) { bytes_.push_back(b); }
    void op(Op o) { byte(static_cast<std::uint8_t>(o)); }
    const std::vector<std::uint8_t>& bytes() const { return bytes_; }

private:
    std::vector<std::uint8_t> bytes_;
};

// Coordinates: bytes below 224 are a grid of 1/16 in [-1, 15/16] (exact in float, so that
// triangles touch, share planes and coincide often); 224 and above are kSpecialCoordinates.
inline constexpr std::uint8_t kFirstSpecialCoordinate = 224;
inline std::uint8_t gridCoordinate(int sixteenths) {  // sixteenths in [-16, 15]
    return static_cast<std::uint8_t>(sixteenths + 16);
}

// A mesh as the program states it (before any rule is checked).
struct Geometry {
    std::uint8_t flags = 0;
    std::vector<std::uint8_t> coordinates;  // 3 per vertex
    std::vector<std::uint8_t> indices;  // 3 per triangle (kDropIndex drops the last)
};

inline Geometry readGeometry(ProgramReader& in) {
    Geometry g;
    const std::uint32_t vertices = 1 + in.byte() % kMaxVertices;
    const std::uint32_t triangles = in.byte() % (kMaxTriangles + 1);
    g.flags = in.byte();
    for (std::uint32_t i = 0; i < 3 * vertices; ++i) g.coordinates.push_back(in.byte());
    for (std::uint32_t i = 0; i < 3 * triangles; ++i) g.indices.push_back(static_cast<std::uint8_t>(in.byte() % (vertices + 1)));
    return g;
}

inline void writeGeometry(ProgramWriter& out, const Geometry& g) {
    const std::size_t vertices = g.coordinates.size() / 3;
    out.byte(static_cast<std::uint8_t>(vertices - 1));
    out.byte(static_cast<std::uint8_t>(g.indices.size() / 3));
    out.byte(g.flags);
    for (std::uint8_t c : g.coordinates) out.byte(c);
    for (std::uint8_t i : g.indices) out.byte(i);
}

// A transform code and, for codes past the table, its 12 coordinate bytes.
struct TransformCode {
    std::uint8_t code = 0;  // 0: identity (world_values.cpp's table)
    std::array<std::uint8_t, 12> matrix{};  // used when code >= kTransformTableSize
};

inline TransformCode readTransform(ProgramReader& in) {
    TransformCode t;
    t.code = in.byte();
    if (t.code >= kTransformTableSize)
        for (std::uint8_t& c : t.matrix) c = in.byte();
    return t;
}

inline void writeTransform(ProgramWriter& out, const TransformCode& t) {
    out.byte(t.code);
    if (t.code >= kTransformTableSize)
        for (std::uint8_t c : t.matrix) out.byte(c);
}

// Settings: 12 bytes, read by world_values.cpp's decodeSettings.
//   0 flags: bit 0 peeling, 1 resolution given, 2 direction given, 3 dual, 4 paper packing,
//            5 region given, 6 contacts, 7 depth-aware off
//   1 flags: bits 0-1 backend (auto, raster, compute, auto), bits 2-3 coverage (centre,
//            dilate, conservative, best), 4 bad objects fail, 5 measure_layers off,
//            6 open_epsilon given, 7 contacts.resolution given
//   2 resolution code, 3 direction code, 4 axes code, 5 layer cap code, 6 timeout code
//   (13, 14, 15 mod 16: 0, 1, 5 ms; else the default), 7 max_pairs code, 8
//   max_candidate_pairs code, 9 epsilon code (open, closed), 10 region code, 11 contact
//   resolution code. All zero: the default settings.
using SettingsBytes = std::array<std::uint8_t, kSettingsBytes>;

inline SettingsBytes readSettings(ProgramReader& in) {
    SettingsBytes s{};
    for (std::uint8_t& b : s) b = in.byte();
    return s;
}

inline void writeSettings(ProgramWriter& out, const SettingsBytes& s) {
    for (std::uint8_t b : s) out.byte(b);
}

}  // namespace vkcollide::fuzz
