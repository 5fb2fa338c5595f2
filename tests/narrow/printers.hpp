// Catch2 printers for narrow-phase types, so failed comparisons show the values.
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include "vkcollide/narrow.hpp"

namespace Catch {
template <>
struct StringMaker<vkcollide::TrianglePair> {
    static std::string convert(const vkcollide::TrianglePair& p) {
        return "(" + std::to_string(p.object_a) + ":" + std::to_string(p.triangle_a) + ", " + std::to_string(p.object_b) +
               ":" + std::to_string(p.triangle_b) + ")";
    }
};
}  // namespace Catch
