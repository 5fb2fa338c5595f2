#include "api/cli_support.hpp"

#include <png.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "support/exact_reference.hpp"
#include "vkcollide/io.hpp"
#include "vkcollide/scene.hpp"

namespace clitest {

Scratch::Scratch(const std::string& name) {
    dir = fs::temp_directory_path() / ("vkcollide-cli-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
}

Scratch::~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
}

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream f(p, std::ios::binary);
    f << text;
    REQUIRE(f.good());
}

std::string readText(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

std::string writeMesh(const Scratch& s, const std::string& file, const vkcollide::HostMesh& mesh) {
    writeText(s / file, vkcollide::writeOff(mesh));
    return s.path(file);
}

std::string writeMeshes(const Scratch& s, const std::string& file, const std::vector<vkcollide::HostMesh>& meshes) {
    writeText(s / file, vkcollide::writeObj(meshes));
    return s.path(file);
}

vkcollide::HostMesh sphere(const std::string& name, vkcollide::Float3 c, float radius) {
    auto m = vkcollide::icosphere(radius, 2);
    REQUIRE(m);
    REQUIRE(vkcollide::transformMesh(*m, vkcollide::Transform3x4{1, 0, 0, c.x, 0, 1, 0, c.y, 0, 0, 1, c.z}));
    m->name = name;
    return std::move(*m);
}

Run runCli(const std::string& args) {
    static int serial = 0;
    const fs::path base = fs::temp_directory_path() / ("vkcollide-cli-run-" + std::to_string(::getpid()) + "-" + std::to_string(serial++));
    const bool detect = args.rfind("detect", 0) == 0;
    const std::string cmd = std::string(VKCOLLIDE_CLI_PATH) + " " + args + (detect ? " --validation" : "") + " > " + base.string() +
                            ".out 2> " + base.string() + ".err";
    UNSCOPED_INFO(cmd);
    const int status = std::system(cmd.c_str());
    Run r;
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : (WIFSIGNALED(status) ? -WTERMSIG(status) : -1000);
    r.out = readText(base.string() + ".out");
    r.err = readText(base.string() + ".err");
    fs::remove(base.string() + ".out");
    fs::remove(base.string() + ".err");
    UNSCOPED_INFO("stdout:\n" << r.out << "stderr:\n" << r.err);
    return r;
}

Json detectJson(const Scratch& scratch, const std::string& args, Run& out_run) {
    const std::string json = scratch.path("out.json");
    fs::remove(json);
    out_run = runCli("detect " + args + " --json " + json);
    REQUIRE(out_run.status == 0);
    return Json::parse(readText(json));
}

Json detectJson(const Scratch& scratch, const std::string& args) {
    Run run;
    return detectJson(scratch, args, run);
}

std::vector<vkcollide::TrianglePair> referencePairs(const std::vector<vkcollide::HostMesh>& world, const std::vector<bool>& self) {
    std::vector<vkcollide::test::ReferenceObject> objects;
    for (std::size_t i = 0; i < world.size(); ++i) objects.push_back({&world[i], vkcollide::test::kIdentityTransform, self.at(i)});
    auto pairs = vkcollide::test::computeReferencePairs(objects);
    REQUIRE(pairs);
    return std::move(*pairs);
}

std::vector<vkcollide::TrianglePair> jsonPairs(const Json& frame) {
    std::vector<vkcollide::TrianglePair> out;
    for (const Json& p : frame["pairs"].array()) {
        REQUIRE(p.size() == 4);
        out.push_back({static_cast<std::uint32_t>(p[0].number()), static_cast<std::uint32_t>(p[1].number()),
                       static_cast<std::uint32_t>(p[2].number()), static_cast<std::uint32_t>(p[3].number())});
    }
    return out;
}

// ---- JSON ----------------------------------------------------------------------------

namespace {

struct JsonParser {
    const std::string& s;
    std::size_t at = 0;

    [[noreturn]] void fail(const std::string& what) {
        FAIL("bad JSON at byte " << at << ": " << what << " near '" << s.substr(at, 40) << "'");
        std::abort();  // FAIL throws; never reached
    }
    void space() {
        while (at < s.size() && std::isspace(static_cast<unsigned char>(s[at]))) ++at;
    }
    bool take(char c) {
        space();
        if (at < s.size() && s[at] == c) {
            ++at;
            return true;
        }
        return false;
    }
    void expect(char c) {
        if (!take(c)) fail(std::string("expected '") + c + "'");
    }
    std::string str() {
        expect('"');
        std::string out;
        while (at < s.size() && s[at] != '"') {
            char c = s[at++];
            if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
            if (c == '\\') {
                if (at >= s.size()) fail("unfinished escape");
                const char e = s[at++];
                if (e == 'u') {
                    if (at + 4 > s.size()) fail("short \\u escape");
                    out += static_cast<char>(std::stoi(s.substr(at, 4), nullptr, 16));
                    at += 4;
                    continue;
                }
                const std::string from = "\"\\/bfnrt", to = "\"\\/\b\f\n\r\t";
                const std::size_t k = from.find(e);
                if (k == std::string::npos) fail("bad escape");
                c = to[k];
            }
            out += c;
        }
        expect('"');
        return out;
    }
    Json value() {
        space();
        if (at >= s.size()) fail("unexpected end");
        Json j;
        const char c = s[at];
        if (c == '{') {
            ++at;
            auto obj = std::make_shared<Json::Object>();
            if (!take('}')) {
                do {
                    space();
                    std::string k = str();
                    expect(':');
                    if (obj->count(k)) fail("duplicate key " + k);
                    (*obj)[k] = value();
                } while (take(','));
                expect('}');
            }
            j.value = obj;
        } else if (c == '[') {
            ++at;
            auto arr = std::make_shared<Json::Array>();
            if (!take(']')) {
                do arr->push_back(value());
                while (take(','));
                expect(']');
            }
            j.value = arr;
        } else if (c == '"') {
            j.value = str();
        } else if (s.compare(at, 4, "true") == 0) {
            at += 4, j.value = true;
        } else if (s.compare(at, 5, "false") == 0) {
            at += 5, j.value = false;
        } else if (s.compare(at, 4, "null") == 0) {
            at += 4, j.value = nullptr;
        } else {
            const std::size_t start = at;
            if (s[at] == '-') ++at;
            while (at < s.size() && (std::isdigit(static_cast<unsigned char>(s[at])) || s[at] == '.' || s[at] == 'e' || s[at] == 'E' ||
                                     s[at] == '+' || s[at] == '-'))
                ++at;
            if (at == start) fail("not a value");
            j.value = std::stod(s.substr(start, at - start));
        }
        return j;
    }
};

}  // namespace

Json Json::parse(const std::string& text) {
    JsonParser p{text};
    Json j = p.value();
    p.space();
    if (p.at != text.size()) p.fail("text after the value");
    return j;
}

double Json::number() const {
    REQUIRE(std::holds_alternative<double>(value));
    return std::get<double>(value);
}
bool Json::boolean() const {
    REQUIRE(std::holds_alternative<bool>(value));
    return std::get<bool>(value);
}
const std::string& Json::string() const {
    REQUIRE(std::holds_alternative<std::string>(value));
    return std::get<std::string>(value);
}
const Json::Array& Json::array() const {
    REQUIRE(std::holds_alternative<std::shared_ptr<Array>>(value));
    return *std::get<std::shared_ptr<Array>>(value);
}
const Json::Object& Json::object() const {
    REQUIRE(std::holds_alternative<std::shared_ptr<Object>>(value));
    return *std::get<std::shared_ptr<Object>>(value);
}
bool Json::has(const std::string& key) const { return object().count(key) != 0; }
const Json& Json::operator[](const std::string& key) const {
    const Object& o = object();
    auto it = o.find(key);
    if (it == o.end()) FAIL("JSON has no key " << key);
    return it->second;
}

// ---- PNG -----------------------------------------------------------------------------

Image readPng(const fs::path& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    REQUIRE(png_image_begin_read_from_file(&image, path.c_str()) != 0);
    image.format = PNG_FORMAT_RGB;
    Image out;
    out.width = image.width;
    out.height = image.height;
    out.rgb.resize(PNG_IMAGE_SIZE(image));
    REQUIRE(png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr) != 0);
    return out;
}

// Shading scales a colour (0.28 to 1 of it), so colours are told apart by ratios.
bool isHighlight(int r, int g, int b) { return r >= 60 && g * 100 < r * 35 && b * 100 < r * 20; }
bool isRay(int r, int g, int b) { return r >= 60 && g * 100 >= r * 75 && g * 100 <= r * 105 && b * 100 < r * 30; }
bool isObject0(int r, int g, int b) { return r >= 30 && b * 100 >= r * 170 && b * 100 <= r * 210 && g * 100 >= r * 120 && g * 100 <= r * 155; }
bool isObject1(int r, int g, int b) { return r >= 30 && g * 100 >= r * 130 && g * 100 <= r * 155 && b * 100 >= r * 85 && b * 100 <= r * 105; }

}  // namespace clitest
