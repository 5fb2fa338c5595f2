# A detection: one or three directions.
list(APPEND VKCOLLIDE_GPU_SOURCES ${CMAKE_CURRENT_LIST_DIR}/axis_union.cpp ${CMAKE_CURRENT_LIST_DIR}/detection.cpp)
