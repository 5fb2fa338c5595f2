// Writes the seed corpus of fuzz_world: one program per kind of call sequence (each
// call, each refusal, each setting, each way to end a detection), in the byte format of
// world_program.hpp. Tiny meshes on the 1/16 grid. Usage: write_world_seeds <folder>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzz/seed_files.hpp"
#include "fuzz/world_program.hpp"

using namespace vkcollide::fuzz;

namespace {

// Vertices in sixteenths of a unit (each in [-16, 15]), indices, geometry flags.
Geometry mesh(std::vector<std::array<int, 3>> vertices, std::vector<std::uint8_t> indices, std::uint8_t flags = 0) {
    Geometry g;
    g.flags = flags;
    for (const auto& v : vertices)
        for (int c : v) g.coordinates.push_back(gridCoordinate(c));
    g.indices = std::move(indices);
    return g;
}

Geometry flatTriangle(int z = 0, std::uint8_t flags = 0) { return mesh({{-8, -8, z}, {8, -8, z}, {0, 8, z}}, {0, 1, 2}, flags); }
// Crosses flatTriangle(0) through the plane x = 0.
Geometry uprightTriangle(std::uint8_t flags = 0) { return mesh({{0, -4, -8}, {0, -4, 8}, {0, 4, 0}}, {0, 1, 2}, flags); }
Geometry tetrahedron(int dx, std::uint8_t flags = 0) {
    return mesh({{-6 + dx, -6, -6}, {6 + dx, -6, -6}, {dx, 6, -6}, {dx, 0, 6}}, {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3}, flags);
}

// Settings bytes with named fields (world_program.hpp, readSettings).
struct Settings {
    SettingsBytes b{};
    Settings& peeling() {
        b[0] |= 1;
        return *this;
    }
    Settings& resolution(std::uint8_t code) {
        b[0] |= 2;
        b[2] = code;
        return *this;
    }
    Settings& direction(std::uint8_t code) {
        b[0] |= 4;
        b[3] = code;
        return *this;
    }
    Settings& dual() {
        b[0] |= 8;
        return *this;
    }
    Settings& paperPacking() {
        b[0] |= 16;
        return *this;
    }
    Settings& region(std::uint8_t code) {
        b[0] |= 32;
        b[10] = code;
        return *this;
    }
    Settings& contacts() {
        b[0] |= 64;
        return *this;
    }
    Settings& depthAwareOff() {
        b[0] |= 128;
        return *this;
    }
    Settings& backend(std::uint8_t code) {
        b[1] = static_cast<std::uint8_t>((b[1] & ~3) | code);
        return *this;
    }
    Settings& coverage(std::uint8_t code) {
        b[1] = static_cast<std::uint8_t>((b[1] & ~12) | (code << 2));
        return *this;
    }
    Settings& failBadObjects() {
        b[1] |= 16;
        return *this;
    }
    Settings& measureOff() {
        b[1] |= 32;
        return *this;
    }
    Settings& openEpsilon(std::uint8_t code) {
        b[1] |= 64;
        b[9] = static_cast<std::uint8_t>((b[9] & ~7) | code);
        return *this;
    }
    Settings& closedEpsilon(std::uint8_t code) {
        b[9] = static_cast<std::uint8_t>((b[9] & 7) | (code << 3));
        return *this;
    }
    Settings& contactResolution(std::uint8_t code) {
        b[1] |= 128;
        b[11] = code;
        return *this;
    }
    Settings& axes(std::uint8_t code) {
        b[4] = code;
        return *this;
    }
    Settings& layerCap(std::uint8_t code) {
        b[5] = code;
        return *this;
    }
    Settings& timeout(std::uint8_t code) {
        b[6] = static_cast<std::uint8_t>((b[6] & ~15) | code);
        return *this;
    }
    Settings& waitPoll(bool sleep_only) {  // else poll up to a second
        b[6] = static_cast<std::uint8_t>(b[6] | 16 | (sleep_only ? 32 : 0));
        return *this;
    }
    Settings& maxPairs(std::uint8_t code) {
        b[7] = code;
        return *this;
    }
    Settings& maxCandidatePairs(std::uint8_t code) {
        b[8] = code;
        return *this;
    }
};

class Program {
public:
    Program& addMesh(const Geometry& g, std::uint8_t transform = 0, std::uint8_t edge = 0) {
        w_.op(Op::AddMesh);
        writeGeometry(w_, g);
        writeTransform(w_, {transform, {}});
        w_.byte(edge);
        return *this;
    }
    Program& addGpuMesh(const Geometry& g, std::uint8_t layout = 0, std::uint8_t transform = 0, std::uint8_t edge = 0) {
        w_.op(Op::AddGpuMesh);
        writeGeometry(w_, g);
        writeTransform(w_, {transform, {}});
        w_.byte(edge);
        w_.byte(layout);
        return *this;
    }
    Program& setGpuMeshBuffers(std::uint8_t pick, std::uint8_t layout, const Geometry& g) {
        w_.op(Op::SetGpuMeshBuffers);
        w_.byte(pick);
        w_.byte(layout);
        writeGeometry(w_, g);
        return *this;
    }
    Program& writeGpuMesh(std::uint8_t pick, std::uint8_t slot, std::uint8_t value) {
        w_.op(Op::WriteGpuMesh);
        w_.byte(pick);
        w_.byte(slot);
        w_.byte(value);
        return *this;
    }
    Program& remove(std::uint8_t pick) { return op(Op::RemoveObject).byte(pick); }
    Program& setTransform(std::uint8_t pick, std::uint8_t transform) {
        op(Op::SetTransform).byte(pick);
        writeTransform(w_, {transform, {}});
        return *this;
    }
    Program& setTransformMatrix(std::uint8_t pick, const std::array<std::uint8_t, 12>& m) {
        op(Op::SetTransform).byte(pick);
        writeTransform(w_, {kTransformTableSize, m});
        return *this;
    }
    Program& setSelfCollision(std::uint8_t pick, bool on) { return op(Op::SetSelfCollision).byte(pick).byte(on ? 1 : 0); }
    // count_code: 0 the object's count, 5 one fewer, 6 one more, 7 none; `vertices` must
    // match the count the code gives.
    Program& updateVertices(std::uint8_t pick, std::uint8_t count_code, std::vector<std::array<int, 3>> vertices, int special = -1) {
        op(Op::UpdateVertices).byte(pick).byte(count_code);
        for (const auto& v : vertices)
            for (int c : v) w_.byte(special >= 0 ? static_cast<std::uint8_t>(special) : gridCoordinate(c));
        return *this;
    }
    Program& pairFilter(PairFilterKind kind) { return op(Op::SetPairFilter).byte(static_cast<std::uint8_t>(kind)); }
    Program& detect(const Settings& s = {}) {
        op(Op::Detect);
        writeSettings(w_, s.b);
        return *this;
    }
    Program& submit(const Settings& s = {}) {
        op(Op::Submit);
        writeSettings(w_, s.b);
        return *this;
    }
    Program& resolve(const Settings& s = {}) {
        op(Op::ResolveSettings);
        writeSettings(w_, s.b);
        return *this;
    }
    Program& collect() { return op(Op::Collect); }
    Program& tryCollect() { return op(Op::TryCollect); }
    Program& ready() { return op(Op::Ready); }
    Program& newWorld() { return op(Op::RecreateWorld); }
    const std::vector<std::uint8_t>& bytes() const { return w_.bytes(); }

private:
    ProgramWriter w_;
    Program& op(Op o) {
        w_.op(o);
        return *this;
    }
    Program& byte(std::uint8_t b) {
        w_.byte(b);
        return *this;
    }
};

// Special coordinate bytes (world_values.cpp's kSpecialCoordinates).
constexpr std::uint8_t kNaNByte = kFirstSpecialCoordinate + 14;
constexpr std::uint8_t kHugeByte = kFirstSpecialCoordinate + 10;  // 1e38

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s <corpus folder>\n", argv[0]);
        return 2;
    }
    const std::string folder = argv[1];
    std::vector<std::pair<std::string, Program>> seeds;

    seeds.emplace_back("crossing", Program().addMesh(flatTriangle()).addMesh(uprightTriangle()).detect());
    seeds.emplace_back("tetrahedra_resolutions", Program()
                                                     .addMesh(tetrahedron(0, kSelfCollision))
                                                     .addMesh(tetrahedron(4))
                                                     .detect(Settings().resolution(1))
                                                     .detect(Settings().resolution(5))
                                                     .detect(Settings().resolution(13).direction(4))
                                                     .detect(Settings().peeling().resolution(10))
                                                     .resolve());
    seeds.emplace_back("in_flight",
                       Program()
                           .addMesh(tetrahedron(0))
                           .addMesh(tetrahedron(3))
                           .submit()
                           .submit(Settings().resolution(9))
                           .submit()  // a third is refused
                           .ready()
                           .tryCollect()
                           .collect()
                           .collect()
                           .collect()  // nothing in flight
                           .tryCollect()
                           .ready());
    seeds.emplace_back("edits_while_in_flight", Program()
                                                    .addMesh(tetrahedron(0))
                                                    .addMesh(tetrahedron(3))
                                                    .submit()
                                                    .addMesh(flatTriangle())
                                                    .remove(0)
                                                    .updateVertices(0, 0, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}})  // allowed
                                                    .setSelfCollision(0, true)
                                                    .pairFilter(PairFilterKind::Never)
                                                    .setTransform(1, 1)  // allowed in flight
                                                    .detect()  // refused in flight
                                                    .collect()
                                                    .detect());
    // Host meshes deformed while detections are in flight: each keeps the vertices it was
    // submitted with (checkResult compares with its snapshot), through every vertex copy.
    seeds.emplace_back("updates_in_flight", Program()
                                                .addMesh(tetrahedron(0))
                                                .addMesh(tetrahedron(3))
                                                .submit()
                                                .updateVertices(0, 0, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}})
                                                .submit()
                                                .updateVertices(0, 0, {{9, 9, 9}, {12, 9, 9}, {9, 12, 9}, {9, 9, 12}})
                                                .collect()
                                                .submit()
                                                .updateVertices(0, 0, {{1, 1, 1}, {5, 1, 1}, {1, 5, 1}, {1, 1, 5}})
                                                .collect()
                                                .collect()
                                                .detect());
    seeds.emplace_back("engine_meshes", Program()
                                            .addMesh(flatTriangle())
                                            .addGpuMesh(uprightTriangle())
                                            .detect()
                                            .writeGpuMesh(1, 4, kNaNByte)  // vertex 1's y: the object is left out
                                            .detect()
                                            .detect(Settings().failBadObjects())
                                            .setGpuMeshBuffers(1, kIndex16 | kRgba, uprightTriangle())
                                            .detect(Settings().peeling())
                                            .setGpuMeshBuffers(1, 0, tetrahedron(0))  // another topology
                                            .writeGpuMesh(1, 128, 7)  // an index out of range
                                            .detect()
                                            .remove(1)
                                            .detect());
    seeds.emplace_back("engine_layouts", Program()
                                             .addGpuMesh(tetrahedron(0), kWideStride | kVertexOffset | kIndexOffset)
                                             .addGpuMesh(tetrahedron(3), kIndex16 | kRgba | kWideStride)
                                             .addGpuMesh(tetrahedron(6), kDeclareExtraVertex)
                                             .addGpuMesh(tetrahedron(6), kNoAddressUsage)
                                             .addGpuMesh(tetrahedron(6), kNullIndexBuffer)
                                             .addGpuMesh(flatTriangle(0, kDropIndex))
                                             .detect()
                                             .submit(Settings().peeling().backend(2))
                                             .collect());
    seeds.emplace_back("bad_settings", Program()
                                           .addMesh(tetrahedron(0))
                                           .addMesh(tetrahedron(3))
                                           .detect(Settings().resolution(0))
                                           .detect(Settings().resolution(14))
                                           .detect(Settings().peeling().resolution(3))
                                           .detect(Settings().direction(5))
                                           .detect(Settings().direction(6))
                                           .detect(Settings().region(1))
                                           .detect(Settings().region(3))
                                           .detect(Settings().axes(6))
                                           .detect(Settings().peeling().coverage(2))
                                           .detect(Settings().contacts().contactResolution(2))
                                           .detect(Settings().peeling().openEpsilon(4))
                                           .detect(Settings().closedEpsilon(3))
                                           .resolve(Settings().resolution(15))
                                           .detect());
    seeds.emplace_back("timeouts", Program()
                                       .addMesh(tetrahedron(0))
                                       .addMesh(tetrahedron(3))
                                       .detect(Settings().timeout(13))
                                       .remove(0)
                                       .updateVertices(1, 0, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}})
                                       .detect()
                                       .submit(Settings().timeout(13).waitPoll(false))
                                       .collect()
                                       .detect(Settings().waitPoll(true))
                                       .detect(Settings().waitPoll(false).peeling())
                                       .submit(Settings().timeout(14).peeling())
                                       .newWorld()  // destroyed with a detection in flight
                                       .addMesh(flatTriangle())
                                       .addMesh(uprightTriangle())
                                       .detect());
    seeds.emplace_back("pair_filters", Program()
                                           .addMesh(tetrahedron(0))
                                           .addMesh(tetrahedron(2))
                                           .addMesh(tetrahedron(4))
                                           .pairFilter(PairFilterKind::SumNotMultipleOf3)
                                           .detect()
                                           .pairFilter(PairFilterKind::Throws)
                                           .detect()
                                           .detect()
                                           .pairFilter(PairFilterKind::Never)
                                           .detect(Settings().peeling())
                                           .pairFilter(PairFilterKind::None)
                                           .submit()
                                           .collect());
    seeds.emplace_back("edits", Program()
                                    .addMesh(tetrahedron(0, kSelfCollision))
                                    .addMesh(tetrahedron(3, kOpen))
                                    .updateVertices(0, 0, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}})
                                    .updateVertices(0, 6, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}, {1, 1, 1}})
                                    .updateVertices(0, 0, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}}, kNaNByte)
                                    .updateVertices(1, 0, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}}, kHugeByte)
                                    .setTransform(0, 11)  // NaN
                                    .setTransform(0, 3)
                                    .setTransformMatrix(1, {gridCoordinate(8), gridCoordinate(0), gridCoordinate(0), gridCoordinate(2),
                                                            gridCoordinate(0), gridCoordinate(8), gridCoordinate(0), gridCoordinate(0),
                                                            gridCoordinate(0), gridCoordinate(0), gridCoordinate(8), gridCoordinate(-2)})
                                    .setSelfCollision(1, true)
                                    .remove(kBogusPick)
                                    .remove(kBogusPick + 1)
                                    .detect()
                                    .remove(0)
                                    .remove(kBogusPick)  // the removed id
                                    .detect(Settings().peeling()));
    seeds.emplace_back("pair_budget", Program()
                                          .addMesh(mesh({{-8, -8, 0}, {8, -8, 0}, {0, 8, 0}, {-8, -8, 1}, {8, -8, 1}, {0, 8, 1}},
                                                        {0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5}, kSelfCollision))
                                          .addMesh(uprightTriangle(kSelfCollision))
                                          .detect(Settings().maxPairs(2))
                                          .detect(Settings().maxPairs(1).peeling())
                                          .detect(Settings().maxCandidatePairs(1))
                                          .detect(Settings().maxPairs(3).maxCandidatePairs(3)));
    seeds.emplace_back("extreme_transforms", Program()
                                                 .addMesh(tetrahedron(0, kSelfCollision), 6)  // every vertex at one point
                                                 .addMesh(tetrahedron(2), 9)  // 1e20
                                                 .detect()
                                                 .setTransform(1, 10)  // 1e-30
                                                 .detect()
                                                 .setTransform(1, 13)  // 1e38 away
                                                 .detect(Settings().peeling())
                                                 .setTransform(1, 14)
                                                 .detect()
                                                 .setTransform(0, 7)
                                                 .setTransform(1, 8)
                                                 .detect());
    seeds.emplace_back("peeling_everything",
                       Program()
                           .addMesh(tetrahedron(0, kSelfCollision))
                           .addMesh(tetrahedron(3, kOpen))
                           .addGpuMesh(tetrahedron(5))
                           .detect(Settings().peeling().dual().paperPacking().backend(2).axes(4).contacts().coverage(1))
                           .detect(Settings().peeling().depthAwareOff().backend(1).layerCap(2).measureOff())
                           .detect(Settings().peeling().openEpsilon(1).closedEpsilon(1).coverage(3).region(0))
                           .submit(Settings().peeling().contacts().contactResolution(3))
                           .collect());
    seeds.emplace_back("bad_meshes", Program()
                                         .addMesh(mesh({{0, 0, 0}}, {}))  // no triangle
                                         .addMesh(mesh({{0, 0, 0}, {1, 0, 0}}, {0, 1, 2}))  // an index out of range
                                         .addMesh(flatTriangle(0, kDropIndex))
                                         .addMesh(flatTriangle(0, kNoName), 11)  // a NaN transform
                                         .addMesh(flatTriangle(), 0, 4)  // a negative typical edge
                                         .addMesh(flatTriangle())
                                         .detect());

    // Found by the fuzzer: the reliable method given a coverage it ignores (Conservative,
    // which lavapipe lacks) broke the broad phase's precondition (an assertion).
    seeds.emplace_back("regression_reliable_ignores_coverage", Program()
                                                                   .addMesh(tetrahedron(0))
                                                                   .addMesh(tetrahedron(3))
                                                                   .detect(Settings().coverage(2))
                                                                   .submit(Settings().coverage(2).backend(2))
                                                                   .collect());

    bool ok = makeCorpusFolder(folder);
    for (const auto& [name, program] : seeds) {
        const auto& bytes = program.bytes();
        ok = writeSeed(folder + "/" + name, std::span(reinterpret_cast<const char*>(bytes.data()), bytes.size())) && ok;
    }
    return corpusStatus(ok, folder);
}
