// libFuzzer target: every input goes through all three readers. A reader may reject
// anything, but must not crash, hang, leak or trip a sanitizer, and what it accepts
// must keep the HostMesh promises (checked here so the fuzzer finds broken ones).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "vkcollide/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    for (const vkcollide::MeshFormat format :
         {vkcollide::MeshFormat::Obj, vkcollide::MeshFormat::Off, vkcollide::MeshFormat::Ply}) {
        const auto meshes = vkcollide::readMesh(bytes, format, "fuzz");
        if (!meshes) {
            if (meshes.error().message().empty()) std::abort();
            continue;
        }
        if (meshes->empty()) std::abort();
        for (const vkcollide::HostMesh& mesh : *meshes) {
            if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) std::abort();
            for (const std::uint32_t index : mesh.indices)
                if (index >= mesh.positions.size()) std::abort();
            for (const vkcollide::Float3& p : mesh.positions)
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
        }
    }
    return 0;
}
