# Explicit source lists, one block per subsystem (src/<subsystem>/).
set(S ${PROJECT_SOURCE_DIR}/src)

set(VKCOLLIDE_HOST_SOURCES
  ${S}/core/result.cpp
  ${S}/core/mesh.cpp
  ${S}/core/types.cpp
  ${S}/graph/graph.cpp
  ${S}/graph/command_tape.cpp  # plain data; replayed through a dispatch table
  ${S}/api/host_passes.cpp  # the world's passes over host positions (no Vulkan)
  ${S}/api/mesh_checks.cpp  # closed meshes: holes and inside-out (no Vulkan)
)
# Subsystems owned elsewhere append to VKCOLLIDE_HOST_SOURCES in their own list file.
foreach(part narrow scene io)
  if(EXISTS ${S}/${part}/sources.cmake)
    include(${S}/${part}/sources.cmake)
  endif()
endforeach()

set(VKCOLLIDE_GPU_SOURCES
  ${S}/vk/loader.cpp
  ${S}/vk/device.cpp
  ${S}/vk/resources.cpp
  ${S}/graph/executor.cpp
  ${S}/passes/axis_union.cpp
  ${S}/passes/broad_phase.cpp
  ${S}/passes/buffer_table.cpp
  ${S}/passes/common_stages.cpp
  ${S}/passes/detection.cpp
  ${S}/passes/engine_mesh.cpp
  ${S}/passes/merging.cpp
  ${S}/passes/mesh_upload.cpp
  ${S}/passes/packing.cpp
  ${S}/passes/peeling_method.cpp
  ${S}/passes/projection.cpp
  ${S}/passes/separation.cpp
  ${S}/passes/stage.cpp
  ${S}/passes/triangle_bounds.cpp
  ${S}/api/contacts.cpp
  ${S}/api/detect.cpp
  ${S}/api/engine_mesh.cpp
  ${S}/api/engine_sync.cpp
  ${S}/api/settings.cpp
  ${S}/api/validation.cpp
  ${S}/api/world.cpp
)
# Rooms of the broad phase (src/passes/<room>/, e.g. sampling/, cells/) list their own
# sources and programs in a sources.cmake of their own: append to VKCOLLIDE_GPU_SOURCES and
# VKCOLLIDE_SHADERS (spirv/<name>.<stage>.glsl). A new room needs no edit here.
file(GLOB VKCOLLIDE_ROOM_LISTS CONFIGURE_DEPENDS ${S}/passes/*/sources.cmake)
foreach(room_list ${VKCOLLIDE_ROOM_LISTS})
  include(${room_list})
endforeach()
# Proximity (src/proximity/): a host part and a GPU part, after both lists exist.
include(${S}/proximity/sources.cmake)
