# Object sampling (paper pass 1): the shared stage, its backends and Auto's choice.
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${S}/passes/sampling/backend_choice.cpp
  ${S}/passes/sampling/compute_sampler.cpp
  ${S}/passes/sampling/object_sampling.cpp
  ${S}/passes/sampling/raster_sampler.cpp
)
