#!/bin/sh
# inputs_test.sh: files a scene names are bounded and safe. A device, a FIFO
# or an oversized (sparse) file is refused with file:line:col before any
# read; a file that is no scene is not echoed in the error; --scene-root
# refuses every file outside its folder, through "..", absolute paths and
# symbolic links alike. Runs the importer only (--dump-scene): no GPU.
. "${srcdir:-.}/tests/setup.sh"
cd "$tmp"
head='LookAt 0 3 3  0 0 0  0 1 0
Camera "perspective" "float fov" [ 45 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 12 ]
WorldBegin
LightSource "point" "rgb I" [ 1 1 1 ]'
quad='"point3 P" [ 0 0 0  1 0 0  1 1 0  0 1 0 ] "integer indices" [ 0 1 2  0 2 3 ]'

# refused NAME TEXT WANT...: the scene TEXT fails with status 3 (invalid)
# and its message holds every WANT. A guard of 120 s stops a hang (a FIFO
# opened for reading waits for a writer): it is not a timing threshold.
refused() {
    name=$1 text=$2
    shift 2
    printf '%s\n%s\n' "$head" "$text" >main.pbrt
    set +e
    timeout 120 "$CAVALRY_BATCH" --dump-scene=main.pbrt $opts >out.txt 2>err.txt
    rc=$?
    set -e
    good=true
    [ "$rc" -eq 3 ] || good=false
    for want in "$@"; do
        grep -qF -- "$want" err.txt || good=false
    done
    if $good; then ok "$name"; else not_ok "$name (status $rc)"; sed 's/^/# /' err.txt | head -5; fi
}
opts=
mkfifo fifo
refused "Include of /dev/zero" 'Include "/dev/zero"' \
    'main.pbrt:6:1: cannot include "/dev/zero"' 'not a regular file'
refused "Import of a FIFO, no hang" 'Import "fifo"' \
    'main.pbrt:6:1: cannot include "fifo"' 'not a regular file'
refused "plymesh from /dev/urandom" 'Shape "plymesh" "string filename" "/dev/urandom"' \
    'main.pbrt:6:1: plymesh "/dev/urandom"' 'not a regular file'
refused "image texture from a FIFO" \
    'Texture "t" "spectrum" "imagemap" "string filename" "fifo"' \
    'main.pbrt:6:1: image "fifo"' 'not a regular file'
refused "spectrum file that is a FIFO" \
    "Material \"conductor\" \"spectrum eta\" \"fifo\" \"spectrum k\" \"fifo\"
Shape \"trianglemesh\" $quad" \
    'main.pbrt:6:' 'spectrum "fifo"' 'not a regular file'
refused "Include of a folder" 'Include "/"' 'main.pbrt:6:1: cannot include "/"' 'is a folder'
# 17 GiB without the disk space: only the size is ever looked at.
truncate -s 17G big.ply
refused "a PLY file over the size limit" 'Shape "plymesh" "string filename" "big.ply"' \
    'main.pbrt:6:1: plymesh "big.ply"' 'bytes an input file may hold'
rm -f big.ply

# A file that is no scene file is not echoed.
printf 'root:$6$s3cr3tHa5h:19000:0:99999:7:::\n' >secret.txt
refused "Include of a non-scene file: refused" 'Include "secret.txt"' \
    'secret.txt:1:1: not a pbrt scene file'
check "Include of a non-scene file: its contents are not echoed" \
    sh -c '! grep -q "s3cr3t\|root:" err.txt'

# --scene-root: the scene's own folder and below only.
mkdir -p root/sub outside
printf '%s\n' 'Shape "sphere"' >outside/o.pbrt
printf '%s\n' 'Shape "sphere"' >root/sub/in.pbrt
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >outside/m.ply
ln -s ../outside/o.pbrt root/link.pbrt
ln -s ../outside root/dirlink
good_root() {
    printf '%s\n%s\n' "$head" "$1" >root/main.pbrt
    "$CAVALRY_BATCH" --dump-scene=root/main.pbrt --scene-root=root >/dev/null 2>err.txt
}
check "--scene-root: an Include inside the root loads" good_root 'Include "sub/in.pbrt"'
in_root() {
    name=$1 text=$2
    printf '%s\n%s\n' "$head" "$text" >root/main.pbrt
    set +e
    "$CAVALRY_BATCH" --dump-scene=root/main.pbrt --scene-root=root >/dev/null 2>err.txt
    rc=$?
    set -e
    if [ "$rc" -eq 3 ] && grep -q 'root/main.pbrt:6:1: .*outside the scene root' err.txt; then
        ok "--scene-root refuses $name"
    else
        not_ok "--scene-root refuses $name (status $rc)"; sed 's/^/# /' err.txt | head -3
    fi
}
in_root '"../" in an Include' 'Include "../outside/o.pbrt"'
in_root 'an absolute path' "Include \"$tmp/outside/o.pbrt\""
in_root 'a symbolic link to a file outside' 'Include "link.pbrt"'
in_root 'a file under a linked folder' 'Shape "plymesh" "string filename" "dirlink/m.ply"'
in_root 'a file outside that does not exist' 'Include "../outside/none.pbrt"'
in_root 'a redundant path that leaves' 'Include "sub/../../outside/o.pbrt"'
set +e
"$CAVALRY_BATCH" --dump-scene=outside/o.pbrt --scene-root=root >/dev/null 2>err.txt
rc=$?
set -e
check "--scene-root refuses a scene file outside it (status $rc)" \
    sh -c "[ $rc -eq 3 ] && grep -q 'outside the scene root' err.txt"
check "without --scene-root the same Include loads" \
    "$CAVALRY_BATCH" --dump-scene=root/main.pbrt
done_testing
