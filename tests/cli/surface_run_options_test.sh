# slc run on surfaces (DESIGN §8), its options: interruption, the view of the pictures,
# --estimate, laws as expressions, a named problem at the run's K and eps, the volume drift
# allowed, and errors. The exact laws are in surface_run_test.sh.
source "$(dirname "$0")/lib.sh" "$1"

# A sphere of radius 0.6 about (0.03, -0.02, 0.01), as slc contours it.
expect_ok "a sphere to move" -- contour --function sphere -K 4 --refine 100 --eps 1e-3 --out ball
cp ball/final.obj ball.obj

# SIGTERM between steps: the run ends after its current step, writes its results whole with
# status interrupted and exits 143 (0 had it finished first).
"$SLC" run --problem sphere-curvature --out stopped --quiet 2>err.txt &
pid=$!
sleep 4
kill -TERM "$pid"
wait "$pid"
status=$?
check "SIGTERM: exit status 143 (0 had it finished)" test "$status" -eq 143 -o "$status" -eq 0
check "SIGTERM: status interrupted (or ok)" grep -qE '"status": "(interrupted|ok)"' stopped/summary.json
check "SIGTERM: the surface reached is written" test -s stopped/final.obj -a -s stopped/history.csv
check "SIGTERM: one line on stderr" test "$(wc -l <err.txt)" -le 1

# The view of the pictures: another direction draws another picture.
expect_ok "a view from below" -- run --initial ball.obj --velocity unit-normal --t-end 0.01 -N 1 -K 3 --view 0,-60 --out below --quiet
expect_ok "the default view" -- run --initial ball.obj --velocity unit-normal --t-end 0.01 -N 1 -K 3 --out above --quiet
check "the pictures differ" test "$(cmp -s below/final.png above/final.png && echo same)" != same
check "the surfaces do not" cmp -s below/final.obj above/final.obj

# --estimate: the run again at half resolution (N 2, K 3, 4 eps) and the distance between the
# two. -K 4 sets eps to 1e-3 4^(5-4) = 4e-3 times the half-width 0.6. The exact error (vertices
# and centroids against the sphere of radius 0.65) measured 1.7e-3, the estimate 5.1e-3: about
# three times it, as second order makes it.
expect_ok "--estimate" -- run --initial ball.obj --velocity unit-normal --t-end 0.05 -N 4 -K 4 --estimate --out est --quiet
sphere_error() {  # sphere_error OBJ: the largest |distance to the sphere of radius 0.65| over vertices and centroids
    python3 - "$1" <<'PY'
import math, sys
v, worst = [], 0.0
def off(p): return abs(math.dist(p, (0.03, -0.02, 0.01)) - 0.65)
for line in open(sys.argv[1]):
    w = line.split()
    if w and w[0] == "v":
        v.append(tuple(map(float, w[1:4])))
        worst = max(worst, off(v[-1]))
    elif w and w[0] == "f":
        a, b, c = (v[int(x.split("/")[0]) - 1] for x in w[1:4])
        worst = max(worst, off(tuple((a[i] + b[i] + c[i]) / 3 for i in range(3))))
print(worst)
PY
}
e=$(sphere_error est/final.obj)
check "estimate: the coarse run named" test "$(json est/summary.json 's["error_estimate"]["coarse"]')" = "N 2, K 3, eps 0.0096"
check "estimate: between the error and ten times it" test "$(json est/summary.json "$e <= s['error_estimate']['estimate'] <= 10 * $e")" = True
expect_error "--estimate with one step" "--estimate compares with the run at half resolution, which needs N >= 2" -- run --initial ball.obj --velocity unit-normal --t-end 0.05 -N 1 --estimate --out x

# Laws as expressions: the same surfaces as the built-in laws they spell.
expect_ok "--speed 1" -- run --initial ball.obj --speed 1 --t-end 0.01 -N 1 -K 3 --out speed1 --quiet
check "--speed 1 moves as unit-normal" cmp -s speed1/final.obj above/final.obj
check "the law is named in the summary" test "$(json speed1/summary.json 's["velocity"]')" = "speed = 1"
expect_ok "--speed C" -- run --initial ball.obj --speed C --t-end 0.005 -N 1 -K 3 --out speedC --quiet
expect_ok "--velocity curvature" -- run --initial ball.obj --velocity curvature --t-end 0.005 -N 1 -K 3 --out curv1 --quiet
check "--speed C moves as curvature" cmp -s speedC/final.obj curv1/final.obj
expect_ok "--field -y,x,0" -- run --initial ball.obj --field "-y, x, 0" --t-end 0.1 -N 1 -K 3 --out field --quiet
expect_ok "--velocity rotation" -- run --initial ball.obj --velocity rotation --t-end 0.1 -N 1 -K 3 --out rot1 --quiet
check "--field -y,x,0 moves as rotation" cmp -s field/final.obj rot1/final.obj
expect_error "a field of two values" "field expression '-y, x': gives 2 values; a flow field needs three, u, v and w" -- run --initial ball.obj --field "-y, x" --t-end 1 --out x
expect_error "two laws" "give one velocity law of --velocity, --speed, --field and --field-file, got --velocity and --speed" -- run --initial ball.obj --velocity curvature --speed 1 --t-end 1 --out x
expect_error "a view of one number" "--view must be two finite numbers AZ,EL in degrees, got '30'" -- run --initial ball.obj --velocity curvature --t-end 1 --view 30 --out x
expect_error "a view for curves" "--view is for surfaces, not curves" -- run --problem vortex --view 30,20 --out x
expect_error "thin cells beyond their range" "--thin-depth: must be an integer from 0 to 8, got '9'" -- run --problem vortex --thin-depth 9 --out x

# Errors.
expect_error "unknown law" "unknown velocity 'spin' for a surface; known: rotation" -- run --initial ball.obj --velocity spin --t-end 1 --out x
touch f.csv
expect_error "a lattice field of curves" "--field-file for a surface takes an OpenVDB vector grid \(.vdb\), got 'f.csv'" -- run --initial ball.obj --field-file f.csv --t-end 1 --out x
expect_error "no law" "--initial with a surface needs --velocity NAME, --speed, --field or --field-file" -- run --initial ball.obj --t-end 1 --out x
expect_error "no end" "--initial needs --t-end" -- run --initial ball.obj --velocity curvature --out x
expect_error "unknown parameter" "problem 'sphere-rotation' has no parameter 'x'; it takes none" -- run --problem sphere-rotation --param x=1 --out x
expect_error "missing parameter" "velocity 'translation' needs parameter uz" -- run --initial ball.obj --velocity translation --param ux=1 --param uy=0 --t-end 1 --out x
# A named problem keeps its fixed domain: leaving it is an error.
expect_status "carried out of the domain" 3 -- run --problem merging-spheres --t-end 3 -N 2 -K 3 --out away3
check "names the boundary" grep -q "domain boundary" err.txt
check "summary records the error" test "$(json away3/summary.json 's["status"]')" = error
# -K and --eps given: the problem's surface is contoured at them too (its own K 5, eps 1e-4 make
# about 28,000 triangles; K 4, eps 2e-3 about 2,000).
expect_ok "a named problem at the run's K and eps" -- run --problem sphere-rotation -N 1 --t-end 0.1 \
    -K 4 --eps 2e-3 --quiet --out coarse
check "its initial surface at K 4, eps 2e-3" test "$(grep -c '^f ' coarse/initial.obj)" -lt 5000
# A rotation keeps the volume: linear contours at K = 3 lose 1% of it by t = 3.9 of 6, where the
# run ends unstable at the default drift of 1%; with --volume-drift 0.05 it finishes and reports
# the drift.
expect_status "volume drifted" 3 -- run --initial ball.obj --velocity rotation --t-end 6 -N 40 -K 3 -P 0 --out drift --quiet
check "names the drift and the option" grep -q "volume drifted by -1.0.%.*(--volume-drift)" err.txt
check "status unstable" test "$(json drift/summary.json 's["status"]')" = unstable
# A flow field's step traces its feet to eps/10 whatever its length, so each step adds its
# contour's error: the run asks for fewer steps, and in 10 it keeps the volume (measured: -0.09%).
check "asks for fewer steps" grep -q "take fewer steps (-N" err.txt
expect_ok "fewer steps" -- run --initial ball.obj --velocity rotation --t-end 6 -N 10 -K 3 -P 0 --out drift10 --quiet
check "fewer steps: ok within 0.5%" test "$(json drift10/summary.json 's["status"] == "ok" and abs(s["volume_change"]) < 0.005')" = True
expect_ok "more drift allowed" -- run --initial ball.obj --velocity rotation --t-end 6 -N 40 -K 3 -P 0 --volume-drift 0.05 --out drift5 --quiet
check "ok, the drift reported" test "$(json drift5/summary.json 's["status"] == "ok" and -0.05 < s["volume_change"] < -0.01')" = True
check "the allowance recorded" test "$(json drift5/summary.json 's["params"]["volume_drift"]')" = 0.05
# Without guards the run goes on to the end and says where it broke its law; its steps were
# kept whole, as the run above kept them, so the surface is the same.
check "the run above split no step" test "$(json drift5/summary.json 's["split_steps"]')" = 0
expect_ok "no guards" -- run --initial ball.obj --velocity rotation --t-end 6 -N 40 -K 3 -P 0 --no-guards --out unguarded --quiet
check "status broken at t = 6" test "$(json unguarded/summary.json 's["status"] == "broken" and s["t"] == 6 and s["params"]["guards"] is False')" = True
check "the first break in its message" grep -q '"message": "at t = 3.9: the volume drifted by -1.0' unguarded/summary.json
check "a warning names it" grep -q "^slc: warning: --no-guards: at t = 3.9: the volume drifted" err.txt
check "the same surface as the guarded run's" cmp -s unguarded/final.obj drift5/final.obj
# A surface smaller than the contours see: named, not a run of nothing.
expect_error "too small to see" "the surface, 1.2 across, is too small for the contours to see: the finest cell at K = 3 in the domain 2e\+03 wide is 250; raise K \(-K\) or give a smaller domain" -- run --initial ball.obj --velocity rotation --t-end 1 --box -700,-700,-700,1300,1300,1300 -K 3 --out x
expect_error "drift for curves" "--volume-drift is for surfaces, not curves" -- run --problem vortex --volume-drift 0.1 --out x
expect_error "drift not positive" "--volume-drift: must be a positive finite number, got '0'" -- run --problem enright --volume-drift 0 --out x
# A part thinner than the cells, torn by the contours, is noted: the torus of tube radius 0.2
# shrunk at unit speed to 0.04 in one step at K = 4 (cells 0.14) with no thin cells ends in
# pieces (measured: 4, 0.055 thick, 29% of the volume lost), with a note naming thin_split; at
# the default --thin-depth, 2, it stays one torus (1.7% below the exact volume).
expect_ok "a torus" -- contour --function torus -K 4 --eps 1e-3 --out tor
cp tor/final.obj tor.obj
expect_ok "the torus shrunk to a thin tube" -- run --initial tor.obj --velocity unit-normal \
    --param speed=-1 --t-end 0.16 -N 1 -K 4 --eps 2e-3 --thin-depth 0 --out thin --quiet
check "thin tube: pieces, thin_split beside the cell" python3 -c "
import json, sys
s = json.load(open('thin/summary.json'))
t = s['thin_split']
sys.exit(not (s['status'] == 'ok' and s['components'] > 1 and t['at_t'] == 0.16 and
              t['thickness'] < t['cell'] and 'thin_split' in s['note']))"
check "thin tube: the note on stderr" grep -q "slc: note: .*split off a part .* thick near (" err.txt
expect_ok "the torus shrunk with thin cells" -- run --initial tor.obj --velocity unit-normal \
    --param speed=-1 --t-end 0.16 -N 1 -K 4 --eps 2e-3 --out thick --quiet
check "thin cells: one torus, no thin_split" python3 -c "
import json, sys
s = json.load(open('thick/summary.json'))
sys.exit(not (s['components'] == 1 and s['genus'] == 1 and 'thin_split' not in s))"
finish
