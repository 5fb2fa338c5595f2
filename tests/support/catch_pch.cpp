// The translation unit that precompiles <catch2/catch.hpp> for the tests (tests/CMakeLists.txt).
