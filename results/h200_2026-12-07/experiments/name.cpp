// Microbenchmark: the host's naming of GPU-sorted pairs (narrow::runSortedPairs' loop) into
// reused result memory, plain stores vs non-temporal stores; 1.7M pairs over 218K triangles.
#include <emmintrin.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>
struct Pair { std::uint32_t a, b; };
struct Named { std::uint32_t oa = 0, ta = 0, ob = 0, tb = 0; };
using Clock = std::chrono::steady_clock;
int main() {
    const std::uint32_t tris = 218000, objects = 120, per = tris / objects;
    std::vector<std::uint32_t> base(objects + 1);
    for (std::uint32_t o = 0; o <= objects; ++o) base[o] = o * per;
    std::vector<Pair> pairs;
    std::mt19937 rng(1);
    for (std::uint32_t a = 0; a < objects * per && pairs.size() < 1700000; ++a) {
        std::uint32_t n = rng() % 16, b = a;
        for (std::uint32_t k = 0; k < n && b + 1 < objects * per; ++k) { b += 1 + rng() % 40; if (b >= objects * per) break; pairs.push_back({a, b}); }
    }
    const std::size_t n = pairs.size();
    std::vector<Named> out(n);
    const unsigned threads = std::min(16u, std::thread::hardware_concurrency());
    auto objectOf = [&](std::uint32_t id) { return std::uint32_t(std::upper_bound(base.begin(), base.end(), id) - base.begin() - 1); };
    auto loop = [&](bool nt, std::size_t begin, std::size_t end) {
        std::uint32_t oa = 0, fa = 0, na = 0, ob = 0, fb = 0, nb = 0;
        for (std::size_t k = begin; k < end; ++k) {
            Pair p = pairs[k];
            if (p.a - fa >= na - fa) { oa = objectOf(p.a); fa = base[oa]; na = base[oa + 1]; }
            if (p.b - fb >= nb - fb) { ob = objectOf(p.b); fb = base[ob]; nb = base[ob + 1]; }
            if (nt) _mm_stream_si128(reinterpret_cast<__m128i*>(&out[k]), _mm_setr_epi32(int(oa), int(p.a - fa), int(ob), int(p.b - fb)));
            else out[k] = Named{oa, p.a - fa, ob, p.b - fb};
        }
        if (nt) _mm_sfence();
    };
    for (int mode = 0; mode < 3; ++mode) {
        double best = 1e9;
        for (int rep = 0; rep < 15; ++rep) {
            std::atomic<unsigned> ready{0};
            std::atomic<bool> go{false};
            std::vector<double> took(threads);
            std::vector<std::thread> ts;
            for (unsigned t = 0; t < threads; ++t)
                ts.emplace_back([&, t] {
                    ready++;
                    while (!go.load()) {}
                    auto t0 = Clock::now();
                    const std::size_t chunk = (n + threads - 1) / threads;
                    if (mode < 2) loop(mode == 1, t * chunk, std::min(n, (t + 1) * chunk));
                    took[t] = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
                });
            while (ready.load() < threads) {}
            go = true;
            for (auto& th : ts) th.join();
            best = std::min(best, *std::max_element(took.begin(), took.end()));
        }
        std::printf("%s: %zu pairs, %u threads: %.3f ms (slowest thread, best of 15)\n", mode == 0 ? "plain stores" : mode == 1 ? "streaming stores" : "empty", n, threads, best);
    }
}
