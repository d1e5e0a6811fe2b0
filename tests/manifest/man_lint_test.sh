#!/bin/sh
# man_lint_test.sh: cavalry-manifest(5) is clean under mandoc -Tlint and
# documents every key the reader accepts.
. "${CAVALRY_DATA_DIR:?}/tests/setup.sh"
page="$CAVALRY_DATA_DIR/man/cavalry-manifest.5"
command -v mandoc >/dev/null 2>&1 || skip_all "mandoc not installed"
# "referenced manual not found" only says that cavalry-batch(1) is not
# installed on this machine yet; every other message counts.
out=$(mandoc -Tlint "$page" 2>&1 | grep -v 'STYLE: referenced manual not found: Xr cavalry-' || true)
if [ -z "$out" ]; then
    ok "mandoc -Tlint is clean"
else
    not_ok "mandoc -Tlint is clean"
    printf '%s\n' "$out" | sed 's/^/# /'
fi
text=$(mandoc -Tascii "$page" | col -b)
for key in version defaults jobs name scene output formats resolution spp time_limit \
    integrator max_depth seed color config display view look exposure aovs exr half \
    compression png bits camera fov lookat rlpath grid directions mix; do
    if printf '%s\n' "$text" | grep -q -w -- "$key"; then
        ok "documents $key"
    else
        not_ok "documents $key"
    fi
done
done_testing
