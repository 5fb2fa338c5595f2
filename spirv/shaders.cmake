# The library's programs, in one folder per room: spirv/<room>/<name>.<stage>.glsl, embedded as
# vkcollide::shaders::<name>_<stage> (names are unique across rooms). Listed here: the
# broad phase's front (common/: its programs and the headers every room shares); each room
# lists its own in its sources.cmake (src/broad/peeling/, src/broad/cells/, src/contacts/).
list(APPEND VKCOLLIDE_SHADERS common/validate.comp common/bounds.comp common/fit.comp)
