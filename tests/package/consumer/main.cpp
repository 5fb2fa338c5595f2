// Two overlapping spheres through the installed public API; exits 0 when pairs are found.
#include <cstdio>

#include <vkcollide/context.hpp>
#include <vkcollide/scene.hpp>
#include <vkcollide/world.hpp>

int main() {
    auto ctx = vkcollide::Context::create();
    if (!ctx) return std::fprintf(stderr, "%s\n", ctx.error().message().c_str()), 1;
    auto world = vkcollide::CollisionWorld::create(**ctx);
    if (!world) return std::fprintf(stderr, "%s\n", world.error().message().c_str()), 1;
    auto a = vkcollide::uvSphere(1.0f, 24, 12), b = vkcollide::uvSphere(1.0f, 24, 12);
    if (!a || !b) return 1;
    vkcollide::ObjectOptions moved;
    moved.transform[3] = 1.2f;
    if (!(*world)->addMesh(*a) || !(*world)->addMesh(*b, moved)) return 1;
    auto hits = (*world)->detect();
    if (!hits) return std::fprintf(stderr, "%s\n", hits.error().message().c_str()), 1;
    std::printf("consumer: %zu pairs\n", hits->pairs.size());
    return hits->pairs.empty() ? 1 : 0;
}
