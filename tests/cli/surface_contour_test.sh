# slc contour in space (DESIGN §8): a built-in implicit surface and a surface file contoured into
# closed, oriented surfaces that slc reads back; the same output for any thread count; errors.
source "$(dirname "$0")/lib.sh" "$1"

expect_ok "torus contours" -- contour --function torus -K 5 --out torus
check "summary says ok" test "$(json torus/summary.json 's["status"]')" = ok
check "the torus keeps its handle" test "$(json torus/summary.json 's["genus"], s["components"]')" = "1 1"
check "linear contour error below 5e-3" test "$(json torus/summary.json 's["error"] < 5e-3')" = True
check "vertices are roots" test "$(json torus/summary.json 's["error_vertices"] < 1e-9')" = True
check "final.obj, final.vtp and final.png written" test -s torus/final.obj -a -s torus/final.vtp -a -s torus/final.png
# final.obj is a valid closed surface: slc reads it back (validation refuses open, non-manifold,
# crossing or inconsistently oriented triangles) and finds the origin outside, 0.35 from it.
printf 'x,y,z\n0,0,0\n0.55,0,0\n' >points.csv
expect_ok "final.obj reads back" -- distance --initial torus/final.obj --points points.csv --domain 1
check "origin outside the torus" test "$(sed -n 2p out.txt | cut -d, -f4 | python3 -c 'print(abs(float(input()) - 0.35) < 2e-3)')" = True
check "tube centre inside" test "$(sed -n 3p out.txt | cut -d, -f4 | python3 -c 'print(abs(float(input()) + 0.2) < 2e-3)')" = True

expect_ok "one thread" -- contour --function cassini -K 5 --threads 1 --out one
expect_ok "two threads" -- contour --function cassini -K 5 --threads 2 --out two
check "the same surface for any thread count" cmp -s one/final.obj two/final.obj
check "no exact distance for cassini: error null" test "$(json one/summary.json 's["error"]')" = None

cat >box.obj <<'OBJ'
v -0.5 -0.4 -0.3
v 0.45 -0.4 -0.3
v 0.45 0.35 -0.3
v -0.5 0.35 -0.3
v -0.5 -0.4 0.5
v 0.45 -0.4 0.5
v 0.45 0.35 0.5
v -0.5 0.35 0.5
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
OBJ
expect_ok "a surface file contours its exact distance" -- contour --initial box.obj -K 5 --out box
check "box volume within 2%" test "$(json box/summary.json 'abs(s["volume"] / (0.95 * 0.75 * 0.8) - 1) < 0.02')" = True
# Without -K, K is the one slc run takes for a user's surface (depth_for_domain): 5 in the default
# cube (1.5 times the box's half-side 0.475), 6 in [-1.4, 1.4]^3 (1.96 times as wide), as
# `slc run --initial box.obj --domain 1.4` takes; a function's default cube is [-1, 1]^3.
expect_ok "a surface's depth by default" -- contour --initial box.obj --thin-depth 0 --out box_k
check "K = 5 by default" test "$(json box_k/summary.json 's["params"]["K"]')" = 5
expect_ok "a wider domain" -- contour --initial box.obj --thin-depth 0 --domain 1.4 --out box_k6
check "K = 6 in a domain 1.96 times as wide" test "$(json box_k6/summary.json 's["params"]["K"]')" = 6
expect_ok "a function's depth by default" -- contour --function sphere --domain 2 --out sphere_k6
check "K = 6 for a function in [-2, 2]^3" test "$(json sphere_k6/summary.json 's["params"]["K"]')" = 6
check "box vertices on the box" test "$(json box/summary.json 's["error_vertices"] < 1e-9')" = True
check "a linear contour says nothing of converging" test "$(json box/summary.json '"converged" in s')" = False

expect_ok "refined until converged" -- contour --function torus -K 4 --refine 100 --eps 1e-4 --out refined
check "refinement converged" test "$(json refined/summary.json 's["converged"]')" = True
check "midpoints and centroids within eps" test "$(json refined/summary.json 's["error"] <= 1e-4')" = True
check "refined torus keeps its handle" test "$(json refined/summary.json 's["genus"]')" = 1
expect_ok "refined final.obj reads back" -- distance --initial refined/final.obj --points points.csv --domain 1
# --eps alone refines until converged, as slc.contour_surface(..., eps=e) does.
expect_ok "eps alone" -- contour --function torus -K 4 --eps 1e-3 --out eps_alone
check "eps alone: until converged, within eps" test "$(json eps_alone/summary.json 's["params"]["P"] == 1000 and s["converged"] and s["error"] <= 1e-3')" = True
# A mesh's flat faces meet at creases and corners, where refinement cuts its triangles: the box
# at K = 3 meets eps = 1e-3, its volume exact.
expect_ok "a box's edges and corners cut to eps" -- contour --initial box.obj -K 3 --refine 100 --eps 1e-3 --out cut
check "converged within eps, the volume exact" test "$(json cut/summary.json 's["converged"] and s["error"] <= 1e-3 and abs(s["volume"] / (0.95 * 0.75 * 0.8) - 1) < 1e-6')" = True
# Refinement that cannot reach eps writes everything, says "unconverged" and exits with status
# 3 naming the settings to change: a pyramid of eight faces at K = 3 without thin cells, whose
# cells of 0.18 hold several of its corners. P passes spent before eps end the same way.
python3 - <<'PY' >pyramid.obj
import math
corners = [(0.5 * math.cos(k * math.pi / 4), 0.5 * math.sin(k * math.pi / 4), -0.3) for k in range(8)]
for x, y, z in corners + [(0, 0, 0.5)]:
    c, s = math.cos(0.3), math.sin(0.3)
    x, y = c * x - s * y, s * x + c * y
    c, s = math.cos(0.2), math.sin(0.2)
    print("v %.17g %.17g %.17g" % (x, c * y - s * z, s * y + c * z))
for k in range(8):
    print("f", k + 1, (k + 1) % 8 + 1, 9)
for k in range(1, 7):
    print("f", 1, k + 2, k + 1)
PY
expect_status "refinement short of eps" 3 -- contour --initial pyramid.obj -K 3 --thin-depth 0 --refine 100 --eps 1e-3 --out coarse
check "one line naming -K and --eps" grep -q "^slc: error: refinement stopped .* raise -K or --eps" err.txt
check "and the place, by a sharp edge or corner of the input" grep -Eq "near \(.*\) by a sharp (edge|corner) of the input, which the contours chamfer" err.txt
check "summary says unconverged" test "$(json coarse/summary.json 's["status"], s["converged"]')" = "unconverged False"
check "its files are written" test -s coarse/final.obj -a -s coarse/final.png
# Pyramids in a general turn, written as bench/creases.py writes them: N faces about an apex
# 0.8 above a regular N-gon of radius 0.5, turned by the random turn of SEED.
pyramid() {
    python3 - "$1" "$2" <<'PY'
import math, random, sys
n, seed = int(sys.argv[1]), int(sys.argv[2])
rng = random.Random(seed)
angles = [rng.uniform(0, 2 * math.pi) for _ in range(3)]
base = [(0.5 * math.cos(2 * math.pi * k / n), 0.5 * math.sin(2 * math.pi * k / n), -0.3) for k in range(n)]
for x, y, z in base + [(0, 0, 0.5)]:
    for angle, axis in zip(angles, "zxz"):
        c, s = math.cos(angle), math.sin(angle)
        if axis == "z":
            x, y = c * x - s * y, s * x + c * y
        else:
            y, z = c * y - s * z, s * y + c * z
    print("v %.17g %.17g %.17g" % (x, y, z))
for face in [tuple(range(n - 1, -1, -1))] + [(k, (k + 1) % n, n) for k in range(n)]:
    for k in range(1, len(face) - 1):
        print(f"f {face[0] + 1} {face[k] + 1} {face[k + 1] + 1}")
PY
}
# The hexagonal pyramid of turn 1: at K = 4 the thin cells following its 60° base edges catch
# them unevenly and give the linear contour a handle at the default thin depth 2. Left at its
# default, the thin depth that keeps the pyramid (1) is kept, the note says so, and refinement
# meets eps; given, it is kept as given, and the note names the handle.
pyramid 6 1 >hexagonal.obj
expect_ok "a pyramid whose edges the default thin cells tear" -- contour --initial hexagonal.obj -K 4 --eps 1e-3 --out hexagonal
check "the note names the thin depth kept" grep -q "^slc: note: .* at --thin-depth 2 has parts, holes or handles .* kept --thin-depth 1" err.txt
check "genus 0, converged, thin depth 1, the volume exact" test "$(json hexagonal/summary.json 's["genus"], s["converged"], s["params"]["thin_depth"], abs(s["volume"] / 0.17320508075688776 - 1) < 1e-5')" = "0 True 1 True"
expect_ok "its linear contour at --thin-depth 2, as given" -- contour --initial hexagonal.obj -K 4 --thin-depth 2 --out torn
check "the note names the handle" grep -q "^slc: note: .*1 handle.*raise --thin-depth (now 2)" err.txt
check "thin depth 2, genus 1" test "$(json torn/summary.json 's["params"]["thin_depth"], s["genus"], s["kept_topology"]')" = "2 1 False"
# At K = 6 the same pyramid's contours have a speck or handles at every thin depth, each decided
# by a mesh vertex a hair from the zero set beside an edge or corner; told the input's topology,
# the contour moves those across it, and keeps the default thin depth.
expect_ok "the hexagonal pyramid at K = 6" -- contour --initial hexagonal.obj -K 6 --refine 0 --out hexagonal6
check "K 6: one component of genus 0 at thin depth 2, vertices moved across" test "$(json hexagonal6/summary.json 's["components"], s["genus"], s["params"]["thin_depth"], s["moved_across"] > 0')" = "1 0 2 True"
# The pyramid of 16 faces of turn 3 at K = 3: a patch across a base edge ends at a base corner
# that a corner's patch placed (a vertex on three planes); it meets eps.
pyramid 16 3 >sixteen.obj
expect_ok "a pyramid of 16 faces" -- contour --initial sixteen.obj -K 3 --eps 1e-3 --out sixteen
check "16 faces: converged, within eps, the volume within 10 eps^2" test "$(json sixteen/summary.json 's["converged"], s["error"] <= 1e-3, abs(s["volume"] - 0.20409783059471456) < 1e-5')" = "True True True"
expect_status "one pass short of eps" 3 -- contour --function torus -K 4 --refine 1 --eps 1e-4 --out short
check "names --refine too" grep -q "raise -K or --eps or --refine" err.txt
expect_error "eps below eta" "eps must be at least eta" -- contour --function torus -K 4 --refine 1 --eps 1e-12 --out x
expect_error "unknown function" "unknown function 'blob'; known: sphere, torus, cassini" -- contour --function blob -K 4 --out x
expect_error "neither input" "give --initial FILE or --function NAME" -- contour -K 4 --out x
expect_status "a domain too small" 3 -- contour --function torus -K 4 --domain 0.5 --out small
check "enlarge the domain" grep -q "enlarge the domain" err.txt
check "summary records the error" test "$(json small/summary.json 's["status"]')" = error
expect_error "depth beyond memory" "would need about .* GiB .* depth [0-9]+ fits" -- contour --function sphere -K 20 --out x
# A surface of any size contours alike: eps and eta scale with it. A sphere of radius 5e-9 and
# one of 5e-91: the same cells and triangles, and the same error relative to the radius, as at
# radius 0.5.
for r in 0.5 5e-9 5e-91; do
    python3 - "$r" <<'PY'
import math, sys
r = float(sys.argv[1])
nu, nv = 24, 12
v = [(0.0, 0.0, r)]
for j in range(1, nv):
    th = math.pi * j / nv
    for i in range(nu):
        ph = 2 * math.pi * i / nu
        v.append((r * math.sin(th) * math.cos(ph), r * math.sin(th) * math.sin(ph), r * math.cos(th)))
v.append((0.0, 0.0, -r))
at = lambda j, i: 1 + (j - 1) * nu + i % nu
f = [(0, at(1, i), at(1, i + 1)) for i in range(nu)]
for j in range(1, nv - 1):
    for i in range(nu):
        f += [(at(j, i), at(j + 1, i), at(j + 1, i + 1)), (at(j, i), at(j + 1, i + 1), at(j, i + 1))]
f += [(len(v) - 1, at(nv - 1, i + 1), at(nv - 1, i)) for i in range(nu)]
with open(f"sphere_{sys.argv[1]}.obj", "w") as out:
    out.writelines("v %r %r %r\n" % p for p in v)
    out.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in f)
PY
    expect_ok "a sphere of radius $r" -- contour --initial "sphere_$r.obj" -K 4 --out "scaled_$r"
done
check "spheres of radius 5e-9 and 5e-91 contour as one of 0.5" python3 - <<'PY'
import json
s = {r: json.load(open(f"scaled_{r}/summary.json")) for r in ("0.5", "5e-9", "5e-91")}
for r in ("5e-9", "5e-91"):
    for key in ("cells", "triangles"):
        assert s[r][key] == s["0.5"][key], (r, key, s[r][key], s["0.5"][key])
    relative = s[r]["error"] / float(r)
    assert abs(relative - s["0.5"]["error"] / 0.5) <= 1e-6 * relative, r
PY

# A surface of the user's whose contour tears a part thinner than its cells says so: a box with a
# wall 0.03 thick (a cavity 0.87 x 0.8 x 0.8 in a unit cube), cells 0.047 at K = 5. Without thin
# cells the wall is pierced (one surface with 288 handles) and the note names the counts and the
# setting; at the default thin depth the two surfaces are kept.
python3 - <<'PY' >wallbox.obj
boxes = [((-.5, -.5, -.5), (.5, .5, .5), False), ((-.47, -.4, -.4), (.4, .4, .4), True)]
faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6),
         (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
out = []
for n, (lo, hi, inward) in enumerate(boxes):
    for x in (lo[0], hi[0]):
        for y in (lo[1], hi[1]):
            for z in (lo[2], hi[2]):
                print(f"v {x} {y} {z}")
    for a, b, c in faces:  # vertex i has x, y, z from bits 4, 2, 1; outward, or inward (a cavity)
        out.append(tuple(8 * n + i + 1 for i in ((a, c, b) if inward else (a, b, c))))
for t in out:
    print("f %d %d %d" % t)
PY
expect_ok "a thin wall torn without thin cells" -- contour --initial wallbox.obj --thin-depth 0 --out wall0
check "the tear is noted" grep -q "slc: note: the contour has 1 component with 288 handles where the input has 2 components with 0 handles: a part is thinner than its cells resolve; raise --thin-depth (now 0) or -K" err.txt
check "summary: the topology not kept" test "$(json wall0/summary.json 's["kept_topology"]')" = False
expect_ok "a thin wall kept by thin cells" -- contour --initial wallbox.obj --out wall2
check "summary: the topology kept" test "$(json wall2/summary.json 's["kept_topology"], s["components"], s["genus"]')" = "True 2 0"
check "no note" test ! -s err.txt
finish
