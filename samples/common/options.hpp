// Command-line options of the samples: a small parser and the options every sample
// shares (frames, output folder, image size, device, mesh data, detection settings).
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vkcollide/world.hpp"

namespace samples {

class Args {
public:
    Args(const char* program, std::string summary);
    // Registers --name with the variable it sets; the help shows the variable's value
    // at registration as the default.
    void option(const char* name, int& value, const char* help);
    void option(const char* name, std::uint32_t& value, const char* help);
    void option(const char* name, float& value, const char* help);
    void option(const char* name, std::string& value, const char* help);
    void flag(const char* name, bool& value, const char* help);  // --name sets true
    // Parses argv; --help prints the usage and exits 0, a bad argument exits 2.
    void parse(int argc, char** argv);
    // Whether --name was on the command line (after parse).
    bool given(const char* name) const;

private:
    struct Entry {
        std::string name, help, default_text;
        bool is_flag = false;
        std::function<bool(const char*)> set;
    };
    void add(const char* name, const char* help, std::string default_text, bool is_flag, std::function<bool(const char*)> set);
    std::string program_, summary_;
    std::vector<Entry> entries_;
    std::vector<std::string> given_;
};

struct CommonOptions {
    int frames = 60;
    std::string out;                 // folder for frame_NNNN.png and frames.csv; default: the sample's name
    std::uint32_t width = 640, height = 400;
    bool no_png = false;             // statistics only
    std::uint32_t png_every = 1;     // write every n-th frame only
    bool quiet = false;              // no line per frame (the progress line stays)
    bool validation = false;         // also on when VKCOLLIDE_TEST_VALIDATION=1 (the test suite)
    std::string device;              // device name substring
    std::string data = "";           // folder with the CGAL meshes; default: data/cgal here or in the source tree
    bool stand_ins = false;          // generated stand-ins instead of the CGAL meshes

    // Detection settings (DetectSettings); 0 / "auto": chosen by vkcollide from the scene.
    // The method as DetectSettings::method: reliable (its default) or peeling (the
    // paper's). Layer cap, dual, backend, axes and coverage shape the peeling method's rays
    // only (detect_settings.hpp): given under the reliable method they are refused, not ignored.
    std::string method = "reliable";
    std::uint32_t resolution = 0;    // reliable: any cell count; peeling: a power of two (the API checks)
    std::uint32_t layer_cap = 0;
    bool dual = false;
    std::string backend = "auto";    // auto, raster, compute
    std::uint32_t axes = 1;
    std::string coverage = "centre"; // centre, dilate, conservative, best
    std::uint32_t threads = 0;       // narrow-phase threads; 0: all

    vkcollide::DetectMethod detectMethod() const;
    vkcollide::DetectSettings detectSettings() const;
};

// Registers the shared options. Call after setting the sample's own defaults in `options`.
void addCommonOptions(Args& args, CommonOptions& options);

// Checks the method and refuses an option the method does not read (exit status 1), turns
// validation on from VKCOLLIDE_TEST_VALIDATION, fills the default output folder and
// creates it. Call after Args::parse.
void finishCommonOptions(const Args& args, CommonOptions& options, const char* sample_name);

// Exits with status 1 when `option` was given (Args::given) but belongs to the other method
// than the one that runs, naming the method it belongs to, as the command-line tool does.
void refuseOtherMethod(const Args& args, const CommonOptions& options, const char* option, vkcollide::DetectMethod belongs_to);

// Whether this frame is written as a PNG (--no-png, --png-every).
bool writesFrame(const CommonOptions& options, int frame);

// Path of a CGAL mesh (tools/fetch_cgal_data.sh), or empty when it is not there.
std::string findDataMesh(const CommonOptions& options, const std::string& file);

}  // namespace samples
