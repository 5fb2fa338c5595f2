#version 460
#extension GL_GOOGLE_include_directive : require
// Cell stage, sweep of the deep cells (cells_deep.glsl.inc) counting its loops against
// CellsParams.loop_guard: for a device that ends them silently past a limit (llvmpipe).
#define CELLS_LOOP_GUARD 1
#include "cells_deep.glsl.inc"
