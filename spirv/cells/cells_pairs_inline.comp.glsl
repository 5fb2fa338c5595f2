#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, pair pass with the double-precision filter and the exact decision
// inline (cells_pairs.glsl.inc): for runs where few candidates reach the exact decision,
// which then costs less than a pass of its own.
#define CELLS_EXACT_INLINE
#include "cells_pairs.glsl.inc"
