# The public API's implementation (CollisionWorld).
list(APPEND VKCOLLIDE_HOST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/vertex_scans.cpp  # the world's loops over host positions (no Vulkan)
  ${CMAKE_CURRENT_LIST_DIR}/mesh_checks.cpp  # closed meshes: holes and inside-out (no Vulkan)
  ${CMAKE_CURRENT_LIST_DIR}/grid_tuner.cpp  # the reliable method's grid per scene, from GPU times (no Vulkan)
)
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/auto_settings.cpp  # the automatic settings
  ${CMAKE_CURRENT_LIST_DIR}/collision_rays.cpp  # DetectSettings::peeling.collision_rays: ray images to world segments
  ${CMAKE_CURRENT_LIST_DIR}/contacts.cpp
  ${CMAKE_CURRENT_LIST_DIR}/detect.cpp
  ${CMAKE_CURRENT_LIST_DIR}/engine_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/engine_sync.cpp
  ${CMAKE_CURRENT_LIST_DIR}/in_flight.cpp  # the detections in flight: two slots
  ${CMAKE_CURRENT_LIST_DIR}/object_registry.cpp  # the objects, ids, the narrow phase's source, the pair mask
  ${CMAKE_CURRENT_LIST_DIR}/prepare_pipelines.cpp  # CollisionWorld::preparePipelines: pipelines made before a detection needs them
  ${CMAKE_CURRENT_LIST_DIR}/validation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/world.cpp
)
