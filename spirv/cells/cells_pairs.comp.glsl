#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, pair pass with the double-precision filter (cells_pairs.glsl.inc).
#include "cells_pairs.glsl.inc"
