# The render graph: declaring, planning and taping are host code; the executor submits.
list(APPEND VKCOLLIDE_HOST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/graph.cpp  # declaring a render graph
  ${CMAKE_CURRENT_LIST_DIR}/use_info.cpp  # what each use of a resource means (stages, access, layout)
  ${CMAKE_CURRENT_LIST_DIR}/compile.cpp  # the plan: order, culling, barriers
  ${CMAKE_CURRENT_LIST_DIR}/command_tape.cpp  # plain data: recording a tape
  ${CMAKE_CURRENT_LIST_DIR}/command_tape_replay.cpp  # replayed through a dispatch table
)
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/executor.cpp  # submitting a graph: resources, taping, waiting
  ${CMAKE_CURRENT_LIST_DIR}/pass_context.cpp  # what a pass records through
)
