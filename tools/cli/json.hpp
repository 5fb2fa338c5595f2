// A small streaming JSON writer (the --json file can hold millions of pairs, so nothing
// is built in memory), and the sections `vkcollide detect` writes with it: the statistics
// (--stats, and each frame of --json) and the whole report (--json; docs/cli.md).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "vkcollide/world.hpp"

namespace cli {

class JsonWriter {
public:
    explicit JsonWriter(std::FILE* out) : out_(out) {}

    // Containers. Layout::Lines puts each member on its own line; Layout::Inline keeps the
    // container on one line (short arrays: a pair, a direction).
    enum class Layout { Lines, Inline };
    void beginObject(Layout layout = Layout::Lines);
    void endObject();
    void beginArray(Layout layout = Layout::Lines);
    void endArray();
    // The key of the next member of an object.
    void key(std::string_view name);
    // Values.
    void string(std::string_view text);
    void number(double value);  // integers exactly, others to 9 significant digits; not finite: null
    void integer(std::uint64_t value);
    void boolean(bool value);
    void null();
    void raw(std::string_view json);  // an already formatted value

    // Shorthands for a member.
    template <typename F>
    void member(std::string_view name, F&& write_value) {
        key(name);
        write_value();
    }

    // Ends the document with a newline.
    void finish();

private:
    void beforeValue();
    void newline();
    struct Level {
        Layout layout;
        bool first = true;
    };
    std::FILE* out_;
    std::vector<Level> levels_;
    bool after_key_ = false;
};

std::string jsonEscape(std::string_view text);

// The statistics of one detection as one JSON object: the paper's Table 1, every narrow-
// phase counter, what ran, the times and the memory. `names`: the objects' names.
void writeStats(JsonWriter& json, const vkcollide::DetectStats& stats, std::size_t pair_count,
                const std::vector<std::string>& names);

}  // namespace cli
