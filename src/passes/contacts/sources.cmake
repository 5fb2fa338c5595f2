# The contact stage (object-level contacts, DetectSettings::contacts; docs/contacts.md):
# host side here, programs in spirv/ (contacts*.glsl, contacts.h).
list(APPEND VKCOLLIDE_GPU_SOURCES
  ${S}/passes/contacts/contact_stage.cpp
  ${S}/passes/contacts/contact_grid.cpp
)
list(APPEND VKCOLLIDE_SHADERS contacts_bounds.comp contacts_setup.comp contacts_tiles.comp contacts_walk.comp)
