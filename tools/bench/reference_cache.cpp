#include "reference_cache.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "support/exact_reference.hpp"

namespace vkcollide::bench {
namespace {

constexpr char kMagic[8] = {'V', 'K', 'C', 'R', 'E', 'F', '1', '\n'};

// FNV-1a over 8-byte words: fast enough for a hundred megabytes and, for this purpose
// (telling scenes apart, not defending against anyone), collision-free in practice.
struct Hasher {
    std::uint64_t h = 1469598103934665603ull;
    void bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        std::size_t i = 0;
        for (; i + 8 <= n; i += 8) {
            std::uint64_t w;
            std::memcpy(&w, p + i, 8);
            h = (h ^ w) * 1099511628211ull;
        }
        for (; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
    template <typename T>
    void value(const T& v) { bytes(&v, sizeof v); }
};

std::string pathFor(const std::string& dir, std::uint64_t hash) {
    char name[40];
    std::snprintf(name, sizeof name, "ref-%016llx.bin", static_cast<unsigned long long>(hash));
    return dir + "/" + name;
}

bool readCache(const std::string& path, std::uint64_t hash, FrameReference& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    char magic[8];
    std::uint64_t stored = 0, count = 0;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&stored), 8);
    in.read(reinterpret_cast<char*>(&count), 8);
    if (!in || std::memcmp(magic, kMagic, 8) != 0 || stored != hash || count > (1ull << 32)) return false;
    out.pairs.resize(count);
    out.crossing.resize(count);
    in.read(reinterpret_cast<char*>(out.pairs.data()), static_cast<std::streamsize>(count * sizeof(TrianglePair)));
    in.read(reinterpret_cast<char*>(out.crossing.data()), static_cast<std::streamsize>(count));
    return static_cast<bool>(in) && in.peek() == std::ifstream::traits_type::eof();
}

void writeCache(const std::string& dir, const std::string& path, const FrameReference& r) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        const std::uint64_t count = r.pairs.size();
        out.write(kMagic, 8);
        out.write(reinterpret_cast<const char*>(&r.hash), 8);
        out.write(reinterpret_cast<const char*>(&count), 8);
        out.write(reinterpret_cast<const char*>(r.pairs.data()), static_cast<std::streamsize>(count * sizeof(TrianglePair)));
        out.write(reinterpret_cast<const char*>(r.crossing.data()), static_cast<std::streamsize>(count));
        if (!out) {
            std::fprintf(stderr, "reference cache: cannot write %s (ignored)\n", tmp.c_str());
            return;
        }
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) std::fprintf(stderr, "reference cache: cannot rename %s: %s (ignored)\n", tmp.c_str(), ec.message().c_str());
}

}  // namespace

std::size_t FrameReference::crossingCount() const {
    std::size_t n = 0;
    for (std::uint8_t c : crossing) n += c;
    return n;
}

std::uint64_t hashObjects(const std::vector<BenchObject>& objects) {
    static_assert(sizeof(TrianglePair) == 16 && sizeof(Float3) == 12);
    Hasher h;
    h.value(kReferenceVersion);
    h.value(objects.size());
    for (const BenchObject& o : objects) {
        h.value(o.mesh.positions.size());
        h.bytes(o.mesh.positions.data(), o.mesh.positions.size() * sizeof(Float3));
        h.value(o.mesh.indices.size());
        h.bytes(o.mesh.indices.data(), o.mesh.indices.size() * sizeof(std::uint32_t));
        h.bytes(o.transform.data(), sizeof o.transform);
        h.value(static_cast<std::uint8_t>(o.self_collision));
    }
    return h.h;
}

Result<FrameReference> referenceFor(const std::vector<BenchObject>& objects, const std::string& cache_dir, unsigned threads) {
    const auto t0 = std::chrono::steady_clock::now();
    FrameReference r;
    r.hash = hashObjects(objects);
    const std::string path = cache_dir.empty() ? std::string() : pathFor(cache_dir, r.hash);
    if (!path.empty() && readCache(path, r.hash, r)) {
        r.from_cache = true;
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return r;
    }
    std::vector<test::ReferenceObject> refs;
    for (const BenchObject& o : objects) refs.push_back({&o.mesh, test::transformFrom3x4(o.transform), o.self_collision});
    auto pairs = test::computeReferencePairs(refs, {.threads = threads});
    if (!pairs) return pairs.error();
    auto contacts = test::classifyPairs(refs, *pairs);
    if (!contacts) return contacts.error();
    r.pairs = std::move(*pairs);
    r.crossing.resize(r.pairs.size());
    for (std::size_t k = 0; k < r.pairs.size(); ++k) r.crossing[k] = (*contacts)[k] == test::Contact::Crossing ? 1 : 0;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!path.empty()) writeCache(cache_dir, path, r);
    return r;
}

}  // namespace vkcollide::bench
