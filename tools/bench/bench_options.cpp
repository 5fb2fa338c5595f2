#include "bench_options.hpp"

#include <charconv>
#include <sstream>
#include <string_view>

namespace vkcollide::bench {
namespace {

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

// The whole text as a number (from_chars: no exception, no trailing text).
template <typename T>
bool number(std::string_view text, T& out) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

void printUsage(std::FILE* out) {
    std::fprintf(out, "usage: vkcollide_bench [--set tuning|held-out|all] [--scenes a,b] [--mesh FILE[:x,y,z]]... "
                      "[--variants names|groups|all] [--resolutions 512,1024] [--scale S] [--frames K] [--threads N] [--data DIR] "
                      "[--cache DIR | --no-cache] [--csv FILE] [--profile FILE] [--pipeline-stats FILE] [--warmup-ms MS] [--list] "
                      "[--reference-only] [--write-obj DIR] [--help]\n");
}

void printHelp() {
    printUsage(stdout);
    std::printf(
        "\nThe speed-against-accuracy sweep: every chosen scene under every chosen settings variant, timed,\n"
        "its pairs against the exact CPU reference (recall of all pairs and of crossing pairs, precision).\n"
        "One CSV row per timed frame (tools/bench/frontier.sh charts it), a table of means on stdout.\n\n"
        "  --mesh FILE[:x,y,z]  your own scene: each OBJ group or OFF/PLY file an object, moved by x,y,z;\n"
        "                       repeat for more files (one scene, named after the files' stems). Alone it\n"
        "                       runs only that scene, variants default,peeling,resolutions, and writes no\n"
        "                       file unless --csv or --cache names one\n"
        "  --set S              built-in scenes of set tuning, held-out or all (default all)\n"
        "  --scenes a,b         built-in scenes by name (--list names them)\n"
        "  --variants V         variant names or groups, comma separated, or all (--list; default\n"
        "                       default,mitigations,resolutions)\n"
        "  --resolutions R      the resolutions of the res-N and cells-N variants (default 512,1024,2048,4096)\n"
        "  --scale S            built-in scenes' triangle counts times S, in (0, 4] (default 1)\n"
        "  --frames K           timed frames of a rigid scene (default 3); charts use frames >= 1\n"
        "  --threads N          narrow-phase and reference threads (default: every hardware thread)\n"
        "  --data DIR           the CGAL meshes of the built-in scenes (tools/fetch_cgal_data.sh; default data/cgal)\n"
        "  --cache DIR          exact references kept there (default bench-cache for built-in scenes)\n"
        "  --no-cache           no reference cache\n"
        "  --csv FILE           the rows (default vkcollide_bench.csv for built-in scenes)\n"
        "  --profile FILE       where each timed frame's time went (tools/bench/profile_table.sh)\n"
        "  --pipeline-stats FILE  every pipeline's compiler statistics (registers, spills...) at the end, as CSV;\n"
        "                       fails where the driver lacks VK_KHR_pipeline_executable_properties\n"
        "  --warmup-ms MS       untimed detections for MS before each scene and variant (warm GPU clocks)\n"
        "  --list               list the scenes and variants and exit\n"
        "  --reference-only     build the scenes and their exact references only (no GPU)\n"
        "  --write-obj DIR      write each chosen scene as DIR/<scene>.obj (moving scenes: <scene>_<frame>.obj), every\n"
        "                       object an o group of its world vertices as the detection sees them, for the CLI\n"
        "                       (vkcollide detect DIR/<scene>.obj finds the scene's exact pairs); no GPU\n"
        "  -h, --help           this help\n");
}

std::optional<Options> parseOptions(int argc, char** argv) {
    Options opt;
    bool variants_given = false, csv_given = false, cache_given = false, scenes_given = false;
    const auto bad = [](const std::string& what) -> std::optional<Options> {
        std::fprintf(stderr, "vkcollide_bench: %s\n", what.c_str());
        printUsage(stderr);
        return std::nullopt;
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool has = i + 1 < argc;
        if (a == "--list") opt.list = true;
        else if (a == "--reference-only") opt.reference_only = true;
        else if (a == "--no-cache") opt.cache.clear(), cache_given = true;
        else if (a == "--help" || a == "-h") opt.help = true;
        else if (a.rfind("--", 0) != 0) return bad("unexpected argument '" + a + "' (a mesh file: --mesh FILE)");
        else if (!has) return bad(a + " needs a value, or is unknown");
        else {
            const std::string v = argv[++i];
            bool ok = true;
            if (a == "--set") opt.set = v, scenes_given = true;
            else if (a == "--scenes") opt.scenes = splitList(v), scenes_given = true;
            else if (a == "--mesh") {
                auto file = parseMeshFile(v);
                if (!file) return bad("--mesh: " + file.error().message());
                opt.meshes.push_back(std::move(*file));
            } else if (a == "--variants") opt.variants = v, variants_given = true;
            else if (a == "--resolutions") {
                opt.resolutions.clear();
                for (const auto& r : splitList(v)) ok = ok && number(r, opt.resolutions.emplace_back());
                ok = ok && !opt.resolutions.empty();
            } else if (a == "--scale") ok = number(v, opt.scale);
            else if (a == "--frames") ok = number(v, opt.frames) && opt.frames >= 1;
            else if (a == "--threads") ok = number(v, opt.threads);
            else if (a == "--data") opt.data = v;
            else if (a == "--cache") opt.cache = v, cache_given = true;
            else if (a == "--csv") opt.csv = v, csv_given = true;
            else if (a == "--profile") opt.profile = v;
            else if (a == "--pipeline-stats") opt.pipeline_stats = v;
            else if (a == "--warmup-ms") ok = number(v, opt.warmup_ms) && opt.warmup_ms >= 0;
            else if (a == "--write-obj") opt.write_obj = v;
            else return bad("unknown option " + a);
            if (!ok) return bad(a + ": bad value '" + v + "'");
        }
    }
    if (opt.set != "all" && opt.set != "tuning" && opt.set != "held-out") return bad("--set needs tuning, held-out or all");
    if (!(opt.scale > 0 && opt.scale <= 4)) return bad("--scale must be in (0, 4]");
    if (!opt.meshes.empty()) {
        // The user's scene compares the two methods, peeling over --resolutions too, and the
        // built-in scenes run only when named.
        if (!variants_given) opt.variants = "default,peeling,resolutions";
        if (!csv_given) opt.csv.clear();
        if (!cache_given) opt.cache.clear();
        if (!scenes_given) opt.set = "none";
    }
    return opt;
}

}  // namespace vkcollide::bench
