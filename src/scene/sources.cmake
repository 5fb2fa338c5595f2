# Procedural meshes, transforms and mesh statistics (include/vkcollide/scene.hpp).
list(APPEND VKCOLLIDE_HOST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/generators.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_tools.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shapes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/subdivide.cpp
  ${CMAKE_CURRENT_LIST_DIR}/deformers.cpp
  ${CMAKE_CURRENT_LIST_DIR}/drape.cpp
)
