#include <catch2/catch.hpp>

#include "vkcollide/result.hpp"

using namespace vkcollide;

TEST_CASE("Result holds a value or an error", "[core]") {
    Result<int> ok = 42;
    REQUIRE(ok);
    CHECK(*ok == 42);
    Result<int> bad = Error(ErrorCode::InvalidMesh, "mesh 'a': vertex 3 is not finite");
    REQUIRE_FALSE(bad);
    CHECK(bad.error().code() == ErrorCode::InvalidMesh);
    CHECK(bad.error().message() == "mesh 'a': vertex 3 is not finite");
    Result<void> fine;
    CHECK(fine);
    Result<void> broken = Error(ErrorCode::VulkanError, "vkX failed", -4);
    CHECK_FALSE(broken);
    CHECK(broken.error().vkResult() == -4);
}

TEST_CASE("every error code has a distinct name", "[core]") {
    std::vector<std::string> names;
    for (int c = 0; c <= static_cast<int>(ErrorCode::LimitExceeded); ++c) names.push_back(toString(static_cast<ErrorCode>(c)));
    std::sort(names.begin(), names.end());
    CHECK(std::adjacent_find(names.begin(), names.end()) == names.end());
    CHECK(std::find(names.begin(), names.end(), std::string("unknown error")) == names.end());
}
