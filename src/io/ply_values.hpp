// The values of a Stanford PLY file (ply_reader.cpp reads the header and the elements):
// the property types and encodings, and reading one value at a time, ascii or binary
// (either byte order), with bounds checks.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "io/reader_util.hpp"

namespace vkcollide::io_detail::ply {

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat : std::uint8_t { Ascii, BinaryLittleEndian, BinaryBigEndian };

inline bool parseType(std::string_view name, PlyType& out_type) {
    struct Named {
        std::string_view name;
        PlyType type;
    };
    // Both the original names and the sized aliases that newer writers use.
    static constexpr Named kTypes[] = {
        {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64},
    };
    for (const Named& t : kTypes) {
        if (t.name == name) {
            out_type = t.type;
            return true;
        }
    }
    return false;
}

inline std::size_t sizeOf(PlyType type) {
    switch (type) {
        case PlyType::Int8:
        case PlyType::UInt8: return 1;
        case PlyType::Int16:
        case PlyType::UInt16: return 2;
        case PlyType::Int32:
        case PlyType::UInt32:
        case PlyType::Float32: return 4;
        case PlyType::Float64: return 8;
    }
    return 1;
}

inline bool isInteger(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

// Range of each integer type, for checking ascii values.
inline void integerRange(PlyType type, std::int64_t& out_min, std::int64_t& out_max) {
    switch (type) {
        case PlyType::Int8: out_min = -128, out_max = 127; return;
        case PlyType::UInt8: out_min = 0, out_max = 255; return;
        case PlyType::Int16: out_min = -32768, out_max = 32767; return;
        case PlyType::UInt16: out_min = 0, out_max = 65535; return;
        case PlyType::Int32: out_min = -2147483648LL, out_max = 2147483647LL; return;
        case PlyType::UInt32: out_min = 0, out_max = 4294967295LL; return;
        case PlyType::Float32:
        case PlyType::Float64: out_min = 0, out_max = 0; return;
    }
}

// Where in the input a value was read: a line for ascii, a byte offset for binary.
struct Location {
    std::size_t value = 0;
    bool is_byte = false;
};

// Reads the values of element instances, ascii or binary, with bounds checks. All
// reads fail (return false) instead of running past the end.
class ValueSource {
public:
    ValueSource(std::string_view data, std::size_t body_offset, std::size_t body_line, PlyFormat format)
        : data_(data), pos_(body_offset), line_(body_line), format_(format) {}

    bool binary() const { return format_ != PlyFormat::Ascii; }
    std::size_t bytesLeft() const { return data_.size() - pos_; }
    Location where() const { return binary() ? Location{pos_, true} : Location{line_, false}; }

    // An integer value of an integer type (list counts, indices).
    bool readInteger(PlyType type, std::int64_t& out_value, std::string& out_problem) {
        if (binary()) {
            unsigned char bytes[8];
            if (!take(bytes, sizeOf(type), out_problem)) return false;
            out_value = decodeInteger(type, bytes);
            return true;
        }
        const std::string_view token = nextAsciiToken();
        if (token.empty()) return fail(out_problem, "truncated data: expected an integer");
        std::int64_t lo = 0, hi = 0;
        integerRange(type, lo, hi);
        if (!parseInt64(token, out_value) || out_value < lo || out_value > hi)
            return fail(out_problem, quoted(token) + " is not a valid integer of the declared type");
        return true;
    }

    // A value of any type, as double (coordinates).
    bool readReal(PlyType type, double& out_value, std::string& out_problem) {
        if (isInteger(type)) {
            std::int64_t value = 0;
            if (!readInteger(type, value, out_problem)) return false;
            out_value = static_cast<double>(value);
            return true;
        }
        if (binary()) {
            unsigned char bytes[8];
            if (!take(bytes, sizeOf(type), out_problem)) return false;
            if (type == PlyType::Float32) {
                out_value = static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(load(bytes, 4))));
            } else {
                out_value = std::bit_cast<double>(load(bytes, 8));
            }
            return true;
        }
        const std::string_view token = nextAsciiToken();
        if (token.empty()) return fail(out_problem, "truncated data: expected a number");
        if (!parseDouble(token, out_value)) return fail(out_problem, quoted(token) + " is not a number");
        return true;
    }

    // Skips `count` values of `type`; a binary skip is one bounds check, not a loop.
    bool skip(PlyType type, std::uint64_t count, std::string& out_problem) {
        if (binary()) {
            if (count > bytesLeft() / sizeOf(type)) return fail(out_problem, "truncated data");
            pos_ += static_cast<std::size_t>(count) * sizeOf(type);
            return true;
        }
        for (std::uint64_t i = 0; i < count; ++i) {
            double unused = 0;
            if (!readReal(type, unused, out_problem)) return false;
        }
        return true;
    }

    // Whatever follows the last element: ascii may end in whitespace, binary in nothing.
    bool atCleanEnd() {
        if (binary()) return pos_ == data_.size();
        return nextAsciiToken().empty();
    }

private:
    static bool fail(std::string& out_problem, std::string what) {
        out_problem = std::move(what);
        return false;
    }

    bool take(unsigned char* out_bytes, std::size_t size, std::string& out_problem) {
        if (bytesLeft() < size) return fail(out_problem, "truncated data");
        std::memcpy(out_bytes, data_.data() + pos_, size);
        pos_ += size;
        return true;
    }

    // Assembles `size` bytes in the file's byte order into an unsigned value.
    std::uint64_t load(const unsigned char* bytes, std::size_t size) const {
        std::uint64_t value = 0;
        for (std::size_t i = 0; i < size; ++i) {
            const std::size_t k = format_ == PlyFormat::BinaryBigEndian ? i : size - 1 - i;
            value = (value << 8) | bytes[k];
        }
        return value;
    }

    std::int64_t decodeInteger(PlyType type, const unsigned char* bytes) const {
        const std::uint64_t raw = load(bytes, sizeOf(type));
        switch (type) {
            case PlyType::Int8: return static_cast<std::int8_t>(raw);
            case PlyType::Int16: return static_cast<std::int16_t>(raw);
            case PlyType::Int32: return static_cast<std::int32_t>(raw);
            default: return static_cast<std::int64_t>(raw);
        }
    }

    std::string_view nextAsciiToken() {
        while (pos_ < data_.size() && (isSpace(data_[pos_]) || data_[pos_] == '\n')) {
            if (data_[pos_] == '\n') ++line_;
            ++pos_;
        }
        const std::size_t begin = pos_;
        while (pos_ < data_.size() && !isSpace(data_[pos_]) && data_[pos_] != '\n') ++pos_;
        return data_.substr(begin, pos_ - begin);
    }

    std::string_view data_;
    std::size_t pos_;
    std::size_t line_;
    PlyFormat format_;
};

}  // namespace vkcollide::io_detail::ply
