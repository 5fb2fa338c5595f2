# The contact stage (object-level contacts, DetectSettings::contacts.objects; docs/contacts.md):
# host side here, programs in spirv/contacts/ (contacts*.glsl, contacts.h).
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/contact_stage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/contact_grid.cpp
)
list(APPEND VKCOLLIDE_SHADERS contacts/contacts_bounds.comp contacts/contacts_setup.comp contacts/contacts_tiles.comp
  contacts/contacts_walk.comp)
# Contact geometry of intersecting triangle pairs (DetectSettings::contacts.geometry): host only.
list(APPEND VKCOLLIDE_HOST_SOURCES ${CMAKE_CURRENT_LIST_DIR}/pair_contacts.cpp ${CMAKE_CURRENT_LIST_DIR}/exact_points.cpp)
