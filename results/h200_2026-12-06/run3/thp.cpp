#include <sys/mman.h>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <cstdlib>
#include <thread>
#include <vector>
struct P { std::uint32_t a=0,b=0,c=0,d=0; };
int main(int argc, char** argv) {
    const std::size_t n = 36u << 20 >> 4;  // 36 MB of P
    int threads = argc > 1 ? std::atoi(argv[1]) : 2;
    for (int mode = 0; mode < 4; ++mode) for (int rep = 0; rep < 3; ++rep) {
        auto t0 = std::chrono::steady_clock::now();
        std::vector<P> v;
        v.reserve(n);
        auto* bytes = reinterpret_cast<unsigned char*>(v.data());
        std::size_t total = n * sizeof(P);
        if (mode & 1) {
            std::uintptr_t b = (reinterpret_cast<std::uintptr_t>(bytes) + (2u<<20) - 1) & ~std::uintptr_t((2u<<20)-1);
            std::uintptr_t e = (reinterpret_cast<std::uintptr_t>(bytes) + total) & ~std::uintptr_t((2u<<20)-1);
            if (e > b) madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
        }
        auto t1 = std::chrono::steady_clock::now();
        if (mode & 2) {
            std::vector<std::thread> ts;
            for (int t = 0; t < threads; ++t) ts.emplace_back([&, t] { std::size_t lo = total * t / threads, hi = total * (t + 1) / threads; std::memset(bytes + lo, 0, hi - lo); });
            for (auto& t : ts) t.join();
        }
        auto t2 = std::chrono::steady_clock::now();
        v.resize(n);
        auto t3 = std::chrono::steady_clock::now();
        auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
        std::printf("thp %d touch %d: madvise %.2f touch %.2f resize %.2f total %.2f\n", mode & 1, (mode >> 1) & 1, ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t0, t3));
    }
}
