// What vkcollide_peer_bench writes: the progress line on stderr, the CSV (--csv) and the
// summary table on stdout.
#pragma once

#include <cstddef>
#include <iostream>
#include <ostream>
#include <string>
#include <unistd.h>
#include <vector>

#include "peers.hpp"

namespace vkcollide::bench::peer_bench {

// A frame of one peer in one mode on one scene: a CSV row, and what the summary reads.
struct Row {
    std::string scene;
    std::size_t triangles = 0, objects = 0;
    std::string peer, mode;
    int frame = 0;
    PeerTimings timings;
    std::size_t pairs = 0, reference_pairs = 0;
    double recall = 1, precision = 1;
};

// The CPU's model name (/proc/cpuinfo), for the host line.
std::string cpuModel();

// One line on stderr, rewritten in place; only on a terminal (a log would get one long
// line of carriage returns).
class Progress {
public:
    void show(const std::string& line) {
        if (!tty_) return;
        std::string padded = line;
        if (padded.size() < width_) padded.append(width_ - padded.size(), ' ');
        width_ = line.size();
        std::cerr << '\r' << padded << std::flush;
    }
    void done() {
        if (width_) std::cerr << '\n';
        width_ = 0;
    }

private:
    bool tty_ = ::isatty(2) != 0;
    std::size_t width_ = 0;
};

// The CSV's comment line (host, peers' threads) and column names.
void writeCsvHeader(std::ostream& csv, const std::string& host, unsigned threads);
// One CSV row, flushed, so that a run cut short keeps the rows it made. set: the scene's
// set (setName).
void writeCsvRow(std::ostream& csv, const Row& row, unsigned threads, const char* set);
// The summary table, a line per (scene, peer, mode) in the order they first appear in
// `rows`, and the notes under it (csv_path: empty without --csv).
void printSummary(const std::vector<Row>& rows, const std::string& csv_path);

}  // namespace vkcollide::bench::peer_bench
