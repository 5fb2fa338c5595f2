#include "cli/values.hpp"

#include <charconv>
#include <cmath>

namespace cli {

Error badValue(std::string what) { return Error(vkcollide::ErrorCode::InvalidArgument, std::move(what)); }

Result<std::uint32_t> parseUint(std::string_view text, std::uint32_t lo, std::uint32_t hi) {
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    const std::string range = "from " + std::to_string(lo) + " to " + std::to_string(hi);
    if (text.empty() || ec == std::errc::invalid_argument || end != text.data() + text.size() ||
        ec == std::errc::result_out_of_range || v < lo || v > hi)
        return badValue("needs a number " + range + ", got '" + std::string(text) + "'");
    return static_cast<std::uint32_t>(v);
}

Result<std::uint64_t> parseUint64(std::string_view text) {
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size())
        return badValue("needs a whole number from 0 to 18446744073709551615, got '" + std::string(text) + "'");
    return v;
}

Result<float> parseFloat(std::string_view text) {
    float v = 0;
    // from_chars takes no leading '+'; accept it as people write it.
    const std::string_view digits = !text.empty() && text[0] == '+' ? text.substr(1) : text;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(v))
        return badValue("needs a finite number, got '" + std::string(text) + "'");
    return v;
}

Result<std::vector<float>> parseFloatList(std::string_view text) {
    std::vector<float> out;
    for (std::size_t at = 0;;) {
        const std::size_t comma = text.find(',', at);
        auto v = parseFloat(text.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at));
        if (!v) return v.error();
        out.push_back(*v);
        if (comma == std::string_view::npos) return out;
        at = comma + 1;
    }
}

const char* enumName(vkcollide::BadObjectPolicy v) {
    switch (v) {
        case vkcollide::BadObjectPolicy::Exclude: return "exclude";
        case vkcollide::BadObjectPolicy::Fail: return "fail";
    }
    return "?";
}

Result<std::vector<bool>> parseFileList(std::string_view text, std::size_t count, const std::string& count_text) {
    std::vector<bool> out(count, false);
    if (text == "all") return std::vector<bool>(count, true);
    if (text == "none") return out;
    for (std::size_t at = 0;;) {
        const std::size_t comma = text.find(',', at);
        const std::string_view item = text.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at);
        const std::size_t dash = item.find('-');
        auto first = parseUint(item.substr(0, dash));
        auto last = dash == std::string_view::npos ? first : parseUint(item.substr(dash + 1));
        if (!first || !last)
            return badValue("needs all, none or file numbers like 1,3-4 (from 1 in command-line order), got '" + std::string(text) + "'");
        if (*first < 1 || *last < *first || *last > count)
            return badValue("names file " + std::string(item) + ", but " + count_text + " (numbered from 1)");
        for (std::uint32_t f = *first; f <= *last; ++f) out[f - 1] = true;
        if (comma == std::string_view::npos) return out;
        at = comma + 1;
    }
}

Result<FileValue> parseFileValue(std::string_view text, std::size_t count, const std::string& count_text) {
    const std::size_t colon = text.find(':');
    if (colon == std::string_view::npos)
        return badValue("needs FILES:VALUE (e.g. 2:... or all:...), got '" + std::string(text) + "'");
    auto files = parseFileList(text.substr(0, colon), count, count_text);
    if (!files) return files.error();
    return FileValue{std::move(*files), text.substr(colon + 1)};
}

}  // namespace cli
