// vkcollide_bench: the speed-against-accuracy sweep. Not a test: a program.
//
//   vkcollide_bench [--set tuning|held-out|all] [--scenes a,b,...] [--mesh FILE[:x,y,z]]...
//                   [--variants default,mitigations,...] [--resolutions 512,1024,...] [--scale S] [--frames K]
//                   [--threads N] [--data DIR] [--cache DIR | --no-cache] [--csv FILE] [--profile FILE]
//                   [--pipeline-stats FILE] [--warmup-ms MS] [--list] [--reference-only] [--write-obj DIR] [--help]
//
// --mesh runs the user's own files as one more scene (set "user"; user_scene.hpp), the same
// way; bench_options.cpp has every option's default.
// --profile FILE writes where each timed frame's time went (GPU passes, narrow-phase stages,
// host totals, the detection's host parts as detect:*; tools/bench/profile_table.sh sums it up). --warmup-ms MS detects untimed for
// that long before each scene and variant: a GPU's clocks drop while it idles.
// --pipeline-stats FILE writes, after the runs, what the driver's compiler says of every
// pipeline they made (ContextCreateInfo::pipeline_statistics: registers, spills, shared
// memory...), one row per statistic; an error where the driver does not offer them.
// --reference-only builds the chosen scenes and their exact references (filling the cache)
// and prints per frame the triangles, reference pairs, crossing pairs and seconds; no GPU.
// For each scene (bench_scenes.hpp) and settings variant (bench_variants.cpp) it runs one
// warm-up detection and then the timed ones: rigid scenes K times, deforming and moving
// scenes once per frame of their motion (new vertices through updateVertices or the engine
// buffer, or new transforms through setTransform, timed from the update to the pair list).
// One CSV row per timed detection: what ran (backend, resolution, direction, axes,
// coverage, layers), every stage time (GPU timestamps per stage, readback, narrow phase,
// update, total wall), the paper's Table 1 counts, GPU and host memory, and against the
// exact reference of that frame: recall of all pairs, recall of crossing pairs, precision.
// The reference pairs are cached per frame (reference_cache.hpp). At the end a table of
// means per scene and variant goes to stdout (tools/bench/summary.sh makes the same from
// the CSV). Every object is self-colliding, as the peers run.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench_options.hpp"
#include "bench_scenes.hpp"
#include "bench_world.hpp"
#include "bench_variants.hpp"
#include "reference_cache.hpp"
#include "support/exact_reference.hpp"
#include "vkcollide/context.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/world.hpp"

using namespace vkcollide;
using namespace vkcollide::bench;

namespace {

using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// Busy host work of `duration` ms on the calling thread (a sleep would let the core idle).
void spinFor(double duration) {
    for (const auto t0 = Clock::now(); ms(t0, Clock::now()) < duration;) {
    }
}

double peakHostMiB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

std::string csvField(std::string s) {
    std::replace(s.begin(), s.end(), ',', ';');
    std::replace(s.begin(), s.end(), '"', '\'');
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

// A progress line on a terminal only (logs of the GPU run stay clean).
const bool kProgress = isatty(2) != 0;
void progress(const std::string& line) {
    if (kProgress) std::fprintf(stderr, "\r\033[K%s", line.c_str()), std::fflush(stderr);
}
void progressDone() {
    if (kProgress) std::fprintf(stderr, "\r\033[K");
}

// Means over the timed frames of one (scene, variant), for the closing table.
struct Summary {
    std::string set, scene, variant, backend;
    std::uint32_t resolution = 0;
    std::size_t frames = 0, triangles = 0, found_crossing = 0, crossing = 0, found = 0, reference = 0, downloaded = 0;
    double total_ms = 0, gpu_ms = 0, narrow_ms = 0, precision_min = 1;
};

void writeProfile(std::ofstream& out, const std::string& prefix, const DetectStats& st, double update_ms, double total_ms) {
    char line[512];
    auto row = [&](const char* kind, const std::string& stage, double ms) {
        std::snprintf(line, sizeof line, "%s,%s,%s,%.4f\n", prefix.c_str(), kind, csvField(stage).c_str(), ms);
        out << line;
    };
    for (const PassTime& p : st.gpu_passes) row("gpu", p.name, p.gpu_ms);
    const NarrowTimings& n = st.narrow_timings;
    row("narrow", "validate", n.validate_ms);
    row("narrow", "gather", n.gather_ms);
    row("narrow", "sweep", n.sweep_ms);
    row("narrow", "filter", n.filter_ms);
    row("narrow", "test", n.test_ms);
    row("narrow", "sort", n.sort_ms);
    row("narrow", "response", n.response_ms);
    row("narrow", "total", n.total_ms);
    row("host", "start", st.host.start_ms);
    row("host", "collect", st.host.collect_ms);
    row("host", "readback", st.readback_ms);
    row("host", "narrow", st.narrow_ms);
    if (st.contacts.geometry_ms > 0) row("host", "contact-geometry", st.contacts.geometry_ms);
    row("host", "update", update_ms);
    row("host", "total", total_ms);
    // The host parts of the detection beyond the GPU and the narrow phase (DetectStats);
    // "rest": the detection's wall time (total_ms) not in any part named here.
    row("detect", "settings", st.host.settings_ms);
    row("detect", "upload", st.host.upload_ms);
    row("detect", "declare", st.host.declare_ms);
    row("detect", "compile", st.host.compile_ms);
    row("detect", "record", st.host.record_ms);
    row("detect", "submit", st.host.submit_ms);
    row("detect", "wait", st.host.wait_ms);
    row("detect", "gpu-span", st.gpu_span_ms);
    row("detect", "launch-wake", st.host.launch_wake_ms);
    row("detect", "prepare", st.host.prepare_ms);  // of collect: not in "rest"
    row("detect", "milestone", st.host.milestone_ms);  // of collect: the pairs named while the GPU ran
    const double named = st.host.settings_ms + st.host.upload_ms + st.host.declare_ms + st.host.compile_ms + st.host.record_ms +
                         st.host.submit_ms + st.host.prepare_ms + st.host.milestone_ms + st.host.wait_ms + st.readback_ms + st.narrow_ms +
                         st.contacts.geometry_ms;
    row("detect", "rest", st.total_ms - named);
    row("detect", "reused", st.host.reused_submissions);  // a count, not ms: submissions submitted again, not recorded
    out.flush();
}

}  // namespace

int main(int argc, char** argv) {
    const std::optional<Options> parsed = parseOptions(argc, argv);
    if (!parsed) return 2;
    const Options& opt = *parsed;
    if (opt.help) return printHelp(), 0;
    std::vector<SceneSpec> all = allScenes(opt.data, opt.scale);
    const std::size_t built_in = all.size();
    if (!opt.meshes.empty()) {
        // Read now: a bad file fails before any reference or GPU work, named by the reader.
        auto mine = userScene(opt.meshes, 0, SceneSet::User);
        if (!mine) return std::fprintf(stderr, "vkcollide_bench: --mesh: %s\n", mine.error().message().c_str()), 1;
        all.push_back(std::move(*mine));
    }
    const std::vector<Variant> every_variant = allVariants(opt.resolutions);
    if (opt.list) {
        for (const SceneSpec& s : all) std::printf("%-24s %-8s %-9s %2d frames  %s\n", s.name.c_str(), setName(s.set), motionName(s.motion), s.frames, s.what.c_str());
        std::printf("\nvariants (name group):\n");
        for (const Variant& v : every_variant) std::printf("  %-16s %s\n", v.name.c_str(), v.group.c_str());
        return 0;
    }
    auto variants = selectVariants(every_variant, opt.variants);
    if (!variants) return std::fprintf(stderr, "vkcollide_bench: %s\n", variants.error().message().c_str()), 2;
    std::vector<const SceneSpec*> chosen;
    for (std::size_t i = 0; i < all.size(); ++i) {
        const SceneSpec& s = all[i];
        const bool named = opt.scenes.empty() || std::find(opt.scenes.begin(), opt.scenes.end(), s.name) != opt.scenes.end();
        if (i >= built_in || (named && (opt.set == "all" || opt.set == setName(s.set)))) chosen.push_back(&s);
    }
    for (const std::string& n : opt.scenes)
        if (std::none_of(all.begin(), all.end(), [&](const SceneSpec& s) { return s.name == n; }))
            return std::fprintf(stderr, "vkcollide_bench: unknown scene '%s' (--list)\n", n.c_str()), 2;

    if (!opt.write_obj.empty()) {
        // The scenes for the CLI or another library: world vertices (transforms baked as the
        // detection computes them), written so they read back bit for bit.
        std::error_code ec;
        std::filesystem::create_directories(opt.write_obj, ec);
        if (ec) return std::fprintf(stderr, "vkcollide_bench: --write-obj %s: %s\n", opt.write_obj.c_str(), ec.message().c_str()), 1;
        for (const SceneSpec* scene : chosen)
            for (int f = 0; f < scene->frames; ++f) {
                auto objects = buildFrame(*scene, f, true);
                if (!objects) return std::fprintf(stderr, "vkcollide_bench: %s: %s\n", scene->name.c_str(), objects.error().message().c_str()), 1;
                std::vector<HostMesh> meshes;
                for (const BenchObject& o : *objects) meshes.push_back(o.mesh);
                const std::string path = opt.write_obj + "/" + scene->name + (scene->frames > 1 ? "_" + std::to_string(f) : "") + ".obj";
                std::ofstream out(path, std::ios::binary);
                out << writeObj(meshes);
                if (!out) return std::fprintf(stderr, "vkcollide_bench: --write-obj: cannot write %s\n", path.c_str()), 1;
                std::printf("%s: %zu objects\n", path.c_str(), meshes.size());
            }
        return 0;
    }
    if (opt.reference_only) {
        std::printf("%-9s %-24s %5s %10s %8s %12s %12s %9s %s\n", "set", "scene", "frame", "triangles", "objects", "exact pairs", "crossing",
                    "seconds", "cached");
        for (const SceneSpec* scene : chosen)
            for (int f = 0; f < scene->frames; ++f) {
                auto objects = buildFrame(*scene, f);
                if (!objects) return std::fprintf(stderr, "vkcollide_bench: %s: %s\n", scene->name.c_str(), objects.error().message().c_str()), 1;
                auto ref = referenceFor(*objects, opt.cache, opt.threads);
                if (!ref) return std::fprintf(stderr, "vkcollide_bench: %s: %s\n", scene->name.c_str(), ref.error().message().c_str()), 1;
                std::size_t triangles = 0;
                for (const BenchObject& o : *objects) triangles += o.mesh.triangleCount();
                std::printf("%-9s %-24s %5d %10zu %8zu %12zu %12zu %9.2f %s\n", setName(scene->set), scene->name.c_str(), f, triangles,
                            objects->size(), ref->pairs.size(), ref->crossingCount(), ref->seconds, ref->from_cache ? "yes" : "no");
                std::fflush(stdout);
            }
        return 0;
    }
    // The test suite's switch (tests/bench): the validation layer on, any message fails the run.
    ContextCreateInfo context_info;
    const char* validation_env = std::getenv("VKCOLLIDE_TEST_VALIDATION");
    context_info.validation = validation_env && std::string(validation_env) == "1";
    context_info.pipeline_statistics = !opt.pipeline_stats.empty();
    auto ctx = Context::create(context_info);
    if (!ctx) return std::fprintf(stderr, "vkcollide_bench: %s\n", ctx.error().message().c_str()), 1;
    const std::string device = csvField((*ctx)->deviceInfo().name);
    std::ofstream csv;
    if (!opt.csv.empty()) {
        csv.open(opt.csv);
        if (!csv) return std::fprintf(stderr, "vkcollide_bench: --csv %s: cannot write it\n", opt.csv.c_str()), 1;
    }
    // One row per stage of every timed frame: where each frame's time went.
    std::ofstream profile;
    if (!opt.profile.empty()) {
        profile.open(opt.profile);
        profile << "device,scene,variant,frame,kind,stage,ms\n";
    }
    csv << "device,set,scene,motion,triangles,objects,gpu_objects,scale,variant,frame,backend,resolution,direction,axes,coverage,dual,"
           "layer_cap,packing,open,async,depth_complexity,layers,peel_passes,"
           "sampling_ms,merging_ms,separation_ms,packing_ms,gpu_ms,readback_ms,narrow_ms,update_ms,total_ms,"
           "collision_rays,downloaded,pot_colliding,tests,positive_tests,pairs,reference_pairs,reference_crossing,"
           "found_crossing,recall,recall_crossing,precision,gpu_mib,host_peak_mib,narrow_threads,reference_s,reference_cached,"
           "method,footprints_ms,pairing_ms,filtering_ms,cell_candidates,cell_survivors,settings_note,"
           "cell_entries,cell_duplicates,cell_filtered,cell_deep_cells,cell_max_cell,gpu_exact_tests,cpu_exact_tests,gpu_span_ms,"
           "sorting_ms\n";
    std::vector<Summary> summaries;
    std::printf("%-9s %-24s %-14s %-8s %5s %9s %9s %9s %9s %8s %8s %8s\n", "set", "scene", "variant", "backend", "res", "gpu ms", "narrow ms",
                "total ms", "downl.", "recall", "crossing", "prec.");
    // A failing scene or (scene, variant) is reported and skipped, so one missing mesh file
    // or one out-of-memory setting does not cost a whole GPU run; the exit code says so.
    int failures = 0;
    const auto failed = [&](const std::string& what, const Error& e) {
        progressDone();
        std::fprintf(stderr, "vkcollide_bench: %s: %s (skipped)\n", what.c_str(), e.message().c_str());
        ++failures;
    };
    for (const SceneSpec* scene : chosen) {
        // Every frame's objects and exact reference first (rigid: one frame).
        std::vector<std::vector<BenchObject>> frames;
        std::vector<FrameReference> refs;
        for (int f = 0; f < scene->frames; ++f) {
            progress(scene->name + ": building frame " + std::to_string(f) + " and its exact reference");
            auto objects = buildFrame(*scene, f);
            if (!objects) {
                failed(scene->name, objects.error());
                break;
            }
            auto ref = referenceFor(*objects, opt.cache, opt.threads);
            if (!ref) {
                failed(scene->name + ": reference", ref.error());
                break;
            }
            refs.push_back(std::move(*ref));
            frames.push_back(std::move(*objects));
        }
        if (static_cast<int>(frames.size()) != scene->frames) continue;
        std::size_t triangles = 0, gpu_objects = 0;
        for (const BenchObject& o : frames[0]) triangles += o.mesh.triangleCount(), gpu_objects += o.gpu;
        const int timed = scene->motion == Motion::Rigid ? opt.frames : scene->frames;
        for (const Variant& v : *variants) {
            if (v.pipelined && scene->motion == Motion::Deforming && gpu_objects > 0) {
                // applyFrame rewrites engine buffers in place: pipelining them needs the
                // engine's double buffering (vkcollide_bench_frames measures that).
                progressDone();
                std::printf("%-9s %-24s %-14s (not run: deforming engine meshes are written in place here)\n", setName(scene->set),
                            scene->name.c_str(), v.name.c_str());
                continue;
            }
            auto world = CollisionWorld::create(**ctx, {.threads = opt.threads});
            if (!world) return std::fprintf(stderr, "\nvkcollide_bench: %s\n", world.error().message().c_str()), 1;
            auto in_world = addToWorld(**world, **ctx, frames[0], v.open);
            if (!in_world) {
                failed(scene->name + ", " + v.name, in_world.error());
                continue;
            }
            const std::vector<ObjectId>& ids = in_world->ids;
            DetectSettings settings;
            v.apply(settings);
            if (v.resolution_scale > 0) {
                auto resolved = (*world)->resolveSettings(settings);
                if (!resolved) {
                    failed(scene->name + ", " + v.name, resolved.error());
                    continue;
                }
                settings.resolution = std::max(1u, static_cast<std::uint32_t>(std::lround(*resolved->resolution * v.resolution_scale)));
            }
            // The GPU's clocks drop while it idles (scene building, the reference): detect
            // until it has been busy for --warmup-ms before the frames are timed.
            // Pipelined: two in flight, so that the second slot exists before the frames.
            for (const auto w0 = Clock::now(); ms(w0, Clock::now()) < opt.warmup_ms;) {
                if (!v.pipelined) {
                    if (!(*world)->detect(settings)) break;
                } else if (!(*world)->submit(settings) || ((*world)->inFlight() == 2 && !(*world)->collect())) {
                    break;
                }
            }
            while ((*world)->pending())
                if (!(*world)->collect()) break;
            Summary sum{setName(scene->set), scene->name, v.name, "", 0, 0, triangles};
            // One timed frame's row: its result `r` against frame f's reference.
            auto emit = [&](int f, const DetectResult& r, double update_ms, double total_ms) {
                const int mf = scene->motion == Motion::Rigid ? 0 : f;
                const DetectStats& st = r.stats;
                const FrameReference& ref = refs[mf];
                auto cmp = test::comparePairs(r.pairs, ref.pairs);
                std::size_t found_crossing = 0;
                for (std::size_t k = 0; k < ref.pairs.size(); ++k)
                    if (ref.crossing[k]) found_crossing += std::binary_search(r.pairs.begin(), r.pairs.end(), ref.pairs[k]);
                const std::size_t crossing = ref.crossingCount();
                std::size_t found_pairs = r.pairs.size();
                if (!settings.reliable.host_pairs) {
                    // The pairs stayed on the GPU: their count against the reference's.
                    const double n = st.reliable.device_pairs_found, m = double(ref.pairs.size());
                    found_pairs = st.reliable.device_pairs_found;
                    cmp.recall = m > 0 ? std::min(n, m) / m : 1.0;
                    cmp.precision = n > 0 ? std::min(n, m) / n : 1.0;
                    found_crossing = found_pairs == ref.pairs.size() ? crossing : 0;
                }
                const double recall_crossing = crossing ? double(found_crossing) / double(crossing) : 1.0;
                double gpu_ms = 0;
                for (const auto& pass : st.gpu_passes) gpu_ms += pass.gpu_ms;
                char row[2048];
                std::snprintf(row, sizeof row,
                              "%s,%s,%s,%s,%zu,%zu,%zu,%g,%s,%d,%s,%u,%.4f;%.4f;%.4f,%u,%s,%d,%u,%s,%d,%d,%u,%u,%u,"
                              "%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,"
                              "%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%zu,%.6f,%.6f,%.6f,%.2f,%.1f,%u,%.3f,%d,",
                              device.c_str(), setName(scene->set), scene->name.c_str(), motionName(scene->motion), triangles, ids.size(), gpu_objects,
                              opt.scale, v.name.c_str(), f, toString(st.peeling.backend), st.resolution, st.direction[0], st.direction[1], st.direction[2],
                              st.peeling.axes, toString(st.peeling.coverage), st.peeling.dual ? 1 : 0, settings.peeling.layer_cap, settings.peeling.packing == PackingMethod::Paper ? "paper" : "scan",
                              v.open ? 1 : 0, v.pipelined ? 2 : v.async ? 1 : 0, st.peeling.depth_complexity, st.peeling.layers, st.peeling.peel_passes, st.sampling_ms, st.peeling.merging_ms,
                              st.peeling.separation_ms, st.peeling.packing_ms, gpu_ms, st.readback_ms, st.narrow_ms, update_ms, total_ms, st.collision_rays,
                              st.triangles_downloaded, st.potentially_colliding_triangles, st.triangle_tests, st.positive_tests, found_pairs,
                              ref.pairs.size(), crossing, found_crossing, cmp.recall, recall_crossing, cmp.precision,
                              double(st.gpu_memory_bytes) / (1024.0 * 1024.0), peakHostMiB(), st.host.narrow_threads, ref.seconds, ref.from_cache ? 1 : 0);
                char cells[256];
                std::snprintf(cells, sizeof cells, "%s,%.4f,%.4f,%.4f,%llu,%llu,", toString(st.method), st.reliable.footprints_ms, st.reliable.pairing_ms,
                              st.reliable.filtering_ms, (unsigned long long)st.cells.candidates, (unsigned long long)st.cells.survivors);
                // The cell stage's own counts (docs/reliable.md), after the note so that the
                // earlier columns keep their places.
                char counts[256];
                std::snprintf(counts, sizeof counts, ",%llu,%llu,%llu,%llu,%llu,%zu,%zu,%.4f,%.4f", (unsigned long long)st.cells.entries,
                              (unsigned long long)st.cells.duplicates, (unsigned long long)st.cells.filtered,
                              (unsigned long long)st.cells.deep_cells, (unsigned long long)st.cells.max_cell, st.gpu_exact_tests,
                              st.cpu_exact_tests, st.gpu_span_ms, st.reliable.sorting_ms);
                csv << row << cells << csvField(st.settings_note) << counts << '\n';
                csv.flush();
                if (profile.is_open()) writeProfile(profile, device + ',' + scene->name + ',' + v.name + ',' + std::to_string(f), st, update_ms, total_ms);
                sum.backend = st.method == DetectMethod::Reliable ? "cells" : toString(st.peeling.backend);
                sum.resolution = st.resolution;
                ++sum.frames;
                sum.found_crossing += found_crossing, sum.crossing += crossing, sum.found += settings.reliable.host_pairs ? cmp.true_positives : std::min(found_pairs, ref.pairs.size()), sum.reference += ref.pairs.size();
                sum.downloaded += st.triangles_downloaded;
                sum.total_ms += total_ms, sum.gpu_ms += gpu_ms, sum.narrow_ms += st.narrow_ms;
                sum.precision_min = std::min(sum.precision_min, cmp.precision);
            };
            // Frames -1 (warm-up on frame 0, not written) to timed - 1. detect() or submit() +
            // collect(): each frame timed from its update to its pair list. Pipelined: step k
            // updates and submits frame k and collects frame k - 1 (its row, timed over the
            // step); the last step submits frame 0 again, collected untimed. The frames run
            // back to back: their rows are compared and written after the loop, so no
            // untimed host work lets the GPU catch up between pipelined steps (which would
            // hide the GPU's part of a step). `slack_ms` puts such work back on purpose: an
            // engine's other work per frame. `drop` compares and releases each frame's result
            // before the next one (its memory goes back, as an engine's would).
            struct TimedFrame {
                int shown;
                DetectResult result;
                double update_ms, total_ms;
            };
            std::vector<TimedFrame> timed_frames;
            DetectResult kept;  // v.into: the result detectInto() fills frame after frame
            const auto frameOf = [&](int f) { return scene->motion == Motion::Rigid ? 0 : std::clamp(f, 0, timed - 1); };
            for (int f = -1; f < timed + (v.pipelined ? 1 : 0); ++f) {
                if (v.slack_ms > 0 && f >= 0) spinFor(v.slack_ms);
                const int mf = v.pipelined && f == timed ? 0 : frameOf(f);
                progress(scene->name + " [" + std::to_string(triangles) + " tris] " + v.name + ": frame " + std::to_string(f + 1) + "/" + std::to_string(timed));
                const auto t0 = Clock::now();
                if (auto ok = applyFrame(**world, *in_world, scene->motion, frames[mf]); !ok) {
                    failed(scene->name + ", " + v.name, ok.error());
                    break;
                }
                const double update_ms = ms(t0, Clock::now());
                Result<DetectResult> r = Error(ErrorCode::InvalidArgument, "");
                Result<void> into_ok;
                if (v.async) {
                    if (auto ok = (*world)->submit(settings); !ok) r = ok.error();
                    else if (v.pipelined && f == -1) continue;  // nothing to collect yet
                    else r = (*world)->collect();
                } else if (v.into) {
                    into_ok = (*world)->detectInto(kept, settings);
                } else {
                    r = (*world)->detect(settings);
                }
                const double total_ms = ms(t0, Clock::now());
                if (v.into) r = into_ok ? Result<DetectResult>(kept) : Result<DetectResult>(into_ok.error());  // copied untimed
                if (!r) {
                    failed(scene->name + ", " + v.name, r.error());
                    break;
                }
                const int shown = v.pipelined ? f - 1 : f;  // the frame this result belongs to
                if (shown >= 0 && v.drop) emit(shown, *r, update_ms, total_ms);  // then released
                else if (shown >= 0)
                    timed_frames.push_back({shown, std::move(*r), update_ms, total_ms});
            }
            if (v.pipelined && (*world)->pending()) (void)(*world)->collect();
            for (const TimedFrame& t : timed_frames) emit(t.shown, t.result, t.update_ms, t.total_ms);
            progressDone();
            if (sum.frames == 0) continue;
            const double n = double(sum.frames);
            std::printf("%-9s %-24s %-14s %-8s %5u %9.3f %9.3f %9.3f %9.0f %8.4f %8.4f %8.4f\n", sum.set.c_str(), sum.scene.c_str(), sum.variant.c_str(),
                        sum.backend.c_str(), sum.resolution, sum.gpu_ms / n, sum.narrow_ms / n, sum.total_ms / n, double(sum.downloaded) / n,
                        sum.reference ? double(sum.found) / double(sum.reference) : 1.0, sum.crossing ? double(sum.found_crossing) / double(sum.crossing) : 1.0,
                        sum.precision_min);
            std::fflush(stdout);
            summaries.push_back(sum);
        }
    }
    progressDone();
    if (!opt.pipeline_stats.empty()) {
        auto stats = (*ctx)->pipelineStatistics();
        if (!stats) {
            std::fprintf(stderr, "vkcollide_bench: --pipeline-stats: %s\n", stats.error().message().c_str());
            ++failures;
        } else {
            std::ofstream out(opt.pipeline_stats);
            out << "device,pipeline,executable,statistic,value\n";
            for (const PipelineStatistics& p : *stats)
                for (const PipelineStatistic& s : p.statistics)
                    out << device << ',' << csvField(p.pipeline) << ',' << csvField(p.executable) << ',' << csvField(s.name) << ','
                        << s.value << '\n';
            if (!out) return std::fprintf(stderr, "vkcollide_bench: --pipeline-stats %s: cannot write it\n", opt.pipeline_stats.c_str()), 1;
            std::printf("pipeline statistics: %zu executables in %s\n", stats->size(), opt.pipeline_stats.c_str());
        }
    }
    std::printf("\nCSV: %s (%zu scene x variant points, %d skipped)\n", opt.csv.empty() ? "none (--csv FILE)" : opt.csv.c_str(),
                summaries.size(), failures);
    if (const std::uint64_t messages = (*ctx)->validationMessageCount(); messages > 0)
        return std::fprintf(stderr, "vkcollide_bench: %llu validation messages\n", (unsigned long long)messages), 3;
    return failures ? 1 : 0;
}
