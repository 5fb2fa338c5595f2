#include "cli/json.hpp"

#include <cmath>

namespace cli {

std::string jsonEscape(std::string_view text) {
    std::string o;
    o.reserve(text.size());
    for (char c : text) {
        if (c == '"' || c == '\\') {
            o += '\\';
            o += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
            o += buf;
        } else {
            o += c;
        }
    }
    return o;
}

void JsonWriter::newline() {
    std::fputc('\n', out_);
    for (std::size_t i = 0; i < levels_.size(); ++i) std::fputs("  ", out_);
}

void JsonWriter::beforeValue() {
    if (after_key_) {
        after_key_ = false;
        return;
    }
    if (levels_.empty()) return;
    Level& l = levels_.back();
    if (!l.first) std::fputc(',', out_);
    if (l.layout == Layout::Lines) newline();
    else if (!l.first) std::fputc(' ', out_);
    l.first = false;
}

void JsonWriter::beginObject(Layout layout) {
    beforeValue();
    std::fputc('{', out_);
    levels_.push_back({layout});
}

void JsonWriter::beginArray(Layout layout) {
    beforeValue();
    std::fputc('[', out_);
    levels_.push_back({layout});
}

void JsonWriter::endObject() {
    const Level l = levels_.back();
    levels_.pop_back();
    if (l.layout == Layout::Lines && !l.first) newline();
    std::fputc('}', out_);
}

void JsonWriter::endArray() {
    const Level l = levels_.back();
    levels_.pop_back();
    if (l.layout == Layout::Lines && !l.first) newline();
    std::fputc(']', out_);
}

void JsonWriter::key(std::string_view name) {
    beforeValue();
    std::fprintf(out_, "\"%s\": ", jsonEscape(name).c_str());
    after_key_ = true;
}

void JsonWriter::string(std::string_view text) {
    beforeValue();
    std::fprintf(out_, "\"%s\"", jsonEscape(text).c_str());
}

void JsonWriter::number(double v) {
    beforeValue();
    if (!std::isfinite(v)) std::fputs("null", out_);
    else if (v == std::floor(v) && std::fabs(v) < 9e15) std::fprintf(out_, "%.0f", v);
    else std::fprintf(out_, "%.9g", v);
}

void JsonWriter::integer(std::uint64_t v) {
    beforeValue();
    std::fprintf(out_, "%llu", static_cast<unsigned long long>(v));
}

void JsonWriter::boolean(bool v) {
    beforeValue();
    std::fputs(v ? "true" : "false", out_);
}

void JsonWriter::null() {
    beforeValue();
    std::fputs("null", out_);
}

void JsonWriter::raw(std::string_view json) {
    beforeValue();
    std::fwrite(json.data(), 1, json.size(), out_);
}

void JsonWriter::finish() { std::fputc('\n', out_); }

// Keyed by DetectStats' names from before its groups ("layers", not "peeling.layers";
// docs/api_changes.md), so that scripts that read the JSON keep working.
void writeStats(JsonWriter& j, const vkcollide::DetectStats& st, std::size_t pair_count, const std::vector<std::string>& names) {
    auto count = [&](const char* k, std::size_t v) { j.member(k, [&] { j.integer(v); }); };
    auto ms = [&](const char* k, double v) { j.member(k, [&] { j.number(v); }); };
    j.beginObject();
    j.key("objects");
    j.beginArray(JsonWriter::Layout::Inline);
    for (const std::string& n : names) j.string(n);
    j.endArray();
    // The paper's Table 1.
    count("triangles", st.triangles);
    count("collision_rays", st.collision_rays);
    count("triangles_downloaded", st.triangles_downloaded);
    count("potentially_colliding_triangles", st.potentially_colliding_triangles);
    count("triangle_tests", st.triangle_tests);
    count("positive_tests", st.positive_tests);
    count("gpu_exact_tests", st.gpu_exact_tests);
    count("cpu_exact_tests", st.cpu_exact_tests);
    j.member("pairs_sorted_on_gpu", [&] { j.boolean(st.reliable.pairs_sorted_on_gpu); });
    j.member("responses_on_gpu", [&] { j.boolean(st.reliable.responses_on_gpu); });
    j.member("pairs_sorted_in_one_pass", [&] { j.boolean(st.reliable.pairs_sorted_in_one_pass); });
    j.member("pairs_named_during_gpu", [&] { j.boolean(st.reliable.pairs_named_during_gpu); });
    if (st.contacts.geometry_ms > 0) j.member("contact_geometry_ms", [&] { j.number(st.contacts.geometry_ms); });
    count("pairs", pair_count);
    if (st.proximity.ran) {
        const vkcollide::ProximityStats& p = st.proximity;
        j.key("proximity");
        j.beginObject(JsonWriter::Layout::Inline);
        j.member("distance", [&] { j.number(p.distance); });
        count("pairs", p.pairs);
        count("vertex_triangle", p.vertex_triangle);
        count("edge_edge", p.edge_edge);
        count("in_band", p.in_band);
        count("triangle_pairs", p.triangle_pairs);
        count("distances", p.distances);
        count("neighbours", p.neighbours);
        count("runs", p.runs);
        ms("gpu_ms", p.gpu_ms);
        ms("host_ms", p.host_ms);
        j.endObject();
    }
    j.key("narrow");
    j.beginObject(JsonWriter::Layout::Inline);
    count("candidates", st.narrow.candidates);
    count("potentially_colliding_triangles", st.narrow.potentially_colliding_triangles);
    count("sap_pairs", st.narrow.sap_pairs);
    count("filtered_pairs", st.narrow.filtered_pairs);
    count("neighbour_pairs", st.narrow.neighbour_pairs);
    count("triangle_tests", st.narrow.triangle_tests);
    count("positive_tests", st.narrow.positive_tests);
    count("input_pairs", st.narrow.input_pairs);
    j.endObject();
    // What ran.
    count("resolution", st.resolution);
    j.key("direction");
    j.beginArray(JsonWriter::Layout::Inline);
    for (float d : st.direction) j.number(d);
    j.endArray();
    j.member("method", [&] { j.string(vkcollide::toString(st.method)); });
    count("cell_entries", st.cells.entries);
    count("cell_candidates", st.cells.candidates);
    count("cell_repeats", st.cells.repeats);
    count("cell_sweep_chunks", st.cells.sweep_chunks);
    count("cell_pair_chunks", st.cells.pair_chunks);
    count("cell_huge_cells", st.cells.huge_cells);
    count("cell_comparisons", st.cells.comparisons);
    count("cell_filtered", st.cells.filtered);
    count("cell_survivors", st.cells.survivors);
    if (st.method == vkcollide::DetectMethod::Reliable) j.member("cell_filter_ran", [&] { j.boolean(st.cells.filter_ran); });
    if (st.cells.exact_ran) j.member("cell_exact_pass", [&] { j.string(st.cells.exact_queued ? "queued" : "inline"); });
    count("deep_rays", st.peeling.deep_rays);
    count("axes", st.peeling.axes);
    count("depth_complexity", st.peeling.depth_complexity);
    count("layers", st.peeling.layers);
    count("peel_passes", st.peeling.peel_passes);
    count("peel_submissions", st.peeling.peel_submissions);
    j.member("dual", [&] { j.boolean(st.peeling.dual); });
    j.member("layers_short", [&] { j.boolean(st.peeling.layers_short); });
    // The reliable method samples no rays: no coverage, no backend.
    const bool reliable = st.method == vkcollide::DetectMethod::Reliable;
    j.member("coverage", [&] { j.string(reliable ? "none" : vkcollide::toString(st.peeling.coverage)); });
    j.member("backend", [&] { j.string(reliable ? "none" : vkcollide::toString(st.peeling.backend)); });
    j.member("backend_reason", [&] { j.string(st.peeling.backend_reason); });
    j.member("settings_note", [&] { j.string(st.settings_note); });
    j.key("mesh_warnings");
    j.beginArray();
    for (const vkcollide::MeshWarning& w : st.mesh_warnings) {
        j.beginObject(JsonWriter::Layout::Inline);
        j.member("object", [&] { j.integer(w.object); });
        j.member("inside_out", [&] { j.boolean(w.inside_out); });
        j.member("boundary_edges", [&] { j.integer(w.boundary_edges); });
        j.member("message", [&] { j.string(w.message); });
        j.endObject();
    }
    j.endArray();
    // Times (GPU stages from timestamps; the rest host wall time).
    ms("sampling_ms", st.sampling_ms);
    ms("merging_ms", st.peeling.merging_ms);
    ms("separation_ms", st.peeling.separation_ms);
    ms("packing_ms", st.peeling.packing_ms);
    ms("footprints_ms", st.reliable.footprints_ms);
    ms("pairing_ms", st.reliable.pairing_ms);
    ms("filtering_ms", st.reliable.filtering_ms);
    ms("readback_ms", st.readback_ms);
    ms("narrow_ms", st.narrow_ms);
    ms("contacts_ms", st.contacts.host_ms);
    ms("contacts_gpu_ms", st.contacts.gpu_ms);
    count("contact_rays_x", st.contacts.rays_x);
    count("contact_rays_y", st.contacts.rays_y);
    count("contact_candidate_pairs", st.contacts.candidate_pairs);
    count("narrow_threads", st.host.narrow_threads);
    ms("total_ms", st.total_ms);
    count("gpu_memory_bytes", st.gpu_memory_bytes);
    j.key("gpu_passes");
    j.beginArray();
    for (const vkcollide::PassTime& p : st.gpu_passes) {
        j.beginObject(JsonWriter::Layout::Inline);
        j.member("name", [&] { j.string(p.name); });
        ms("gpu_ms", p.gpu_ms);
        j.endObject();
    }
    j.endArray();
    j.endObject();
}

}  // namespace cli
