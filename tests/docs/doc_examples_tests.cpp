// The pages' C++ examples are the ones doc_examples.cpp compiles: every ```cpp block of
// README.md and docs/api.md equals one of its "doc example" regions, and every region is
// still on its page.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    REQUIRE(in);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The text between each line `open` and the next line `close` (lines included whole).
std::vector<std::string> blocks(const std::string& text, const std::string& open, const std::string& close) {
    std::vector<std::string> out;
    std::size_t at = 0;
    while ((at = text.find(open, at)) != std::string::npos) {
        const std::size_t begin = at + open.size();
        const std::size_t end = text.find(close, begin);
        REQUIRE(end != std::string::npos);
        out.push_back(text.substr(begin, end - begin));
        at = end + close.size();
    }
    return out;
}

}  // namespace

TEST_CASE("docs: every C++ example of README.md and docs/api.md is one doc_examples.cpp compiles", "[docs]") {
    const std::string root = VKCOLLIDE_SOURCE_DIR;
    const std::string compiled = readFile(root + "/tests/docs/doc_examples.cpp");
    std::size_t examples = 0;
    for (const char* page : {"README.md", "docs/api.md"}) {
        const std::string text = readFile(root + "/" + page);
        const auto compiled_here = blocks(compiled, std::string("// doc example: ") + page + "\n", "// end of doc example\n");
        const auto shown = blocks(text, "\n```cpp\n", "```\n");
        for (const std::string& example : shown) {
            INFO(page << ":\n" << example);
            CHECK(std::find(compiled_here.begin(), compiled_here.end(), example) != compiled_here.end());
        }
        for (const std::string& example : compiled_here) {
            INFO("doc_examples.cpp's example of " << page << " is no longer there:\n" << example);
            CHECK(std::find(shown.begin(), shown.end(), example) != shown.end());
        }
        examples += shown.size();
    }
    CHECK(examples >= 1);
}
