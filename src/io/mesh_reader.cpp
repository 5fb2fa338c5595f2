// Format dispatch and file reading for the mesh readers.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>

#include <sys/stat.h>

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

namespace {

// The readers allocate only what the input's bytes can hold, but a large valid file can
// still need more memory than there is: the API does not throw, so that is OutOfMemory.
Error outOfMemory(std::string_view source_name, std::string_view what) {
    return Error(ErrorCode::OutOfMemory, std::string(source_name) + ": out of host memory " + std::string(what));
}

}  // namespace

Result<std::vector<HostMesh>> readMesh(std::string_view in_data, MeshFormat format, std::string_view source_name) {
    try {
        switch (format) {
            case MeshFormat::Obj: return io_detail::readObj(in_data, source_name);
            case MeshFormat::Off: return io_detail::readOff(in_data, source_name);
            case MeshFormat::Ply: return io_detail::readPly(in_data, source_name);
        }
    } catch (const std::bad_alloc&) {
        return outOfMemory(source_name, "while parsing " + std::to_string(in_data.size()) + " bytes");
    } catch (const std::length_error&) {
        return outOfMemory(source_name, "while parsing " + std::to_string(in_data.size()) + " bytes");
    }
    return Error(ErrorCode::InvalidArgument, std::string(source_name) + ": unknown MeshFormat value");
}

Result<std::vector<HostMesh>> readMeshFile(const std::string& path) {
    Result<MeshFormat> format = meshFormatFromPath(path);
    if (!format) return format.error();

    // stdio rather than iostreams: errno says why an open or read failed.
    const auto io_error = [&path](const char* what, int error_number) {
        return Error(ErrorCode::IoError, path + ": " + what + ": " + std::strerror(error_number));
    };
    // Only regular files (symbolic links are followed): a device such as /dev/zero never
    // ends, a FIFO blocks, a directory has nothing to read. Checked before opening, since
    // opening a FIFO already blocks, and again on the opened file.
    struct stat info {};
    errno = 0;
    if (::stat(path.c_str(), &info) != 0) return io_error("cannot open", errno);
    const auto not_regular = [&path] {
        return Error(ErrorCode::IoError, path + ": not a regular file (a device, pipe, socket or directory); "
                                                "mesh files are read from regular files only");
    };
    if (!S_ISREG(info.st_mode)) return not_regular();
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) return io_error("cannot open", errno);
    if (::fstat(::fileno(file.get()), &info) != 0) return io_error("cannot read", errno);
    if (!S_ISREG(info.st_mode)) return not_regular();
    const auto size = static_cast<std::uint64_t>(info.st_size);
    if (size > kMaxMeshFileBytes)
        return Error(ErrorCode::IoError, path + ": " + std::to_string(size) + " bytes exceed the readers' limit of " +
                                             std::to_string(kMaxMeshFileBytes) + " bytes (kMaxMeshFileBytes)");
    std::string data;
    try {
        data.resize(static_cast<std::size_t>(size));
    } catch (const std::bad_alloc&) {
        return outOfMemory(path, "for the file's " + std::to_string(size) + " bytes");
    } catch (const std::length_error&) {
        return outOfMemory(path, "for the file's " + std::to_string(size) + " bytes");
    }
    // Read what fstat promised, no more: a file that grows meanwhile is read as it was.
    const std::size_t got = std::fread(data.data(), 1, data.size(), file.get());
    if (std::ferror(file.get())) return io_error("cannot read", errno != 0 ? errno : EIO);
    data.resize(got);
    return readMesh(data, *format, path);
}

}  // namespace vkcollide
