#!/bin/sh
# k8s_test.sh: contrib/k8s/cavalry-job.yaml is a valid Indexed Job for
# Cavalry, checked offline by k8s_check.py against the Job API's types from
# the Kubernetes Python client (kubectl cannot validate without an API
# server); the checker rejects broken variants; and pods run with the Job's
# arguments and JOB_COMPLETION_INDEX = 0..completions-1 cover a manifest's jobs
# exactly once. Skips without Python's kubernetes and yaml modules.
. "${srcdir:-.}/tests/setup.sh"
here=$(cd "${srcdir:-.}" && pwd)
job="$here/contrib/k8s/cavalry-job.yaml"
checker="$here/tests/contrib/k8s_check.py"
# Debian's python3-kubernetes is for the system Python, which may not be the
# first python3 on PATH.
py=
for p in python3 /usr/bin/python3; do
    if "$p" -c 'import kubernetes, yaml' >/dev/null 2>&1; then py=$p; break; fi
done
[ -n "$py" ] || skip_all "no python3 with the kubernetes and yaml modules (Debian: python3-kubernetes)"
cd "$tmp"

check "the shipped Job is valid" "$py" "$checker" "$job"
# Each variant breaks one rule; the checker must name it.
reject() {
    d=$1; want=$2; shift 2
    sed "$@" "$job" >broken.yaml
    if "$py" "$checker" broken.yaml 2>broken.err; then
        not_ok "rejects $d"
    else
        check "rejects $d" grep -q "$want" broken.err
    fi
}
reject "a misspelt field" "no such field" -e 's/completionMode:/completionsMode:/'
reject "a value of the wrong type" "wants int" -e 's/parallelism: 4/parallelism: four/'
reject "a container without a name" "must not be .None." -e 's/- name: cavalry$/- imagePullPolicy: Always/'
reject "a Job that is not Indexed" "wants Indexed" -e 's/completionMode: Indexed/completionMode: NonIndexed/'
reject "a shard count unlike completions" "wants --shard-count=3" -e 's/completions: 4/completions: 3/'
reject "a pod without a GPU" "nvidia.com/gpu" -e '/nvidia.com\/gpu/d'
reject "a pod with two GPUs" "nvidia.com/gpu" -e 's/nvidia.com\/gpu: 1/nvidia.com\/gpu: 2/'
reject "restartPolicy Always" "restartPolicy" -e 's/restartPolicy: Never/restartPolicy: Always/'
reject "a mount of no volume" "names no volume" -e '0,/- name: farm$/s//- name: other/'
reject "no graphics driver capability" "graphics" -e 's/compute,utility,graphics/compute,utility/'

# The pods' command lines, with the Job's manifest replaced by a local one.
"$py" "$checker" "$job" --print-args >args.txt
count=$(sed -n 's/^--shard-count=//p' args.txt)
sed '$d' args.txt >opts.txt
cp "$CV_TEST_DATA/batch/tiny.pbrt" "$CV_TEST_DATA/batch/five.yaml" .
"$CAVALRY_BATCH" --dry-run five.yaml | cut -d: -f1 | sort >all.txt
: >union.txt
i=0
while [ "$i" -lt "$count" ]; do
    # shellcheck disable=SC2046 # one argument a line, none with spaces
    JOB_COMPLETION_INDEX=$i "$CAVALRY_BATCH" --dry-run $(cat opts.txt) five.yaml | cut -d: -f1 >>union.txt
    i=$((i + 1))
done
sort union.txt >union.sorted
check "$count pods cover every job exactly once" cmp -s all.txt union.sorted
done_testing
