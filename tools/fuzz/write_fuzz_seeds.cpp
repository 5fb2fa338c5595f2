// Writes the seed corpus for fuzz_mesh_readers: small generated meshes in every format
// and encoding the readers accept, plus a few hand-written files that use the syntax
// the writers never produce (groups, polygons, relative indices, comments, skipped
// PLY elements). Usage: write_fuzz_seeds <folder>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzz/seed_files.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

namespace {

// Through std::string: the literals below would otherwise reach writeSeed's span with their
// terminating zero.
bool writeFile(const std::string& path, const std::string& bytes) { return vkcollide::fuzz::writeSeed(path, bytes); }

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s <corpus folder>\n", argv[0]);
        return 2;
    }
    const std::string folder = argv[1];
    const bool made = vkcollide::fuzz::makeCorpusFolder(folder);
    std::vector<vkcollide::HostMesh> meshes;
    for (auto r : {vkcollide::uvSphere(1.0f, 5, 3), vkcollide::torus(2.0f, 0.5f, 4, 3),
                   vkcollide::box(vkcollide::Float3{1.0f, 0.5f, 2.0f}, 1), vkcollide::clothGrid(1.0f, 1.0f, 2, 1)}) {
        if (!r) {
            std::fprintf(stderr, "generator failed: %s\n", r.error().message().c_str());
            return 1;
        }
        meshes.push_back(std::move(*r));
    }
    bool ok = made && writeFile(folder + "/all.obj", vkcollide::writeObj(meshes));
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const std::string stem = folder + "/" + meshes[i].name;
        ok = ok && writeFile(stem + ".off", vkcollide::writeOff(meshes[i]));
        ok = ok && writeFile(stem + "_ascii.ply", vkcollide::writePly(meshes[i], vkcollide::PlyEncoding::Ascii));
        ok = ok && writeFile(stem + "_le.ply", vkcollide::writePly(meshes[i], vkcollide::PlyEncoding::BinaryLittleEndian));
        ok = ok && writeFile(stem + "_be.ply", vkcollide::writePly(meshes[i], vkcollide::PlyEncoding::BinaryBigEndian));
    }
    ok = ok && writeFile(folder + "/syntax.obj",
                         "# comment\nmtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                         "o quad\nusemtl m\ns 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\ng tri\nf -4//1 -3//1 -2//1\n"
                         "g\nf 1/1 3/1 \\\n 4/1\n");
    ok = ok && writeFile(folder + "/syntax.off",
                         "COFF # colours\n4 2 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n1 1 0 0 0 1 1\n0 1 0 1 1 1 1\n\n"
                         "4 0 1 2 3 255 0 0\n3 0 2 3\n");
    ok = ok && writeFile(folder + "/syntax.ply",
                         "ply\nformat ascii 1.0\ncomment c\nelement junk 1\nproperty list uchar double w\n"
                         "element vertex 3\nproperty double x\nproperty uchar r\nproperty float y\nproperty float z\n"
                         "element face 1\nproperty uchar flags\nproperty list uint int vertex_index\nend_header\n"
                         "2 0.5 0.5\n0 1 0 0\n1 2 0 0\n0 3 1 0\n7 3 0 1 2\n");
    // Integer extremes in every index position: the readers must refuse them without
    // overflowing (UBSan found -9223372036854775808 negated in the OBJ reader).
    ok = ok && writeFile(folder + "/extremes.obj",
                         "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\nf 9223372036854775807 1 2\n"
                         "f -1 -2 -3/-9223372036854775808/9223372036854775807\n");
    ok = ok && writeFile(folder + "/extremes.off",
                         "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -9223372036854775808\n");
    return vkcollide::fuzz::corpusStatus(ok, folder);
}
