#include "common/options.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "common/render.hpp"

namespace samples {
namespace {

std::string formatFloat(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
    return buf;
}

}  // namespace

Args::Args(const char* program, std::string summary) : program_(program), summary_(std::move(summary)) { setProgramName(program); }

void Args::add(const char* name, const char* help, std::string default_text, bool is_flag, std::function<bool(const char*)> set) {
    entries_.push_back({std::string("--") + name, help, std::move(default_text), is_flag, std::move(set)});
}

void Args::option(const char* name, int& value, const char* help) {
    add(name, help, std::to_string(value), false, [&value](const char* s) {
        char* end = nullptr;
        const long v = std::strtol(s, &end, 10);
        value = static_cast<int>(v);
        return *s && !*end;
    });
}

void Args::option(const char* name, std::uint32_t& value, const char* help) {
    add(name, help, std::to_string(value), false, [&value](const char* s) {
        char* end = nullptr;
        const unsigned long v = std::strtoul(s, &end, 10);
        value = static_cast<std::uint32_t>(v);
        return *s && !*end && s[0] != '-';
    });
}

void Args::option(const char* name, float& value, const char* help) {
    add(name, help, formatFloat(value), false, [&value](const char* s) {
        char* end = nullptr;
        value = std::strtof(s, &end);
        return *s && !*end;
    });
}

void Args::option(const char* name, std::string& value, const char* help) {
    add(name, help, value.empty() ? "" : value, false, [&value](const char* s) {
        value = s;
        return true;
    });
}

void Args::flag(const char* name, bool& value, const char* help) {
    add(name, help, "", true, [&value](const char*) {
        value = true;
        return true;
    });
}

void Args::parse(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::printf("%s: %s\n\noptions:\n", program_.c_str(), summary_.c_str());
            for (const Entry& e : entries_) {
                std::string left = e.name + (e.is_flag ? "" : " V");
                std::printf("  %-22s %s%s\n", left.c_str(), e.help.c_str(),
                            e.default_text.empty() ? "" : (" (default " + e.default_text + ")").c_str());
            }
            std::exit(0);
        }
        const Entry* found = nullptr;
        for (const Entry& e : entries_)
            if (e.name == a) found = &e;
        if (!found) {
            std::fprintf(stderr, "%s: unknown argument '%s' (--help lists the options)\n", program_.c_str(), a.c_str());
            std::exit(2);
        }
        const char* value = "";
        if (!found->is_flag) {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s: %s needs a value\n", program_.c_str(), a.c_str());
                std::exit(2);
            }
            value = argv[++i];
        }
        if (!found->set(value)) {
            std::fprintf(stderr, "%s: bad value '%s' for %s\n", program_.c_str(), value, a.c_str());
            std::exit(2);
        }
        given_.push_back(a);
    }
}

bool Args::given(const char* name) const {
    for (const std::string& g : given_)
        if (g == std::string("--") + name) return true;
    return false;
}

void addCommonOptions(Args& args, CommonOptions& o) {
    args.option("frames", o.frames, "frames to simulate, detect and render");
    args.option("out", o.out, "output folder: frame_NNNN.png and frames.csv (default: the sample's name)");
    args.option("width", o.width, "image width in pixels");
    args.option("height", o.height, "image height in pixels");
    args.flag("no-png", o.no_png, "write no images (statistics only)");
    args.option("png-every", o.png_every, "write every n-th frame only");
    args.flag("quiet", o.quiet, "no line per frame, only the progress line and the summary");
    args.flag("validation", o.validation, "Vulkan validation layer on; any message fails the run (also VKCOLLIDE_TEST_VALIDATION=1)");
    args.option("device", o.device, "Vulkan device name substring (also VKCOLLIDE_DEVICE)");
    args.option("data", o.data, "folder of the CGAL meshes (tools/fetch_cgal_data.sh; default data/cgal)");
    args.flag("stand-ins", o.stand_ins, "generated stand-ins instead of the CGAL meshes");
    args.option("method", o.method,
                "reliable (every intersecting pair: cells and pairs on the GPU) or peeling (the paper's depth peeling)");
    args.option("resolution", o.resolution,
                "reliable: cells per side, 1 to 16384; peeling: rays per image side, a power of two in [4, 16384]; 0: automatic");
    args.option("layer-cap", o.layer_cap, "peeling only: most depth layers to peel; 0: the measured depth complexity");
    args.flag("dual", o.dual, "peeling only: dual depth peeling (front and back at once)");
    args.option("backend", o.backend, "peeling only: object sampling: auto, raster or compute");
    args.option("axes", o.axes, "peeling only: sampling directions: 1 (the paper) or 3");
    args.option("coverage", o.coverage, "peeling only: thin triangles: centre (the paper), dilate, conservative or best");
    args.option("threads", o.threads, "narrow-phase threads; 0: all hardware threads");
}

vkcollide::DetectMethod CommonOptions::detectMethod() const {
    if (method == "reliable") return vkcollide::DetectMethod::Reliable;
    if (method == "peeling") return vkcollide::DetectMethod::Peeling;
    die("--method takes reliable or peeling, not '" + method + "'");
}

vkcollide::DetectSettings CommonOptions::detectSettings() const {
    vkcollide::DetectSettings s;
    s.method = detectMethod();
    // Passed on as given: under the peeling method a count that is not a power of two
    // fails the first detection with the API's message.
    if (resolution) s.resolution = resolution;
    s.peeling.layer_cap = layer_cap;
    s.peeling.dual = dual;
    s.peeling.axes = axes;
    if (backend == "raster") s.peeling.backend = vkcollide::SamplingBackend::Raster;
    else if (backend == "compute") s.peeling.backend = vkcollide::SamplingBackend::Compute;
    else if (backend != "auto") die("--backend takes auto, raster or compute");
    if (coverage == "dilate") s.peeling.coverage = vkcollide::Coverage::Dilate;
    else if (coverage == "conservative") s.peeling.coverage = vkcollide::Coverage::Conservative;
    else if (coverage == "best") s.peeling.coverage = vkcollide::Coverage::Best;
    else if (coverage != "centre") die("--coverage takes centre, dilate, conservative or best");
    return s;
}

void refuseOtherMethod(const Args& args, const CommonOptions& o, const char* option, vkcollide::DetectMethod belongs_to) {
    const vkcollide::DetectMethod runs = o.detectMethod();
    if (runs == belongs_to || !args.given(option + 2)) return;
    const bool peeling = belongs_to == vkcollide::DetectMethod::Peeling;
    die(std::string(option) + " belongs to the " + vkcollide::toString(belongs_to) + " method (--method " +
        vkcollide::toString(belongs_to) + (peeling ? "" : ", the default") + "); the " + vkcollide::toString(runs) +
        " method does not read it");
}

void finishCommonOptions(const Args& args, CommonOptions& o, const char* sample_name) {
    // The options that shape the peeling method's rays (DetectSettings, detect_settings.hpp).
    for (const char* option : {"--layer-cap", "--dual", "--backend", "--axes", "--coverage"})
        refuseOtherMethod(args, o, option, vkcollide::DetectMethod::Peeling);
    if (const char* env = std::getenv("VKCOLLIDE_TEST_VALIDATION"); env && std::strcmp(env, "1") == 0) o.validation = true;
    if (o.frames < 1) die("--frames must be at least 1");
    if (o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192) die("--width and --height must be in [16, 8192]");
    if (o.png_every < 1) die("--png-every must be at least 1");
    if (o.out.empty()) o.out = sample_name;
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) die("cannot create the output folder " + o.out + ": " + ec.message());
}

bool writesFrame(const CommonOptions& o, int frame) { return !o.no_png && frame % int(o.png_every) == 0; }

std::string findDataMesh(const CommonOptions& o, const std::string& file) {
    namespace fs = std::filesystem;
    std::vector<fs::path> dirs;
    if (!o.data.empty()) dirs.emplace_back(o.data);
    else {
        dirs.emplace_back("data/cgal");
        dirs.emplace_back(fs::path(VKCOLLIDE_SOURCE_DIR) / "data" / "cgal");
    }
    for (const fs::path& d : dirs)
        if (std::error_code ec; fs::is_regular_file(d / file, ec)) return (d / file).string();
    return {};
}

}  // namespace samples
