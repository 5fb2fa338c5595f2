// Format dispatch and file reading for the mesh readers.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "io/reader_util.hpp"

namespace vkcollide {

Result<MeshFormat> meshFormatFromPath(std::string_view path) {
    const std::size_t dot = path.rfind('.');
    const std::size_t slash = path.find_last_of("/\\");
    std::string extension;
    if (dot != std::string_view::npos && (slash == std::string_view::npos || dot > slash)) {
        for (const char c : path.substr(dot + 1))
            extension += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    }
    if (extension == "obj") return MeshFormat::Obj;
    if (extension == "off") return MeshFormat::Off;
    if (extension == "ply") return MeshFormat::Ply;
    return Error(ErrorCode::InvalidArgument,
                 std::string(path) + ": unknown mesh file extension (expected .obj, .off or .ply)");
}

Result<std::vector<HostMesh>> readMesh(std::string_view in_data, MeshFormat format, std::string_view source_name) {
    switch (format) {
        case MeshFormat::Obj: return io_detail::readObj(in_data, source_name);
        case MeshFormat::Off: return io_detail::readOff(in_data, source_name);
        case MeshFormat::Ply: return io_detail::readPly(in_data, source_name);
    }
    return Error(ErrorCode::InvalidArgument, std::string(source_name) + ": unknown MeshFormat value");
}

Result<std::vector<HostMesh>> readMeshFile(const std::string& path) {
    Result<MeshFormat> format = meshFormatFromPath(path);
    if (!format) return format.error();

    // stdio rather than iostreams: errno says why an open or read failed, and a
    // directory opens but fails on read (EISDIR), which ferror() catches.
    const auto io_error = [&path](const char* what, int error_number) {
        return Error(ErrorCode::IoError, path + ": " + what + ": " + std::strerror(error_number));
    };
    errno = 0;
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) return io_error("cannot open", errno);
    std::string data;
    char buffer[1 << 16];
    while (true) {
        const std::size_t got = std::fread(buffer, 1, sizeof(buffer), file.get());
        data.append(buffer, got);
        if (got < sizeof(buffer)) break;
    }
    if (std::ferror(file.get())) return io_error("cannot read", errno != 0 ? errno : EIO);
    return readMesh(data, *format, path);
}

}  // namespace vkcollide
