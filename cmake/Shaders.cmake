# GLSL in <dir>/[<room>/]<name>.<stage>.glsl -> glslangValidator (Vulkan 1.3) -> spirv-val ->
# spirv-opt -> a generated header with one typed constant per program
# (vkcollide::shaders::<name>_<stage>), embedded in the binary that includes it: nothing is
# read from disk at run time. cmake/CompileShader.cmake compiles one program; a compile
# error fails the build with glslang's file:line message.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
find_program(SPIRV_VAL spirv-val REQUIRED)
find_program(SPIRV_OPT spirv-opt REQUIRED)
# Builds that share a folder here (or in the environment variable of the same name) compile
# each program once between them (cmake/CompileShader.cmake says how it is keyed).
set(VKCOLLIDE_SHADER_CACHE_DIR "$ENV{VKCOLLIDE_SHADER_CACHE_DIR}" CACHE PATH
    "A folder of compiled shader headers shared between builds (empty: none)")
set(vkcollide_shader_tools_key "")
foreach(tool ${GLSLANG_VALIDATOR} ${SPIRV_VAL} ${SPIRV_OPT})
  execute_process(COMMAND ${tool} --version OUTPUT_VARIABLE version ERROR_VARIABLE version)
  string(APPEND vkcollide_shader_tools_key "${tool} ${version}")
endforeach()
string(SHA256 vkcollide_shader_tools_key "${vkcollide_shader_tools_key}")

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
    string(REPLACE ";" "|" deps "${headers}")
    add_custom_command(OUTPUT ${hdr}
      COMMAND ${CMAKE_COMMAND} -DGLSLANG=${GLSLANG_VALIDATOR} -DSPIRV_VAL=${SPIRV_VAL} -DSPIRV_OPT=${SPIRV_OPT}
              -DTOOLS_KEY=${vkcollide_shader_tools_key} -DSRC=${src} -DSTAGE=${stage}
              "-DINCLUDES=${ARG_SOURCE_DIR}|${PROJECT_SOURCE_DIR}/spirv" "-DDEPS=${deps}" -DSPV=${spv} -DOUT=${hdr}
              -DIDENT=${ident} -DCACHE_DIR=${VKCOLLIDE_SHADER_CACHE_DIR} -P ${PROJECT_SOURCE_DIR}/cmake/CompileShader.cmake
      DEPENDS ${src} ${headers} ${PROJECT_SOURCE_DIR}/cmake/CompileShader.cmake
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
