// vkcollide command-line tool.
//   vkcollide info      list the Vulkan devices and what each supports or lacks
#include <cstdio>
#include <cstring>
#include <string>

#include "vkcollide/context.hpp"

using namespace vkcollide;

namespace {

int usage() {
    std::fprintf(stderr, "usage: vkcollide info\n");
    return 2;
}

int info() {
    auto devices = Context::listDevices();
    if (!devices) {
        std::fprintf(stderr, "vkcollide: %s\n", devices.error().message().c_str());
        return 1;
    }
    if (devices->empty()) std::printf("no Vulkan devices\n");
    for (const DeviceInfo& d : *devices) {
        std::printf("%s\n  type: %s\n  Vulkan %u.%u.%u, driver %s\n  timestamp period: %.3f ns, subgroup size: %u\n",
                    d.name.c_str(), toString(d.type), VK_API_VERSION_MAJOR(d.api_version), VK_API_VERSION_MINOR(d.api_version),
                    VK_API_VERSION_PATCH(d.api_version), d.driver.c_str(), d.timestamp_period_ns, d.subgroup_size);
        std::printf("  conservative rasterization: %s\n", d.conservative_rasterization ? "yes" : "no");
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

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    if (std::strcmp(argv[1], "info") == 0) return info();
    return usage();
}
