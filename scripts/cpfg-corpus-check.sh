#!/usr/bin/env bash
# Compatibility check against the cpfg corpus (not part of `cargo test`).
#
# Builds lsys in release mode and runs `lsys check` on the main file of every
# model folder in the cpfg corpus (see ../shared/corpus/README.md). A model's
# main file is the last `__`-separated component of its folder name plus `.l`:
#   11-CPFG__01-Introduction__01-quadratic-Koch__fractal/fractal.l
# Each model is checked from inside its own folder (as cpfg runs it), so that
# relative #include lines resolve. Corpus files are only read, never copied.
#
# Usage: scripts/cpfg-corpus-check.sh [--no-build] [CORPUS_DIR]
#   CORPUS_DIR defaults to $(git rev-parse --show-toplevel)/../shared/corpus/cpfg
#   --no-build  use the existing target/release/lsys
# Environment: LSYS_CHECK_TIMEOUT (seconds per model, default 60).
# Exit status: 0 if every model parses, 1 if some fail, 2 on a setup error.

set -u -o pipefail

build=1
corpus=""
for arg in "$@"; do
    case "$arg" in
        --no-build) build=0 ;;
        -h|--help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "unknown option: $arg" >&2; exit 2 ;;
        *) corpus="$arg" ;;
    esac
done

root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel 2>/dev/null) || {
    echo "error: $(dirname "$0") is not inside a git repository" >&2
    exit 2
}
[ -n "$corpus" ] || corpus="$root/../shared/corpus/cpfg"
if [ ! -d "$corpus" ]; then
    echo "error: no corpus at $corpus (pass its path as an argument)" >&2
    exit 2
fi
corpus=$(cd "$corpus" && pwd)

if [ "$build" = 1 ]; then
    (cd "$root" && cargo build --release --quiet) || {
        echo "error: cargo build --release failed" >&2
        exit 2
    }
fi
lsys="$root/target/release/lsys"
if [ ! -x "$lsys" ]; then
    echo "error: $lsys not found" >&2
    exit 2
fi

timeout_s=${LSYS_CHECK_TIMEOUT:-60}
have_timeout=0
command -v timeout >/dev/null 2>&1 && have_timeout=1

# First non-blank line of a diagnostic, without colour codes or indentation.
first_line() {
    sed -e 's/\x1b\[[0-9;]*[A-Za-z]//g' -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' \
        | grep -m1 -v '^$' || true
}

export NO_COLOR=1 CLICOLOR=0 TERM=dumb
total=0
passed=0
for dir in "$corpus"/*/; do
    dir=${dir%/}
    model=$(basename "$dir")
    main="${model##*__}.l"
    total=$((total + 1))
    if [ ! -f "$dir/$main" ]; then
        printf 'FAIL  %s: no main file %s\n' "$model" "$main"
        continue
    fi
    if [ "$have_timeout" = 1 ]; then
        output=$(cd "$dir" && timeout "$timeout_s" "$lsys" check "$main" 2>&1)
    else
        output=$(cd "$dir" && "$lsys" check "$main" 2>&1)
    fi
    status=$?
    if [ "$status" = 0 ]; then
        passed=$((passed + 1))
        printf 'ok    %s\n' "$model"
    else
        if [ "$have_timeout" = 1 ] && [ "$status" = 124 ]; then
            msg="timed out after ${timeout_s}s"
        else
            msg=$(printf '%s\n' "$output" | first_line)
            [ -n "$msg" ] || msg="exit status $status, no message"
        fi
        printf 'FAIL  %s: %s\n' "$model" "$msg"
    fi
done

echo "$passed of $total models parse"
[ "$passed" = "$total" ] && [ "$total" -gt 0 ] && exit 0
exit 1
