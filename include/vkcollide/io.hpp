// vkcollide: strict readers (and small writers) for Wavefront OBJ, OFF and PLY meshes.
//
// The readers are written for untrusted input: every count is checked against what the
// input could possibly hold before anything is allocated, every index is range-checked,
// every coordinate must be finite as a float, and no input makes them crash or hang
// (tools/fuzz/fuzz_mesh_readers.cpp keeps it that way).
//
// Thread safety: all functions are reentrant; they share no state.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vkcollide/export.hpp"
#include "vkcollide/mesh.hpp"
#include "vkcollide/result.hpp"

namespace vkcollide {

enum class MeshFormat {
    Obj,  // Wavefront OBJ, text
    Off,  // Object File Format (OFF, COFF, NOFF, CNOFF, STOFF...), text
    Ply,  // Stanford PLY: ascii, binary_little_endian or binary_big_endian
};

// The format named by a path's extension (.obj, .off, .ply, any letter case).
// Error: InvalidArgument for any other extension.
VKCOLLIDE_API Result<MeshFormat> meshFormatFromPath(std::string_view path);

// Parses a whole mesh file held in memory.
//   in_data:     the file's bytes (text or binary PLY); only read during the call.
//   format:      how to read them.
//   source_name: used in error messages ("<source_name>:<line>: what") and to name
//                objects that the file does not name (its stem: "a/bunny.off" -> "bunny").
//
// What comes back, per format:
//   OBJ: one HostMesh per `o` / `g` group (faces before the first group form one
//        named after the source). Groups with the same name are merged. Vertices are
//        global in OBJ; each object gets only the vertices its faces use, in file
//        order (a file with one object keeps its vertex numbering). Faces accept v, v/vt, v/vt/vn and v//vn, and negative
//        (relative) indices; polygons are fan-triangulated. vt/vn/vp, s, usemtl, mtllib,
//        l, p and the other statements of the spec are ignored; unknown ones are errors.
//        Groups without faces are dropped.
//   OFF: one HostMesh. Comments (#), colours and normals are accepted and ignored;
//        polygons are fan-triangulated. 4OFF/nOFF and binary OFF are rejected.
//   PLY: one HostMesh from `element vertex` (scalar properties x, y, z of any type;
//        other properties ignored) and `element face` (a list property named
//        vertex_indices or vertex_index with any integer count and index types);
//        other elements are skipped. Polygons are fan-triangulated.
//
// Every mesh returned has at least one triangle, three indices per triangle, every
// index below its vertex count and finite coordinates.
//
// Errors: ParseError with "<source_name>:<line>: what" (binary PLY body:
// "<source_name>: byte <offset>: what"), naming the object for out-of-range indices and
// bad coordinates. Absurd counts, truncation and files without any triangle are
// ParseErrors too. OutOfMemory when host memory runs out (nothing is thrown).
VKCOLLIDE_API Result<std::vector<HostMesh>> readMesh(std::string_view in_data, MeshFormat format,
                                       std::string_view source_name);

// The largest file readMeshFile() reads (it holds the whole file in memory).
inline constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t(4) << 30;  // 4 GiB

// Reads the file at `path` and parses it with the format its extension names. Symbolic
// links are followed; the file they lead to must be a regular file.
// Errors: IoError when the file cannot be opened or read, is not a regular file (a
// device such as /dev/zero, a pipe, a directory) or is larger than kMaxMeshFileBytes;
// OutOfMemory when its bytes do not fit in memory; InvalidArgument for an unknown
// extension; and everything readMesh() returns.
VKCOLLIDE_API Result<std::vector<HostMesh>> readMeshFile(const std::string& path);

// --- Writers: exact round trip (shortest float text that reads back bit-exactly). ---
// The meshes are written as given; no validation. Used by the fuzz seed corpus and the
// round-trip tests.

enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

// One `o <name>` block per mesh; indices are made global (1-based) as OBJ wants.
VKCOLLIDE_API std::string writeObj(std::span<const HostMesh> meshes);
VKCOLLIDE_API std::string writeOff(const HostMesh& mesh);
// float x, y, z per vertex; `list uchar uint vertex_indices` per triangle.
VKCOLLIDE_API std::string writePly(const HostMesh& mesh, PlyEncoding encoding);

}  // namespace vkcollide
