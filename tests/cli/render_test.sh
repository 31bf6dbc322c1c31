# slc render and slc tree: the pictures and summary are written, and bad input is refused.
source "$(dirname "$0")/lib.sh" "$1"

square_json >square.json
echo '{"curves": [{"points": [[0, 0], [2, 0], [2, 2], [0, 2]]}]}' >shifted.json
expect_ok "render svg" -- render square.json shifted.json --out both.svg --title "two squares"
check "svg written" test -s both.svg
check "svg is an SVG document" grep -q "<svg" both.svg
expect_ok "render png" -- render square.json --out one.png
check "png signature" bash -c "head -c 8 one.png | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a'"
expect_error "bad extension" "extension|\.pdf" -- render square.json --out one.pdf
expect_error "missing input" "missing.json" -- render missing.json --out x.svg

expect_ok "tree of a built-in shape" -- tree --shape propeller --tree-depth 5 --out demo
for f in summary.json interface.json tree.svg tree.png distance.png extension.png whitney.png; do
    check "tree writes $f" test -s "demo/$f"
done
check "summary: exact against brute force" grep -q '"max_abs_difference": 0.0' demo/summary.json
expect_error "unknown shape" "unknown shape" -- tree --shape hexagon --out x
expect_error "no input" "--initial|--shape" -- tree --out x
finish
