#!/bin/sh
# shared_scenes_test.sh: every real pbrt scene in ../shared/scenes loads
# without error, and the v3 and v4 files of the same scene import to the
# same flat scene (the dump differs only in the film file name). Also the
# project's own v3/v4 twin in tests/data/scene. Skips the shared part when
# the folder is absent.
. "$CAVALRY_DATA_DIR/tests/setup.sh"
dump="$CV_TEST_BUILDDIR/scene/dump_scene"

# load DESC OUT ARGS...: dump into OUT; ok when it loads.
load() {
    d=$1; o=$2; shift 2
    if "$dump" "$@" > "$o" 2> "$tmp/stderr"; then ok "$d"; else not_ok "$d"; sed 's/^/# /' "$tmp/stderr"; fi
}

same() { # same A B: the dumps match apart from film.filename
    grep -v '^film.filename' "$1" > "$tmp/a" && grep -v '^film.filename' "$2" > "$tmp/b" && diff "$tmp/a" "$tmp/b"
}

load "tiny-v3.pbrt loads" "$tmp/tiny3" "$CV_TEST_DATA/scene/tiny-v3.pbrt"
load "tiny-v4.pbrt loads, even with --strict" "$tmp/tiny4" --strict "$CV_TEST_DATA/scene/tiny-v4.pbrt"
check "tiny v3 and v4 give the same flat scene" same "$tmp/tiny3" "$tmp/tiny4"

if [ ! -d "$CV_SHARED_SCENES" ]; then
    done_testing
    exit $?
fi
for f in cornell-box/scene-v3.pbrt cornell-box/scene-v4.pbrt veach-mis/scene-v3.pbrt veach-mis/scene-v4.pbrt \
         veach-bidir/scene-v4.pbrt killeroos/killeroo-simple.pbrt killeroos/killeroo-gold.pbrt \
         killeroos/killeroo-coated-gold.pbrt killeroos/killeroo-moving.pbrt caustic-glass/caustic-glass-v4.pbrt; do
    out="$tmp/$(echo "$f" | tr / _).dump"
    if [ ! -f "$CV_SHARED_SCENES/$f" ]; then
        ok "$f # SKIP not present"
        continue
    fi
    load "$f loads with no error" "$out" "$CV_SHARED_SCENES/$f"
    check "$f has triangles and lights" sh -c "grep -q '^triangles [1-9]' '$out' && grep -q '^lights [1-9]' '$out'"
done
for s in cornell-box veach-mis; do
    [ -f "$tmp/${s}_scene-v3.pbrt.dump" ] || continue
    check "$s: v3 and v4 give the same flat scene" same "$tmp/${s}_scene-v3.pbrt.dump" "$tmp/${s}_scene-v4.pbrt.dump"
done
done_testing
