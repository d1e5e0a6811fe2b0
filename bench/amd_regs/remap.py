# bench/amd_regs/remap.py IN.spvasm OUT.spvasm LAYOUT: GL's separate binding namespaces to
# Vulkan sets (0 SSBO, 1 UBO, 2 samplers/texel buffers); LAYOUT lists "set binding type"
import re, sys
src = open(sys.argv[1]).read()
lines = src.split('\n')
ptr = {}   # pointer type -> pointee
for l in lines:
    m = re.match(r'\s*(%\S+) = OpTypePointer (\w+) (%\S+)', l)
    if m: ptr[m.group(1)] = m.group(3)
block = set(re.findall(r'OpDecorate (%\S+) Block\b', src))
var = {}
for l in lines:
    m = re.match(r'\s*(%\S+) = OpVariable (%\S+) (Uniform|UniformConstant|StorageBuffer)$', l)
    if m:
        pointee = ptr.get(m.group(2))
        if m.group(3) == 'UniformConstant': var[m.group(1)] = (2, 'tex')
        elif pointee in block and m.group(3) == 'Uniform': var[m.group(1)] = (1, 'ubo')
        else: var[m.group(1)] = (0, 'ssbo')
binding = {}
for l in lines:
    m = re.match(r'\s*OpDecorate (%\S+) Binding (\d+)', l)
    if m: binding[m.group(1)] = int(m.group(2))
out = []
for l in lines:
    m = re.match(r'(\s*OpDecorate (%\S+) DescriptorSet) (\d+)', l)
    if m and m.group(2) in var:
        l = '%s %d' % (m.group(1), var[m.group(2)][0])
    out.append(l)
open(sys.argv[2], 'w').write('\n'.join(out))
with open(sys.argv[3], 'w') as f:
    for v, (s, t) in var.items():
        f.write('%d %d %s\n' % (s, binding.get(v, 0), t))
