// glsl/trace/unroll_hint.glsl: asks NVIDIA's compiler not to unroll the
// loops of a shade kernel that holds more than the diffuse lobe (the coated
// walk above all, bsdf/layered.glsl). Unrolled, the walk's kernel takes
// most of a new scene's program build; not unrolled, it renders as fast
// (bench/RESULTS.md, "The walk kernel without unrolling"). The diffuse
// kernel keeps its unrolling, which it runs faster with. Other drivers
// ignore the pragma, as GLSL asks of pragmas they do not know. Included
// after the kernel's bin defines and before its code: the pragma holds
// for the loops that follow it.
#if !defined(CV_BSDF_DIFFUSE_ONLY)
#pragma optionNV(unroll none)
#endif
