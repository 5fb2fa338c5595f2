// Session 53 throwaway: one array after the other against both together (narrow::resizeFresh).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>
#include "narrow/parallel.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"
using namespace vkcollide;
int main(int argc, char** argv) {
    const unsigned threads = argc > 1 ? unsigned(std::atoi(argv[1])) : 2;
    ThreadPool pool(threads);
    const std::size_t np = 1706460 * 9 / 8, nr = 400000 * 9 / 8;
    auto ms = [](auto t0) { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(); };
    std::vector<double> seq, both;
    std::vector<std::vector<TrianglePair>> keep_p;
    std::vector<std::vector<TriangleResponse>> keep_r;
    for (int round = 0; round < 30; ++round) {
        for (int mode = 0; mode < 2; ++mode) {
            std::vector<TrianglePair> p;
            std::vector<TriangleResponse> r;
            const auto t0 = std::chrono::steady_clock::now();
            if (mode == 0) {
                narrow::resizeFresh(p, np, pool);
                narrow::resizeFresh(r, nr, pool);
            } else {
                narrow::resizeFresh(p, np, r, nr, pool);
            }
            (mode == 0 ? seq : both).push_back(ms(t0));
            if (argc > 2) { keep_p.push_back(std::move(p)); keep_r.push_back(std::move(r)); }  // kept, as the bench's default
        }
    }
    std::sort(seq.begin(), seq.end());
    std::sort(both.begin(), both.end());
    std::printf("threads %u, %zu + %zu B: one after the other median %.2f ms (min %.2f), together %.2f (min %.2f)\n", threads,
                np * sizeof(TrianglePair), nr * sizeof(TriangleResponse), seq[seq.size() / 2], seq[0], both[both.size() / 2], both[0]);
}
