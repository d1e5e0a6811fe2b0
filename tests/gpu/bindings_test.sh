#!/bin/sh
# bindings_test.sh: shader resources by name. Host and shaders agree on
# glsl/shared/bindings.h's CV_BIND_* names, never on a number: no file but
# bindings.h spells a slot as CV_BIND_STAGE0 + k, no storage block under
# glsl/ takes a bare number, and each scene buffer the trace stages read is
# declared once (a copy in a second file could drift from the first), as
# is each read-only table's buffer texture (CV_TEXUNIT_*), on a unit of its
# own.
. "${srcdir:-.}/tests/setup.sh"
src=${CAVALRY_DATA_DIR:?}
cd "$src"

find glsl src tests -type f \( -name '*.c' -o -name '*.h' -o -name '*.glsl' -o -name '*.comp' \) \
    ! -path glsl/shared/bindings.h ! -name glsl_embedded.c | sort >"$tmp/files"
xargs grep -l 'CV_BIND_STAGE0' <"$tmp/files" >"$tmp/stage0" || true
check "no slot spelled CV_BIND_STAGE0 + k outside bindings.h ($(wc -l <"$tmp/stage0") files:$(tr '\n' ' ' <"$tmp/stage0"))" \
    test ! -s "$tmp/stage0"

find glsl -type f \( -name '*.glsl' -o -name '*.comp' \) | sort | \
    xargs grep -n 'binding *= *[0-9]' >"$tmp/numbered" || true
check "no block under glsl/ bound by number ($(wc -l <"$tmp/numbered") lines)" test ! -s "$tmp/numbered"

for b in VERTICES TRIANGLES TRI_LIGHT MATERIALS TEXTURES TEXELS LIGHTS ENV_DIST; do
    n=$(find glsl -type f \( -name '*.glsl' -o -name '*.comp' \) | sort | \
        xargs grep -l "binding = CV_BIND_$b)" | tr '\n' ' ')
    check "CV_BIND_$b declared in one file ($n)" test "$(echo $n | wc -w)" -eq 1
done

units=$(sed -n 's/^#define CV_TEXUNIT_\([A-Z_]*\) .*/\1/p' glsl/shared/bindings.h)
check "bindings.h names texture units ($(echo $units | wc -w))" test -n "$units"
for u in $units; do
    n=$(find glsl -type f \( -name '*.glsl' -o -name '*.comp' \) | sort | \
        xargs grep -l "binding = CV_TEXUNIT_$u)" | tr '\n' ' ')
    check "CV_TEXUNIT_$u declared in one file ($n)" test "$(echo $n | wc -w)" -eq 1
done
dups=$(sed -n 's/^#define CV_TEXUNIT_[A-Z_]* \([0-9]*\).*/\1/p' glsl/shared/bindings.h | sort | uniq -d |
       tr '\n' ' ')
check "each texture unit is one table's (repeated: ${dups:-none})" test -z "$dups"
done_testing
