// The readers' tests: the message of a refused file, checked to be a ParseError.
#pragma once

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide::test {

inline std::string errorOf(const Result<std::vector<HostMesh>>& result) {
    REQUIRE_FALSE(result);
    CHECK(result.error().code() == ErrorCode::ParseError);
    return result.error().message();
}

}  // namespace vkcollide::test
