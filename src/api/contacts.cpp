// Object-level contacts of one detection (DetectSettings::contacts.objects): the contact stage run
// on the detection's objects (bad engine meshes already left out) along its direction,
// with the pair filter's answers; its sums turned into ObjectContacts named by ObjectId,
// each marked contained or not from the detection's triangle pairs.
#include <algorithm>
#include <chrono>

#include "api/world_impl.hpp"
#include "contacts/contact_stage.hpp"
#include "contacts/pair_contacts.hpp"
#include "narrow/slots.hpp"

namespace vkcollide {
namespace {

Float3 toFloat3(const std::array<double, 3>& v) {
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

}  // namespace

Result<void> CollisionWorld::Impl::addPairContacts(const Run& run, const passes::DetectionResult& detected, std::span<const ObjectId> ids,
                                                   DetectResult& out) {
    const auto t0 = std::chrono::steady_clock::now();
    // ids[i] is the detection's object i, run mesh detected.objects[i]: run meshes by id.
    std::vector<std::uint32_t> mesh_of(ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end()) + 1, 0);
    for (std::size_t i = 0; i < ids.size(); ++i) mesh_of[ids[i]] = detected.objects[i];
    const auto lookup = [&](std::uint32_t id, std::uint32_t triangle) {
        const std::uint32_t k = mesh_of[id];
        const std::span<const Float3> positions = run.positions[k];
        const std::vector<std::uint32_t>& indices = registry.objects[id].host_indices;
        const Transform3x4& m = run.meshes[k].transform;
        std::array<Float3, 3> v;
        for (int c = 0; c < 3; ++c) v[c] = narrow::toWorld(m, positions[indices[3 * std::size_t{triangle} + c]]);
        return v;
    };
    contacts::pairContacts(out.pairs, lookup, *executor, out.pair_contacts, out.pair_contact_totals);
    out.stats.contacts.geometry_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return {};
}

Result<void> CollisionWorld::Impl::addContacts(const Run& run, const passes::DetectionResult& detected, std::span<const ObjectId> ids,
                                               DetectResult& out) {
    const auto t0 = std::chrono::steady_clock::now();
    // A follow-up of the slot's detection: on the objects it tested, within what is left of
    // its deadline, on its executor and buffer table.
    auto stage = run.detection->followUp(passes::ContactStage::create);
    if (!stage) return stage.error();
    auto& contact_stage = static_cast<passes::ContactStage&>(**stage);  // what ContactStage::create makes
    passes::ContactInput in;
    in.direction = detected.directions[0];
    in.resolution = *run.settings.contacts.resolution;
    // The filter's answers, as the narrow phase had them (detect.cpp): the kept mask, or
    // the filter itself beyond the mask's object limit.
    std::optional<Error> filter_threw;
    const passes::ObjectPairMask* mask =
        registry.pair_filter && registry.pair_mask.objects == run.ids.size() && !registry.pair_mask_dirty ? &registry.pair_mask : nullptr;
    const std::vector<std::uint32_t>& live = detected.objects;
    if (mask) {
        in.may_collide = [mask, &live](std::uint32_t a, std::uint32_t b) { return mask->allows(live[a], live[b]); };
    } else if (registry.pair_filter) {
        in.may_collide = [this, ids, &filter_threw](std::uint32_t a, std::uint32_t b) {
            if (filter_threw) return false;
            auto answer = registry.callPairFilter(ids[a], ids[b]);
            if (answer) return *answer;
            filter_threw = answer.error();
            return false;
        };
    }
    contact_stage.setInput(std::move(in));
    auto ran = run.detection->runFollowUp(contact_stage);
    if (filter_threw) return *filter_threw;
    if (!ran) return ran.error();
    const passes::ContactStageResult* r = &contact_stage.result();

    // Object pairs with intersecting triangles (ObjectIds, a < b): not contained.
    std::vector<std::array<ObjectId, 2>> touching;
    for (const TrianglePair& p : out.pairs)
        if (p.object_a != p.object_b) touching.push_back({p.object_a, p.object_b});
    std::sort(touching.begin(), touching.end());
    touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
    auto intersecting = [&](ObjectId a, ObjectId b) { return std::binary_search(touching.begin(), touching.end(), std::array<ObjectId, 2>{a, b}); };

    std::vector<ObjectContact>& contacts = out.contacts;
    for (const passes::StageContact& c : r->contacts) {
        ObjectContact oc;
        oc.object_a = ids[c.a];
        oc.object_b = ids[c.b];
        oc.volume = static_cast<float>(c.volume);
        oc.normal = toFloat3(c.normal);
        oc.depth = static_cast<float>(c.depth);
        oc.point = toFloat3(c.point);
        oc.contained = !intersecting(oc.object_a, oc.object_b);
        contacts.push_back(oc);
    }
    // Closed pairs whose triangles intersect but whose overlap no ray sampled (touching,
    // thinner than a ray spacing): a contact with volume 0 at the middle of their boxes'
    // overlap.
    for (const auto& pair : touching) {
        // Not a structured binding: clang before 16 cannot capture one in the lambda below.
        const ObjectId a = pair[0], b = pair[1];
        if (registry.objects[a].options.open || registry.objects[b].options.open) continue;
        if (std::any_of(contacts.begin(), contacts.end(), [&](const ObjectContact& c) { return c.object_a == a && c.object_b == b; })) continue;
        ObjectContact oc;
        oc.object_a = a;
        oc.object_b = b;
        for (std::size_t k = 0; k < r->candidates.size(); ++k)
            if (ids[r->candidates[k][0]] == a && ids[r->candidates[k][1]] == b) oc.point = toFloat3(r->candidate_middles[k]);
        contacts.push_back(oc);
    }
    // Run indices grow with ids: the stage's order survives; the volume-0 ones are merged in.
    std::sort(contacts.begin(), contacts.end(),
              [](const ObjectContact& x, const ObjectContact& y) { return x.object_a < y.object_a || (x.object_a == y.object_a && x.object_b < y.object_b); });

    DetectStats& st = out.stats;
    st.contacts.gpu_ms = r->gpu_ms;
    st.gpu_passes.push_back({"contacts", r->gpu_ms});  // both submissions, so GPU sums over passes include them
    st.contacts.rays_x = r->width;
    st.contacts.rays_y = r->height;
    st.contacts.layers = r->layers;
    st.contacts.candidate_pairs = static_cast<std::uint32_t>(r->candidates.size());
    st.contacts.nested_rays = r->nested_rays;
    st.contacts.runs = r->runs;
    st.contacts.host_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return {};
}

}  // namespace vkcollide
