// glsl/lib/index.glsl: the linear invocation index of a 1D job that
// cv_program_dispatch_1d may have split across y (llvmpipe allows only
// 65535 groups per dimension). Include it after the local_size layout:
// gl_WorkGroupSize is undeclared before that.
#ifndef CV_LIB_INDEX_GLSL
#define CV_LIB_INDEX_GLSL

uint cv_global_index()
{
    return gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) +
           gl_GlobalInvocationID.x;
}

#endif
