// Writing a seed corpus (write_fuzz_seeds, write_world_seeds): the folder, each seed a file
// of its bytes, and the one message and exit status when any of it failed.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

namespace vkcollide::fuzz {

// Makes the corpus folder (and its parents); false when it cannot.
inline bool makeCorpusFolder(const std::string& folder) {
    std::error_code made;
    std::filesystem::create_directories(folder, made);
    return !made;
}

inline bool writeSeed(const std::string& path, std::span<const char> bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return static_cast<bool>(out);
}

// main()'s exit status: 0, or 1 with a message naming the folder.
inline int corpusStatus(bool ok, const std::string& folder) {
    if (ok) return 0;
    std::fprintf(stderr, "cannot write into %s\n", folder.c_str());
    return 1;
}

}  // namespace vkcollide::fuzz
