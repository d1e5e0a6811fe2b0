# bench/common.sh: what the bench scripts share. Sourced by them after they
# set `here` (their own folder); POSIX sh.

# The script's header comment (after the #! line) as its --help.
bench_usage()
{
    awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$1"
}

# bench_binary SCRIPT GIVEN CANDIDATE...: prints GIVEN, or else the first
# executable candidate; says how to get one and returns 2 if there is none.
bench_binary()
{
    script=$1 given=$2
    shift 2
    if [ -z "$given" ]; then
        for b in "$@"; do
            [ -x "$b" ] && { given=$b; break; }
        done
    fi
    if [ -z "$given" ] || [ ! -x "$given" ]; then
        echo "$script: $(basename "${1:-binary}") not found; build it (make) or pass --binary PATH" >&2
        return 2
    fi
    echo "$given"
}
