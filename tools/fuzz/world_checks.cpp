// fuzz_world's checks of a detection's result (world_checks.hpp).
#include "fuzz/world_checks.hpp"

#include <cstdio>
#include <cstdlib>
#include <tuple>
#include <vector>

#include "support/exact_reference.hpp"

namespace vkcollide::fuzz {

void fail(const std::string& what) {
    std::fprintf(stderr, "fuzz_world: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

void trace(const std::string& line) {
    static const bool on = [] {
        const char* env = std::getenv("VKCOLLIDE_FUZZ_VERBOSE");
        return env && std::string(env) == "1";
    }();
    if (on) std::fprintf(stderr, "  %s\n", line.c_str());
}

bool allowed(PairFilterKind kind, ObjectId a, ObjectId b) {
    switch (kind) {
        case PairFilterKind::SumNotMultipleOf3: return (a + b) % 3 != 0;
        case PairFilterKind::Never: return false;
        default: return true;
    }
}

namespace {

std::uint32_t triangles(const Object& o) { return static_cast<std::uint32_t>(o.mesh.indices.size() / 3); }

// Host meshes only: the exact reference of tests/support, with the same filter.
void checkAgainstReference(const DetectResult& r, const Snapshot& snap, const char* call) {
    if (r.incomplete || !r.excluded.empty() || snap.filter_threw) return;
    std::vector<test::ReferenceObject> objects;
    std::vector<ObjectId> ids;
    for (const auto& [id, o] : snap.objects) {
        if (o.gpu) return;  // GPU-computed world coordinates may differ by an ulp
        objects.push_back({&o.mesh, test::transformFrom3x4(o.transform), o.self_collision});
        ids.push_back(id);
    }
    test::ReferenceOptions options;
    options.threads = 1;
    if (snap.filter != PairFilterKind::None)
        options.may_collide = [&](std::uint32_t a, std::uint32_t b) { return allowed(snap.filter, ids[a], ids[b]); };
    auto reference = test::computeReferencePairs(objects, options);
    if (!reference) return;  // e.g. world coordinates that overflow float: no reference
    for (TrianglePair& p : *reference) {
        p.object_a = ids[p.object_a];
        p.object_b = ids[p.object_b];
    }
    const test::PairComparison cmp = test::comparePairs(r.pairs, *reference);
    if (cmp.false_positives > 0)
        fail(std::string(call) + ": " + std::to_string(cmp.false_positives) + " pairs the exact reference does not have");
    if (snap.settings.method == DetectMethod::Reliable && cmp.false_negatives > 0)
        fail(std::string(call) + ": the reliable method missed " + std::to_string(cmp.false_negatives) + " of " +
             std::to_string(reference->size()) + " pairs of the exact reference");
}

}  // namespace

void checkResult(const DetectResult& r, const Snapshot& snap, const char* call) {
    trace(std::string(call) + ": " + std::to_string(r.pairs.size()) + " pairs, " + std::to_string(r.excluded.size()) + " excluded, " +
          std::to_string(r.contacts.size()) + " contacts" + (r.incomplete ? ", incomplete" : "") + ", method " + toString(r.stats.method) +
          ", resolution " + std::to_string(r.stats.resolution));
    const auto where = [&](const std::string& what) { fail(std::string(call) + ": " + what); };
    if (r.pairs.size() > snap.settings.limits.max_pairs) where("more pairs than max_pairs");
    if (r.pairs_left_out > 0 && (!r.incomplete || r.incomplete->code() != ErrorCode::LimitExceeded))
        where("pairs left out without a LimitExceeded error");
    if (r.incomplete && r.incomplete->message().empty()) where("incomplete with an empty message");
    std::map<std::pair<ObjectId, std::uint32_t>, std::uint32_t> partners;
    for (std::size_t i = 0; i < r.pairs.size(); ++i) {
        const TrianglePair& p = r.pairs[i];
        if (i > 0 && !(r.pairs[i - 1] < p)) where("pairs not sorted or repeated");
        if (!(std::tie(p.object_a, p.triangle_a) < std::tie(p.object_b, p.triangle_b))) where("a pair out of order");
        const auto a = snap.objects.find(p.object_a), b = snap.objects.find(p.object_b);
        if (a == snap.objects.end() || b == snap.objects.end()) where("a pair of an object not in the world");
        if (p.triangle_a >= triangles(a->second) || p.triangle_b >= triangles(b->second))
            where("a pair of a triangle the object does not have");
        if (p.object_a == p.object_b && !a->second.self_collision) where("a pair inside an object without self-collision");
        if (p.object_a != p.object_b && !snap.filter_threw && !allowed(snap.filter, p.object_a, p.object_b))
            where("a pair the pair filter forbids");
        ++partners[{p.object_a, p.triangle_a}];
        ++partners[{p.object_b, p.triangle_b}];
    }
    for (const ExcludedObject& x : r.excluded) {
        const auto o = snap.objects.find(x.object);
        if (o == snap.objects.end() || !o->second.gpu) where("excluded an object that is not an engine mesh");
        if (x.error.message().empty()) where("an excluded object without a message");
    }
    if (!r.incomplete) {
        if (r.responses.size() != partners.size()) where("not one response per colliding triangle");
        for (const TriangleResponse& t : r.responses) {
            const auto it = partners.find({t.object, t.triangle});
            if (it == partners.end() || it->second != t.partner_count) where("a response's partner count is wrong");
        }
    }
    for (std::size_t i = 0; i < r.contacts.size(); ++i) {
        const ObjectContact& c = r.contacts[i];
        if (c.object_a >= c.object_b) where("a contact out of order");
        if (i > 0 && std::tie(r.contacts[i - 1].object_a, r.contacts[i - 1].object_b) >= std::tie(c.object_a, c.object_b))
            where("contacts not sorted");
    }
    checkAgainstReference(r, snap, call);
}

}  // namespace vkcollide::fuzz
