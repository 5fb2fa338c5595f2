// Fresh-memory provisioning probe: how fast can 16 threads make 30 MB of new anonymous memory
// ready, by page touches, memset or MADV_POPULATE_WRITE, with and without MADV_HUGEPAGE.
#include <sys/mman.h>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>
#include <algorithm>
#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23
#endif
using Clock = std::chrono::steady_clock;
static long hugeKbFor(void* p) {
    std::ifstream f("/proc/self/smaps"); std::string line; bool in = false; long kb = -1;
    auto a = reinterpret_cast<unsigned long>(p);
    while (std::getline(f, line)) {
        unsigned long lo, hi;
        if (std::sscanf(line.c_str(), "%lx-%lx", &lo, &hi) == 2 && line.find(' ') != std::string::npos && line[0] != 'A') in = (a >= lo && a < hi);
        if (in && line.rfind("AnonHugePages:", 0) == 0) { kb = std::stol(line.substr(14)); break; }
    }
    return kb;
}
int main(int argc, char** argv) {
    const std::size_t bytes = (argc > 1 ? std::stoul(argv[1]) : 30) << 20;
    const int threads = argc > 2 ? std::stoi(argv[2]) : 16;
    const char* names[] = {"touch4k", "touch4k+huge", "memset+huge", "populate1+huge", "populateN+huge", "populateN", "touch4k-1thread+huge"};
    std::vector<void*> keep;
    for (int rep = 0; rep < 6; ++rep) for (int c = 0; c < 7; ++c) {
        void* p = mmap(nullptr, bytes + (2 << 20), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        auto* base = reinterpret_cast<unsigned char*>((reinterpret_cast<unsigned long>(p) + (2 << 20) - 1) & ~((2ul << 20) - 1));
        const bool huge = c != 0 && c != 5;
        if (huge) madvise(base, bytes, MADV_HUGEPAGE);
        const int n = c == 3 || c == 6 ? 1 : threads;
        const std::size_t chunk = ((bytes / n + (2 << 20) - 1) / (2 << 20)) * (2 << 20);
        std::atomic<int> go{0}; std::atomic<int> rc_bad{0};
        auto work = [&](int t) {
            while (!go.load()) {}
            unsigned char* lo = base + std::min(bytes, t * chunk); unsigned char* hi = base + std::min(bytes, (t + 1) * chunk);
            if (hi <= lo) return;
            if (c == 0 || c == 1 || c == 6) { volatile unsigned char* v = lo; for (std::size_t o = 0; o < std::size_t(hi - lo); o += 4096) v[o] = 0; }
            else if (c == 2) std::memset(lo, 0, hi - lo);
            else if (madvise(lo, hi - lo, MADV_POPULATE_WRITE) != 0) rc_bad++;
        };
        std::vector<std::thread> ts; for (int t = 0; t < n; ++t) ts.emplace_back(work, t);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        auto t0 = Clock::now(); go = 1; for (auto& t : ts) t.join(); auto t1 = Clock::now();
        // then a memset over the now-ready memory: what writing it costs once the pages are there
        auto t2 = Clock::now(); std::memset(base, 1, bytes); auto t3 = Clock::now();
        std::printf("%d,%s,%zu MB,%d threads,%.3f ms,then one-thread memset %.3f ms,AnonHuge %ld kB,bad %d\n", rep, names[c], bytes >> 20, n,
                    std::chrono::duration<double, std::milli>(t1 - t0).count(), std::chrono::duration<double, std::milli>(t3 - t2).count(), hugeKbFor(base), rc_bad.load());
        keep.push_back(p);  // kept, as detect()'s results are: the next one is new memory
    }
}
