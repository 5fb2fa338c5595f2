# The cell pair stage (reliable mode, GPU pair stage; docs/reliable.md): host side here,
# programs in spirv/ (cells*.glsl, tritri_filter.glsl.inc, cells.h).
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/cell_pairs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cell_pairs_record.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reliable_method.cpp
  ${CMAKE_CURRENT_LIST_DIR}/device_pairs.cpp
)
list(APPEND VKCOLLIDE_SHADERS
  cells_setup.comp cells_big.comp cells_scan.comp cells_fill.comp cells_sweep.comp cells_deep.comp cells_args.comp
  cells_pairs.comp cells_pairs_nofp64.comp cells_filter_test.comp device_pairs.comp)
