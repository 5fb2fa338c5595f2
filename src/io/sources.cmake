# Mesh readers and writers (include/vkcollide/io.hpp).
list(APPEND VKCOLLIDE_HOST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/mesh_reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_writer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/obj_reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/off_reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ply_reader.cpp
)
