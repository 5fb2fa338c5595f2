#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, pair pass for devices without shaderFloat64: no filter.
#define CELLS_NO_FLOAT64 1
#include "cells_pairs.glsl.inc"
