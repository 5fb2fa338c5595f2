#version 460
#extension GL_GOOGLE_include_directive : require
// Cell pair stage, setup pass with shaderFloat64: the CPU's world vertices (cells_setup.glsl.inc).
#include "cells_setup.glsl.inc"
