# Helpers for the command-line tests: each test script is run as `bash X_test.sh path/to/slc`.
set -u
SLC="$1"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
failures=0
passes=0

pass() { passes=$((passes + 1)); }
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# expect_error NAME PATTERN -- ARGS...: exit status 2, exactly one line on stderr matching PATTERN.
expect_error() {
    local name="$1" pattern="$2"
    shift 3
    "$SLC" "$@" >out.txt 2>err.txt
    local status=$?
    local lines
    lines=$(wc -l <err.txt)
    if [ "$status" -ne 2 ]; then fail "$name: status $status, want 2 ($(cat err.txt))"; return; fi
    if [ "$lines" -ne 1 ]; then fail "$name: $lines lines on stderr, want 1: $(cat err.txt)"; return; fi
    if ! grep -qE -- "$pattern" err.txt; then fail "$name: stderr '$(cat err.txt)' lacks /$pattern/"; return; fi
    pass
}

# expect_ok NAME -- ARGS...: exit status 0.
expect_ok() {
    local name="$1"
    shift 2
    "$SLC" "$@" >out.txt 2>err.txt
    local status=$?
    if [ "$status" -ne 0 ]; then fail "$name: status $status: $(cat err.txt)"; return; fi
    pass
}

# expect_status NAME STATUS -- ARGS...: exit status STATUS and one line on stderr.
expect_status() {
    local name="$1" want="$2"
    shift 3
    "$SLC" "$@" >out.txt 2>err.txt
    local status=$?
    if [ "$status" -ne "$want" ]; then fail "$name: status $status, want $want ($(cat err.txt))"; return; fi
    if [ "$(wc -l <err.txt)" -ne 1 ]; then fail "$name: want one line on stderr: $(cat err.txt)"; return; fi
    pass
}

check() {  # check NAME CONDITION...
    local name="$1"
    shift
    if "$@"; then pass; else fail "$name"; fi
}

finish() {
    echo "$passes passed, $failures failed"
    [ "$failures" -eq 0 ]
}

json() {  # json FILE EXPRESSION: prints a Python expression of the parsed file `s`
    python3 -c "import json, sys; s = json.load(open(sys.argv[1])); print($2)" "$1"
}

square_json() {  # the square [-1, 1]^2, counterclockwise
    echo '{"time": 0, "curves": [{"points": [[-1, -1], [1, -1], [1, 1], [-1, 1]]}]}'
}
