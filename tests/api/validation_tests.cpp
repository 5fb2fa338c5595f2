// The one validation gate (src/api/validation.cpp): each rule refused at the API with an
// error that names the object once and the rule, before anything is uploaded or recorded.
#include <catch2/catch.hpp>

#include <limits>
#include <string>

#include "api/engine_copy.hpp"
#include "api/validation.hpp"
#include "broad/broad_phase_types.hpp"
#include "support/error_text.hpp"
#include "support/gpu_fixture.hpp"
#include "support/world_fixture.hpp"
#include "vkcollide/scene.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::test;

namespace {

using test::mentions;

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("addMesh names the object once and checks the transform before uploading", "[api][gpu][validation]") {
    ValidatedContext ctx;
    auto world = CollisionWorld::create(ctx.context(), {.threads = 1});
    REQUIRE(world);
    auto sphere = uvSphere(1.0f, 12, 6);
    REQUIRE(sphere);
    sphere->name = "mesh-name";
    HostMesh torn = *sphere;
    torn.indices[4] = 100000;
    auto r = (*world)->addMesh(torn, {.name = "torn"});
    REQUIRE_FALSE(r);
    CHECK(r.error().message().rfind("object 0 ('torn'): ", 0) == 0);
    CHECK(count(r.error().message(), "object") == 1);
    CHECK_FALSE(mentions(r.error(), "mesh-name"));  // the mesh's own name is not a second prefix
    CHECK(mentions(r.error(), "index 100000 of triangle 1 is out of range"));

    ObjectOptions inf;
    inf.name = "far";
    inf.transform[7] = std::numeric_limits<float>::infinity();
    const std::uint64_t before = (*world)->objectCount();
    r = (*world)->addMesh(*sphere, inf);
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidArgument);
    CHECK(r.error().message() == "object 0 ('far'): transform is not finite");
    CHECK((*world)->objectCount() == before);
    // A refused object takes no id and leaves nothing behind.
    auto ok = (*world)->addMesh(*sphere, {.name = "fine"});
    REQUIRE(ok);
    CHECK(*ok == 0);
    auto bad_update = (*world)->setTransform(*ok, inf.transform);
    REQUIRE_FALSE(bad_update);
    CHECK(bad_update.error().message() == "object 0 ('fine'): transform is not finite");
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("bad input gets an error that names the object and the problem", "[api][gpu]") {
    ValidatedContext ctx;
    auto world = makeWorld(ctx);
    auto empty = world->detect();
    REQUIRE_FALSE(empty);
    CHECK(mentions(empty.error(), "no objects"));

    auto sphere = uvSphere(1.0f, 12, 6);
    REQUIRE(sphere);
    HostMesh nan = *sphere;
    nan.positions[5].z = std::numeric_limits<float>::quiet_NaN();
    auto r = world->addMesh(nan, {.name = "melted"});
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::InvalidMesh);
    CHECK(mentions(r.error(), "melted"));
    HostMesh bad_index = *sphere;
    bad_index.indices[4] = 100000;
    r = world->addMesh(bad_index, {.name = "torn"});
    REQUIRE_FALSE(r);
    CHECK(mentions(r.error(), "torn"));
    HostMesh short_indices = *sphere;
    short_indices.indices.pop_back();
    r = world->addMesh(short_indices, {.name = "short"});
    REQUIRE_FALSE(r);
    CHECK(mentions(r.error(), "multiple of three"));
    r = world->addMesh(HostMesh{"nothing", {}, {}}, {.name = "nothing"});
    REQUIRE_FALSE(r);
    CHECK(mentions(r.error(), "nothing"));
    ObjectOptions inf_transform;
    inf_transform.transform[3] = std::numeric_limits<float>::infinity();
    CHECK_FALSE(world->addMesh(*sphere, inf_transform));
    CHECK(world->objectCount() == 0);

    EngineMesh e = engineCopy(ctx.device(), *sphere, 12, VK_FORMAT_R32G32B32_SFLOAT, false);
    GpuMeshDesc d = e.desc;
    d.vertex_count += 1;
    auto small = world->addGpuMesh(d, {.name = "skinned"});
    REQUIRE_FALSE(small);
    CHECK(small.error().code() == ErrorCode::BufferTooSmall);
    CHECK(mentions(small.error(), "skinned"));
    d = e.desc;
    d.vertex_buffer_size *= 4;  // more than the buffer holds
    small = world->addGpuMesh(d);
    REQUIRE_FALSE(small);
    CHECK(small.error().code() == ErrorCode::BufferTooSmall);
    d = e.desc;
    d.position_format = VK_FORMAT_R16G16B16A16_SFLOAT;
    auto format = world->addGpuMesh(d);
    REQUIRE_FALSE(format);
    CHECK(format.error().code() == ErrorCode::UnsupportedFeature);
    d = e.desc;
    d.index_count -= 1;
    CHECK_FALSE(world->addGpuMesh(d));
    d = e.desc;
    d.index_count = 0;
    CHECK_FALSE(world->addGpuMesh(d));
    d = e.desc;
    d.index_buffer = VK_NULL_HANDLE;
    CHECK_FALSE(world->addGpuMesh(d));

    auto ok = world->addMesh(*sphere, {.name = "fine"});
    REQUIRE(ok);
    CHECK_FALSE(world->setTransform(*ok + 1, {}));
    DetectSettings s;
    s.method = DetectMethod::Peeling;
    s.resolution = 100;
    auto bad_res = world->detect(s);
    REQUIRE_FALSE(bad_res);
    CHECK(mentions(bad_res.error(), "power of two"));
    s.method = DetectMethod::Reliable;  // cells per side: any count up to 16384
    CHECK(world->detect(s));
    s.resolution = 16385;
    bad_res = world->detect(s);
    REQUIRE_FALSE(bad_res);
    CHECK(mentions(bad_res.error(), "16384"));
    CHECK(world->detect());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("detection settings are refused at the API, naming the rule", "[api][gpu][validation]") {
    ValidatedContext ctx;
    auto world = CollisionWorld::create(ctx.context(), {.threads = 1});
    REQUIRE(world);
    auto none = (*world)->detect();
    REQUIRE_FALSE(none);
    CHECK(mentions(none.error(), "no objects"));
    CHECK_FALSE((*world)->resolveSettings());
    auto sphere = uvSphere(1.0f, 12, 6);
    REQUIRE(sphere);
    REQUIRE((*world)->addMesh(*sphere));
    struct Bad {
        const char* what;
        void (*spoil)(DetectSettings&);
        ErrorCode code;
        const char* says;
    };
    const Bad bad[] = {
        {"resolution", [](DetectSettings& s) { s.resolution = 100; }, ErrorCode::InvalidArgument, "power of two in [4, 16384]"},
        {"resolution too big", [](DetectSettings& s) { s.resolution = 32768; }, ErrorCode::InvalidArgument, "power of two"},
        {"direction", [](DetectSettings& s) { s.direction = std::array<float, 3>{0, 0, 0}; }, ErrorCode::InvalidArgument, "direction"},
        {"direction NaN", [](DetectSettings& s) { s.direction = std::array<float, 3>{std::nanf(""), 0, 1}; }, ErrorCode::InvalidArgument,
         "direction"},
        {"open epsilon", [](DetectSettings& s) { s.peeling.open_epsilon = -1.0f; }, ErrorCode::InvalidArgument, "open_epsilon"},
        {"closed epsilon", [](DetectSettings& s) { s.peeling.closed_epsilon = std::numeric_limits<float>::infinity(); },
         ErrorCode::InvalidArgument, "closed_epsilon"},
        {"region", [](DetectSettings& s) { s.region = std::array<float, 6>{1, 0, 0, 0, 1, 1}; }, ErrorCode::InvalidArgument,
         "min <= max"},
        {"axes", [](DetectSettings& s) { s.peeling.axes = 2; }, ErrorCode::InvalidArgument, "axes must be 1 or 3"},
        {"compute with dilation", [](DetectSettings& s) { s.peeling.coverage = Coverage::Dilate, s.peeling.backend = SamplingBackend::Compute; },
         ErrorCode::UnsupportedFeature, "raster sampling backend"},
        // The reliable method: cells per side, any count in [1, 16384].
        {"cells", [](DetectSettings& s) { s.method = DetectMethod::Reliable, s.resolution = 0; }, ErrorCode::InvalidArgument,
         "not in [1, 16384]"},
        {"cells too many", [](DetectSettings& s) { s.method = DetectMethod::Reliable, s.resolution = 16385; }, ErrorCode::InvalidArgument,
         "cells per side"},
        {"reliable direction", [](DetectSettings& s) { s.method = DetectMethod::Reliable, s.direction = std::array<float, 3>{0, 0, 0}; },
         ErrorCode::InvalidArgument, "direction"},
        {"method", [](DetectSettings& s) { s.method = static_cast<DetectMethod>(5); }, ErrorCode::InvalidArgument, "DetectMethod"},
    };
    for (const Bad& b : bad) {
        INFO(b.what);
        DetectSettings s;
        s.method = DetectMethod::Peeling;  // the paper's rules unless the case says otherwise
        b.spoil(s);
        auto r = (*world)->detect(s);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == b.code);
        CHECK(mentions(r.error(), b.says));
        auto resolved = (*world)->resolveSettings(s);  // the same gate
        REQUIRE_FALSE(resolved);
        CHECK(resolved.error().message() == r.error().message());
        CHECK_FALSE((*world)->submit(s));
        CHECK_FALSE((*world)->pending());
    }
    CHECK((*world)->detect());  // still usable
    // What only shapes the paper's ray sampling does not concern the reliable method.
    DetectSettings reliable;
    reliable.resolution = 100;
    reliable.peeling.coverage = Coverage::Dilate;
    reliable.peeling.backend = SamplingBackend::Compute;
    CHECK((*world)->detect(reliable));
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

// A value outside an enum of the settings selected no branch: Coverage(77)
// made the paper's method sample nothing and return no pairs, without an error. Every enum
// of DetectSettings is checked by the gate, under either method (the reliable method
// ignores coverage, backend and packing, but a value outside them is still a caller's bug).
TEST_CASE("enum values out of range are refused at the API, naming the field", "[api][gpu][validation]") {
    ValidatedContext ctx;
    auto world = CollisionWorld::create(ctx.context(), {.threads = 1});
    REQUIRE(world);
    auto sphere = uvSphere(1.0f, 12, 6);
    REQUIRE(sphere);
    REQUIRE((*world)->addMesh(*sphere));
    struct Bad {
        const char* says;
        void (*spoil)(DetectSettings&, int);
    };
    const Bad bad[] = {
        {"method", [](DetectSettings& s, int v) { s.method = static_cast<DetectMethod>(v); }},
        {"peeling.coverage", [](DetectSettings& s, int v) { s.peeling.coverage = static_cast<Coverage>(v); }},
        {"peeling.backend", [](DetectSettings& s, int v) { s.peeling.backend = static_cast<SamplingBackend>(v); }},
        {"peeling.packing", [](DetectSettings& s, int v) { s.peeling.packing = static_cast<PackingMethod>(v); }},
        {"bad_objects", [](DetectSettings& s, int v) { s.bad_objects = static_cast<BadObjectPolicy>(v); }},
    };
    const char* types[] = {"DetectMethod", "Coverage", "SamplingBackend", "PackingMethod", "BadObjectPolicy"};
    for (DetectMethod method : {DetectMethod::Peeling, DetectMethod::Reliable})
        for (int value : {77, -1})
            for (std::size_t k = 0; k < std::size(bad); ++k) {
                INFO(bad[k].says << " = " << value << ", method " << toString(method));
                DetectSettings s;
                s.method = method;
                bad[k].spoil(s, value);
                auto r = (*world)->detect(s);
                REQUIRE_FALSE(r);
                CHECK(r.error().code() == ErrorCode::InvalidArgument);
                CHECK(r.error().message().rfind(std::string(bad[k].says) + " " + std::to_string(value) + " is not a " + types[k], 0) == 0);
                auto resolved = (*world)->resolveSettings(s);
                REQUIRE_FALSE(resolved);
                CHECK(resolved.error().message() == r.error().message());
                CHECK_FALSE((*world)->submit(s));
                CHECK_FALSE((*world)->pending());
            }
    // The last value of each enum is still accepted (the paper's method reads them all).
    DetectSettings last;
    last.method = DetectMethod::Peeling;
    last.peeling.coverage = Coverage::Best;
    last.peeling.packing = PackingMethod::Paper;
    last.bad_objects = BadObjectPolicy::Fail;
    last.peeling.backend = SamplingBackend::Raster;
    auto r = (*world)->detect(last);
    REQUIRE(r);
    last.peeling.backend = SamplingBackend::Compute;
    last.peeling.coverage = Coverage::Centre;
    CHECK((*world)->detect(last));
    CHECK((*world)->detect());
    REQUIRE_NO_VALIDATION_MESSAGES(ctx);
}

TEST_CASE("engine mesh layouts are checked without a device", "[api][validation]") {
    GpuMeshDesc d;
    d.vertex_buffer = reinterpret_cast<VkBuffer>(std::uintptr_t{1});
    d.index_buffer = reinterpret_cast<VkBuffer>(std::uintptr_t{2});
    d.vertex_count = 4;
    d.vertex_buffer_size = 48;
    d.index_count = 6;
    d.index_buffer_size = 24;
    CHECK(validation::checkGpuMeshDesc(d));
    GpuMeshDesc short16 = d;
    short16.index_type = VK_INDEX_TYPE_UINT16;
    short16.index_count = 3;
    short16.index_buffer_size = 6;  // 3 x 2 bytes, but read in whole words: 8 needed
    auto r = validation::checkGpuMeshDesc(short16);
    REQUIRE_FALSE(r);
    CHECK(r.error().code() == ErrorCode::BufferTooSmall);
    CHECK(mentions(r.error(), "pad by 2 bytes"));
    short16.index_buffer_size = 8;
    CHECK(validation::checkGpuMeshDesc(short16));
    GpuMeshDesc other = d;
    other.vertex_stride = 16;  // a different layout of the same topology: fine
    other.vertex_buffer_size = 64;
    CHECK(validation::checkSameTopology(d, other));
    other.index_count = 9;
    auto topology = validation::checkSameTopology(d, other);
    REQUIRE_FALSE(topology);
    CHECK(mentions(topology.error(), "index count 9 differs from the 6"));
    other = d;
    other.position_format = VK_FORMAT_R32G32B32A32_SFLOAT;
    CHECK_FALSE(validation::checkSameTopology(d, other));
    CHECK(validation::vertexBytes(d) == 48);
    CHECK(validation::indexBytes(short16) == 8);
    CHECK(validation::checkTypicalEdge(0.0f));
    CHECK_FALSE(validation::checkTypicalEdge(-1.0f));
    const Float3 points[2] = {{0, 0, 0}, {1, std::numeric_limits<float>::quiet_NaN(), 0}};
    CHECK_FALSE(validation::checkVertices(points, 3));
    auto nan = validation::checkVertices(points, 2);
    REQUIRE_FALSE(nan);
    CHECK(nan.error().message() == "vertex 1 is NaN or infinite");
}

TEST_CASE("GPU check findings are worded from data", "[api][validation]") {
    passes::ObjectFault index{3, passes::ObjectFault::Kind::IndexOutOfRange, 7, 2, 50};
    CHECK(passes::describe(index) == "triangle 7 has an index >= the vertex count 50 (2 triangles affected)");
    passes::ObjectFault nan{0, passes::ObjectFault::Kind::NonFinitePosition, 1, 9, 12};
    CHECK(passes::describe(nan) == "triangle 1 has a vertex position that is NaN or infinite, or beyond +-1e30 after the object's "
                                   "transform (the sampling range) (9 triangles affected)");
    passes::ObjectFault far{2, passes::ObjectFault::Kind::OutOfRange, 4, 1, 30};
    CHECK(passes::describe(far) ==
          "triangle 4 has a position, transform entry or world coordinate of magnitude 2^62 or more (the reliable method's limit)");
}
