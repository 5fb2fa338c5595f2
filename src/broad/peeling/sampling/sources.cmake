# Object sampling (paper pass 1): the shared stage, its backends and Auto's choice.
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/backend_choice.cpp
  ${CMAKE_CURRENT_LIST_DIR}/compute_sampler.cpp
  ${CMAKE_CURRENT_LIST_DIR}/object_sampling.cpp
  ${CMAKE_CURRENT_LIST_DIR}/raster_sampler.cpp
)
