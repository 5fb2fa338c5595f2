# Proximity (DetectSettings::proximity, docs/proximity.md): which primitives each triangle
# owns (host only), the GPU pass after the cell stage and its records as the host result.
list(APPEND VKCOLLIDE_HOST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/ownership.cpp
)
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/proximity_stage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/proximity_results.cpp
)
list(APPEND VKCOLLIDE_SHADERS proximity/proximity_pairs.comp proximity/proximity_sort.comp)
