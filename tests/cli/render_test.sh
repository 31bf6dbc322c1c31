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

# Panels: each file in its own; the frames of two runs overlaid at chosen times.
expect_ok "panels of files" -- render square.json shifted.json --columns 2 --out panels.png
check "panels: one picture twice as wide as tall" python3 -c "
import struct
w, h = struct.unpack('>II', open('panels.png', 'rb').read()[16:24])
assert 1.8 < w / h < 2.4, (w, h)"
expect_ok "frames of a run" -- run --problem triangle-normal -N 4 -K 4 -P 0 --frames 4 --out tri --quiet
expect_ok "frames of another" -- run --problem triangle-normal -N 8 -K 4 -P 0 --frames 8 --out tri8 --quiet
expect_ok "panels of two runs at times" -- render --frames tri tri8/ --columns 3 --times 0,0.2,0.4 --out times.svg
check "three panels in a row" python3 -c "
import re
w, h = (float(v) for v in re.search(r'<svg[^>]*width=\"([0-9.]+)[a-z]*\"[^>]*height=\"([0-9.]+)', open('times.svg').read()).groups())
assert 2.5 < w / h < 4.2, (w, h)"
expect_ok "a panel a run" -- render --frames tri tri8 --by-run --columns 2 --out byrun.png
check "two panels side by side" python3 -c "
import struct
w, h = struct.unpack('>II', open('byrun.png', 'rb').read()[16:24])
assert 1.8 < w / h < 2.4, (w, h)"
expect_error "a panel a run without columns" "--by-run" -- render --frames tri --by-run --out x.png
expect_error "times without panels" "--times" -- render --frames tri --times 0.2 --out x.svg
expect_error "an animation of two runs" "one run" -- render --frames tri tri8 --out x.svg
expect_error "zero columns" "columns" -- render square.json --columns 0 --out x.png

expect_ok "tree of a built-in shape" -- tree --shape propeller --tree-depth 5 --out demo
for f in summary.json interface.json tree.svg tree.png velocity.png distance.png extension.png whitney.png panels.png; do
    check "tree writes $f" test -s "demo/$f"
done
check "summary: exact against brute force" grep -q '"max_abs_difference": 0.0' demo/summary.json
expect_error "unknown shape" "unknown shape" -- tree --shape hexagon --out x
expect_error "no input" "--initial|--shape" -- tree --out x
finish
