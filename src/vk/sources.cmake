# Device-layer files added after cmake/Sources.cmake's list (which names loader, device
# and resources); included from the top-level CMakeLists.txt.
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/adopt.cpp
  ${CMAKE_CURRENT_LIST_DIR}/features.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline.cpp
  ${CMAKE_CURRENT_LIST_DIR}/engine_buffer.cpp
)
