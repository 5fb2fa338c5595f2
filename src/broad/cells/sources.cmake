# The cell stage (reliable mode, GPU pair stage; docs/reliable.md): host side here,
# programs in spirv/cells/ (cells*.glsl, tritri_filter.glsl.inc, the exact decision, cells.h).
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/cell_stage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cell_stage_buffers.cpp  # the buffer plan: refused by name, then created
  ${CMAKE_CURRENT_LIST_DIR}/cell_stage_record.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reliable_method.cpp
  ${CMAKE_CURRENT_LIST_DIR}/device_pairs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/device_responses.cpp
  ${CMAKE_CURRENT_LIST_DIR}/small_sort.cpp  # few pairs: sorted and responded in one pass
)
list(APPEND VKCOLLIDE_SHADERS
  cells/cells_setup.comp cells/cells_setup_nofp64.comp cells/cells_big.comp cells/cells_scan.comp cells/cells_fill.comp cells/cells_fill_per_footprint.comp cells/cells_sweep.comp
  cells/cells_sweep_plain.comp cells/cells_deep_sort.comp cells/cells_deep.comp cells/cells_deep_guarded.comp cells/cells_args.comp cells/cells_pairs.comp cells/cells_pairs_nofp64.comp cells/cells_pairs_inline.comp cells/cells_exact.comp
  cells/device_pairs.comp cells/device_responses.comp cells/device_responses_sum.comp cells/small_sort.comp cells/small_sort_respond.comp)
