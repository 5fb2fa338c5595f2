# One program (cmake/Shaders.cmake runs this script per program, at build time):
#   GLSL -> glslangValidator -> spirv-val -> spirv-opt -O -> spirv-val -> a header holding
#   the words as `inline constexpr std::uint32_t <IDENT>_words[]` and a span <IDENT>.
# A compile error fails the build with glslang's file:line message.
#
# With CACHE_DIR, headers are also kept there, named by a hash of everything that makes
# them: the tools' versions (TOOLS_KEY), the stage and name, the program's text and the text
# of every header it may include (DEPS). A build that finds its hash copies the header
# instead of compiling. tools/test.sh points its two builds and the package test's shared
# build at one cache, so the programs compile once per run.
#
# -D: GLSLANG SPIRV_VAL SPIRV_OPT TOOLS_KEY SRC STAGE INCLUDES DEPS SPV OUT IDENT [CACHE_DIR]
#     (INCLUDES and DEPS: lists separated by '|').
string(REPLACE "|" ";" includes "${INCLUDES}")
string(REPLACE "|" ";" deps "${DEPS}")

if(CACHE_DIR)
  file(SHA256 ${SRC} key)
  file(SHA256 ${CMAKE_CURRENT_LIST_FILE} script_hash)  # the flags and the header's form
  string(APPEND key " ${script_hash} ${TOOLS_KEY} ${STAGE} ${IDENT}")
  list(SORT deps)
  foreach(dep ${deps})
    get_filename_component(name ${dep} NAME)
    file(SHA256 ${dep} dep_hash)
    string(APPEND key " ${name}:${dep_hash}")
  endforeach()
  string(SHA256 key "${key}")
  set(cached ${CACHE_DIR}/${IDENT}-${key}.hpp)
  if(EXISTS ${cached})
    file(COPY_FILE ${cached} ${OUT} ONLY_IF_DIFFERENT)
    return()
  endif()
endif()

function(run_tool)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    list(GET ARGN 0 tool)
    message(FATAL_ERROR "${SRC}: ${tool} failed (${status}):\n${out}${err}")
  endif()
endfunction()

set(include_flags)
foreach(dir ${includes})
  list(APPEND include_flags -I${dir})
endforeach()
run_tool(${GLSLANG} --quiet -V --target-env vulkan1.3 -S ${STAGE} ${include_flags} -o ${SPV}.raw ${SRC})
run_tool(${SPIRV_VAL} --target-env vulkan1.3 --scalar-block-layout ${SPV}.raw)
run_tool(${SPIRV_OPT} -O --target-env=vulkan1.3 ${SPV}.raw -o ${SPV})
run_tool(${SPIRV_VAL} --target-env vulkan1.3 --scalar-block-layout ${SPV})

file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" n)
math(EXPR rem "${n} % 8")
if(NOT rem EQUAL 0)
  message(FATAL_ERROR "${SPV}: size is not a multiple of 4 bytes")
endif()
# SPIR-V words are little-endian on disk: reverse each group of 4 bytes.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "((0x[0-9a-f]+u,){8})" "\\1\n    " words "${words}")
get_filename_component(program ${SRC} NAME)
file(WRITE ${OUT}.tmp "// Generated from ${program}; do not edit.\n#pragma once\n#include <cstdint>\n#include <span>\nnamespace vkcollide::shaders {\ninline constexpr std::uint32_t ${IDENT}_words[] = {\n    ${words}\n};\ninline constexpr std::span<const std::uint32_t> ${IDENT}{${IDENT}_words};\n}  // namespace vkcollide::shaders\n")
if(CACHE_DIR)
  # Written under a name of its own, then renamed: a build reading the cache never sees half a file.
  file(MAKE_DIRECTORY ${CACHE_DIR})
  string(RANDOM LENGTH 12 tag)
  file(COPY_FILE ${OUT}.tmp ${cached}.${tag})
  file(RENAME ${cached}.${tag} ${cached})
endif()
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUT}.tmp)
