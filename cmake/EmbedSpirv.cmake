# Turns a .spv file into a header: inline constexpr std::uint32_t array + a span.
file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" n)
math(EXPR rem "${n} % 8")
if(NOT rem EQUAL 0)
  message(FATAL_ERROR "${SPV}: size is not a multiple of 4 bytes")
endif()
# SPIR-V words are little-endian on disk: reverse each group of 4 bytes.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "((0x[0-9a-f]+u,){8})" "\\1\n    " words "${words}")
file(WRITE ${OUT}.tmp "// Generated from ${SPV}; do not edit.\n#pragma once\n#include <cstdint>\n#include <span>\nnamespace vkcollide::shaders {\ninline constexpr std::uint32_t ${IDENT}_words[] = {\n    ${words}\n};\ninline constexpr std::span<const std::uint32_t> ${IDENT}{${IDENT}_words};\n}  // namespace vkcollide::shaders\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
