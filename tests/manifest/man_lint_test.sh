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
# The keys come from the reader's own table (cavalry-batch --list-keys):
# each has an .It entry (a nested key after its section's), each name of an
# enum or list appears, and an integer range is the page's range.
line_of() { grep -n -E "^\.It Cm $1( |\$)" "$page" | head -n 1 | cut -d: -f1; }
# the first entry of $1 after line $2: a leaf such as "scale" may be a key
# of several sections
line_after() { grep -n -E "^\.It Cm $1( |\$)" "$page" | cut -d: -f1 | awk -v from="$2" '$1 > from { print; exit }'; }
"$CAVALRY_BATCH" --list-keys >"$tmp/keys"
n_keys=$(wc -l <"$tmp/keys")
check "--list-keys lists the keys ($n_keys)" test "$n_keys" -gt 20
for key in version defaults jobs; do
    check "documents $key" test -n "$(line_of "$key")"
done
tab=$(printf '\t')
while IFS="$tab" read -r key type default help; do
    leaf=${key##*.}
    at=$(line_of "$leaf")
    if [ "$leaf" != "$key" ]; then
        section=$(line_of "${key%.*}")
        at=$(line_after "$leaf" "${section:-0}")
        check "documents $key" test -n "$at" -a -n "$section" -a "${at:-0}" -gt "${section:-0}"
    else
        check "documents $key" test -n "$at"
    fi
    case $type in
    integer\ *..*)
        range=${type#integer }
        item=$(sed -n "${at:-1}p" "$page")
        case $item in
        *integer*)
            if printf '%s\n' "$item" | grep -q -F -- "${range%%..*} to ${range##*..}"; then
                ok "$key: range ${range%%..*} to ${range##*..} as in the table"
            else
                not_ok "$key: range ${range%%..*} to ${range##*..} as in the table (page: $item)"
            fi
            ;;
        esac
        ;;
    *\|*)
        for name in $(printf '%s\n' "${type#list of }" | tr '|' ' '); do
            check "$key: documents $name" grep -q -E "Cm $name( |\$)" "$page"
        done
        ;;
    esac
done <"$tmp/keys"
done_testing
