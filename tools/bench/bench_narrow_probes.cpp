#include "bench_narrow_probes.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>
#include <utility>

#include "narrow/pair_keys.hpp"
#include "vkcollide/thread_pool.hpp"

namespace vkcollide::bench {
namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

double usSince(Clock::time_point start) { return std::chrono::duration<double, std::micro>(Clock::now() - start).count(); }

}  // namespace

void wakeProbe(const std::vector<unsigned>& threads, unsigned repeat, unsigned gap_us) {
    std::printf("%-8s %-8s %10s %10s %10s %10s\n", "threads", "prepare", "first us", "middle us", "last us", "loop us");
    for (const unsigned count : threads) {
        ThreadPool pool(count);
        const unsigned workers = pool.threadCount() - 1;
        if (workers == 0) continue;
        for (const bool prepare : {false, true}) {
            std::vector<double> first, middle, last, loop;
            for (unsigned round = 0; round < repeat; ++round) {
                std::this_thread::sleep_for(std::chrono::microseconds(std::max(2000u, gap_us)));
                std::mutex m;
                std::vector<std::pair<std::thread::id, double>> joined;
                const std::thread::id caller = std::this_thread::get_id();
                const Clock::time_point start = Clock::now();
                if (prepare) pool.prepare(pool.threadCount());
                pool.parallelFor(64 * std::size_t{pool.threadCount()}, 1, [&](std::size_t, std::size_t) {
                    const Clock::time_point until = Clock::now() + std::chrono::microseconds(2);
                    const std::thread::id self = std::this_thread::get_id();
                    if (self != caller) {
                        const std::lock_guard lock(m);
                        if (std::none_of(joined.begin(), joined.end(), [&](const auto& j) { return j.first == self; })) {
                            joined.push_back({self, usSince(start)});
                        }
                    }
                    while (Clock::now() < until) {
                    }
                });
                const double end = usSince(start);
                std::vector<double> t;
                for (const auto& j : joined) t.push_back(j.second);
                t.resize(workers, end);
                std::sort(t.begin(), t.end());
                first.push_back(t.front());
                middle.push_back(t[(workers - 1) / 2]);
                last.push_back(t.back());
                loop.push_back(end);
            }
            std::printf("%-8u %-8s %10.1f %10.1f %10.1f %10.1f\n", pool.threadCount(), prepare ? "yes" : "no", median(first),
                        median(middle), median(last), median(loop));
        }
    }
}

void frontProbeHeader() {
    std::printf("%-24s %9s %4s %12s %12s %9s\n", "workload", "pairs", "thr", "serial ms", "parallel ms", "serial <");
}

void frontProbe(const std::string& label, std::span<const CandidatePair> pairs, std::uint32_t total,
                const std::vector<unsigned>& threads, unsigned repeat, unsigned gap_us) {
    for (const unsigned count : threads) {
        ThreadPool pool(count);
        NarrowWorkspace workspace;
        double ms[2] = {0, 0};
        for (int f = 0; f < 2; ++f) {
            const narrow::PairKeysForm form = f == 0 ? narrow::PairKeysForm::Serial : narrow::PairKeysForm::Parallel;
            std::vector<double> times;
            for (unsigned r = 0; r <= repeat; ++r) {
                if (gap_us) std::this_thread::sleep_for(std::chrono::microseconds(gap_us));
                const Clock::time_point start = Clock::now();
                if (pairs.size() >= 256) pool.prepare(pool.threadCount());  // as runPairNarrowPhase
                narrow::PairKeys keys;
                if (narrow::buildPairKeys(pool, pairs, total, form, workspace.impl(), keys)) {
                    std::fprintf(stderr, "front probe: %s: a bad pair\n", label.c_str());
                    return;
                }
                if (r > 0) times.push_back(usSince(start) / 1000.0);  // the first call warms up
            }
            ms[f] = median(times);
        }
        std::printf("%-24s %9zu %4u %12.4f %12.4f %9s\n", label.c_str(), pairs.size(), pool.threadCount(), ms[0], ms[1],
                    ms[0] <= ms[1] ? "yes" : "no");
        std::fflush(stdout);
    }
}

}  // namespace vkcollide::bench
