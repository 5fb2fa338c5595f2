# The benchmark scene set and its reference cache (tools/bench/bench_scenes.hpp), shared by
# vkcollide_bench (tools/CMakeLists.txt), the peers' benchmark (tools/bench/CMakeLists.txt),
# the scene tests and the recall guard (tests/scene/CMakeLists.txt): compiled once, into
# vkcollide_bench_scenes, which they link. It links vkcollide_test_support_host (tests/support:
# the exact reference), so whoever includes this file first has that target already.
set(VKCOLLIDE_BENCH_SCENE_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/bench_scenes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_kinds.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_piles.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_pairs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reference_cache.cpp
  ${CMAKE_CURRENT_LIST_DIR}/user_scene.cpp
)
if(NOT TARGET vkcollide_bench_scenes)
  add_library(vkcollide_bench_scenes STATIC ${VKCOLLIDE_BENCH_SCENE_SOURCES})
  target_include_directories(vkcollide_bench_scenes PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(vkcollide_bench_scenes PUBLIC vkcollide_test_support_host PRIVATE vkcollide_warnings)
endif()

# Adding a scene to a CollisionWorld (engine buffers included): needs the GPU library.
set(VKCOLLIDE_BENCH_WORLD_SOURCES ${CMAKE_CURRENT_LIST_DIR}/bench_world.cpp)
