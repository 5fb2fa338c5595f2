// Internal helpers shared by the OBJ, OFF and PLY readers: line and token scanning,
// strict number parsing and error text. Nothing here allocates in proportion to a count
// read from the input.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "vkcollide/io.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide::io_detail {

// Per-format entry points (src/io/{obj,off,ply}_reader.cpp).
Result<std::vector<HostMesh>> readObj(std::string_view in_text, std::string_view source_name);
Result<std::vector<HostMesh>> readOff(std::string_view in_text, std::string_view source_name);
Result<std::vector<HostMesh>> readPly(std::string_view in_data, std::string_view source_name);

// "source<separator><position>: what"
inline Error parseErrorAt(std::string_view source_name, std::string_view separator, std::size_t position,
                          std::string_view what) {
    std::string message(source_name);
    message += separator;
    message += std::to_string(position);
    message += ": ";
    message += what;
    return Error(ErrorCode::ParseError, std::move(message));
}

inline Error parseErrorAtLine(std::string_view source_name, std::size_t line, std::string_view what) {
    return parseErrorAt(source_name, ":", line, what);
}

// Binary data has no lines; the byte offset from the start of the file locates it.
inline Error parseErrorAtByte(std::string_view source_name, std::size_t offset, std::string_view what) {
    return parseErrorAt(source_name, ": byte ", offset, what);
}

// "dir/bunny.off" -> "bunny": the name of an object the file does not name itself.
inline std::string stemOf(std::string_view path) {
    const std::size_t slash = path.find_last_of("/\\");
    if (slash != std::string_view::npos) path.remove_prefix(slash + 1);
    const std::size_t dot = path.rfind('.');
    if (dot != std::string_view::npos && dot > 0) path = path.substr(0, dot);
    return path.empty() ? std::string("mesh") : std::string(path);
}

inline std::string quoted(std::string_view text) {
    // Error messages quote input; cap it so a megabyte-long token cannot flood a log.
    constexpr std::size_t kMaxQuoted = 40;
    std::string out = "'";
    for (const char c : text.substr(0, kMaxQuoted)) {
        const auto u = static_cast<unsigned char>(c);
        out += (u >= 0x20 && u < 0x7f) ? c : '?';
    }
    if (text.size() > kMaxQuoted) out += "...";
    out += '\'';
    return out;
}

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Walks a text one line at a time; numbers lines from 1 and drops a trailing '\r'.
class LineCursor {
public:
    explicit LineCursor(std::string_view text) : rest_(text) {
        // A UTF-8 byte-order mark is not content (some Windows tools write one).
        if (rest_.starts_with("\xEF\xBB\xBF")) rest_.remove_prefix(3);
    }

    bool next(std::string_view& out_line) {
        if (rest_.empty()) return false;
        const std::size_t end = rest_.find('\n');
        out_line = rest_.substr(0, end);
        rest_.remove_prefix(end == std::string_view::npos ? rest_.size() : end + 1);
        if (!out_line.empty() && out_line.back() == '\r') out_line.remove_suffix(1);
        ++line_;
        return true;
    }
    std::size_t line() const { return line_; }
    std::size_t bytesLeft() const { return rest_.size(); }

private:
    std::string_view rest_;
    std::size_t line_ = 0;
};

// Pops the next whitespace-separated token off `io_rest`; empty when none is left.
inline std::string_view nextToken(std::string_view& io_rest) {
    std::size_t begin = 0;
    while (begin < io_rest.size() && isSpace(io_rest[begin])) ++begin;
    std::size_t end = begin;
    while (end < io_rest.size() && !isSpace(io_rest[end])) ++end;
    const std::string_view token = io_rest.substr(begin, end - begin);
    io_rest.remove_prefix(end);
    return token;
}

inline std::string_view stripComment(std::string_view line) {
    const std::size_t hash = line.find('#');
    return hash == std::string_view::npos ? line : line.substr(0, hash);
}

inline bool isBlank(std::string_view text) {
    for (const char c : text)
        if (!isSpace(c)) return false;
    return true;
}

// The whole token must be a number; from_chars rejects a leading '+', which some
// exporters write, so it is skipped here.
inline bool parseDouble(std::string_view token, double& out_value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), out_value);
    return ec == std::errc() && ptr == token.data() + token.size();
}

inline bool parseInt64(std::string_view token, std::int64_t& out_value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), out_value);
    return ec == std::errc() && ptr == token.data() + token.size();
}

// A coordinate is usable only when it is finite after narrowing to float: 1e39 is a
// fine double but infinite as a float.
inline bool toFiniteFloat(double value, float& out_value) {
    if (!std::isfinite(value) || std::fabs(value) > static_cast<double>(std::numeric_limits<float>::max()))
        return false;
    out_value = static_cast<float>(value);
    return true;
}

// Appends the fan (p0, pi, pi+1) of one polygon; the caller has checked count >= 3.
inline void appendFan(std::vector<std::uint32_t>& io_indices, const std::uint32_t* polygon, std::size_t count) {
    for (std::size_t i = 1; i + 1 < count; ++i) {
        io_indices.push_back(polygon[0]);
        io_indices.push_back(polygon[i]);
        io_indices.push_back(polygon[i + 1]);
    }
}

// Vertices past this count cannot be addressed by the 32-bit index type.
inline constexpr std::uint64_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();

}  // namespace vkcollide::io_detail
