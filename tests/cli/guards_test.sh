# The run's physical guards (docs/errors.md, "What the guards catch"): a run whose numerics break
# what its law keeps ends unstable with exit 3 and one line, or is rescued by sub-steps, instead of
# ending "ok" (or "vanished") with a physically impossible result.
source "$(dirname "$0")/lib.sh" "$1"

awk 'BEGIN { printf "{\"curves\": [{\"points\": ["; for (i = 0; i < 32; i++)
    printf "%s[%.17g, %.17g]", (i ? ", " : ""), cos(2 * 3.141592653589793 * i / 32), sin(2 * 3.141592653589793 * i / 32)
    print "]}]}" }' >c.json
awk 'BEGIN { printf "{\"curves\": [{\"points\": ["; for (i = 0; i < 64; i++)
    printf "%s[%.17g, %.17g]", (i ? ", " : ""), cos(2 * 3.141592653589793 * i / 64), sin(2 * 3.141592653589793 * i / 64)
    printf "]}, {\"points\": ["; for (i = 0; i < 16; i++)
    printf "%s[%.17g, %.17g]", (i ? ", " : ""), 3 + 0.002 * cos(2 * 3.141592653589793 * i / 16), 0.002 * sin(2 * 3.141592653589793 * i / 16)
    print "]}]}" }' >two.json
value() { sed -n "s/.*\"$2\": \\([-0-9.e+]*\\).*/\\1/p" "$1/summary.json" | head -1; }
within() { awk -v a="$1" -v b="$2" -v tol="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && d <= tol * (b < 0 ? -b : b)) }'; }
one_line() { test "$(wc -l <err.txt)" -eq 1; }

# A growing curve cannot vanish: 4 steps of speed 20 are split into sub-steps, and the area is
# the exact pi (1 + 20)^2 to 1e-4.
expect_ok "growing at speed 20 in 4 steps" -- run --initial c.json --velocity unit-normal --param speed=20 \
    --t-end 1 --steps 4 --out grow --quiet
check "growing: ok" grep -q '"status": "ok"' grow/summary.json
check "growing: steps split" grep -q '"split_steps"' grow/summary.json
check "growing: area pi 21^2" within "$(value grow area)" 1385.4423602330987 1e-4
# A rigid rotation by 10 radians in 4 steps (it vanished before the guards): the area of the
# circle read as arcs, pi, is kept to 2% (measured 7e-6).
expect_ok "rotation omega 10 in 4 steps" -- run --initial c.json --velocity rotation --param omega=10 \
    --t-end 1 --steps 4 --out spin --quiet
check "rotation: area kept" within "$(value spin area)" 3.141592653589793 2e-2
check "rotation: one curve" grep -q '"components": 1' spin/summary.json
# Zalesak's disk in 10 steps lost 85% of its area with status ok; now the steps are split and the
# area stays within 5%.
expect_ok "zalesak in 10 steps" -- run --problem zalesak -N 10 --out z10 --quiet
check "zalesak: area within 5%" within "$(value z10 area)" 0.05824 0.05
# What sub-steps cannot rescue ends unstable, exit 3, one line naming what broke and what to raise.
expect_status "vortex in 4 steps" 3 -- run --problem vortex --steps 4 --out v4 --quiet
check "vortex: unstable" grep -q '"status": "unstable"' v4/summary.json
check "vortex: one line naming the split and N" sh -c 'one_line() { test "$(wc -l <err.txt)" -eq 1; }; one_line && grep -q "number of curves rose.*also in 256 sub-steps: raise the steps N" err.txt'
# Stepped directly, the vortex's feet are traced to eps/10 at any step, so each step adds its
# contour's error: the same break asks for fewer steps, and one step from t = 0 to T keeps it.
expect_status "vortex stepped directly in 4 steps at K 4" 3 -- run --problem vortex --steps 4 --extension direct -K 4 -P 0 --out vd4 --quiet
check "vortex stepped directly: asks for fewer steps" grep -q "also in 256 sub-steps: raise the depth K, or take fewer steps N" err.txt
expect_ok "vortex stepped directly in 1 step at K 4" -- run --problem vortex --steps 1 --extension direct -K 4 -P 0 --out vd1 --quiet
check "vortex in 1 step: one curve" grep -q '"components": 1' vd1/summary.json
# A speck of radius 0.0034 in the vortex at the defaults (10 steps of 0.8): a step carries it clear
# of its small domain. Its images traced forward at t + k say so, and the domain grows for the step;
# its forward Euler images stayed inside, and the empty contour read as the speck vanishing until
# the step was split in two.
python3 -c 'import json, math
c = [[0.7625 + 0.0034 * math.cos(2 * math.pi * i / 128), 0.6143 + 0.0034 * math.sin(2 * math.pi * i / 128)] for i in range(128)]
print(json.dumps({"curves": [{"points": c}]}))' >speck.json
expect_ok "a speck carried out of its domain in a step" -- run --initial speck.json --velocity vortex --t-end 8 --out speck --quiet
check "speck: the domain grew, no sub-steps, the area kept" test "$(json speck/summary.json 's["status"], "substeps" in s, s["domain_grown"]["doublings"] >= 1, abs(s["area"] / (3.141592653589793 * 0.0034 ** 2) - 1) < 1e-3')" = "ok False True True"
# Two turns of the propeller in one step: the step fails whole and in halves, and goes on in the
# 64ths that keep the law (measured: 63 sub-steps, the area -0.26%, E_inf 0.17, as at N = 64).
expect_ok "propeller in 1 step" -- run --problem propeller-rotation -N 1 --out p1 --quiet
check "propeller in 1 step: split, most sub-steps at least 32" python3 -c "
import json, sys; s = json.load(open('p1/summary.json'))['substeps']; sys.exit(not s['most'] >= 32)"
check "propeller in 1 step: area within 1%" within "$(value p1 area)" 3.534203027957245 1e-2
# Zalesak's disk in one step at K = 4 tears its slot even in 256 sub-steps: a rigid motion,
# named.
expect_status "zalesak in 1 step at K 4" 3 -- run --problem zalesak -N 1 -K 4 --out z1 --quiet
check "zalesak in 1 step: the rigid motion named" grep -q "a rigid motion changed the number of curves" err.txt
# Curvature flow of the paper's circle at K = 7 with the paper's embedded module: it ended ok
# with an error of 0.94; its area cannot fall at 2 pi, and it says so.
expect_status "circle-curvature -K 7" 3 -- run --problem circle-curvature -K 7 --out cc7 --quiet
check "curvature: the area rate named" grep -qE "where the law changes it by|more than the law's rate gives" err.txt
# Nothing moves under zero speed: a circle of radius 0.002 beside cells of 0.19 at K = 5 is kept
# by the default thin cells (6 levels, 0.003); without them the contours lose it at the start,
# which is refused before the first step, naming the setting.
expect_ok "zero speed keeps a small circle" -- run --initial two.json --velocity unit-normal \
    --param speed=0 --t-end 1 -N 1 --out still2 --quiet
check "zero speed: two curves" test "$(tail -1 still2/history.csv | cut -d, -f4)" = 2
expect_status "zero speed without thin cells drops a small circle" 3 -- run --initial two.json \
    --velocity unit-normal --param speed=0 --t-end 1 -N 1 --thin-depth 0 --out still --quiet
check "zero speed: the start refused" grep -q "do not keep the curves as given: 2 components with 0 holes became 1 component with 0 holes, and the part near (3.002, 0) lies .* from them; a part is thinner than they resolve: raise --thin-depth (now 0) or -K" err.txt
# Nothing moves under zero speed: the unit circle alone is kept, area and all.
expect_ok "zero speed keeps the circle" -- run --initial c.json --velocity unit-normal --param speed=0 \
    --t-end 1 -N 1 --out still1 --quiet
check "zero speed: one curve" test "$(tail -1 still1/history.csv | cut -d, -f4)" = 1
# A rigid motion (zero speed) keeps the user's 32-gon as the polygon it is (its sides, 0.196,
# are longer than two of the contours' cells), not the circle through its vertices: its area
# 16 sin(pi/16) to 1e-4.
check "zero speed: the 32-gon's area to 1e-4" within "$(value still1 area)" 3.121445152258052 1e-4
# The nearest-point extension of a rotation has kinks that a contour refined to convergence
# resolves down to eps, and every step adds more (the campaign's runs without an end): a rigid
# motion keeps the shape, so a contour needing over 4 times the first one's segments ends the run.
expect_status "rotation, nearest, converged" 3 -- run --initial c.json --velocity rotation \
    --param omega=3 --param cx=0.2 --param cy=-0.8 --t-end 1 -K 7 -P converged \
    --extension nearest --out rough --quiet
check "rotation, nearest: roughening named" grep -q "the steps roughen the curves; use --extension direct" err.txt
expect_ok "rotation, direct, converged" -- run --initial c.json --velocity rotation \
    --param omega=3 --param cx=0.2 --param cy=-0.8 --t-end 1 -K 7 -P converged --out smooth --quiet
# A rigid motion keeps its area (one step of a turn loses 5%); a law that keeps area cannot vanish them.
# Eq. 13 keeps a circle. With the embedded module at S = 3 and the default 40 steps (k/h² = 23)
# the steps roughen it a little each, under a step's 1%: the run-wide budget on the length of a
# law that shortens curves ends the run, naming the cure; the arclength module keeps the circle.
expect_status "a circle under Eq. 13, embedded, S = 3" 3 -- run --initial c.json \
    --velocity volume-preserving-curvature --t-end 2 --geometry embedded -S 3 --out bumpy --quiet
check "Eq. 13, embedded: the length's growth named" grep -q "the length has grown by .* since t = .* use --geometry arclength" err.txt
expect_ok "a circle under Eq. 13, arclength" -- run --initial c.json \
    --velocity volume-preserving-curvature --t-end 2 --out round --quiet
expect_status "spiral in 10 steps" 3 -- run --problem spiral-nonlocal -N 10 --out s10 --quiet
check "spiral in 10 steps: not vanished" grep -q '"status": "unstable"' s10/summary.json
# Table 5's propeller at N = 40, K = 3, P = 0 drifts past the run's 5% of area at t = 2.2: with
# the guards it ends there, unstable; with --no-guards (as for surfaces) it goes on to the end,
# exit 0, status broken, the first break named in summary.json and in one warning.
expect_ok "propeller, no guards" -- run --problem propeller-rotation -N 40 -K 3 -P 0 --no-guards \
    --out p40 --quiet
check "propeller, no guards: broken at the end" python3 -c "
import json, math, sys
s = json.load(open('p40/summary.json'))
sys.exit(not (s['status'] == 'broken' and math.isclose(s['t'], 4 * math.pi) and s['params']['guards'] is False
              and 'the area has drifted by' in s['message']))"
check "propeller, no guards: one warning" grep -q "^slc: warning: --no-guards: at t = 2.199.*the area has drifted by" err.txt
# One step of the paper's embedded curvature at K = 11: no contradictory defaults of eps and eta,
# and no "vanished". A step of k = 0.01 (the whole k = 2 splits the curve in thousands, in 45 s)
# loses area at 1.6 times the law's rate, also in sub-steps: unstable, naming the area.
expect_status "circle-curvature -K 11 -N 1" 3 -- run --problem circle-curvature -K 11 -N 1 --t-end 0.01 \
    --out cc11 --quiet
check "circle-curvature -K 11: unstable" grep -q '"status": "unstable"' cc11/summary.json
check "circle-curvature -K 11: the area named" grep -q "the area changed by .* where the law changes it by" err.txt
# The thin ellipse 1 x 0.1 under curvature (exact extinction at t = 0.05): at defaults (steps of
# 0.0025, a twentieth of its life) its first steps, at tips of curvature 100, lag the law's area
# by 0.15% of the start's each unless split; a user's run holds each step to its share of the
# 1% (area_step_share), so it vanishes within a step of 0.05 (it ended unstable by t = 0.03 when
# only the run's total was held); at N = 320 it vanishes at 0.0503.
awk 'BEGIN { printf "{\"curves\": [{\"points\": ["; for (i = 0; i < 64; i++)
    printf "%s[%.17g, %.17g]", (i ? ", " : ""), cos(2 * 3.141592653589793 * i / 64), 0.1 * sin(2 * 3.141592653589793 * i / 64)
    print "]}]}" }' >thin.json
expect_ok "thin ellipse under curvature at defaults" -- run --initial thin.json --velocity curvature --t-end 0.1 --out thin0 --quiet
check "thin ellipse at defaults: vanished" grep -q '"status": "vanished"' thin0/summary.json
check "thin ellipse at defaults: vanished at 0.05 to 0.0525" awk -v t="$(value thin0 t)" 'BEGIN { exit !(t >= 0.05 && t <= 0.0525 + 1e-12) }'
check "thin ellipse at defaults: its steps split" awk -v n="$(value thin0 split_steps)" 'BEGIN { exit !(n > 0) }'
expect_ok "thin ellipse under curvature, N 320" -- run --initial thin.json --velocity curvature --t-end 0.1 -N 320 --out thin --quiet
check "thin ellipse: vanished" grep -q '"status": "vanished"' thin/summary.json
check "thin ellipse: vanished at 0.05 to 0.0505" awk -v t="$(value thin t)" 'BEGIN { exit !(t >= 0.05 && t <= 0.0505) }'
# A thinner ellipse, 1 x 0.05, to t = 0.01: in 40 whole steps its area would end 3.9% off the
# law's A0 - 2 pi t; at defaults it ends ok within the 1% of A0 that a user's run allows, and at
# N = 160 within 1% of A0 - 2 pi t itself.
awk 'BEGIN { printf "{\"curves\": [{\"points\": ["; for (i = 0; i < 400; i++)
    printf "%s[%.17g, %.17g]", (i ? ", " : ""), cos(2 * 3.141592653589793 * i / 400), 0.05 * sin(2 * 3.141592653589793 * i / 400)
    print "]}]}" }' >thinner.json
expect_ok "thinner ellipse at defaults" -- run --initial thinner.json --velocity curvature --t-end 0.01 --out thinner0 --quiet
check "thinner ellipse at defaults: area within 1% of A0 of A0 - 2 pi t" awk -v a="$(value thinner0 area)" 'BEGIN { d = a - 0.0942413200464105; if (d < 0) d = -d; exit !(d <= 0.01 * 0.15707963267948966) }'
expect_ok "thinner ellipse, N 160" -- run --initial thinner.json --velocity curvature --t-end 0.01 -N 160 --out thinner --quiet
check "thinner ellipse, N 160: area within 1% of A0 - 2 pi t" within "$(value thinner area)" 0.0942413200464105 1e-2
# A circle under an anisotropic speed whose Wulff shape is not convex (R = -1.25, eps = 1, m = 3):
# the step leaves G loops smaller than a cell at the corners, which thin cells 6 levels deep
# resolve as holes a shrinking region cannot make, and deeper ones as more; those steps keep the
# shallower cells that make none (thin_shallower), and the run ends ok with the area of the run at
# the law's default of 2 levels (0.3% apart).
awk 'BEGIN { printf "{\"curves\": [{\"points\": ["; for (i = 0; i < 64; i++)
    printf "%s[%.17g, %.17g]", (i ? ", " : ""), cos(2 * 3.141592653589793 * i / 64), sin(2 * 3.141592653589793 * i / 64)
    print "]}]}" }' >c64.json
wulff="--velocity anisotropic --param R=-1.25 --param eps=1 --param m=3 --param tilt=2.35 --t-end 0.3"
expect_ok "a non-convex Wulff shape at --thin-depth 6" -- run --initial c64.json $wulff --thin-depth 6 --out wulff6 --quiet
check "a non-convex Wulff shape: shallower cells kept" json wulff6/summary.json '1 if s["thin_shallower"]["depth"] < 6 else exit(1)'
expect_ok "a non-convex Wulff shape at defaults" -- run --initial c64.json $wulff --out wulff2 --quiet
check "a non-convex Wulff shape at defaults: ok" grep -q '"status": "ok"' wulff2/summary.json
check "a non-convex Wulff shape at defaults: thin depth 2" json wulff2/summary.json '1 if s["params"]["thin_depth"] == 2 else exit(1)'
check "a non-convex Wulff shape: the same area at 6 and at 2 levels" within "$(value wulff6 area)" "$(value wulff2 area)" 1e-2
# The same circle under curvature at defaults: area 2 pi t lost, to 1e-3.
expect_ok "curvature at defaults, K 7" -- run --initial c.json --velocity curvature --t-end 0.1 -K 7 --out c7 --quiet
check "curvature at K 7: area pi (1 - 0.2)" within "$(value c7 area)" 2.5132741228718345 1e-3
# A growing region's parts merge, never split. The campaign's sharp seven-pointed star grown at
# unit speed by three times its size in 10 steps, with the nearest-point extension of its
# vertex velocities (whose W jumps across the normals at the corners): it ended ok in 337
# curves; now the first step's 1 part becoming many is unstable, naming the extension; the
# direct extension grows it as one curve.
cat >star7.json <<'JSON'
{"curves": [{"points": [[0.9676930493080062, 0.4554603547600791], [0.7113374359920746, 0.5742931067126968], [0.7782653599189283, 0.8488110048797583], [0.5255230627423331, 0.7224751246512281], [0.3526252054823421, 0.9459605925683246], [0.2938163292223609, 0.669589574753037], [0.011288303765844603, 0.6737534968058495], [0.19069713172869875, 0.4554603547600791], [0.011288303765844532, 0.23716721271430888], [0.29381632922236083, 0.24133113476712122], [0.3526252054823420, -0.035039883048166516], [0.52552306274233274, 0.18844558486893007], [0.7782653599189281, 0.06210970464039988], [0.7113374359920746, 0.33662760280746156]]}]}
JSON
expect_status "a star grown with the nearest-point extension" 3 -- run --initial star7.json \
    --velocity unit-normal --param speed=2.14423 --t-end 1.44777 -N 10 --no-arcs --extension nearest \
    --out star_nearest --quiet
check "star, nearest: the parts named, and the extension" grep -q "the region's parts rose from 1 to .* under a law that only grows it.*or use --extension direct" err.txt
check "star, nearest: unstable" grep -q '"status": "unstable"' star_nearest/summary.json
expect_ok "a star grown with the direct extension" -- run --initial star7.json \
    --velocity unit-normal --param speed=2.14423 --t-end 1.44777 -N 10 --no-arcs --out star_direct --quiet
check "star, direct: one curve at every step" sh -c 'test "$(cut -d, -f4 star_direct/history.csv | sort -u | tr "\n" " ")" = "1 components "'
finish
