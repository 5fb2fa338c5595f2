// Creates and destroys Contexts (and a world detecting two triangles) in a loop; prints the
// open file descriptors and the first failure. argv[1]: rounds, argv[2]: 1 = validation.
#include <vkcollide/context.hpp>
#include <vkcollide/world.hpp>
#include <dirent.h>
#include <cstdio>
#include <cstdlib>
static int fds() { int n = 0; if (DIR* d = opendir("/proc/self/fd")) { while (readdir(d)) ++n; closedir(d); } return n - 2; }
static long rssKb() { FILE* f = fopen("/proc/self/statm", "r"); long a = 0, b = 0; if (f) { if (fscanf(f, "%ld %ld", &a, &b) != 2) b = 0; fclose(f); } return b * 4; }
int main(int argc, char** argv) {
    using namespace vkcollide;
    int rounds = argc > 1 ? std::atoi(argv[1]) : 100;
    ContextCreateInfo info;
    info.validation = argc > 2 && std::atoi(argv[2]) == 1;
    for (int i = 0; i < rounds; ++i) {
        auto ctx = Context::create(info);
        if (!ctx) { std::printf("round %d: %s (fds %d)\n", i, ctx.error().message().c_str(), fds()); return 1; }
        auto world = CollisionWorld::create(**ctx);
        if (!world) { std::printf("round %d world: %s\n", i, world.error().message().c_str()); return 1; }
        HostMesh a{"a", {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {0, 1, 2}};
        HostMesh b{"b", {{-0.3f, -0.2f, -0.5f}, {0.3f, -0.2f, -0.5f}, {0.0f, 0.1f, 0.5f}}, {0, 1, 2}};
        (void)(*world)->addMesh(a, {}); (void)(*world)->addMesh(b, {});
        auto r = (*world)->detect();
        if (!r) { std::printf("round %d detect: %s\n", i, r.error().message().c_str()); return 1; }
        if (i % 10 == 0 || i + 1 == rounds) std::printf("round %d: %zu pairs, fds %d, rss %ld KB\n", i, r->pairs.size(), fds(), rssKb());
    }
    return 0;
}
