# Object sampling (paper pass 1): the shared stage, its backends and Auto's choice.
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/backend_choice.cpp
  ${CMAKE_CURRENT_LIST_DIR}/compute_sampler.cpp
  ${CMAKE_CURRENT_LIST_DIR}/object_sampling.cpp
  ${CMAKE_CURRENT_LIST_DIR}/raster_sampler.cpp
)
# Its programs (spirv/peeling/): the raster backend's, the compute backend's (csample_*) and
# the passes both share.
list(APPEND VKCOLLIDE_SHADERS
  peeling/sample.vert peeling/count.frag peeling/peel.frag
  peeling/csample_setup.comp peeling/csample_bin.comp peeling/csample_args.comp peeling/csample_count.comp
  peeling/csample_peel.comp peeling/csample_gather.comp peeling/csample_pick.comp
  peeling/reduce_max.comp peeling/peel_init.comp peeling/classify.comp peeling/finalize.comp)
