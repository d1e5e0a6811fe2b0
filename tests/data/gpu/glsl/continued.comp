#version 450
// #defines continued over lines, then an error, for program_test: the
// loader joins the lines and line 9's error still reports line 9.
#include "inc/continued.glsl"
#define SUM3 \
    (1.0 + \
     2.0 + 3.0)
layout(local_size_x = 1) in;
void main() { float x = SUM3 + PAIR_SUM + undeclared_after_define; }
