// Values on the command line: strict numbers, number lists, enum names and file lists.
// Every parser's error starts with what was expected ("needs a number from 1 to 1024, got
// '0'"); the caller puts the option first ("--threads needs ..."), so every message names
// the option and the problem.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vkcollide/result.hpp"
#include "vkcollide/types.hpp"
#include "vkcollide/world.hpp"

namespace cli {

using vkcollide::Error;
using vkcollide::Result;

Error badValue(std::string what);  // ErrorCode::InvalidArgument

// A whole decimal number (no sign, no spaces, no trailing text) in [lo, hi].
Result<std::uint32_t> parseUint(std::string_view text, std::uint32_t lo = 0, std::uint32_t hi = 0xFFFFFFFFu);
// A finite float (decimal or exponent form, no trailing text).
Result<std::uint64_t> parseUint64(std::string_view text);
Result<float> parseFloat(std::string_view text);
// Comma-separated finite floats, as many as there are.
Result<std::vector<float>> parseFloatList(std::string_view text);
// Exactly N comma-separated finite floats.
template <std::size_t N>
Result<std::array<float, N>> parseFloats(std::string_view text) {
    auto list = parseFloatList(text);
    if (!list) return list.error();
    if (list->size() != N)
        return badValue("needs " + std::to_string(N) + " comma-separated numbers, got " + std::to_string(list->size()) + " in '" +
                        std::string(text) + "'");
    std::array<float, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = (*list)[i];
    return out;
}

// Names of enum values as the options spell them: vkcollide's toString (found by argument-
// dependent lookup, so a new settings enum with a toString needs nothing here), or the
// tool's own where the library has none.
const char* enumName(vkcollide::BadObjectPolicy v);
template <typename E>
const char* enumName(E v) {
    return toString(v);
}

// Every value of an enum whose values are 0, 1, ... (enumName gives "?" past the last).
template <typename E>
std::vector<E> enumValues() {
    std::vector<E> out;
    for (int i = 0; i < 64 && std::string_view(enumName(static_cast<E>(i))) != "?"; ++i) out.push_back(static_cast<E>(i));
    return out;
}
// "scan or paper", "auto, raster or compute".
template <typename E>
std::string enumChoices() {
    const std::vector<E> values = enumValues<E>();
    std::string out;
    for (std::size_t i = 0; i < values.size(); ++i)
        out += std::string(i == 0 ? "" : (i + 1 == values.size() ? " or " : ", ")) + enumName(values[i]);
    return out;
}
template <typename E>
Result<E> parseEnum(std::string_view text) {
    for (E v : enumValues<E>())
        if (text == enumName(v)) return v;
    return badValue("needs " + enumChoices<E>() + ", got '" + std::string(text) + "'");
}

// A set of file slots (numbered from 1): "all", "none", or numbers and ranges "1,3-5".
// `count`: how many slots there are (files, or files per frame with --sequence);
// `count_text` says so in an error ("there are 2 files").
Result<std::vector<bool>> parseFileList(std::string_view text, std::size_t count, const std::string& count_text);
// "LIST:VALUE" (the value may itself hold ':'): the file list and the value.
struct FileValue {
    std::vector<bool> files;
    std::string_view value;
};
Result<FileValue> parseFileValue(std::string_view text, std::size_t count, const std::string& count_text);

}  // namespace cli
