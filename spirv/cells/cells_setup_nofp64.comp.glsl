#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, setup pass for devices without shaderFloat64: float world vertices and their bound.
#define CELLS_NO_FLOAT64 1
#include "cells_setup.glsl.inc"
