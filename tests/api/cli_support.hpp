// What the command-line tests share: scratch folders, mesh files, running `vkcollide` as a
// process (with the validation layer on), a small JSON reader (the tests check that --json
// is well-formed JSON and read values from it), a PNG reader and the exact reference on
// the scene the tool saw.
#pragma once

#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"

namespace clitest {

namespace fs = std::filesystem;

// A folder removed at the end of the test.
struct Scratch {
    explicit Scratch(const std::string& name);
    ~Scratch();
    fs::path dir;
    fs::path operator/(const std::string& file) const { return dir / file; }
    std::string path(const std::string& file) const { return (dir / file).string(); }
};

void writeText(const fs::path& p, const std::string& text);
std::string readText(const fs::path& p);
// OFF of one mesh; OBJ of several (one `o` group each).
std::string writeMesh(const Scratch& s, const std::string& file, const vkcollide::HostMesh& mesh);
std::string writeMeshes(const Scratch& s, const std::string& file, const std::vector<vkcollide::HostMesh>& meshes);

// A closed sphere (icosphere, 320 triangles) of radius r centred at c.
vkcollide::HostMesh sphere(const std::string& name, vkcollide::Float3 centre, float radius = 1.0f);

struct Run {
    int status = 0;   // the exit status, or -signal
    std::string out;  // stdout
    std::string err;  // stderr
};
// Runs `vkcollide <args>`; `detect` runs get --validation (exit status 3 on any message).
Run runCli(const std::string& args);

// `vkcollide detect <args> --json <scratch>/out.json`, required to succeed; the JSON.
struct Json;
Json detectJson(const Scratch& scratch, const std::string& args);
// Its stdout too.
Json detectJson(const Scratch& scratch, const std::string& args, Run& out_run);

// The exact pairs (object, triangle) of world-space meshes, self-collision per object.
std::vector<vkcollide::TrianglePair> referencePairs(const std::vector<vkcollide::HostMesh>& world, const std::vector<bool>& self);
// Pairs of a --json frame, as TrianglePairs.
std::vector<vkcollide::TrianglePair> jsonPairs(const Json& frame);

// A parsed JSON value. Parsing fails the test with the position of the first error.
struct Json {
    using Object = std::map<std::string, Json>;
    using Array = std::vector<Json>;
    std::variant<std::nullptr_t, bool, double, std::string, std::shared_ptr<Array>, std::shared_ptr<Object>> value;

    static Json parse(const std::string& text);
    bool isNull() const { return std::holds_alternative<std::nullptr_t>(value); }
    double number() const;
    bool boolean() const;
    const std::string& string() const;
    const Array& array() const;
    const Object& object() const;
    bool has(const std::string& key) const;
    const Json& operator[](const std::string& key) const;
    const Json& operator[](std::size_t index) const { return array().at(index); }
    std::size_t size() const { return array().size(); }
};

// An RGB image read from a PNG.
struct Image {
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> rgb;
    // Pixels whose colour passes `test(r, g, b)`.
    template <typename F>
    std::size_t count(F&& test) const {
        std::size_t n = 0;
        for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) n += test(rgb[i], rgb[i + 1], rgb[i + 2]) ? 1 : 0;
        return n;
    }
};
Image readPng(const fs::path& path);

// Colours the renderer draws (tools/render): the highlight of colliding triangles (orange),
// the collision rays (yellow) and the first two objects' colours, each under any shading.
bool isHighlight(int r, int g, int b);
bool isRay(int r, int g, int b);
bool isObject0(int r, int g, int b);
bool isObject1(int r, int g, int b);

}  // namespace clitest
