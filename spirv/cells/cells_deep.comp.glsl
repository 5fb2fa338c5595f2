#version 460
#extension GL_GOOGLE_include_directive : require
// Cell stage, sweep of the deep cells (cells_deep.glsl.inc), without loop counters: for
// devices that run long loops to the end.
#include "cells_deep.glsl.inc"
