#include "cli/report.hpp"

namespace cli {
namespace {

using vkcollide::Error;
using vkcollide::ErrorCode;
using Layout = JsonWriter::Layout;

vkcollide::Result<std::FILE*> create(const char* option, const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return Error(ErrorCode::IoError, std::string(option) + ": cannot write " + path);
    return f;
}

vkcollide::Result<void> closeFile(std::FILE*& f, const char* option, const std::string& path) {
    if (!f) return {};
    const bool ok = !std::ferror(f) && std::fclose(f) == 0;
    f = nullptr;
    if (!ok) return Error(ErrorCode::IoError, std::string(option) + ": writing " + path + " failed");
    return {};
}

void transformJson(JsonWriter& j, const vkcollide::Transform3x4& t) {
    j.beginArray(Layout::Inline);
    for (float v : t) j.number(v);
    j.endArray();
}

}  // namespace

vkcollide::Result<std::unique_ptr<Report>> Report::open(const CommandLine& line, const Scene& scene, const std::string& device,
                                                         const vkcollide::DetectSettings& used) {
    std::unique_ptr<Report> r(new Report(line));
    if (!line.pairs_path.empty()) {
        auto f = create("--pairs", line.pairs_path);
        if (!f) return f.error();
        r->pairs_ = *f;
    }
    if (!line.proximity_path.empty()) {
        auto f = create("--proximity-pairs", line.proximity_path);
        if (!f) return f.error();
        r->proximity_ = *f;
    }
    if (line.json_path.empty()) return r;
    auto f = create("--json", line.json_path);
    if (!f) return f.error();
    r->json_file_ = *f;
    r->json_ = std::make_unique<JsonWriter>(r->json_file_);
    JsonWriter& j = *r->json_;
    j.beginObject();
    j.member("tool", [&] { j.string("vkcollide detect"); });
    j.member("format", [&] { j.integer(1); });
    j.member("device", [&] { j.string(device); });
    j.member("sequence", [&] { j.boolean(line.sequence); });
    j.key("files");
    j.beginArray();
    for (const std::string& file : line.files) j.string(file);
    j.endArray();
    j.key("options");
    j.beginArray();
    for (const auto& [name, value] : line.given) {
        j.beginArray(Layout::Inline);
        j.string(name);
        if (!value.empty()) j.string(value);
        j.endArray();
    }
    j.endArray();
    j.key("objects");
    j.beginArray();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        j.beginObject(Layout::Inline);
        j.member("id", [&] { j.integer(i); });
        j.member("name", [&] { j.string(o.options.name); });
        j.member("file", [&] { j.integer(o.slot + 1); });
        j.member("triangles", [&] { j.integer(o.mesh.triangleCount()); });
        j.member("vertices", [&] { j.integer(o.mesh.positions.size()); });
        j.member("first_triangle", [&] { j.integer(o.first_triangle); });
        j.member("open", [&] { j.boolean(o.options.open); });
        j.member("self_collision", [&] { j.boolean(o.options.self_collision); });
        j.member("gpu_mesh", [&] { j.boolean(o.gpu_mesh); });
        j.member("typical_edge_length", [&] { j.number(o.options.typical_edge_length); });
        j.key("transform");
        transformJson(j, o.options.transform);
        j.endObject();
    }
    j.endArray();
    // Asked on the command line (null: automatic), and what frame 0 resolved them to.
    j.key("settings");
    j.beginObject();
    for (const auto& [label, settings] : {std::pair<const char*, const vkcollide::DetectSettings*>{"asked", &line.settings}, {"used", &used}}) {
        j.key(label);
        j.beginObject(Layout::Inline);
        for (const auto& [field, value] : settingsJson(*settings)) j.member(field, [&] { j.raw(value); });
        j.endObject();
    }
    j.endObject();
    j.key("frames");
    j.beginArray();
    return r;
}

Report::~Report() {
    if (pairs_) std::fclose(pairs_);
    if (proximity_) std::fclose(proximity_);
    if (json_file_) std::fclose(json_file_);
}

void Report::frame(std::size_t frame, const Scene& scene, const vkcollide::DetectResult& result) {
    if (pairs_) {
        // (object, triangle) order is global order: the lower number comes first.
        for (const vkcollide::TrianglePair& p : result.pairs) {
            const unsigned long long a = scene.objects[p.object_a].first_triangle + p.triangle_a;
            const unsigned long long b = scene.objects[p.object_b].first_triangle + p.triangle_b;
            if (line_.sequence) std::fprintf(pairs_, "%zu,%llu,%llu\n", frame, a, b);
            else std::fprintf(pairs_, "%llu,%llu\n", a, b);
        }
    }
    if (proximity_)
        for (const vkcollide::ProximityPair& p : result.proximity) {
            if (line_.sequence) std::fprintf(proximity_, "%zu,", frame);
            std::fprintf(proximity_, "%s,%u,%u,%d,%u,%u,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n",
                         p.kind == vkcollide::ProximityKind::EdgeEdge ? "edge-edge" : "vertex-triangle", p.object_a, p.a0,
                         p.a1 == vkcollide::kNoPrimitive ? -1 : int(p.a1), p.object_b, p.b0, p.b1 == vkcollide::kNoPrimitive ? -1 : int(p.b1),
                         p.distance, p.weight_a, p.weights_b[0], p.weights_b[1], p.weights_b[2], p.normal[0], p.normal[1], p.normal[2],
                         (p.flags & vkcollide::kProximityInBand) ? 1 : 0);
        }
    if (!json_) return;
    JsonWriter& j = *json_;
    j.beginObject();
    j.member("frame", [&] { j.integer(frame); });
    j.key("files");
    j.beginArray(Layout::Inline);
    for (const std::string& file : line_.frameFiles(frame)) j.string(file);
    j.endArray();
    // [object_a, triangle_a, object_b, triangle_b], sorted.
    j.key("pairs");
    j.beginArray();
    for (const vkcollide::TrianglePair& p : result.pairs) {
        j.beginArray(Layout::Inline);
        for (std::uint32_t v : {p.object_a, p.triangle_a, p.object_b, p.triangle_b}) j.integer(v);
        j.endArray();
    }
    j.endArray();
    // A Float3 as the member `key`: [x, y, z].
    const auto vec3 = [&](const char* key, vkcollide::Float3 v) {
        j.key(key);
        j.beginArray(Layout::Inline);
        for (float x : {v.x, v.y, v.z}) j.number(x);
        j.endArray();
    };
    j.key("responses");
    j.beginArray();
    for (const vkcollide::TriangleResponse& r : result.responses) {
        j.beginObject(Layout::Inline);
        j.member("object", [&] { j.integer(r.object); });
        j.member("triangle", [&] { j.integer(r.triangle); });
        vec3("direction", r.direction);
        j.member("partners", [&] { j.integer(r.partner_count); });
        j.endObject();
    }
    j.endArray();
    // Object-pair contacts (--contacts; empty without it): docs/contacts.md.
    j.key("contacts");
    j.beginArray();
    for (const vkcollide::ObjectContact& c : result.contacts) {
        j.beginObject(Layout::Inline);
        j.member("object_a", [&] { j.integer(c.object_a); });
        j.member("object_b", [&] { j.integer(c.object_b); });
        j.member("volume", [&] { j.number(c.volume); });
        vec3("normal", c.normal);
        vec3("point", c.point);
        j.member("depth", [&] { j.number(c.depth); });
        j.member("contained", [&] { j.boolean(c.contained); });
        j.endObject();
    }
    j.endArray();
    // Contact geometry (--contact-geometry; empty without it): one per pair, in `pairs`' order,
    // and the sums per pair of objects (docs/contacts.md).
    j.key("pair_contacts");
    j.beginArray();
    for (const vkcollide::PairContact& c : result.pair_contacts) {
        j.beginObject(Layout::Inline);
        j.member("shape", [&] {
            j.string(c.shape == vkcollide::ContactShape::Segment ? "segment" : c.shape == vkcollide::ContactShape::Point ? "point" : "coplanar");
        });
        vec3("start", c.start);
        vec3("end", c.end);
        vec3("normal", c.normal);
        j.member("area", [&] { j.number(c.area); });
        j.endObject();
    }
    j.endArray();
    j.key("pair_contact_totals");
    j.beginArray();
    for (const vkcollide::ObjectPairContact& t : result.pair_contact_totals) {
        j.beginObject(Layout::Inline);
        j.member("object_a", [&] { j.integer(t.object_a); });
        j.member("object_b", [&] { j.integer(t.object_b); });
        j.member("pairs", [&] { j.integer(t.pairs); });
        j.member("length", [&] { j.number(t.length); });
        j.member("area", [&] { j.number(t.area); });
        vec3("normal", t.normal);
        j.endObject();
    }
    j.endArray();
    // Proximity pairs (--proximity; empty without it): docs/proximity.md.
    j.key("proximity");
    j.beginArray();
    for (const vkcollide::ProximityPair& p : result.proximity) {
        j.beginObject(Layout::Inline);
        j.member("kind", [&] { j.string(p.kind == vkcollide::ProximityKind::EdgeEdge ? "edge-edge" : "vertex-triangle"); });
        j.member("object_a", [&] { j.integer(p.object_a); });
        j.key("a");
        j.beginArray(Layout::Inline);
        j.integer(p.a0);
        if (p.a1 != vkcollide::kNoPrimitive) j.integer(p.a1);
        j.endArray();
        j.member("object_b", [&] { j.integer(p.object_b); });
        j.key("b");
        j.beginArray(Layout::Inline);
        j.integer(p.b0);
        if (p.b1 != vkcollide::kNoPrimitive) j.integer(p.b1);
        j.endArray();
        j.member("distance", [&] { j.number(p.distance); });
        j.member("weight_a", [&] { j.number(p.weight_a); });
        j.key("weights_b");
        j.beginArray(Layout::Inline);
        for (float w : p.weights_b) j.number(w);
        j.endArray();
        j.key("normal");
        j.beginArray(Layout::Inline);
        for (float w : p.normal) j.number(w);
        j.endArray();
        j.member("in_band", [&] { j.boolean((p.flags & vkcollide::kProximityInBand) != 0); });
        j.endObject();
    }
    j.endArray();
    j.key("excluded");
    j.beginArray();
    for (const vkcollide::ExcludedObject& e : result.excluded) {
        j.beginObject(Layout::Inline);
        j.member("object", [&] { j.integer(e.object); });
        j.member("name", [&] { j.string(scene.objects.at(e.object).options.name); });
        j.member("error", [&] { j.string(e.error.message()); });
        j.endObject();
    }
    j.endArray();
    j.key("stats");
    writeStats(j, result.stats, result.pairs.size(), scene.names());
    j.endObject();
}

vkcollide::Result<void> Report::close() {
    if (json_) {
        json_->endArray();
        json_->endObject();
        json_->finish();
    }
    auto pairs = closeFile(pairs_, "--pairs", line_.pairs_path);
    auto near = closeFile(proximity_, "--proximity-pairs", line_.proximity_path);
    if (!near) return near;
    auto json = closeFile(json_file_, "--json", line_.json_path);
    if (!pairs) return pairs;
    return json;
}

vkcollide::Result<void> writeStatsFile(const std::string& path, const Scene& scene, const vkcollide::DetectResult& result) {
    auto f = create("--stats", path);
    if (!f) return f.error();
    JsonWriter j(*f);
    writeStats(j, result.stats, result.pairs.size(), scene.names());
    j.finish();
    return closeFile(*f, "--stats", path);
}

}  // namespace cli
