#include "cli/file_options.hpp"

#include <cmath>

namespace cli {
namespace {

using vkcollide::Transform3x4;

// 3x4 row-major affine transforms: outer applied after inner.
Transform3x4 compose(const Transform3x4& outer, const Transform3x4& inner) {
    Transform3x4 out{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            double s = c == 3 ? outer[r * 4 + 3] : 0.0;
            for (int k = 0; k < 3; ++k) s += double(outer[r * 4 + k]) * inner[k * 4 + c];
            out[r * 4 + c] = static_cast<float>(s);
        }
    return out;
}
void applyAfter(FileSlot& slot, const Transform3x4& op) { slot.options.transform = compose(op, slot.options.transform); }

}  // namespace

Result<void> slotTransform(FileSlot& slot, std::string_view text) {
    auto m = parseFloats<12>(text);
    if (!m) return m.error();
    applyAfter(slot, *m);
    return {};
}
Result<void> slotTranslate(FileSlot& slot, std::string_view text) {
    auto t = parseFloats<3>(text);
    if (!t) return t.error();
    applyAfter(slot, {1, 0, 0, (*t)[0], 0, 1, 0, (*t)[1], 0, 0, 1, (*t)[2]});
    return {};
}
Result<void> slotRotate(FileSlot& slot, std::string_view text) {
    auto a = parseFloats<4>(text);
    if (!a) return a.error();
    const double len = std::sqrt(double((*a)[0]) * (*a)[0] + double((*a)[1]) * (*a)[1] + double((*a)[2]) * (*a)[2]);
    if (!(len > 0)) return badValue("needs a non-zero axis x,y,z then degrees, got '" + std::string(text) + "'");
    // Rodrigues: R = cos I + sin [k]x + (1 - cos) k k^T.
    const double x = (*a)[0] / len, y = (*a)[1] / len, z = (*a)[2] / len, angle = (*a)[3] * 3.14159265358979323846 / 180.0;
    const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    const double r[9] = {c + t * x * x, t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, c + t * y * y,
                         t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, c + t * z * z};
    Transform3x4 op{};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) op[row * 4 + col] = static_cast<float>(r[row * 3 + col]);
    applyAfter(slot, op);
    return {};
}
Result<void> slotScale(FileSlot& slot, std::string_view text) {
    auto s = parseFloatList(text);
    if (!s || (s->size() != 1 && s->size() != 3))
        return badValue("needs one factor or three (x,y,z), got '" + std::string(text) + "'");
    const float x = (*s)[0], y = s->size() == 3 ? (*s)[1] : x, z = s->size() == 3 ? (*s)[2] : x;
    applyAfter(slot, {x, 0, 0, 0, 0, y, 0, 0, 0, 0, z, 0});
    return {};
}
Result<void> slotName(FileSlot& slot, std::string_view text) {
    if (text.empty()) return badValue("needs a name after the ':'");
    slot.options.name = std::string(text);
    return {};
}
Result<void> slotEdge(FileSlot& slot, std::string_view text) {
    auto e = parseFloat(text);
    if (!e || *e <= 0) return badValue("needs a length > 0 in object units, got '" + std::string(text) + "'");
    slot.options.typical_edge_length = *e;
    return {};
}
Result<void> slotOpen(FileSlot& slot, std::string_view) {
    slot.options.open = true;
    return {};
}
Result<void> slotSelf(FileSlot& slot, std::string_view) {
    slot.self_listed = true;
    return {};
}
Result<void> slotGpu(FileSlot& slot, std::string_view) {
    slot.gpu_mesh = true;
    return {};
}

}  // namespace cli
