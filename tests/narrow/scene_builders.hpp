// Small mesh builders shared by the narrow-phase tests.
#pragma once

#include <cmath>
#include <cstdint>

#include "vkcollide/mesh.hpp"

namespace vkcollide::test {

// Unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), outward counter-clockwise faces.
inline HostMesh makeTetrahedron(const char* name = "tetra") {
    HostMesh m;
    m.name = name;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    return m;
}

// A closed UV sphere with `stacks` x `slices` quads (pole rows are fans):
// 2 * slices * (stacks - 1) triangles.
inline HostMesh makeSphere(float radius, Float3 centre, std::uint32_t stacks, std::uint32_t slices) {
    HostMesh m;
    m.name = "sphere";
    const double pi = 3.14159265358979323846;
    m.positions.push_back({centre.x, centre.y, centre.z + radius});
    for (std::uint32_t i = 1; i < stacks; ++i) {
        const double theta = pi * i / stacks;
        for (std::uint32_t j = 0; j < slices; ++j) {
            const double phi = 2 * pi * j / slices;
            m.positions.push_back({centre.x + static_cast<float>(radius * std::sin(theta) * std::cos(phi)),
                                   centre.y + static_cast<float>(radius * std::sin(theta) * std::sin(phi)),
                                   centre.z + static_cast<float>(radius * std::cos(theta))});
        }
    }
    m.positions.push_back({centre.x, centre.y, centre.z - radius});
    const std::uint32_t bottom = static_cast<std::uint32_t>(m.positions.size() - 1);
    const auto ring = [&](std::uint32_t i, std::uint32_t j) { return 1 + (i - 1) * slices + (j % slices); };
    for (std::uint32_t j = 0; j < slices; ++j) m.indices.insert(m.indices.end(), {0, ring(1, j), ring(1, j + 1)});
    for (std::uint32_t i = 1; i + 1 < stacks; ++i) {
        for (std::uint32_t j = 0; j < slices; ++j) {
            const std::uint32_t a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j), d = ring(i + 1, j + 1);
            m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
        }
    }
    for (std::uint32_t j = 0; j < slices; ++j) {
        m.indices.insert(m.indices.end(), {bottom, ring(stacks - 1, j + 1), ring(stacks - 1, j)});
    }
    return m;
}

}  // namespace vkcollide::test
