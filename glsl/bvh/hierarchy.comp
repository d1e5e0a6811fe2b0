#version 450
// glsl/bvh/hierarchy.comp: the binary radix tree of Karras 2012 over the
// sorted Morton codes, one invocation per inner node. Equal codes are told
// apart by their index (the key is code:index), so duplicates still give a
// valid tree, balanced over the run of equal codes. Also resets the refit
// counters and fills every leaf's link (bounds come in refit.comp).
#include "shared/bvh.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_BUILD_KEYS) readonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_BUILD_NODES) buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_BUILD_COUNTERS) writeonly buffer Counters { uint counters[]; };

uniform uint u_n;

int delta(int i, int j)
{
    if (j < 0 || j >= int(u_n))
        return -1;
#ifdef KEY64
    uvec2 a = uvec2(keys[2 * i], keys[2 * i + 1]), b = uvec2(keys[2 * j], keys[2 * j + 1]);
    if (a == b)
        return 64 + 31 - findMSB(uint(i ^ j));
    if (a.y != b.y)
        return 31 - findMSB(a.y ^ b.y);
    return 32 + 31 - findMSB(a.x ^ b.x);
#else
    uint a = keys[i], b = keys[j];
    if (a == b)
        return 32 + 31 - findMSB(uint(i ^ j));
    return 31 - findMSB(a ^ b);
#endif
}

void main()
{
    uint gi = cv_global_index();
    int n = int(u_n);
    if (gi < u_n)
        nodes[n - 1 + int(gi)].link.xy = ivec2(-1);
    if (gi + 1u >= u_n)
        return;
    int i = int(gi);
    counters[i] = 0u;
    int d = delta(i, i + 1) - delta(i, i - 1) >= 0 ? 1 : -1;
    int dmin = delta(i, i - d);
    int lmax = 2;
    while (delta(i, i + lmax * d) > dmin)
        lmax <<= 1;
    int l = 0;
    for (int t = lmax >> 1; t >= 1; t >>= 1)
        if (delta(i, i + (l + t) * d) > dmin)
            l += t;
    int j = i + l * d;
    int dnode = delta(i, j);
    int s = 0;
    int t = l;
    do {
        t = (t + 1) >> 1;
        if (delta(i, i + (s + t) * d) > dnode)
            s += t;
    } while (t > 1);
    int gamma = i + s * d + min(d, 0);
    int left = min(i, j) == gamma ? n - 1 + gamma : gamma;
    int right = max(i, j) == gamma + 1 ? n + gamma : gamma + 1;
    nodes[i].link.xy = ivec2(left, right);
    nodes[left].link.z = i;
    nodes[right].link.z = i;
    if (i == 0)
        nodes[0].link.z = -1;
}
