#include "peer_bench_output.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <tuple>

namespace vkcollide::bench::peer_bench {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

}  // namespace

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(colon + 2);
        }
    }
    return "unknown CPU";
}

void writeCsvHeader(std::ostream& csv, const std::string& host, unsigned threads) {
    csv << "# vkcollide_peer_bench: " << host << "; peers run with " << threads << " threads\n";
    csv << "scene,triangles,objects,peer,mode,frame,build_ms,query_ms,total_ms,pairs,recall,precision,"
           "candidates,memory_mb,reference_pairs,threads,set\n";
}

void writeCsvRow(std::ostream& csv, const Row& row, unsigned threads, const char* set) {
    csv << row.scene << ',' << row.triangles << ',' << row.objects << ',' << row.peer << ',' << row.mode << ',' << row.frame << ','
        << fixed(row.timings.build_ms, 3) << ',' << fixed(row.timings.query_ms, 3) << ',' << fixed(row.timings.total_ms, 3) << ','
        << row.pairs << ',' << fixed(row.recall, 6) << ',' << fixed(row.precision, 6) << ',' << row.timings.candidates << ','
        << fixed(static_cast<double>(row.timings.memory_bytes) / 1048576.0, 1) << ',' << row.reference_pairs << ',' << threads << ',' << set
        << '\n';
    csv.flush();
}

void printSummary(const std::vector<Row>& rows, const std::string& csv_path) {
    // Medians per (scene, peer, mode); deforming scenes over frames >= 1 (the
    // per-frame update), with frame 0's build shown apart.
    std::cout << "\n"
              << "scene              tris      peer          mode               frames  build0_ms  build_ms  query_ms  "
                 "total_ms     pairs   ref_pairs  recall    precision\n";
    std::map<std::tuple<std::string, std::string, std::string>, std::vector<const Row*>> groups;
    std::vector<std::tuple<std::string, std::string, std::string>> order;
    for (const Row& r : rows) {
        const auto key = std::make_tuple(r.scene, r.peer, r.mode);
        if (!groups.count(key)) order.push_back(key);
        groups[key].push_back(&r);
    }
    for (const auto& key : order) {
        const std::vector<const Row*>& g = groups[key];
        const bool deforming = g.front()->mode.rfind("deforming", 0) == 0;
        std::vector<double> build, query, total;
        double min_recall = 1, min_precision = 1;
        // Pair counts are counts, not timings: the frames' own, as a range when they differ.
        std::size_t pairs_lo = g.front()->pairs, pairs_hi = pairs_lo, ref_lo = g.front()->reference_pairs, ref_hi = ref_lo;
        for (const Row* r : g) {
            pairs_lo = std::min(pairs_lo, r->pairs), pairs_hi = std::max(pairs_hi, r->pairs);
            ref_lo = std::min(ref_lo, r->reference_pairs), ref_hi = std::max(ref_hi, r->reference_pairs);
        }
        const auto range = [](std::size_t lo, std::size_t hi) {
            return lo == hi ? std::to_string(lo) : std::to_string(lo) + "-" + std::to_string(hi);
        };
        for (const Row* r : g) {
            min_recall = std::min(min_recall, r->recall);
            min_precision = std::min(min_precision, r->precision);
            if (deforming && r->frame == 0 && g.size() > 1) continue;
            build.push_back(r->timings.build_ms);
            query.push_back(r->timings.query_ms);
            total.push_back(r->timings.total_ms);
        }
        char line[512];
        std::snprintf(line, sizeof line, "%-18s %-9zu %-13s %-18s %6zu %10.2f %9.2f %9.2f %9.2f %9s %11s  %.6f  %.6f",
                      g.front()->scene.c_str(), g.front()->triangles, g.front()->peer.c_str(), g.front()->mode.c_str(), g.size(),
                      g.front()->timings.build_ms, median(build), median(query), median(total), range(pairs_lo, pairs_hi).c_str(),
                      range(ref_lo, ref_hi).c_str(), min_recall, min_precision);
        std::cout << line << '\n';
    }
    std::cout << "\ntimes: medians; deforming: over frames >= 1 (build0 = the first frame's build); pairs and ref_pairs:\n"
                 "the count found and the exact count (lowest-highest over the frames where they differ); recall and\n"
                 "precision: the lowest over the frames."
              << (csv_path.empty() ? std::string() : " CSV: " + csv_path) << '\n';
}

}  // namespace vkcollide::bench::peer_bench
