// Throwaway: what a detection's fresh result memory costs on a host (session 52).
#include <sys/mman.h>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <thread>
#include <vector>
#include <algorithm>
using Clock = std::chrono::steady_clock;
static double ms(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }
static void advise(void* data, size_t bytes) {
    const uintptr_t H = uintptr_t{2} << 20;
    uintptr_t b = (reinterpret_cast<uintptr_t>(data) + H - 1) & ~(H - 1), e = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(H - 1);
    if (e > b) madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
}
struct Pool {
    int n; std::vector<std::thread> t; std::atomic<int> gen{0}, done{0}; std::function<void(int)> job; std::atomic<bool> quit{false};
    explicit Pool(int n_) : n(n_) {
        for (int i = 0; i < n; ++i) t.emplace_back([this, i] { int seen = 0; for (;;) { while (gen.load() == seen && !quit) std::this_thread::yield(); if (quit) return; seen = gen.load(); job(i); done++; } });
    }
    void run(std::function<void(int)> f) { job = std::move(f); done = 0; gen++; while (done.load() < n) std::this_thread::yield(); }
    ~Pool() { quit = true; for (auto& x : t) x.join(); }
};
int main(int argc, char** argv) {
    int threads = argc > 1 ? atoi(argv[1]) : 16;
    for (const char* f : {"/sys/kernel/mm/transparent_hugepage/enabled", "/sys/kernel/mm/transparent_hugepage/defrag"}) {
        std::ifstream in(f); std::string s; std::getline(in, s); std::cout << f << ": " << s << "\n";
    }
    Pool pool(threads);
    const size_t chunk = size_t{1} << 20;
    for (size_t mb : {27, 36}) {
        const size_t bytes = mb << 20;
        auto par = [&](unsigned char* p, bool touch_only) {
            size_t tasks = (bytes + chunk - 1) / chunk; std::atomic<size_t> next{0};
            pool.run([&](int) { for (size_t k; (k = next++) < tasks;) { unsigned char* q = p + k * chunk; size_t len = std::min(chunk, bytes - k * chunk);
                if (touch_only) for (size_t o = 0; o < len; o += 4096) q[o] = 0; else std::memset(q, 0, len); } });
        };
        const size_t hchunk = size_t{2} << 20;
        auto populate = [&](unsigned char* p, bool overlap) {
            size_t tasks = (bytes + hchunk - 1) / hchunk; std::atomic<size_t> next{0};
            std::atomic<int> ok{1};
            auto work = [&] { for (size_t k; (k = next++) < tasks;) { size_t off = k * hchunk; size_t len = std::min(hchunk, bytes - off);
                uintptr_t b = reinterpret_cast<uintptr_t>(p + off) & ~uintptr_t{4095}; uintptr_t e = reinterpret_cast<uintptr_t>(p + off + len);
                if (madvise(reinterpret_cast<void*>(b), e - b, MADV_POPULATE_WRITE) != 0) ok = 0; } };
            if (!overlap) { pool.run([&](int) { work(); }); }
            else {
                std::thread helper([&] { pool.run([&](int) { work(); }); });
                std::memset(p, 0, bytes); asm volatile("" ::"r"(p) : "memory");
                helper.join();
            }
            if (!ok) std::printf("(populate failed)\n");
        };
        struct Way { const char* name; bool huge, touch_only, single; };
        const Way ways[] = {{"current: huge, par memset, +1-thread zero", true, false, true},
                            {"no-huge, par memset, +1-thread zero", false, false, true},
                            {"huge, par touch/page, +1-thread zero", true, true, true},
                            {"huge, par memset only", true, false, false},
                            {"no-huge, par memset only", false, false, false},
                            {"huge, par touch/page only", true, true, false},
                            {"1-thread zero only (fresh, no par)", true, false, true},
                            {"huge, par POPULATE_WRITE, +1-thread zero", true, false, true},
                            {"no-huge, par POPULATE_WRITE, +1-thread zero", false, false, true},
                            {"huge, POPULATE_WRITE overlapped with 1-thread zero", true, false, true},
                            {"no-huge, POPULATE_WRITE overlapped with 1-thread zero", false, false, true}};
        int wi = 0;
        for (const Way& w : ways) {
            std::vector<double> t;
            for (int rep = 0; rep < 15; ++rep) {
                auto a = Clock::now();
                auto* p = static_cast<unsigned char*>(std::malloc(bytes));
                if (w.huge) advise(p, bytes);
                if (wi < 6) par(p, w.touch_only);
                if (wi == 7 || wi == 8) populate(p, false);
                if (wi == 9 || wi == 10) populate(p, true);
                else if (w.single) { std::memset(p, 0, bytes); asm volatile("" ::"r"(p) : "memory"); }
                auto b = Clock::now();
                t.push_back(ms(a, b));
                std::free(p);
            }
            std::sort(t.begin(), t.end());
            std::printf("%2zu MB, %d threads: %-45s median %.2f ms, min %.2f, max %.2f\n", mb, threads, w.name, t[t.size() / 2], t[0], t.back());
            ++wi;
        }
        // The bench's pattern: the last result alive while the next one's memory is made
        // (current way), then the last freed: does glibc hand back warm pages?
        for (int huge = 1; huge >= 0; --huge) {
            std::vector<double> t;
            unsigned char* last = nullptr;
            for (int rep = 0; rep < 15; ++rep) {
                auto a = Clock::now();
                auto* p = static_cast<unsigned char*>(std::malloc(bytes));
                if (huge) advise(p, bytes);
                par(p, false);
                std::memset(p, 0, bytes); asm volatile("" ::"r"(p) : "memory");
                t.push_back(ms(a, Clock::now()));
                std::free(last); last = p;
            }
            std::free(last);
            std::sort(t.begin(), t.end());
            std::printf("%2zu MB, %d threads: last alive, then freed (huge %d): median %.2f ms, min %.2f, max %.2f\n", mb, threads, huge, t[t.size() / 2], t[0], t.back());
        }
        // Every allocation kept (as the bench keeps every frame's result): the process grows.
        for (int huge = 1; huge >= 0; --huge) {
            std::vector<double> t;
            std::vector<unsigned char*> kept;
            for (int rep = 0; rep < 15; ++rep) {
                auto a = Clock::now();
                auto* p = static_cast<unsigned char*>(std::malloc(bytes));
                if (huge) advise(p, bytes);
                par(p, false);
                std::memset(p, 0, bytes); asm volatile("" ::"r"(p) : "memory");
                t.push_back(ms(a, Clock::now()));
                kept.push_back(p);
            }
            for (auto* p : kept) std::free(p);
            std::sort(t.begin(), t.end());
            std::printf("%2zu MB, %d threads: every one kept (huge %d): median %.2f ms, min %.2f, max %.2f\n", mb, threads, huge, t[t.size() / 2], t[0], t.back());
        }
        // The resize pass alone over warm memory.
        auto* p = static_cast<unsigned char*>(std::malloc(bytes)); std::memset(p, 1, bytes);
        std::vector<double> t;
        for (int rep = 0; rep < 15; ++rep) { auto a = Clock::now(); std::memset(p, 0, bytes); asm volatile("" ::"r"(p) : "memory"); t.push_back(ms(a, Clock::now())); }
        std::sort(t.begin(), t.end());
        std::printf("%2zu MB: 1-thread zero of warm memory median %.2f ms\n", mb, t[t.size() / 2]);
        std::free(p);
    }
}
