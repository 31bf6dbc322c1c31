# slc run on surfaces of one's own at the default settings (docs/defaults.md: 20 steps, K = 5,
# eps 1e-3 l, refinement until converged) against exact offsets, convex and with saddles.
source "$(dirname "$0")/lib.sh" "$1"

# A sphere of radius 0.6 about (0.03, -0.02, 0.01), as slc contours it.
expect_ok "a sphere to move" -- contour --function sphere -K 4 --refine 100 --eps 1e-3 --out ball
cp ball/final.obj ball.obj

# Unit normal speed: the sphere of radius 0.6 + t (defaults: 20 steps, K = 5, eps 1e-3 l).
expect_ok "unit normal speed" -- run --initial ball.obj --velocity unit-normal --t-end 0.1 --out grow --quiet
check "status ok" test "$(json grow/summary.json 's["status"]')" = ok
check "radius 0.7: volume within 0.5%" test "$(json grow/summary.json 'abs(s["volume"] / (4 / 3 * 3.141592653589793 * 0.7**3) - 1) < 5e-3')" = True
check "final.obj, .vtp, .png, history" test -s grow/final.obj -a -s grow/final.vtp -a -s grow/final.png -a -s grow/history.png
check "history has the start and 20 steps" test "$(wc -l <grow/history.csv)" = 22
printf 'x,y,z\n0.73,-0.02,0.01\n0.03,-0.02,0.01\n' >points.csv
expect_ok "final.obj reads back" -- distance --initial grow/final.obj --points points.csv --domain 1.5
check "on the sphere of radius 0.7" test "$(sed -n 2p out.txt | cut -d, -f4 | python3 -c 'print(abs(float(input())) < 2e-3)')" = True

# A torus of one's own at the defaults under unit normal speed: the offset torus of tube radius
# 0.2 + t, saddles included (measured: vertices within 9.5e-5 of it at t = 0.05, eps 7.5e-4).
expect_ok "a torus to grow" -- contour --function torus -K 4 --eps 1e-3 --out tor
cp tor/final.obj tor.obj
expect_ok "the torus grown at the defaults" -- run --initial tor.obj --velocity unit-normal --t-end 0.05 --out torgrow --quiet
check "ok, genus 1, one component" test "$(json torgrow/summary.json 's["status"], s["genus"], s["components"]')" = "ok 1 1"
check "vertices within 3e-4 of the offset torus" test "$(python3 -c '
import math
v = [list(map(float, l.split()[1:4])) for l in open("torgrow/final.obj") if l.startswith("v ")]
print(max(abs(math.hypot(math.hypot(x, y) - 0.55, z) - 0.25) for x, y, z in v) < 3e-4)')" = True
finish
