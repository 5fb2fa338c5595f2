#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "vkcollide/mesh.hpp"

using namespace vkcollide;

namespace {
HostMesh triangle() {
    HostMesh m;
    m.name = "tri";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    return m;
}
}  // namespace

TEST_CASE("validateMesh accepts a good mesh", "[core][mesh]") { CHECK(validateMesh(triangle())); }

TEST_CASE("validateMesh names the mesh and the broken rule", "[core][mesh]") {
    SECTION("empty") {
        HostMesh m;
        m.name = "empty";
        auto r = validateMesh(m);
        REQUIRE_FALSE(r);
        CHECK(r.error().code() == ErrorCode::InvalidMesh);
        CHECK_THAT(r.error().message(), Catch::Contains("'empty'") && Catch::Contains("no triangles"));
    }
    SECTION("index count") {
        HostMesh m = triangle();
        m.indices.push_back(0);
        auto r = validateMesh(m);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("'tri'") && Catch::Contains("multiple of three"));
    }
    SECTION("out of range index") {
        HostMesh m = triangle();
        m.indices[2] = 7;
        auto r = validateMesh(m);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("index 7") && Catch::Contains("out of range"));
    }
    SECTION("NaN vertex") {
        HostMesh m = triangle();
        m.positions[1].y = std::numeric_limits<float>::quiet_NaN();
        auto r = validateMesh(m);
        REQUIRE_FALSE(r);
        CHECK_THAT(r.error().message(), Catch::Contains("vertex 1") && Catch::Contains("not finite"));
    }
    SECTION("infinite vertex") {
        HostMesh m = triangle();
        m.positions[2].z = std::numeric_limits<float>::infinity();
        CHECK_FALSE(validateMesh(m));
    }
}
