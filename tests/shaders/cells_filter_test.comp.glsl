#version 460
#extension GL_GOOGLE_include_directive : require
// The triangle-triangle filter alone, for its unit tests (tests/gpu/cells_filter_tests.cpp):
// one CellsFilterCase per invocation, verdict 1 when rejected (proved disjoint).
#include "cells/cells_common.glsl.inc"
#include "cells/tritri_filter.glsl.inc"
layout(local_size_x = kCellsGroupSize) in;

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer FilterParamsRef { CellsFilterParams p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer FilterCasesRef { CellsFilterCase c[]; };

void main() {
    CellsFilterParams F = FilterParamsRef(pc.frame).p;
    uint id = globalIndex();
    if (id >= F.count) return;
    CellsFilterCase fc = FilterCasesRef(F.cases).c[id];
    FilterPoint a[3], b[3];
    filterTriangle(fc.a, fc.eps_a, a);
    filterTriangle(fc.b, fc.eps_b, b);
    UintsRef(F.verdict).v[id] = filterRejects(a, b) ? 1u : 0u;
}
