# Results, meshes, public types (host code only).
list(APPEND VKCOLLIDE_HOST_SOURCES ${CMAKE_CURRENT_LIST_DIR}/result.cpp ${CMAKE_CURRENT_LIST_DIR}/mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/types.cpp ${CMAKE_CURRENT_LIST_DIR}/huge_pages.cpp)
