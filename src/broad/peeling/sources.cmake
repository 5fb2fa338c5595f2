# The peeling method (the paper's passes 1-4; docs/broadphase.md): object sampling
# (sampling/, its own list), ray merging, primitive separation, packing, and the method
# that composes them.
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/merging.cpp
  ${CMAKE_CURRENT_LIST_DIR}/packing.cpp
  ${CMAKE_CURRENT_LIST_DIR}/peeling_method.cpp
  ${CMAKE_CURRENT_LIST_DIR}/separation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/triangle_bounds.cpp
)
include(${CMAKE_CURRENT_LIST_DIR}/sampling/sources.cmake)
# Its programs (spirv/peeling/; object sampling's are listed in sampling/sources.cmake).
list(APPEND VKCOLLIDE_SHADERS
  peeling/merge.comp peeling/separate.comp peeling/tri_bounds.comp
  peeling/pack_rowcount.comp peeling/scan_counts.comp peeling/pack_shift.comp peeling/pack_move.comp
  peeling/scan_blocksum.comp peeling/scan_scatter.comp)
