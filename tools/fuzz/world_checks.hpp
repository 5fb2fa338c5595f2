// fuzz_world's model of a world and its checks of a detection's result: the promises of
// DetectResult (detect_result.hpp) and, for host meshes, the exact reference of tests/support.
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include "fuzz/world_program.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::fuzz {

// Prints `what` and aborts: a finding.
[[noreturn]] void fail(const std::string& what);
// VKCOLLIDE_FUZZ_VERBOSE=1: every call and its outcome on stderr (to read a finding).
void trace(const std::string& line);

struct Object {
    bool gpu = false;
    HostMesh mesh;  // host meshes: what the world holds; engine meshes: the buffers' geometry
    Transform3x4 transform = kIdentity3x4;
    bool self_collision = false;
    std::size_t engine = 0;  // engine meshes: which buffers (fuzz_world.cpp)
};

// What a detection was submitted with, to check its result against.
struct Snapshot {
    std::map<ObjectId, Object> objects;
    PairFilterKind filter = PairFilterKind::None;
    bool filter_threw = false;  // a throwing filter was in place at some time: no oracle
    DetectSettings settings;
};

// The pair filter of each kind, as a pure function of the two ids.
bool allowed(PairFilterKind kind, ObjectId a, ObjectId b);

// Aborts unless `r`, the result of `call` for a detection submitted as `snap` says, keeps
// DetectResult's promises (fuzz_world.cpp lists them); with host meshes only and a
// complete result, its pairs must be the exact reference's (reliable) or among them
// (peeling).
void checkResult(const DetectResult& r, const Snapshot& snap, const char* call);

}  // namespace vkcollide::fuzz
