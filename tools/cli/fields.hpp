// How a DetectSettings field is read from its option's text and written into the JSON:
// by its type (uint32, uint64, float, std::array<float, N>, std::optional of those, an enum with
// a name per value in values.hpp), so a new field needs no code of its own here.
#pragma once

#include <array>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "cli/options.hpp"
#include "cli/values.hpp"

namespace cli::fields {

template <typename T>
struct IsOptional : std::false_type {};
template <typename T>
struct IsOptional<std::optional<T>> : std::true_type {};
template <typename T>
struct IsFloatArray : std::false_type {};
template <std::size_t N>
struct IsFloatArray<std::array<float, N>> : std::true_type {};

// One value of a settings field's type from its text.
template <typename T>
Result<T> parseAs(std::string_view text) {
    if constexpr (IsOptional<T>::value) {
        auto v = parseAs<typename T::value_type>(text);
        if (!v) return v.error();
        return T(*v);
    } else if constexpr (std::is_same_v<T, std::uint32_t>) {
        return parseUint(text);
    } else if constexpr (std::is_same_v<T, std::uint64_t>) {
        return parseUint64(text);
    } else if constexpr (std::is_same_v<T, float>) {
        return parseFloat(text);
    } else if constexpr (IsFloatArray<T>::value) {
        return parseFloats<std::tuple_size_v<T>>(text);
    } else {
        static_assert(std::is_enum_v<T>, "a settings field the table cannot parse: add its type to parseAs");
        return parseEnum<T>(text);
    }
}

inline std::string jsonNumber(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

// A settings field's value as JSON.
template <typename T>
std::string jsonOf(const T& v) {
    if constexpr (IsOptional<T>::value) {
        return v ? jsonOf(*v) : "null";
    } else if constexpr (std::is_same_v<T, bool>) {
        return v ? "true" : "false";
    } else if constexpr (std::is_arithmetic_v<T>) {
        return jsonNumber(static_cast<double>(v));
    } else if constexpr (IsFloatArray<T>::value) {
        std::string out = "[";
        for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + jsonNumber(v[i]);
        return out + "]";
    } else {
        static_assert(std::is_enum_v<T>, "a settings field the table cannot show: add its type to jsonOf");
        return std::string("\"") + enumName(v) + "\"";
    }
}

// A settings field by its path of members: &DetectSettings::region, or a grouped one,
// &DetectSettings::peeling, &PeelingSettings::dual.
template <auto First, auto... Rest>
constexpr auto& at(auto& s) {
    if constexpr (sizeof...(Rest) == 0) return s.*First;
    else return at<Rest...>(s.*First);
}

// The option's setter and the field's JSON, for the table (options.cpp).
template <auto... Path>
Result<void> setting(CommandLine& c, std::string_view text) {
    using T = std::remove_cvref_t<decltype(at<Path...>(c.settings))>;
    auto v = parseAs<T>(text);
    if (!v) return v.error();
    at<Path...>(c.settings) = std::move(*v);
    return {};
}
template <bool kValue, auto... Path>
Result<void> settingFlag(CommandLine& c, std::string_view) {
    at<Path...>(c.settings) = kValue;
    return {};
}
template <auto... Path>
std::string show(const vkcollide::DetectSettings& s) {
    return jsonOf(at<Path...>(s));
}

}  // namespace cli::fields
