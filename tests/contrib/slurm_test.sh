#!/bin/sh
# slurm_test.sh: contrib/slurm/cavalry.sbatch on a real single-node Slurm.
# Starts munged, slurmctld and slurmd on 127.0.0.1 with a private
# configuration, key, sockets and state under the test's temp folder, submits
# a 3-task array over a 5-job manifest and checks that the tasks together
# render every job exactly once. Skips when Slurm is not installed. Without
# munged, or with CV_SLURM_AUTH=none, it uses Slurm's auth/none instead.
. "${srcdir:-.}/tests/setup.sh"
for p in slurmctld slurmd sbatch squeue scancel sinfo; do
    command -v "$p" >/dev/null 2>&1 || skip_all "Slurm is not installed ($p not found)"
done
"$CAVALRY_BATCH" --list-gpus >/dev/null 2>&1 || skip_all "no GPU context"
script="${srcdir:-.}/contrib/slurm/cavalry.sbatch"
script=$(cd "$(dirname "$script")" && pwd)/$(basename "$script")

# Two TCP ports nobody listens on, from /proc/net/tcp{,6} (state 0A: LISTEN).
listening=$(cat /proc/net/tcp /proc/net/tcp6 2>/dev/null |
    awk '$4 == "0A" { split($2, a, ":"); print a[2] }')
free_port() {
    p=$1
    while [ "$p" -lt 65000 ]; do
        h=$(printf '%04X' "$p")
        case " $(echo $listening) " in *" $h "*) ;; *) echo "$p"; return ;; esac
        p=$((p + 1))
    done
    return 1
}
base=$((20000 + $$ % 20000))
ctld_port=$(free_port "$base")
slurmd_port=$(free_port $((ctld_port + 1)))

# Run inside a Slurm job or with sbatch defaults set, the test's own sbatch
# would inherit them.
for v in $(env | sed -n 's/^\(S\(LURM\|BATCH\)_[A-Za-z0-9_]*\)=.*/\1/p'); do unset "$v"; done
s="$tmp/slurm"
mkdir -p "$s/state" "$s/spool"
user=$(id -un)
auth=${CV_SLURM_AUTH:-munge}
command -v munged >/dev/null 2>&1 || auth=none
if [ "$auth" = munge ]; then
    auth_conf="AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$s/munge.sock"
else
    auth_conf="AuthType=auth/none
CredType=cred/none"
fi
host=$(uname -n | cut -d. -f1)
export SLURM_CONF="$s/slurm.conf"
cat >"$SLURM_CONF" <<CONF
ClusterName=cavalrytest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
$auth_conf
SlurmUser=$user
SlurmdUser=$user
StateSaveLocation=$s/state
SlurmdSpoolDir=$s/spool
SlurmctldPidFile=$s/slurmctld.pid
SlurmdPidFile=$s/slurmd.pid
SlurmctldLogFile=$s/slurmctld.log
SlurmdLogFile=$s/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
GresTypes=gpu
SlurmdParameters=config_overrides
ReturnToService=2
KillWait=5
MailProg=/bin/true
NodeName=cv0 NodeHostname=$host NodeAddr=127.0.0.1 CPUs=3 RealMemory=1000 Gres=gpu:3 State=UNKNOWN
PartitionName=cv Nodes=cv0 Default=YES MaxTime=12 State=UP
CONF
# Three pretend GPUs: Slurm drops GPUs without a device file, and with no
# device cgroups (task/none) any character device will do. Slurm still hands
# each task one of them in CUDA_VISIBLE_DEVICES, as on a GPU node.
printf 'Name=gpu File=%s\n' /dev/null /dev/zero /dev/full >"$s/gres.conf"

# The daemons run in the foreground under timeout, so they stop by themselves
# even if this shell is killed; the trap stops them first.
ctld_pid= slurmd_pid= munged_pid=
stop_slurm() {
    [ -z "$ctld_pid" ] || scancel --quiet --user="$user" 2>/dev/null || :
    for pid in $slurmd_pid $ctld_pid $munged_pid; do kill "$pid" 2>/dev/null || :; done
    for pid in $slurmd_pid $ctld_pid $munged_pid; do wait "$pid" 2>/dev/null || :; done
    ctld_pid= slurmd_pid= munged_pid=
}
trap 'stop_slurm; cleanup' EXIT
trap 'exit 1' INT TERM HUP
if [ "$auth" = munge ]; then
    # A private key and socket; -f lets munged use a socket folder that
    # only its owner may enter.
    dd if=/dev/urandom of="$s/munge.key" bs=1024 count=1 2>/dev/null
    chmod 400 "$s/munge.key"
    timeout 900 munged -F -f --socket="$s/munge.sock" --key-file="$s/munge.key" \
        --pid-file="$s/munged.pid" --seed-file="$s/munged.seed" \
        --log-file="$s/munged.log" >"$s/munged.out" 2>&1 &
    munged_pid=$!
    i=0
    while [ ! -S "$s/munge.sock" ] && [ "$i" -lt 30 ]; do sleep 1; i=$((i + 1)); done
fi
timeout 900 slurmctld -D -c -f "$SLURM_CONF" >"$s/slurmctld.out" 2>&1 &
ctld_pid=$!
timeout 900 slurmd -D -N cv0 -f "$SLURM_CONF" >"$s/slurmd.out" 2>&1 &
slurmd_pid=$!

# Bounded wait for the node to register and go idle.
state=
i=0
while [ "$i" -lt 60 ]; do
    state=$(sinfo -h -n cv0 -o %T 2>/dev/null || :)
    [ "$state" = idle ] && break
    sleep 1
    i=$((i + 1))
done
check "single-node Slurm with auth/$auth comes up (node $state)" test "$state" = idle
if [ "$state" != idle ]; then
    for f in "$s"/*.log "$s"/*.out; do sed 's/^/# /' "$f"; done
    done_testing
    exit 1
fi

data="$CV_TEST_DATA/batch"
cp "$data/tiny.pbrt" "$data/five.yaml" "$tmp/"
cd "$tmp"
"$CAVALRY_BATCH" --dry-run five.yaml | cut -d: -f1 | sort >all.txt
check "the manifest has 5 jobs" test "$(wc -l <all.txt)" -eq 5

# The bound leaves room for three tasks compiling the GPU programs at once
# on a loaded llvmpipe machine when the program cache is still cold.
check_out "a 3-task array runs to the end" submit.txt timeout 600 \
    sbatch --wait --array=0-2 --output="$tmp/task-%a.log" "$script" --progress=json five.yaml
for t in 0 1 2; do
    check "task $t logged" test -s "task-$t.log"
    check "task $t rendered at least one job" grep -q '"event":"job_finished"' "task-$t.log"
    check "task $t was given one GPU" grep -Eq '^cavalry.sbatch: .* GPU [0-9]+$' "task-$t.log"
done
cat task-*.log | sed -n 's/.*"event":"job_finished".*"job":"\([^"]*\)".*/\1/p' | sort >rendered.txt
check "every job rendered exactly once" cmp -s all.txt rendered.txt
for j in $(cat all.txt); do
    check "$j written" test -s "out/$j.png"
done
check "no temporary files left" test -z "$(find out -name '.*.tmp')"
[ "$tap_failed" -eq 0 ] || for f in "$s"/*.log task-*.log; do sed 's/^/# /' "$f"; done
done_testing
