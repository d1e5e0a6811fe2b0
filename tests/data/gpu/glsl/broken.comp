#version 450
// A shader with an error in an included file, for program_test.
#include "inc/fine.glsl"
#include "inc/bad.glsl"
layout(local_size_x = 1) in;
void main() { fine(); }
