# One mechanism lists the library's sources: every room (src/<room>/, and each method
# src/broad/<method>/) has a sources.cmake that appends its files to
# VKCOLLIDE_HOST_SOURCES (host code, no Vulkan: also the host-only build),
# VKCOLLIDE_GPU_SOURCES and VKCOLLIDE_SHADERS (spirv/<room>/<name>.<stage>.glsl; the shared
# programs are in spirv/shaders.cmake). A new room needs no edit here.
set(S ${PROJECT_SOURCE_DIR}/src)
set(VKCOLLIDE_HOST_SOURCES)
set(VKCOLLIDE_GPU_SOURCES)
set(VKCOLLIDE_SHADERS)
file(GLOB VKCOLLIDE_ROOM_LISTS CONFIGURE_DEPENDS ${S}/*/sources.cmake ${S}/broad/*/sources.cmake)
foreach(room_list ${VKCOLLIDE_ROOM_LISTS})
  include(${room_list})
endforeach()
