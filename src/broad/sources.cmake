# The broad phase's seam: the run, the method interface, buffers, stages, projection. Each
# method is a room below it with a sources.cmake of its own (cmake/Sources.cmake finds them).
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/broad_phase.cpp
  ${CMAKE_CURRENT_LIST_DIR}/buffer_table.cpp
  ${CMAKE_CURRENT_LIST_DIR}/common_stages.cpp
  ${CMAKE_CURRENT_LIST_DIR}/projection.cpp
  ${CMAKE_CURRENT_LIST_DIR}/stage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dispatch.cpp
)
