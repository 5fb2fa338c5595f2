# The benchmark scene set and its reference cache (tools/bench/bench_scenes.hpp), shared by
# vkcollide_bench (tools/CMakeLists.txt), the peers' benchmark (tools/bench/CMakeLists.txt)
# and the recall guard (tests/scene/CMakeLists.txt). Users also compile
# vkcollide_test_support_host (tests/support: the exact reference).
set(VKCOLLIDE_BENCH_SCENE_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/bench_scenes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_kinds.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_piles.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_pairs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reference_cache.cpp
)

# Adding a scene to a CollisionWorld (engine buffers included): needs the GPU library.
set(VKCOLLIDE_BENCH_WORLD_SOURCES ${CMAKE_CURRENT_LIST_DIR}/bench_world.cpp)
