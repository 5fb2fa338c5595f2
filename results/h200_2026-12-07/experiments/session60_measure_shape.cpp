// Session 60: vertex_scans::measureShape on one thread (g++ -O2 -std=c++20 -Isrc -Iinclude FILE build/libvkcollide_host.a -lpthread).
#include "api/vertex_scans.hpp"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>
using namespace vkcollide;
int main() {
    int nu = 160, nv = 157; std::vector<Float3> pos; std::vector<std::uint32_t> ind;
    for (int j = 0; j <= nv; ++j) for (int i = 0; i < nu; ++i) { double th = M_PI * j / nv, ph = 2 * M_PI * i / nu; pos.push_back({float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)), float(std::cos(th))}); }
    for (int j = 0; j < nv; ++j) for (int i = 0; i < nu; ++i) { uint32_t a = j * nu + i, b = j * nu + (i + 1) % nu, c = a + nu, d = b + nu; ind.insert(ind.end(), {a, c, b, b, c, d}); }
    ThreadPool one(1);
    double best = 1e9; float chk = 0;
    for (int r = 0; r < 300; ++r) {
        auto t0 = std::chrono::steady_clock::now();
        auto s = vertex_scans::measureShape(one, pos, ind);
        best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        chk += s.edge_length + float(s.axis_area[0]);
    }
    std::printf("measureShape best %.4f ms (%g)\n", best, chk);
}
