#version 450
// glsl/bvh/radix_scatter.comp: last step of one radix sort pass. Each
// workgroup walks its block's tiles of 1024 keys in order, carrying the
// block's next slot per digit: the digit's base (an exclusive scan of the
// digits' totals, done here) plus the block's first slot in the digit's row
// (radix_count.comp, radix_spine.comp).
// A tile is sorted in shared memory by its digit, one nibble at a time
// (stable, low nibble first): each invocation owns KEYS consecutive keys
// and counts their nibbles, 16 bits per value packed into two uvec4; a scan
// of those counts across the group gives every key its rank among equal
// nibbles, and so its place. Wide digits halve the passes over the keys
// (8 bits: 4 passes for 30-bit Morton codes, against 8 of 4 bits, each
// three dispatches), and the sorted tile leaves in runs of consecutive
// slots, one per digit. A key's slot is its run's slot plus its place
// minus the place where its run starts.
// 128 invocations of 8 keys use 19 KiB of shared memory, which limits no
// GPU we know: 256 of 4 keys, or the scan sharing the tile's memory (one
// barrier more per nibble), sorted slower (bench/RESULTS.md).
#include "shared/bindings.h"

#define THREADS 128
#define KEYS (1024 / THREADS)
layout(local_size_x = THREADS) in;

layout(std430, binding = CV_BIND_SORT_KEYS) readonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_SORT_VALS) readonly buffer Vals { uint vals[]; };
layout(std430, binding = CV_BIND_SORT_COUNTS) readonly buffer Counts { uint counts[]; };
layout(std430, binding = CV_BIND_SORT_KEYS_OUT) writeonly buffer KeysOut { uint keys_out[]; };
layout(std430, binding = CV_BIND_SORT_VALS_OUT) writeonly buffer ValsOut { uint vals_out[]; };

uniform uint u_n;
uniform uint u_shift;
uniform uint u_block_tiles;

#include "radix_digits.glsl"

#define SPLITS ((RADIX_BITS + 3) / 4)

shared RadixKey s_key[1024];
shared uint s_val[1024];
shared uvec4 s_lo[2][THREADS], s_hi[2][THREADS];
// Per digit: the block's next output slot, and where its run starts in the
// current tile (set only for digits the tile holds).
shared uint s_base[RADIX_BINS], s_start[RADIX_BINS];
shared uint s_tot[2][THREADS];

RadixKey load_key(uint i)
{
#ifdef KEY64
    return uvec2(keys[2u * i], keys[2u * i + 1u]);
#else
    return keys[i];
#endif
}

void store_key(uint i, RadixKey k)
{
#ifdef KEY64
    keys_out[2u * i] = k.x;
    keys_out[2u * i + 1u] = k.y;
#else
    keys_out[i] = k;
#endif
}

void main()
{
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint block_keys = u_block_tiles * 1024u;
    uint n_blocks = (u_n + block_keys - 1u) / block_keys;
    if (block >= n_blocks)
        return;
    uint l = gl_LocalInvocationID.x;

    // Invocation l scans digits 2l and 2l + 1 (THREADS * 2 >= RADIX_BINS).
    uint d0 = 2u * l, d1 = 2u * l + 1u;
    uint t0 = d0 < RADIX_BINS ? counts[RADIX_BINS * n_blocks + d0] : 0u;
    uint t1 = d1 < RADIX_BINS ? counts[RADIX_BINS * n_blocks + d1] : 0u;
    uint src = 0u;
    s_tot[0][l] = t0 + t1;
    barrier();
    for (uint off = 1u; off < uint(THREADS); off <<= 1) {
        uint a = s_tot[src][l];
        if (l >= off)
            a += s_tot[src][l - off];
        s_tot[1u - src][l] = a;
        src = 1u - src;
        barrier();
    }
    uint digit_base = s_tot[src][l] - t0 - t1;
    if (d0 < RADIX_BINS)
        s_base[d0] = digit_base + counts[d0 * n_blocks + block];
    if (d1 < RADIX_BINS)
        s_base[d1] = digit_base + t0 + counts[d1 * n_blocks + block];
    // The tiles' barriers order these before their use.

    for (uint tile = block * u_block_tiles; tile < (block + 1u) * u_block_tiles; tile++) {
        uint first = tile * 1024u;
        if (first >= u_n)
            break;
        uint m = min(1024u, u_n - first);
        RadixKey key[KEYS];
        // dig is 16 (no key) or the nibble | the key's rank among this
        // invocation's keys of that nibble << 8.
        uint val[KEYS], dig[KEYS];
        for (uint k = 0u; k < uint(KEYS); k++) {
            uint p = l * uint(KEYS) + k;
            if (p < m) {
                key[k] = load_key(first + p);
                val[k] = vals[first + p];
            }
        }
        for (uint split = 0u; split < uint(SPLITS); split++) {
            uvec4 lo = uvec4(0u), hi = uvec4(0u);
            for (uint k = 0u; k < uint(KEYS); k++) {
                dig[k] = 16u;
                if (l * uint(KEYS) + k < m) {
                    uint d = (cv_radix_digit(key[k], u_shift) >> (4u * split)) & 15u;
                    dig[k] = d | (cv_radix_field(d < 8u ? lo : hi, d) << 8);
                    cv_radix_count(d, lo, hi);
                }
            }
            // Inclusive Hillis-Steele scan of the packed counts, ping-ponging.
            src = 0u;
            s_lo[0][l] = lo;
            s_hi[0][l] = hi;
            barrier();
            for (uint off = 1u; off < uint(THREADS); off <<= 1) {
                uvec4 a = s_lo[src][l], b = s_hi[src][l];
                if (l >= off) {
                    a += s_lo[src][l - off];
                    b += s_hi[src][l - off];
                }
                s_lo[1u - src][l] = a;
                s_hi[1u - src][l] = b;
                src = 1u - src;
                barrier();
            }
            // Where each nibble value starts in the tile: an exclusive scan
            // of the tile's totals, packed like them.
            uvec4 tlo = s_lo[src][THREADS - 1], thi = s_hi[src][THREADS - 1];
            uvec4 slo = uvec4(0u), shi = uvec4(0u);
            uint sum = 0u;
            for (uint v = 0u; v < 16u; v++) {
                uvec4 one = uvec4(0u);
                one[(v & 7u) >> 1] = sum << (16u * (v & 1u));
                if (v < 8u)
                    slo += one;
                else
                    shi += one;
                sum += cv_radix_field(v < 8u ? tlo : thi, v);
            }
            // Exclusive prefix of this invocation = inclusive minus its own,
            // plus where the value starts.
            uvec4 plo = s_lo[src][l] - lo + slo, phi = s_hi[src][l] - hi + shi;
            for (uint k = 0u; k < uint(KEYS); k++) {
                uint d = dig[k] & 0xffu;
                if (d < 16u) {
                    uint at = cv_radix_field(d < 8u ? plo : phi, d) + (dig[k] >> 8);
                    s_key[at] = key[k];
                    s_val[at] = val[k];
                }
            }
            barrier();
            // The next split's scan barriers order these reads before its
            // writes.
            if (split + 1u < uint(SPLITS)) {
                for (uint k = 0u; k < uint(KEYS); k++) {
                    uint p = l * uint(KEYS) + k;
                    if (p < m) {
                        key[k] = s_key[p];
                        val[k] = s_val[p];
                    }
                }
            }
        }
        // The tile is sorted by digit: mark where each run starts, then
        // write consecutive places to consecutive slots.
        for (uint k = 0u; k < uint(KEYS); k++) {
            uint p = k * uint(THREADS) + l;
            dig[k] = RADIX_BINS;
            if (p < m) {
                key[k] = s_key[p];
                dig[k] = cv_radix_digit(key[k], u_shift);
                if (p == 0u || cv_radix_digit(s_key[p - 1u], u_shift) != dig[k])
                    s_start[dig[k]] = p;
            }
        }
        barrier();
        for (uint k = 0u; k < uint(KEYS); k++) {
            uint p = k * uint(THREADS) + l;
            val[k] = 0u;
            if (p < m) {
                uint d = dig[k];
                uint start = s_start[d];
                uint dst = s_base[d] + p - start;
                store_key(dst, key[k]);
                vals_out[dst] = s_val[p];
                // The run's last key moves the digit's slot on.
                if (p + 1u == m || cv_radix_digit(s_key[p + 1u], u_shift) != d)
                    val[k] = p + 1u - start;
            }
        }
        barrier();
        // The next tile's barriers order this update before its use, and
        // these reads of s_key before its writes.
        for (uint k = 0u; k < uint(KEYS); k++)
            if (val[k] > 0u)
                s_base[dig[k]] += val[k];
    }
}
