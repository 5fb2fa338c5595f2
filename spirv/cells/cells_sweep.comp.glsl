#version 460
#extension GL_GOOGLE_include_directive : require
// Cell stage, sweep of the shallow cells with the repeat checks (cells_sweep_shallow.glsl.inc).
#include "cells_sweep_shallow.glsl.inc"
