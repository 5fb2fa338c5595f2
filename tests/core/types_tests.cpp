#include <catch2/catch.hpp>

#include <string>

#include "vkcollide/types.hpp"

using namespace vkcollide;

TEST_CASE("shared enums are named as the command-line options spell them", "[core]") {
    CHECK(std::string(toString(PackingMethod::Scan)) == "scan");
    CHECK(std::string(toString(PackingMethod::Paper)) == "paper");
    CHECK(std::string(toString(Coverage::Centre)) == "centre");
    CHECK(std::string(toString(Coverage::Dilate)) == "dilate");
    CHECK(std::string(toString(Coverage::Conservative)) == "conservative");
    CHECK(std::string(toString(Coverage::Best)) == "best");
    CHECK(std::string(toString(SamplingBackend::Auto)) == "auto");
    CHECK(std::string(toString(SamplingBackend::Raster)) == "raster");
    CHECK(std::string(toString(SamplingBackend::Compute)) == "compute");
    CHECK(std::string(toString(DetectMethod::Reliable)) == "reliable");
    CHECK(std::string(toString(DetectMethod::Peeling)) == "peeling");
    CHECK(std::string(toString(static_cast<DetectMethod>(7))) == "?");
    // Out-of-range values (a cast from bad data) do not crash.
    CHECK(std::string(toString(static_cast<Coverage>(99))) == "?");
}

TEST_CASE("the identity transform maps every point to itself", "[core]") {
    const Float3 p{1.5f, -2.0f, 3.25f};
    const Transform3x4& t = kIdentity3x4;
    CHECK(t[0] * p.x + t[1] * p.y + t[2] * p.z + t[3] == p.x);
    CHECK(t[4] * p.x + t[5] * p.y + t[6] * p.z + t[7] == p.y);
    CHECK(t[8] * p.x + t[9] * p.y + t[10] * p.z + t[11] == p.z);
}
