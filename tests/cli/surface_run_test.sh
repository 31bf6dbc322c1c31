# slc run on surfaces (DESIGN §8): a user's surface under built-in laws of surfaces against exact
# motions (rotation, translation, mean curvature, the volume kept), a named problem, frames, and
# the same output for any thread count. Offsets at the defaults are in
# surface_run_defaults_test.sh, the options and errors in surface_run_options_test.sh.
source "$(dirname "$0")/lib.sh" "$1"

# A sphere of radius 0.6 about (0.03, -0.02, 0.01), as slc contours it.
expect_ok "a sphere to move" -- contour --function sphere -K 4 --refine 100 --eps 1e-3 --out ball
cp ball/final.obj ball.obj

# A rigid turn about the x axis through the sphere's centre's neighbour keeps volume and shape.
expect_ok "rotation about x" -- run --initial ball.obj --velocity rotation --param ax=1 --param az=0 --param cy=0.1 --t-end 1.5707963 -N 8 -K 4 --out turn --quiet --frames 2
check "volume kept within 0.2%" test "$(json turn/summary.json 'abs(s["volume_change"]) < 2e-3')" = True
check "one component, genus 0" test "$(json turn/summary.json 's["components"], s["genus"]')" = "1 0"
check "frames: the start and two more" test "$(grep -c '<DataSet' turn/frames.pvd)" = 3
check "frame pictures" test -s turn/frames/frame_0000.png -a -s turn/frames/frame_0002.png

# A translation out of the default domain (1.5 times the bounding box): the domain doubles about
# its centre with K a level deeper, as for curves, and the sphere arrives whole.
expect_ok "translation out of the domain" -- run --initial ball.obj --velocity translation --param ux=1 --param uy=0 --param uz=0 --t-end 1.5 -N 6 -K 4 --out away --quiet
check "the domain grew" test "$(json away/summary.json 's["status"], s["domain_grown"]["doublings"] >= 1')" = "ok True"
check "and a note says so" grep -q "the domain grew to" err.txt
check "the sphere moved by 1.5, its radius kept" test "$(python3 -c '
xs = [list(map(float, l.split()[1:4])) for l in open("away/final.obj") if l.startswith("v ")]
r = [((x - 1.53) ** 2 + (y + 0.02) ** 2 + (z - 0.01) ** 2) ** 0.5 for x, y, z in xs]
print(max(abs(v - 0.6) for v in r) < 3e-3)')" = True

# A box turned off the axes keeps sharp edges the refinement cannot split to eps: the run says
# how far its contours stayed, and a smooth surface's says none did.
printf 'v -0.4 -0.3 -0.35\nv 0.4 -0.3 -0.35\nv -0.4 0.3 -0.35\nv 0.4 0.3 -0.35\nv -0.4 -0.3 0.35\nv 0.4 -0.3 0.35\nv -0.4 0.3 0.35\nv 0.4 0.3 0.35\nf 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n' >box.obj
expect_ok "a box turned" -- run --initial box.obj --velocity rotation --t-end 0.5 -N 2 -K 4 --eps 1e-3 --out boxturn --quiet
check "its steps left beyond eps are counted" test "$(json boxturn/summary.json 's["unconverged_steps"], s["largest_residual"] > 2e-3')" = "2 True"
check "and a note says so" grep -q "in 2 of 2 steps refinement left" err.txt
check "a smooth surface's contours stay within 1.5 eps" test "$(json turn/summary.json 's.get("largest_residual", 0) < 1.5 * s["params"]["eps"]')" = True
# One level more where G bends, as along its sharp edges: recorded in the summary.
expect_ok "thin cells" -- run --initial box.obj --velocity rotation --t-end 0.5 -N 2 -K 4 --eps 1e-3 --thin-depth 1 --out boxthin --quiet
check "--thin-depth recorded" test "$(json boxthin/summary.json 's["params"]["thin_depth"]')" = 1
check "2 for --initial by default" test "$(json boxturn/summary.json 's["params"]["thin_depth"]')" = 2

# Mean curvature flow: R^2 = 0.36 - 4t, so t = 0.05 leaves R = 0.4.
expect_ok "mean curvature" -- run --initial ball.obj --velocity curvature --t-end 0.05 -N 10 -K 4 --out shrink --quiet
check "radius 0.4: volume within 2%" test "$(json shrink/summary.json 'abs(s["volume"] / (4 / 3 * 3.141592653589793 * 0.4**3) - 1) < 2e-2')" = True

# Volume-preserving mean curvature keeps a sphere: the volume correction gives back what the
# steps lose, as summary.json reports, and --no-area-correction turns it off.
expect_ok "volume-preserving curvature" -- run --initial ball.obj --velocity volume-preserving-curvature --t-end 0.004 -N 2 -K 3 --out kept --quiet
check "volume kept to 1e-6 with the correction" test "$(json kept/summary.json 'abs(s["volume_change"]) < 1e-6')" = True
check "the volume given back is reported" test "$(json kept/summary.json '"volume_corrected" in s')" = True
expect_ok "without the volume correction" -- run --initial ball.obj --velocity volume-preserving-curvature --t-end 0.004 -N 2 -K 3 --no-area-correction --out unkept --quiet
check "no correction reported when off" test "$(json unkept/summary.json '"volume_corrected" in s')" = False

expect_ok "one thread" -- run --initial ball.obj --velocity enright --param period=1 --t-end 0.1 -N 2 -K 4 --threads 1 --out one --quiet
expect_ok "two threads" -- run --initial ball.obj --velocity enright --param period=1 --t-end 0.1 -N 2 -K 4 --threads 2 --out two --quiet
check "the same surface for any thread count" cmp -s one/final.obj two/final.obj

# A named problem: two spheres grow into one.
expect_ok "merging spheres" -- run --problem merging-spheres -K 4 --eps 1e-3 --out merge --quiet
check "they merged" test "$(json merge/summary.json 's["components"], s["genus"]')" = "1 0"
check "e_inf within 3e-3" test "$(json merge/summary.json 's["e_inf"] < 3e-3')" = True

# --until-components: two spheres growing until they merge stop there, before t_end; the frames
# end with where they stopped.
expect_ok "merging spheres until one" -- run --problem merging-spheres -K 4 -N 20 \
    --until-components 1 --frames 2 --out merge1 --quiet
check "merging spheres: one left" test "$(json merge1/summary.json 's["components"]')" = 1
check "merging spheres: the last frame is where it stopped" \
    grep -q "timestep=\"$(json merge1/summary.json 's["t"]')\".*frame_0001.vtp" merge1/frames.pvd
check "merging spheres: no frame beyond it" test ! -e merge1/frames/frame_0002.vtp

# Two meshed spheres of one's own (0.3 and 0.25 across, 0.13 apart, one turned) growing into
# each other at K 4: where they meet, deeper thin cells make handles of the gap narrowing between
# them, no two depths alike, and the step keeps the shallower cells that make none: one component
# of genus 0, as without thin cells.
"$SLC" contour --function sphere -K 3 --out sphere >/dev/null 2>&1
awk 'BEGIN { c = cos(0.7); s = sin(0.7) }
    /^v / { n++; x[n] = $2; y[n] = $3; z[n] = $4 }
    /^f / { m++; f[m] = $2 " " $3 " " $4 }
    END {
        for (i = 1; i <= n; i++) printf "v %.17g %.17g %.17g\n", 0.5 * x[i] - 0.32, 0.5 * y[i], 0.5 * z[i]
        for (i = 1; i <= n; i++)
            printf "v %.17g %.17g %.17g\n", 0.42 * (c * x[i] - s * y[i]) + 0.36,
                0.42 * (s * x[i] + c * y[i]) + 0.03, 0.42 * z[i] + 0.01
        for (j = 1; j <= m; j++) print "f " f[j]
        for (j = 1; j <= m; j++) { split(f[j], a, " "); printf "f %d %d %d\n", a[1] + n, a[2] + n, a[3] + n }
    }' sphere/final.obj >pair.obj
expect_ok "meshed spheres meeting" -- run --initial pair.obj --velocity unit-normal --t-end 0.1 -K 4 \
    --out pair --quiet
check "meshed spheres meeting: merged" test "$(json pair/summary.json 's["components"], s["genus"]')" = "1 0"
check "meshed spheres meeting: shallower thin cells kept" \
    test "$(json pair/summary.json 's["thin_shallower"]["depth"] < 2')" = True
check "meshed spheres meeting: the note" grep -q "kept the shallower cells that made none, down to 1 level (summary.json: thin_shallower)" err.txt
expect_ok "meshed spheres meeting without thin cells" -- run --initial pair.obj --velocity unit-normal \
    --t-end 0.1 -K 4 --thin-depth 0 --out pair0 --quiet
check "meshed spheres: one component of genus 0" test "$(json pair0/summary.json 's["components"], s["genus"]')" = "1 0"

finish
