#include "cli/options.hpp"

#include <algorithm>
#include <cctype>
#include <optional>

#include "cli/fields.hpp"
#include "cli/file_options.hpp"

namespace cli {
namespace {

using vkcollide::ContactSettings;
using vkcollide::DetectSettings;
using vkcollide::LimitSettings;
using vkcollide::PeelingSettings;
using vkcollide::ReliableSettings;
// DetectSettings' groups, the first member of a grouped field's path.
constexpr auto kPeeling = &DetectSettings::peeling;
constexpr auto kReliable = &DetectSettings::reliable;
constexpr auto kContacts = &DetectSettings::contacts;
constexpr auto kLimits = &DetectSettings::limits;
using fields::setting;
using fields::settingFlag;
using fields::show;

// More narrow-phase threads than any machine has cores for only costs memory and start-up
// time; an absurd count (4294967295) would not even fit the thread table.
constexpr std::uint32_t kMaxThreads = 1024;
constexpr std::uint32_t kMaxImageSide = 8192;

using Setter = Result<void> (*)(CommandLine&, std::string_view);
using SlotSetter = Result<void> (*)(FileSlot&, std::string_view);
using Shower = std::string (*)(const DetectSettings&);

enum class Section { Settings, Objects, Run, Output };

// How an option takes its argument.
enum class Takes {
    Nothing,    // a flag
    Value,      // one value, for the whole run
    Files,      // FILES: the files it applies to
    FileValue,  // FILES:VALUE
};

struct Option {
    const char* name;
    const char* arg;  // as the help shows it; "" for a flag
    Section section;
    const char* help;
    const char* cost;
    Setter set = nullptr;          // Takes::Nothing or Value
    const char* field = nullptr;   // the DetectSettings field it sets: its JSON key (its name before the groups)
    const char* path = nullptr;    // its path ("peeling.dual"); either names the option in library errors
    Shower show = nullptr;         // that field as JSON
    SlotSetter set_slot = nullptr; // Takes::Files or FileValue: applied to each file named
    Takes takes = Takes::Value;
    // Read by the peeling method only (detect_settings.hpp says which fields): refused under the
    // reliable method, left out of the JSON's settings then.
    std::optional<vkcollide::DetectMethod> only;
};

Option peeling(Option o) {
    o.only = vkcollide::DetectMethod::Peeling;
    return o;
}

Option reliable(Option o) {
    o.only = vkcollide::DetectMethod::Reliable;
    return o;
}

Option flag(const char* name, Section section, const char* help, const char* cost, Setter set, const char* field = nullptr,
            const char* path = nullptr, Shower show = nullptr) {
    return {name, "", section, help, cost, set, field, path, show, nullptr, Takes::Nothing};
}
Option perFile(const char* name, const char* arg, const char* help, const char* cost, SlotSetter set, Takes takes) {
    return {name, arg, Section::Objects, help, cost, nullptr, nullptr, nullptr, nullptr, set, takes};
}

template <std::string CommandLine::*kPath>
Result<void> path(CommandLine& c, std::string_view text) {
    if (text.empty()) return badValue("needs a file name");
    c.*kPath = std::string(text);
    return {};
}

// The table. Settings first, in the order DetectSettings had before its groups (the JSON's
// order); every field of DetectSettings and ObjectOptions has its option.
const std::vector<Option>& options() {
    static const std::vector<Option> table = {
        {"--method", "M", Section::Settings, "reliable (default: every intersecting pair, cells and pairs on the GPU) or peeling (the paper's depth peeling)",
         "reliable: GPU passes over triangles, cells and candidate pairs; peeling: faster on some scenes, may miss pairs (docs/stability.md)",
         setting<&DetectSettings::method>, "method", "method", show<&DetectSettings::method>},
        {"--resolution", "N", Section::Settings, "reliable: cells per side, 1 to 16384; peeling: rays per image side, a power of two in [4, 16384] (default: from the typical triangle edge)",
         "GPU time and memory grow with N^2; a larger N resolves thinner contacts and downloads fewer triangles",
         setting<&DetectSettings::resolution>, "resolution", "resolution", show<&DetectSettings::resolution>},
        {"--direction", "x,y,z", Section::Settings, "projection direction (default: chosen from the scene)",
         "free; a direction along which the scene is deep peels more layers", setting<&DetectSettings::direction>, "direction", "direction",
         show<&DetectSettings::direction>},
        peeling({"--cap", "L", Section::Settings, "peel at most L layers; deeper rays count as collision rays (0: as many as the scene needs)",
         "saves peeling passes on deep scenes; rays past the cap send all their triangles to the CPU",
         setting<kPeeling, &PeelingSettings::layer_cap>, "layer_cap", "peeling.layer_cap", show<kPeeling, &PeelingSettings::layer_cap>}),
        peeling(flag("--dual", Section::Settings, "peel from the front and the back at once", "half the peeling passes, a second key buffer",
             settingFlag<true, kPeeling, &PeelingSettings::dual>, "dual", "peeling.dual", show<kPeeling, &PeelingSettings::dual>)),
        peeling({"--packing", "M", Section::Settings, "compaction before the readback: scan, or the paper's count/shift/move (same records)",
         "paper: more passes and a packing texture; for comparison only", setting<kPeeling, &PeelingSettings::packing>, "packing", "peeling.packing",
         show<kPeeling, &PeelingSettings::packing>}),
        peeling({"--backend", "B", Section::Settings, "object sampling: auto, raster or compute (default: chosen per device and scene)",
         "same rays and records; only the speed differs by device", setting<kPeeling, &PeelingSettings::backend>, "backend", "peeling.backend",
         show<kPeeling, &PeelingSettings::backend>}),
        peeling({"--open-epsilon", "E", Section::Settings, "open surfaces: hits closer than E along a ray may collide (world units; default: half their typical edge)",
         "a larger E downloads more triangles near open surfaces; a smaller one may miss grazing contacts",
         setting<kPeeling, &PeelingSettings::open_epsilon>, "open_epsilon", "peeling.open_epsilon", show<kPeeling, &PeelingSettings::open_epsilon>}),
        {"--region", "x0,y0,z0,x1,y1,z1", Section::Settings,
         "the world box the image covers (default: fitted to the scene); reliable: the grid's square spans it, what lies outside "
         "falls into the border cells and is still found; peeling: only this box is sampled",
         "reliable: the same cells on a smaller box see finer detail, the border cells cost time; peeling: contacts outside the box are not found",
         setting<&DetectSettings::region>, "region", "region", show<&DetectSettings::region>},
        peeling(flag("--no-measure-layers", Section::Settings, "peel as many layers as the last detection measured instead of measuring first",
             "saves one host wait per frame (--frames, --sequence); rays that need more layers become collision rays",
             settingFlag<false, kPeeling, &PeelingSettings::measure_layers>, "measure_layers", "peeling.measure_layers", show<kPeeling, &PeelingSettings::measure_layers>)),
        peeling({"--axes", "1|3", Section::Settings, "sampling directions: 1 (the paper) or 3 (also the two perpendicular ones, candidates united)",
         "3: about 3x the GPU time; finds contacts one direction sees edge-on", setting<kPeeling, &PeelingSettings::axes>, "axes", "peeling.axes",
         show<kPeeling, &PeelingSettings::axes>}),
        peeling({"--coverage", "C", Section::Settings, "thin triangles: centre (the paper), dilate, conservative or best (conservative where the device has it, else dilate)",
         "dilate/conservative: more collision rays and downloads, no missed slivers; need the raster backend",
         setting<kPeeling, &PeelingSettings::coverage>, "coverage", "peeling.coverage", show<kPeeling, &PeelingSettings::coverage>}),
        peeling({"--closed-epsilon", "E", Section::Settings, "closed surfaces this close along a ray (world units) count as touching (default 0: exact ties only)",
         "a larger E finds near-contacts as candidates and downloads more triangles", setting<kPeeling, &PeelingSettings::closed_epsilon>,
         "closed_epsilon", "peeling.closed_epsilon", show<kPeeling, &PeelingSettings::closed_epsilon>}),
        {"--bad-objects", "P", Section::Settings, "a --gpu-mesh that fails the GPU check: exclude (detect the rest, name it) or fail",
         "exclude: one more GPU run per bad object that frame", setting<&DetectSettings::bad_objects>, "bad_objects", "bad_objects",
         show<&DetectSettings::bad_objects>},
        peeling(flag("--no-depth-aware", Section::Settings,
                     "the paper's separation: keep every triangle under a collision ray whatever its depth (default: depth-aware)",
                     "downloads 2-30x more triangles where meshes overlap deeply; saves 48 bytes per triangle and 19 per ray of GPU memory",
                     settingFlag<false, kPeeling, &PeelingSettings::depth_aware>, "depth_aware", "peeling.depth_aware", show<kPeeling, &PeelingSettings::depth_aware>)),
        {"--timeout", "MS", Section::Settings, "longest the detection waits for all of its GPU work together (every submission and rerun), milliseconds (default 60000); beyond it the detection fails",
         "free; a detection past it fails with Timeout, and the GPU finishes the submission in flight (one chunk: about 200 ms of work) before the world is free", setting<kLimits, &LimitSettings::timeout_ms>, "timeout_ms", "limits.timeout_ms",
         show<kLimits, &LimitSettings::timeout_ms>},
        {"--wait-poll", "US", Section::Settings, "microseconds the waiting thread polls the GPU's fence around the work's expected end before it sleeps (default 500; 0: sleep only)",
         "a core busy up to US + 150 microseconds per detection; sleeping wakes 0.05-0.2 ms late on an H200", setting<kLimits, &LimitSettings::wait_poll_us>,
         "wait_poll_us", "limits.wait_poll_us", show<kLimits, &LimitSettings::wait_poll_us>},
        {"--max-pairs", "N", Section::Settings, "most colliding pairs to keep (default 16777216); more are counted and reported",
         "about 40 bytes per pair kept", setting<kLimits, &LimitSettings::max_pairs>, "max_pairs", "limits.max_pairs", show<kLimits, &LimitSettings::max_pairs>},
        {"--max-candidate-pairs", "N", Section::Settings,
         "the candidate budget (default 134217728): reliable: footprint box cells and GPU candidate pairs, 64x as many "
         "comparisons; peeling: box pairs the narrow phase sweeps; past it the detection fails",
         "bounds time and memory: reliable 20 bytes per footprint and 12 per candidate on the GPU, peeling up to 8 bytes per pair", setting<kLimits, &LimitSettings::max_candidate_pairs>,
         "max_candidate_pairs", "limits.max_candidate_pairs", show<kLimits, &LimitSettings::max_candidate_pairs>},
        flag("--contacts", Section::Settings,
             "object-level contacts of closed objects: intersection volume, normal, depth and centroid per overlapping pair (docs/contacts.md)",
             "a second GPU stage: rays over where closed objects' boxes overlap, 72 bytes per triangle; about 3-60 % of a detection on lavapipe",
             settingFlag<true, kContacts, &ContactSettings::objects>, "contacts", "contacts.objects", show<kContacts, &ContactSettings::objects>),
        flag("--contact-geometry", Section::Settings,
             "where each intersecting pair meets (a segment, a point or a coplanar overlap) with a normal, and per object pair the "
             "totals; in the JSON (docs/contacts.md)",
             "host work after the narrow phase, in parallel: 0.4-0.7 microseconds of one thread a pair (25-45 ns on 16 threads)",
             settingFlag<true, kContacts, &ContactSettings::geometry>, "contact_geometry", "contacts.geometry", show<kContacts, &ContactSettings::geometry>),
        {"--contact-resolution", "N", Section::Settings, "--contacts: rays across the region where closed objects' boxes overlap, 16 to 4096 (default 128)",
         "GPU time grows with N^2; the volume error shrinks about as 1/N", setting<kContacts, &ContactSettings::resolution>,
         "contact_resolution", "contacts.resolution", show<kContacts, &ContactSettings::resolution>},
        reliable({"--exact", "WHERE", Section::Settings,
                  "where the exact triangle test decides the candidates: auto (the GPU where it has 64-bit floats), gpu or cpu (the reference path)",
                  "gpu: only intersecting pairs are read back and the CPU computes responses alone; cpu: every pair the GPU filter keeps is tested on the CPU; same pairs",
                  setting<kReliable, &ReliableSettings::exact>, "exact", "reliable.exact", show<kReliable, &ReliableSettings::exact>}),
        reliable({"--exact-pass", "HOW", Section::Settings,
                  "with the exact decision on the GPU: queued (a pass of its own over the candidates the pair pass's filter leaves), "
                  "inline (inside the pair pass) or auto (queued from 65,536 candidates in their canonical cells in the last detection; "
                  "docs/exact_gpu.md)",
                  "queued: full subgroups on the exact path and a lighter filter, about 15 us more a chunk; same pairs",
                  setting<kReliable, &ReliableSettings::exact_pass>, "exact_pass", "reliable.exact_pass",
                  show<kReliable, &ReliableSettings::exact_pass>}),
        reliable({"--pair-sort", "WHERE", Section::Settings,
                  "where the exact decision's pairs are put in order: auto (the GPU: its device-pairs passes from 4096 pairs in the last "
                  "detection, below that one pass where the survivors fit it), gpu or cpu (the narrow phase; docs/exact_gpu.md)",
                  "gpu: the device-pairs passes and one copy; auto below 4096: one workgroup's sort, a pass over the responders and "
                  "one copy; cpu: the host sorts; same pairs and responses",
                  setting<kReliable, &ReliableSettings::pair_sort>, "pair_sort", "reliable.pair_sort", show<kReliable, &ReliableSettings::pair_sort>}),
        reliable({"--responses", "WHERE", Section::Settings,
                  "where the responses are computed when the pairs are sorted on the GPU: auto (the GPU), gpu (the pairs sorted "
                  "there too) or cpu (the narrow phase; docs/exact_gpu.md)",
                  "gpu: three GPU passes over the triangles and one copy, the host only checks and copies; same responses to the bit",
                  setting<kReliable, &ReliableSettings::responses>, "responses", "reliable.responses",
                  show<kReliable, &ReliableSettings::responses>}),
        reliable({"--pair-naming", "WHEN", Section::Settings,
                  "with the responses on the GPU, when the host names the sorted pairs: auto (while the GPU computes the "
                  "responses, from 32768 pairs in the last detection; the host polls a VkEvent) or after-fence (after the "
                  "submission's fence, the host synchronisation Vulkan specifies; docs/exact_gpu.md)",
                  "after-fence: the naming no longer overlaps the GPU, but the GPU span is shorter (measured at most 0.07 ms "
                  "slower than auto on 0.2-1.7M pairs); same result",
                  setting<kReliable, &ReliableSettings::pair_naming>, "pair_naming", "reliable.pair_naming",
                  show<kReliable, &ReliableSettings::pair_naming>}),
        reliable({"--grid-tuning", "HOW", Section::Settings,
                  "with an automatic --resolution: on (the grid chosen per scene from the detections' GPU times), off (2 cells "
                  "per typical edge) or auto (the library's choice: on on a GPU, off on a CPU implementation such as lavapipe)",
                  "on: a scene's first detections try neighbouring grids, some slower; same pairs at every grid",
                  setting<kReliable, &ReliableSettings::grid_tuning>, "grid_tuning", "reliable.grid_tuning",
                  show<kReliable, &ReliableSettings::grid_tuning>}),
        reliable({"--proximity", "D", Section::Settings,
                  "also every vertex-triangle and edge-edge pair within distance D (world units) with its distance, closest points "
                  "and normal (docs/proximity.md; host meshes, 64-bit floats on the GPU)",
                  "a GPU pass over the candidates of triangles grown by D/2: more candidates, 64 bytes per pair found",
                  [](CommandLine& c, std::string_view v) -> Result<void> {
                      auto d = parseFloat(v);
                      if (!d) return d.error();
                      c.settings.proximity.distance = *d;
                      return {};
                  },
                  "proximity", "proximity.distance", [](const DetectSettings& s) { return fields::jsonNumber(s.proximity.distance); }}),
        reliable({"--proximity-capacity", "N", Section::Settings,
                  "--proximity: pairs the GPU buffer holds; a detection finding more fails naming the count (default 0: grows as needed)",
                  "64 bytes per pair of device-visible host memory",
                  [](CommandLine& c, std::string_view v) -> Result<void> {
                      auto n = parseUint(v);
                      if (!n) return n.error();
                      c.settings.proximity.capacity = *n;
                      return {};
                  },
                  "proximity_capacity", "proximity.capacity", [](const DetectSettings& s) { return fields::jsonOf(s.proximity.capacity); }}),
        peeling(flag("--paper-packing", Section::Settings, "the same as --packing paper", "as --packing paper",
             [](CommandLine& c, std::string_view) -> Result<void> {
                 c.settings.peeling.packing = vkcollide::PackingMethod::Paper;
                 return {};
             })),

        perFile("--name", "FILES:NAME", "names the objects of those files (an OBJ with several groups: NAME/group)", "free",
                slotName, Takes::FileValue),
        perFile("--open", "FILES", "open surfaces (cloth, terrain): tested by depth proximity, not inside/outside", "more candidates near each other than closed objects give",
                slotOpen, Takes::Files),
        perFile("--self", "FILES", "these files' objects also test their own triangles (default: none do, as in the API)",
                "self-collision tests an object's triangles against each other: more candidate pairs", slotSelf, Takes::Files),
        // Kept for scripts written when self-collision was on by default.
        flag("--no-self-collision", Section::Objects, "the same as --self none (the default)", "free",
             [](CommandLine&, std::string_view) -> Result<void> { return {}; }),
        perFile("--transform", "FILES:m00,...,m23", "object -> world, 12 numbers, row-major 3x4 [R|t], applied after the transforms before it", "free",
                slotTransform, Takes::FileValue),
        perFile("--translate", "FILES:x,y,z", "move by x,y,z (after the transforms before it)", "free", slotTranslate, Takes::FileValue),
        perFile("--rotate", "FILES:x,y,z,deg", "rotate by deg degrees about the axis x,y,z through the origin", "free", slotRotate,
                Takes::FileValue),
        perFile("--scale", "FILES:s|sx,sy,sz", "scale about the origin", "free", slotScale, Takes::FileValue),
        perFile("--gpu-mesh", "FILES", "add as an engine's GPU buffers (addGpuMesh): the tool's own Vulkan device is lent to vkcollide",
                "each detection checks their indices and positions on the GPU", slotGpu, Takes::Files),
        perFile("--edge-length", "FILES:L", "typical edge length of a --gpu-mesh, object units (host meshes are measured)",
                "only steers the automatic resolution", slotEdge, Takes::FileValue),

        flag("--sequence", Section::Run, "the files are frames of the same objects (same topology), detected in order",
             "one detection per frame; later frames only update vertices", [](CommandLine& c, std::string_view) -> Result<void> {
                 c.sequence = true;
                 return {};
             }),
        {"--frame-files", "K", Section::Run, "--sequence: each frame is K consecutive files (default 1)", "free",
         [](CommandLine& c, std::string_view v) -> Result<void> {
             auto k = parseUint(v, 1, 1u << 20);
             if (!k) return k.error();
             c.files_per_frame = *k;
             return {};
         }},
        {"--frames", "K", Section::Run, "detect the same scene K times (timings of the last; the first allocates)", "K detections",
         [](CommandLine& c, std::string_view v) -> Result<void> {
             auto k = parseUint(v, 1, 1u << 24);
             if (!k) return k.error();
             c.repeats = *k;
             return {};
         }},
        {"--threads", "T", Section::Run, "narrow-phase threads, 1 to 1024 (default: every hardware thread)", "memory per thread",
         [](CommandLine& c, std::string_view v) -> Result<void> {
             auto t = parseUint(v, 1, kMaxThreads);
             if (!t) return badValue(t.error().message() + " (leave it out to use every hardware thread)");
             c.threads = *t;
             return {};
         }},
        {"--device", "NAME", Section::Run, "use the Vulkan device whose name contains NAME (vkcollide info lists them)", "free",
         [](CommandLine& c, std::string_view v) -> Result<void> {
             c.device = std::string(v);
             return {};
         }},
        flag("--no-robust-access", Section::Run, "create the device without robustBufferAccess(2)", "measures what robustness costs; no second line of defence",
             [](CommandLine& c, std::string_view) -> Result<void> {
                 c.robust_access = false;
                 return {};
             }),
        flag("--validation", Section::Run, "Khronos validation layer on; any message makes the exit status 3",
             "much slower; needs vulkan-validationlayers", [](CommandLine& c, std::string_view) -> Result<void> {
                 c.validation = true;
                 return {};
             }),
        flag("--quiet", Section::Run, "no line per frame (the summary and the progress line stay)", "free",
             [](CommandLine& c, std::string_view) -> Result<void> {
                 c.quiet = true;
                 return {};
             }),

        {"--pairs", "FILE", Section::Output, "colliding pairs as CSV lines a,b (global triangle numbers, a < b); --sequence: frame,a,b",
         "a line per pair", path<&CommandLine::pairs_path>},
        {"--proximity-pairs", "FILE", Section::Output,
         "--proximity: its pairs as CSV (kind,object_a,a0,a1,object_b,b0,b1,distance,weight_a,wb0,wb1,wb2,nx,ny,nz,in_band); "
         "--sequence: frame first",
         "a line per pair", path<&CommandLine::proximity_path>},
        {"--json", "FILE", Section::Output, "everything as JSON: objects, settings asked and used, per frame pairs, responses, excluded objects, statistics (docs/cli.md)",
         "a few lines per pair", path<&CommandLine::json_path>},
        {"--stats", "FILE", Section::Output, "the last frame's statistics as JSON (the paper's Table 1, settings, stage times)", "free",
         path<&CommandLine::stats_path>},
        {"--csv", "FILE", Section::Output, "a line of statistics per frame (the paper's Table 1 columns and stage times, as the samples write)",
         "free", path<&CommandLine::csv_path>},
        {"--png", "FILE", Section::Output, "a picture of the scene, colliding triangles highlighted; --sequence: FILE_0000.png ... per frame",
         "a second Vulkan device (unless --gpu-mesh lent one) and a render per frame", path<&CommandLine::png_path>},
        {"--png-size", "W,H", Section::Output, "the picture's size in pixels (default 800,600)", "render time grows with W x H",
         [](CommandLine& c, std::string_view v) -> Result<void> {
             const std::size_t comma = v.find(',');
             auto w = parseUint(v.substr(0, comma), 16, kMaxImageSide);
             auto h = comma == std::string_view::npos ? w : parseUint(v.substr(comma + 1), 16, kMaxImageSide);
             if (comma == std::string_view::npos || !w || !h)
                 return badValue("needs W,H, each from 16 to " + std::to_string(kMaxImageSide) + ", got '" + std::string(v) + "'");
             c.png_width = *w, c.png_height = *h;
             return {};
         }},
        {"--view", "x,y,z", Section::Output, "--png: look at the scene from this direction (from its centre towards the eye)", "free",
         [](CommandLine& c, std::string_view v) -> Result<void> {
             auto d = parseFloats<3>(v);
             if (!d) return d.error();
             if ((*d)[0] == 0 && (*d)[1] == 0 && (*d)[2] == 0) return badValue("needs a non-zero direction");
             c.view = *d;
             return {};
         }},
        peeling(flag("--rays", Section::Output, "--png: draw the collision rays (of every sampling direction) as thin yellow sticks",
             "reads back N^2 flags per drawn frame and maps the collision rays to world space", [](CommandLine& c, std::string_view) -> Result<void> {
                 c.rays = true;
                 return {};
             })),
    };
    return table;
}

const char* sectionTitle(Section s) {
    switch (s) {
        case Section::Settings: return "Detection settings (DetectSettings; left out: chosen from the scene, the settings note says how)";
        case Section::Objects:
            return "Objects, per file (ObjectOptions). FILES: all, none, or file numbers from 1 in command-line order such as\n"
                   "1,3-4; with --sequence, the file's place in each frame. Repeated options add up; transforms compose in order";
        case Section::Run: return "Running";
        case Section::Output: return "Output";
    }
    return "";
}

const Option* find(std::string_view name) {
    for (const Option& o : options())
        if (name == o.name) return &o;
    return nullptr;
}

std::string slotsText(const CommandLine& c, std::size_t count) {
    if (c.sequence) return "each frame has " + std::to_string(count) + (count == 1 ? " file" : " files");
    return count == 1 ? "there is 1 file" : "there are " + std::to_string(count) + " files";
}

}  // namespace

std::span<const std::string> CommandLine::frameFiles(std::size_t f) const {
    if (!sequence) return files;
    return std::span<const std::string>(files).subspan(f * files_per_frame, files_per_frame);
}

void printUsage(std::FILE* out) {
    std::fputs("usage: vkcollide info\n"
               "       vkcollide detect FILE... [options]      (vkcollide detect --help: every option)\n",
               out);
}

void printHelp(std::FILE* out) {
    printUsage(out);
    std::fputs("\n  info    list the Vulkan devices and what each supports or lacks\n"
               "  detect  find the intersecting triangle pairs of the scene in FILE...\n"
               "  FILE    .obj (each o/g group is an object), .off or .ply (one object); objects are numbered from 0\n"
               "          and triangles globally from 0, in command-line then file order\n",
               out);
    const Section sections[] = {Section::Settings, Section::Objects, Section::Run, Section::Output};
    for (Section s : sections) {
        std::fprintf(out, "\n%s:\n", sectionTitle(s));
        for (const Option& o : options()) {
            if (o.section != s) continue;
            const std::string head = std::string(o.name) + (*o.arg ? " " : "") + o.arg;
            const std::string help = (o.only ? std::string(vkcollide::toString(*o.only)) + " only: " : std::string()) + o.help;
            if (head.size() <= 26) std::fprintf(out, "  %-26s %s\n", head.c_str(), help.c_str());
            else std::fprintf(out, "  %s\n  %-26s %s\n", head.c_str(), "", help.c_str());
            std::fprintf(out, "  %-26s cost: %s\n", "", o.cost);
        }
    }
    std::fputs("\n  -h, --help                 print this help\n"
               "Exit status: 0 done, 1 an error (the message names the option or file and the problem),\n"
               "2 an option or command it does not know, or no FILE, 3 --validation saw a message. docs/cli.md has the details.\n",
               out);
}

Parsed parseDetect(std::span<const char* const> args) {
    Parsed p;
    CommandLine& c = p.line;
    for (const char* a : args)
        if (std::string_view(a) == "--help" || std::string_view(a) == "-h") return {Parsed::Kind::Help, {}, {}};
    auto error = [&](Parsed::Kind kind, std::string what) {
        p.kind = kind;
        p.error = std::move(what);
        return p;
    };
    struct Deferred {
        const Option* option;
        std::string value;
    };
    std::vector<Deferred> deferred;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string_view a = args[i];
        if (a.size() < 2 || a[0] != '-') {
            c.files.emplace_back(a);
            continue;
        }
        // --name=value is --name value.
        std::optional<std::string_view> inline_value;
        if (const std::size_t eq = a.find('='); eq != std::string_view::npos) inline_value = a.substr(eq + 1), a = a.substr(0, eq);
        const Option* o = find(a);
        if (!o) return error(Parsed::Kind::Usage, "unknown option " + std::string(args[i]));
        std::string value;
        if (o->takes == Takes::Nothing) {
            if (inline_value) return error(Parsed::Kind::Error, std::string(o->name) + " takes no value");
        } else if (inline_value) {
            value = std::string(*inline_value);
        } else if (i + 1 < args.size() && !(std::string_view(args[i + 1]).rfind("--", 0) == 0 && find(args[i + 1]))) {
            // (An option's name where its value should be means the value was left out.)
            value = args[++i];
        } else {
            return error(Parsed::Kind::Error, std::string(o->name) + " needs a value (" + o->arg + ")");
        }
        c.given.emplace_back(o->name, value);
        if (o->set_slot) {
            deferred.push_back({o, value});
        } else if (auto ok = o->set(c, value); !ok) {
            return error(Parsed::Kind::Error, std::string(o->name) + " " + ok.error().message());
        }
    }
    if (c.files.empty()) return error(Parsed::Kind::Usage, "detect needs at least one scene file");
    if (c.sequence && c.files.size() % c.files_per_frame != 0)
        return error(Parsed::Kind::Error, "--frame-files " + std::to_string(c.files_per_frame) + ": " + std::to_string(c.files.size()) +
                                              " files do not make whole frames of " + std::to_string(c.files_per_frame));
    if (!c.sequence && c.files_per_frame != 1) return error(Parsed::Kind::Error, "--frame-files needs --sequence");
    if (c.sequence && c.repeats != 1) return error(Parsed::Kind::Error, "--frames repeats one scene; with --sequence the files are the frames");

    // Options naming files, now that the files are known, in command-line order.
    const std::size_t count = c.sequence ? c.files_per_frame : c.files.size();
    c.slots.assign(count, FileSlot{});
    for (const Deferred& d : deferred) {
        Result<FileValue> fv = d.option->takes == Takes::Files ? Result<FileValue>(FileValue{{}, {}}) : parseFileValue(d.value, count, slotsText(c, count));
        if (fv && d.option->takes == Takes::Files) {
            auto files = parseFileList(d.value, count, slotsText(c, count));
            if (!files) fv = files.error();
            else fv->files = std::move(*files);
        }
        if (!fv) return error(Parsed::Kind::Error, std::string(d.option->name) + " " + fv.error().message());
        for (std::size_t f = 0; f < count; ++f) {
            if (!fv->files[f]) continue;
            if (auto ok = d.option->set_slot(c.slots[f], fv->value); !ok)
                return error(Parsed::Kind::Error, std::string(d.option->name) + " " + d.value + ": " + ok.error().message());
        }
    }
    for (std::size_t f = 0; f < count; ++f) {
        FileSlot& s = c.slots[f];
        s.options.self_collision = s.self_listed;  // off unless listed, as ObjectOptions' default
        if (s.options.typical_edge_length > 0 && !s.gpu_mesh)
            return error(Parsed::Kind::Error, "--edge-length: file " + std::to_string(f + 1) +
                                                  " is not a --gpu-mesh (the edges of host meshes are measured)");
    }
    // Options the method that runs does not read are refused, not ignored.
    for (const auto& given : c.given)
        if (const Option* o = find(given.first); o && o->only && *o->only != c.settings.method) {
            const bool peeling = *o->only == vkcollide::DetectMethod::Peeling;
            return error(Parsed::Kind::Error, given.first + " belongs to the " + vkcollide::toString(*o->only) + " method (--method " +
                                                  vkcollide::toString(*o->only) + (peeling ? "" : ", the default") + "); the " +
                                                  vkcollide::toString(c.settings.method) +
                                                  (given.first == "--rays" ? " method casts no rays" : " method does not read it"));
        }
    if (c.rays && c.png_path.empty()) return error(Parsed::Kind::Error, "--rays draws on the --png picture: give --png FILE too");
    bool any_gpu = false;
    for (const FileSlot& s : c.slots) any_gpu = any_gpu || s.gpu_mesh;
    if (any_gpu && !c.robust_access)
        return error(Parsed::Kind::Error, "--no-robust-access applies to vkcollide's own device; with --gpu-mesh the tool's "
                                          "engine device is lent to vkcollide as it is");
    return p;
}

namespace {

// Whether `message` names `name` as a whole: "peeling.axes" names the path, not "axes" or
// "peeling"; "contacts.geometry" does not name "contacts".
bool names(const std::string& message, const std::string& name) {
    const auto part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = message.find(name); at != std::string::npos; at = message.find(name, at + 1)) {
        const std::size_t end = at + name.size();
        const bool starts = at == 0 || (!part(message[at - 1]) && message[at - 1] != '.');
        const bool member_follows = end + 1 < message.size() && message[end] == '.' && part(message[end + 1]);
        const bool ends = end == message.size() || (!part(message[end]) && !member_follows);
        if (starts && ends) return true;
    }
    return false;
}

}  // namespace

std::string nameSettingOptions(const CommandLine& line, const std::string& message) {
    std::string named;
    for (const Option& o : options()) {
        if (!o.field) continue;
        // The library words its rules with the field's path ("peeling.open_epsilon"), its name
        // ("open_epsilon") or its words ("open epsilon").
        std::string words = o.field;
        std::replace(words.begin(), words.end(), '_', ' ');
        if (!(o.path && names(message, o.path)) && !names(message, o.field) && !names(message, words)) continue;
        for (const auto& [name, value] : line.given)
            if (name == o.name) named += (named.empty() ? "" : ", ") + name + (value.empty() ? "" : " " + value);
    }
    return named.empty() ? message : named + ": " + message;
}

std::vector<std::pair<std::string, std::string>> settingsJson(const DetectSettings& settings) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const Option& o : options())
        if (o.field && o.show && (!o.only || *o.only == settings.method))
            out.emplace_back(o.field, o.show(settings));
    return out;
}

}  // namespace cli
