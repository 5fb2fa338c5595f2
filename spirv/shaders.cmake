# Broad-phase programs (spirv/<name>.<stage>.glsl), embedded as vkcollide::shaders::<name>_<stage>.
list(APPEND VKCOLLIDE_SHADERS
  validate.comp bounds.comp fit.comp sample.vert count.frag peel.frag reduce_max.comp peel_init.comp classify.comp
  finalize.comp merge.comp separate.comp tri_bounds.comp
  pack_rowcount.comp scan_counts.comp pack_shift.comp pack_move.comp scan_blocksum.comp scan_scatter.comp
  csample_setup.comp csample_bin.comp csample_args.comp csample_count.comp csample_peel.comp csample_gather.comp csample_pick.comp)
