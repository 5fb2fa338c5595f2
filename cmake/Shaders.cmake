# GLSL in spirv/<name>.<stage>.glsl -> glslangValidator (Vulkan 1.3) -> spirv-val ->
# spirv-opt -> a generated header with one typed constant per program, embedded in the
# library: nothing is read from disk at run time. A compile error fails the build with
# glslang's file:line message.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
find_program(SPIRV_VAL spirv-val REQUIRED)
find_program(SPIRV_OPT spirv-opt REQUIRED)

set(VKCOLLIDE_SHADERS
  graph_test_draw.vert graph_test_draw.frag graph_test_sum.comp
)
include(${PROJECT_SOURCE_DIR}/spirv/shaders.cmake OPTIONAL)

file(GLOB VKCOLLIDE_SHADER_HEADERS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/spirv/*.h ${PROJECT_SOURCE_DIR}/spirv/*.glsl.inc)
set(VKCOLLIDE_SHADER_INCLUDE_DIR ${PROJECT_BINARY_DIR}/generated)
set(out_dir ${VKCOLLIDE_SHADER_INCLUDE_DIR}/shaders)
file(MAKE_DIRECTORY ${out_dir})

set(embedded_headers)
set(program_includes "")
foreach(shader ${VKCOLLIDE_SHADERS})
  string(REGEX MATCH "[^.]+$" stage ${shader})
  string(REPLACE "." "_" ident ${shader})
  set(src ${PROJECT_SOURCE_DIR}/spirv/${shader}.glsl)
  set(spv ${out_dir}/${ident}.spv)
  set(hdr ${out_dir}/${ident}.hpp)
  add_custom_command(OUTPUT ${hdr}
    COMMAND ${GLSLANG_VALIDATOR} --quiet -V --target-env vulkan1.3 -S ${stage} -I${PROJECT_SOURCE_DIR}/spirv
            -o ${spv}.raw ${src}
    COMMAND ${SPIRV_VAL} --target-env vulkan1.3 --scalar-block-layout ${spv}.raw
    COMMAND ${SPIRV_OPT} -O --target-env=vulkan1.3 ${spv}.raw -o ${spv}
    COMMAND ${SPIRV_VAL} --target-env vulkan1.3 --scalar-block-layout ${spv}
    COMMAND ${CMAKE_COMMAND} -DSPV=${spv} -DOUT=${hdr} -DIDENT=${ident} -P ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    DEPENDS ${src} ${VKCOLLIDE_SHADER_HEADERS} ${PROJECT_SOURCE_DIR}/cmake/EmbedSpirv.cmake
    COMMENT "SPIR-V ${shader}"
    VERBATIM)
  list(APPEND embedded_headers ${hdr})
  string(APPEND program_includes "#include \"shaders/${ident}.hpp\"\n")
endforeach()

file(WRITE ${out_dir}/all.hpp.in "// Generated: every embedded SPIR-V program (vkcollide::shaders::<name>_<stage>).\n#pragma once\n${program_includes}")
configure_file(${out_dir}/all.hpp.in ${out_dir}/all.hpp COPYONLY)
add_custom_target(vkcollide_shaders DEPENDS ${embedded_headers})
