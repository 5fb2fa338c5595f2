// vkcollide command-line tool.
//   vkcollide info                      list the Vulkan devices and what each supports or lacks
//   vkcollide detect FILE... [options]  find the intersecting triangle pairs of the scene
//
// Every option is in one table (options.cpp), which parsing, --help and the JSON read;
// docs/cli.md is the manual.
#include <cstdio>
#include <cstring>
#include <span>

#include "cli/detect.hpp"
#include "cli/options.hpp"
#include "vkcollide/context.hpp"

namespace {

int info() {
    auto devices = vkcollide::Context::listDevices();
    if (!devices) {
        std::fprintf(stderr, "vkcollide: %s\n", devices.error().message().c_str());
        return 1;
    }
    if (devices->empty()) std::printf("no Vulkan devices\n");
    for (const vkcollide::DeviceInfo& d : *devices) {
        std::printf("%s\n  type: %s\n  Vulkan %u.%u.%u, driver %s\n  timestamp period: %.3f ns, subgroup size: %u\n", d.name.c_str(),
                    vkcollide::toString(d.type), VK_API_VERSION_MAJOR(d.api_version), VK_API_VERSION_MINOR(d.api_version),
                    VK_API_VERSION_PATCH(d.api_version), d.driver.c_str(), d.timestamp_period_ns, d.subgroup_size);
        const auto yes = [](bool b) { return b ? "yes" : "no"; };
        std::printf("  optional: conservative rasterization %s, push descriptors %s, robustness2 %s, shaderFloat64 %s\n",
                    yes(d.conservative_rasterization), yes(d.push_descriptor), yes(d.robustness2), yes(d.shader_float64));
        if (d.missing.empty()) {
            std::printf("  usable by vkcollide: yes\n");
        } else {
            std::printf("  usable by vkcollide: no, lacks:");
            for (const auto& m : d.missing) std::printf(" %s", m.c_str());
            std::printf("\n");
        }
    }
    return 0;
}

int usageError(const std::string& what) {
    if (!what.empty()) std::fprintf(stderr, "vkcollide: %s\n", what.c_str());
    cli::printUsage(stderr);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usageError("");
    const std::string_view command = argv[1];
    if (command == "info") return info();
    if (command == "--help" || command == "-h") {
        cli::printHelp(stdout);
        return 0;
    }
    if (command != "detect") return usageError("unknown command " + std::string(command));
    const cli::Parsed parsed = cli::parseDetect(std::span<const char* const>(argv + 2, static_cast<std::size_t>(argc - 2)));
    switch (parsed.kind) {
        case cli::Parsed::Kind::Help: cli::printHelp(stdout); return 0;
        case cli::Parsed::Kind::Usage: return usageError(parsed.error);
        case cli::Parsed::Kind::Error: std::fprintf(stderr, "vkcollide: %s\n", parsed.error.c_str()); return 1;
        case cli::Parsed::Kind::Run: break;
    }
    return cli::runDetect(parsed.line);
}
