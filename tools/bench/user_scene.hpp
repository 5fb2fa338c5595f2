// The user's own scene from mesh files, shared by vkcollide_bench (--mesh FILE[:x,y,z]) and
// vkcollide_peer_bench (--scene a.obj,b.off:x,y,z): the library's readers (vkcollide/io.hpp) read
// each file, and every OBJ group or OFF/PLY file is one object, self-colliding as in the
// built-in scenes.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "bench_scenes.hpp"

namespace vkcollide::bench {

struct MeshFile {
    std::string path;
    Float3 offset{0, 0, 0};  // moves the file's objects in world space
};

// "FILE" or "FILE:x,y,z". The text after the last ':' is an offset only when it is three
// comma-separated finite numbers, so a path that holds ':' still reads as a path.
// Error: InvalidArgument for an empty path.
Result<MeshFile> parseMeshFile(std::string_view text);

// A comma-separated list of FILE or FILE:x,y,z (vkcollide_peer_bench --scene), each item read
// by parseMeshFile. The offset's own commas are told from the list's: an item and the two
// after it are one FILE:x,y,z where, joined, they read as a file with an offset.
// Error: InvalidArgument for an empty list or an item without a file name.
Result<std::vector<MeshFile>> parseMeshList(std::string_view text);

// "a/bunny.off" -> "bunny".
std::string fileStem(const std::string& path);

// The scene of `files` in set `set`. per_frame 0: all files make one rigid frame; else frame
// f is files [f * per_frame, (f + 1) * per_frame) of a deforming scene whose frames keep
// frame 0's topology (checked when a frame is built; the error names the files). Named
// after frame 0's file stems, '+' between them ("-sequence" after a deforming one), with
// '_' for any character but letters, digits and . _ -.
// Frame 0 is read here, so that a file that is missing or unreadable, holds no triangle or
// a coordinate that is not finite fails before any GPU work, with the reader's error (which
// names the file).
Result<SceneSpec> userScene(const std::vector<MeshFile>& files, std::size_t per_frame, SceneSet set);

}  // namespace vkcollide::bench
