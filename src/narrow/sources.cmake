# Narrow phase (host only): exact predicates, triangle test, triangle source, sweep and
# prune, the shared back half, the record and pair entries, the thread pool.
list(APPEND VKCOLLIDE_HOST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/exact_predicates.cpp
  ${CMAKE_CURRENT_LIST_DIR}/triangle_intersection.cpp
  ${CMAKE_CURRENT_LIST_DIR}/radix_sort.cpp
  ${CMAKE_CURRENT_LIST_DIR}/triangle_source.cpp
  ${CMAKE_CURRENT_LIST_DIR}/slots.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sweep_and_prune.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exact_stage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/responses.cpp
  ${CMAKE_CURRENT_LIST_DIR}/narrow_phase.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pair_keys.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pair_narrow_phase.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sorted_pairs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/thread_pool.cpp
)
