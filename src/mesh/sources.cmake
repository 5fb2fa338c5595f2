# Mesh intake: engine meshes and uploads.
list(APPEND VKCOLLIDE_GPU_SOURCES ${CMAKE_CURRENT_LIST_DIR}/engine_mesh.cpp ${CMAKE_CURRENT_LIST_DIR}/mesh_upload.cpp)
