# Explicit source lists, one block per subsystem (src/<subsystem>/).
set(S ${PROJECT_SOURCE_DIR}/src)

set(VKCOLLIDE_HOST_SOURCES
  ${S}/core/result.cpp
  ${S}/core/mesh.cpp
  ${S}/core/types.cpp
  ${S}/graph/graph.cpp  # declaring a render graph
  ${S}/graph/use_info.cpp  # what each use of a resource means (stages, access, layout)
  ${S}/graph/compile.cpp  # the plan: order, culling, barriers
  ${S}/graph/command_tape.cpp  # plain data: recording a tape
  ${S}/graph/command_tape_replay.cpp  # replayed through a dispatch table
  ${S}/api/vertex_scans.cpp  # the world's loops over host positions (no Vulkan)
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
  # The broad phase's seam (src/broad/): the run, the method interface, buffers, stages, projection.
  ${S}/broad/broad_phase.cpp
  ${S}/broad/buffer_table.cpp
  ${S}/broad/common_stages.cpp
  ${S}/broad/projection.cpp
  ${S}/broad/stage.cpp
  ${S}/broad/dispatch.cpp
  ${S}/detect/axis_union.cpp  # one or three directions (src/detect/)
  ${S}/detect/detection.cpp
  ${S}/mesh/engine_mesh.cpp  # mesh intake (src/mesh/)
  ${S}/mesh/mesh_upload.cpp
  ${S}/api/collision_rays.cpp  # DetectSettings::collision_rays: ray images to world segments
  ${S}/api/contacts.cpp
  ${S}/api/detect.cpp
  ${S}/api/engine_mesh.cpp
  ${S}/api/engine_sync.cpp
  ${S}/api/settings.cpp
  ${S}/api/validation.cpp
  ${S}/api/world.cpp
)
# Rooms list their own sources and programs in a sources.cmake of their own: append to
# VKCOLLIDE_GPU_SOURCES and VKCOLLIDE_SHADERS (spirv/<room>/<name>.<stage>.glsl). Each method
# of the broad phase is a room under src/broad/ (peeling/, cells/: a new one needs no edit
# here); the GPU concerns beside the broad phase (contacts/) are named here.
file(GLOB VKCOLLIDE_ROOM_LISTS CONFIGURE_DEPENDS ${S}/broad/*/sources.cmake)
foreach(room_list ${VKCOLLIDE_ROOM_LISTS} ${S}/contacts/sources.cmake)
  include(${room_list})
endforeach()
# Proximity (src/proximity/): a host part and a GPU part, after both lists exist.
include(${S}/proximity/sources.cmake)
