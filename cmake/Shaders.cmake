# GLSL in <dir>/[<room>/]<name>.<stage>.glsl -> glslangValidator (Vulkan 1.3) -> spirv-val ->
# spirv-opt -> a generated header with one typed constant per program
# (vkcollide::shaders::<name>_<stage>), embedded in the binary that includes it: nothing is
# read from disk at run time. A compile error fails the build with glslang's file:line message.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
find_program(SPIRV_VAL spirv-val REQUIRED)
find_program(SPIRV_OPT spirv-opt REQUIRED)

# vkcollide_embed_shaders(<target> SOURCE_DIR <dir> HEADER_DIR <name> SHADERS [<room>/]<name.stage>...)
#   Adds the custom target <target> that compiles every program (<dir>/[<room>/]<name.stage>.glsl)
#   and writes ${PROJECT_BINARY_DIR}/generated/<name>/<program>.hpp and <name>/all.hpp (every
#   program); a program is named by its file alone, so names are unique across rooms.
#   Programs include the headers of their own folder by name, and those of <dir> and of
#   spirv/ by path ("common/broadphase.h", "cells/cells.h"); a change to any of them
#   recompiles the set.
function(vkcollide_embed_shaders target)
  cmake_parse_arguments(ARG "" "SOURCE_DIR;HEADER_DIR" "SHADERS" ${ARGN})
  file(GLOB_RECURSE headers CONFIGURE_DEPENDS ${ARG_SOURCE_DIR}/*.h ${ARG_SOURCE_DIR}/*.glsl.inc
       ${PROJECT_SOURCE_DIR}/spirv/*.h ${PROJECT_SOURCE_DIR}/spirv/*.glsl.inc)
  set(out_dir ${PROJECT_BINARY_DIR}/generated/${ARG_HEADER_DIR})
  file(MAKE_DIRECTORY ${out_dir})
  set(embedded_headers)
  set(program_includes "")
  set(idents)
  foreach(shader ${ARG_SHADERS})
    get_filename_component(program ${shader} NAME)
    string(REGEX MATCH "[^.]+$" stage ${program})
    string(REPLACE "." "_" ident ${program})
    if(ident IN_LIST idents)
      message(FATAL_ERROR "${ARG_HEADER_DIR}: two programs named ${program} (${shader})")
    endif()
    list(APPEND idents ${ident})
    set(src ${ARG_SOURCE_DIR}/${shader}.glsl)
    set(spv ${out_dir}/${ident}.spv)
    set(hdr ${out_dir}/${ident}.hpp)
    add_custom_command(OUTPUT ${hdr}
      COMMAND ${GLSLANG_VALIDATOR} --quiet -V --target-env vulkan1.3 -S ${stage} -I${ARG_SOURCE_DIR}
              -I${PROJECT_SOURCE_DIR}/spirv -o ${spv}.raw ${src}
      COMMAND ${SPIRV_VAL} --target-env vulkan1.3 --scalar-block-layout ${spv}.raw
      COMMAND ${SPIRV_OPT} -O --target-env=vulkan1.3 ${spv}.raw -o ${spv}
      COMMAND ${SPIRV_VAL} --target-env vulkan1.3 --scalar-block-layout ${spv}
      COMMAND ${CMAKE_COMMAND} -DSPV=${spv} -DOUT=${hdr} -DIDENT=${ident} -P ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      DEPENDS ${src} ${headers} ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
      COMMENT "SPIR-V ${shader}"
      VERBATIM)
    list(APPEND embedded_headers ${hdr})
    string(APPEND program_includes "#include \"${ARG_HEADER_DIR}/${ident}.hpp\"\n")
  endforeach()
  file(WRITE ${out_dir}/all.hpp.in
       "// Generated: every embedded SPIR-V program of ${ARG_HEADER_DIR} (vkcollide::shaders::<name>_<stage>).\n#pragma once\n${program_includes}")
  configure_file(${out_dir}/all.hpp.in ${out_dir}/all.hpp COPYONLY)
  add_custom_target(${target} DEPENDS ${embedded_headers})
endfunction()

# The library's programs: spirv/shaders.cmake lists them, and the rooms (src/broad/<method>/,
# src/contacts/) append theirs in their sources.cmake (cmake/Sources.cmake, read before this file).
# Test-only programs live in tests/shaders/ and are embedded by tests/CMakeLists.txt.
include(${PROJECT_SOURCE_DIR}/spirv/shaders.cmake)
set(VKCOLLIDE_SHADER_INCLUDE_DIR ${PROJECT_BINARY_DIR}/generated)
vkcollide_embed_shaders(vkcollide_shaders SOURCE_DIR ${PROJECT_SOURCE_DIR}/spirv HEADER_DIR shaders SHADERS ${VKCOLLIDE_SHADERS})
