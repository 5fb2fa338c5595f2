// fuzz_world's values: what the bytes of a program (world_program.hpp) stand for:
// coordinates, transforms, typical edges and DetectSettings, right and wrong ones.
#pragma once

#include <cstdint>
#include <string>

#include "fuzz/world_program.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide::fuzz {

// Bytes below kFirstSpecialCoordinate: the 1/16 grid in [-1, 15/16]; above: extremes (0,
// -0, subnormals, 1e-30, 1e30, 1e38, FLT_MAX, NaN, infinities, ...).
float coordinate(std::uint8_t b);
// Codes below kTransformTableSize: identity, translations, rotations, scales (0, 2, 1e20,
// 1e-30, 1e30), a mirror, a shear, NaN and infinite entries; above: the 12 coordinates.
Transform3x4 transformOf(const TransformCode& t);
// ObjectOptions::typical_edge_length: 0, good ones, negative, NaN, infinite, 1e-30.
float typicalEdge(std::uint8_t b);
// The 12 settings bytes (world_program.hpp lists the fields). Resolutions stay at most
// 256, so that no single detection is slow; the absurd ones are refused at once.
DetectSettings decodeSettings(const SettingsBytes& b);
// The fields that differ from the defaults (VKCOLLIDE_FUZZ_VERBOSE).
std::string describe(const DetectSettings& s);

}  // namespace vkcollide::fuzz
