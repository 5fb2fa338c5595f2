# Narrow phase (host only): exact predicates, triangle test, sweep and prune, thread pool.
list(APPEND VKCOLLIDE_HOST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/exact_predicates.cpp
  ${CMAKE_CURRENT_LIST_DIR}/triangle_intersection.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sweep_and_prune.cpp
  ${CMAKE_CURRENT_LIST_DIR}/thread_pool.cpp
  ${CMAKE_CURRENT_LIST_DIR}/narrow_phase.cpp
)
