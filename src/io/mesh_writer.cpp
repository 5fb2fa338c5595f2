// Minimal OBJ/OFF/PLY writers: the readers' round-trip tests and the fuzz seed corpus.
#include <bit>
#include <charconv>
#include <cstdint>
#include <string>

#include "vkcollide/io.hpp"

namespace vkcollide {
namespace {

// Shortest text that reads back to the same float: round trips are exact.
void appendFloat(std::string& io_out, float value) {
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
    io_out.append(buffer, ec == std::errc() ? end : buffer);
}

void appendInt(std::string& io_out, std::uint64_t value) {
    char buffer[24];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
    io_out.append(buffer, ec == std::errc() ? end : buffer);
}

void appendPosition(std::string& io_out, const Float3& p) {
    appendFloat(io_out, p.x);
    io_out += ' ';
    appendFloat(io_out, p.y);
    io_out += ' ';
    appendFloat(io_out, p.z);
}

void appendBytes(std::string& io_out, std::uint32_t value, std::size_t size, bool big_endian) {
    for (std::size_t i = 0; i < size; ++i) {
        const std::size_t shift = 8 * (big_endian ? size - 1 - i : i);
        io_out += static_cast<char>((value >> shift) & 0xffu);
    }
}

}  // namespace

std::string writeObj(std::span<const HostMesh> meshes) {
    std::string out;
    std::uint64_t base = 1;  // OBJ indices are 1-based and global across objects
    for (const HostMesh& mesh : meshes) {
        out += "o ";
        out += mesh.name.empty() ? std::string("mesh") : mesh.name;
        out += '\n';
        for (const Float3& p : mesh.positions) {
            out += "v ";
            appendPosition(out, p);
            out += '\n';
        }
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            out += 'f';
            for (std::size_t k = 0; k < 3; ++k) {
                out += ' ';
                appendInt(out, base + mesh.indices[i + k]);
            }
            out += '\n';
        }
        base += mesh.positions.size();
    }
    return out;
}

std::string writeOff(const HostMesh& mesh) {
    std::string out = "OFF\n";
    appendInt(out, mesh.positions.size());
    out += ' ';
    appendInt(out, mesh.indices.size() / 3);
    out += " 0\n";
    for (const Float3& p : mesh.positions) {
        appendPosition(out, p);
        out += '\n';
    }
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        out += '3';
        for (std::size_t k = 0; k < 3; ++k) {
            out += ' ';
            appendInt(out, mesh.indices[i + k]);
        }
        out += '\n';
    }
    return out;
}

std::string writePly(const HostMesh& mesh, PlyEncoding encoding) {
    std::string out = "ply\nformat ";
    out += encoding == PlyEncoding::Ascii                ? "ascii"
           : encoding == PlyEncoding::BinaryLittleEndian ? "binary_little_endian"
                                                         : "binary_big_endian";
    out += " 1.0\ncomment written by vkcollide\nelement vertex ";
    appendInt(out, mesh.positions.size());
    out += "\nproperty float x\nproperty float y\nproperty float z\nelement face ";
    appendInt(out, mesh.indices.size() / 3);
    out += "\nproperty list uchar uint vertex_indices\nend_header\n";
    const bool big_endian = encoding == PlyEncoding::BinaryBigEndian;
    for (const Float3& p : mesh.positions) {
        if (encoding == PlyEncoding::Ascii) {
            appendPosition(out, p);
            out += '\n';
        } else {
            for (const float c : {p.x, p.y, p.z}) appendBytes(out, std::bit_cast<std::uint32_t>(c), 4, big_endian);
        }
    }
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        if (encoding == PlyEncoding::Ascii) {
            out += '3';
            for (std::size_t k = 0; k < 3; ++k) {
                out += ' ';
                appendInt(out, mesh.indices[i + k]);
            }
            out += '\n';
        } else {
            out += static_cast<char>(3);
            for (std::size_t k = 0; k < 3; ++k) appendBytes(out, mesh.indices[i + k], 4, big_endian);
        }
    }
    return out;
}

}  // namespace vkcollide
