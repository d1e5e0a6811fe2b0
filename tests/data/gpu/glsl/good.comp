#version 450
// A shader that compiles, for program_test's requests.
#include "inc/fine.glsl"
layout(local_size_x = 8) in;
void main() { fine(); }
