// How a test checks that an error names something (a setting, an object, a rule).
#pragma once

#include <string>

#include "vkcollide/result.hpp"

namespace vkcollide::test {

inline bool mentions(const Error& e, const std::string& what) { return e.message().find(what) != std::string::npos; }
inline bool mentions(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace vkcollide::test
