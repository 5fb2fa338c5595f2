#version 460
#extension GL_GOOGLE_include_directive : require
// Cell stage, sweep of the shallow cells without the repeat checks (cells_sweep_shallow.glsl.inc):
// their state slows the whole sweep on a GPU, whose pair pass drops repeats anyway.
#define CELLS_SWEEP_PLAIN 1
#include "cells_sweep_shallow.glsl.inc"
