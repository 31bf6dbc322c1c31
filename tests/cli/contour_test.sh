# slc contour: contours the exact distance of an interface; files, summary keys, accuracy, bad input.
source "$(dirname "$0")/lib.sh" "$1"

square_json >square.json
expect_ok "linear contour" -- contour --initial square.json -K 5 --domain 2 --out lin
for f in final.json summary.json final.svg final.png; do check "contour writes $f" test -s "lin/$f"; done
for key in cells segments mean_segment_length error cpu_s g_evals g_evals_per_vertex; do
    check "summary has $key" grep -q "\"$key\":" lin/summary.json
done
# A smooth curve (a 256-gon of radius 1): refinement to convergence reaches every midpoint. (At a
# sharp corner the safeguards may refuse a split; the summary counts those as "rejected".)
awk 'BEGIN { printf "{\"curves\": [{\"points\": ["; for (i = 0; i < 256; i++) {
    a = 2 * 3.141592653589793 * i / 256; printf "%s[%.17g, %.17g]", (i ? ", " : ""), cos(a), sin(a) }
    print "]}]}" }' >circle.json
expect_ok "adaptive contour" -- contour --initial circle.json -K 4 --eps 1e-4 --refine 20 --domain 2 --out ada
error=$(grep -o '"error": [0-9.e+-]*' ada/summary.json | awk '{print $2}')
check "adaptive error within eps ($error)" awk -v e="$error" 'BEGIN { exit !(e <= 1e-4) }'
# --eps alone asks for that tolerance: refinement until converged; --refine 0 keeps the linear
# contour, whose error is far above it.
expect_ok "eps alone" -- contour --initial circle.json -K 4 --eps 1e-4 --domain 2 --out eps_alone
check "eps alone refines until converged" python3 -c "import json, sys; s = json.load(open('eps_alone/summary.json')); sys.exit(not (s['params']['P'] == 1000 and s['passes'] > 0 and s['error'] <= 1e-4))"
expect_ok "refine 0 with eps" -- contour --initial circle.json -K 4 --eps 1e-4 --refine 0 --domain 2 --out eps_linear
check "refine 0 is the linear contour" python3 -c "import json, sys; s = json.load(open('eps_linear/summary.json')); sys.exit(not (s['params']['P'] == 0 and s['passes'] == 0 and s['error'] > 1e-4))"
expect_error "negative eps" "eps" -- contour --initial square.json -K 4 --eps -1 --domain 2 --out x
# Without -K, K is the one slc run takes for a user's curves (depth_for_domain): 5 in the default
# domain, a level deeper for each doubling beyond it ([-2, 2]^2 is 4/3 of the square's default
# [-1.5, 1.5]^2: K = 6; [-20, 20]^2, 13.3 times: K = 9).
expect_ok "depth by default" -- contour --initial square.json --out default_depth
check "the default depth is a run's, K = 5" test "$(json default_depth/summary.json 's["params"]["K"]')" = 5
for b in 2 20; do
    expect_ok "depth by default in [-$b, $b]^2" -- contour --initial square.json --domain $b --out default_depth_$b
    expect_ok "a run in [-$b, $b]^2" -- run --initial square.json --domain $b --velocity rotation --t-end 0.1 -N 1 --quiet --out run_depth_$b
    check "contour and run take the same K in [-$b, $b]^2" test "$(json default_depth_$b/summary.json 's["params"]["K"]')" = "$(json run_depth_$b/summary.json 's["params"]["K"]')"
done
check "K = 6 and 9" test "$(json default_depth_2/summary.json 's["params"]["K"]') $(json default_depth_20/summary.json 's["params"]["K"]')" = "6 9"

# A shape of any size contours alike: eps and eta scale with it (1e-10 absolute would exceed
# every |G| of a circle of radius 5e-9). The same cells, segments and relative error at 5e-9 and
# 1e-60 as at 1.
for r in 1 5e-9 1e-60; do
    python3 -c "import json, math; json.dump({'time': 0, 'curves': [{'points': [[$r * math.cos(2 * math.pi * i / 64), $r * math.sin(2 * math.pi * i / 64)] for i in range(64)]}]}, open('circle_$r.json', 'w'))"
    expect_ok "a circle of radius $r" -- contour --initial "circle_$r.json" --refine 3 --out "scaled_$r"
done
check "circles of radius 5e-9 and 1e-60 contour as the unit one" python3 - <<'PY'
import json
s = {r: json.load(open(f"scaled_{r}/summary.json")) for r in ("1", "5e-9", "1e-60")}
for r in ("5e-9", "1e-60"):
    for key in ("cells", "segments", "passes"):
        assert s[r][key] == s["1"][key], (r, key, s[r][key], s["1"][key])
    assert abs(s[r]["error"] / float(r) - s["1"]["error"]) <= 1e-6 * s["1"]["error"], r
    assert abs(s[r]["params"]["eta"] / float(r) - s["1"]["params"]["eta"]) <= 1e-12, r
PY
expect_error "missing file" "nope.json" -- contour --initial nope.json -K 4 --out x

# Curves of the user's whose contour tears a part thinner than its cells say so: a ring whose
# wall is 0.01 wide at K = 4 (cells 0.094) comes apart without thin cells, and the note names the
# counts and the setting; at the default thin depth its two curves are kept.
awk 'BEGIN { pi = atan2(0, -1); printf "{\"curves\": [{\"points\": [";
    for (i = 0; i < 256; i++) printf "%s[%.17g, %.17g]", (i ? ", " : ""), 0.5 * cos(2 * pi * i / 256), 0.5 * sin(2 * pi * i / 256);
    printf "]}, {\"points\": [";
    for (i = 0; i < 256; i++) printf "%s[%.17g, %.17g]", (i ? ", " : ""), 0.49 * cos(-2 * pi * i / 256), 0.49 * sin(-2 * pi * i / 256);
    print "]}]}" }' >ring.json
expect_ok "a thin wall torn without thin cells" -- contour --initial ring.json -K 4 --thin-depth 0 --out ring0
check "the tear is noted" grep -q "slc: note: the contour has .* where the input has 2 components with 1 hole: a part is thinner than its cells resolve; raise --thin-depth (now 0) or -K" err.txt
check "summary: the topology not kept" test "$(json ring0/summary.json 's["kept_topology"]')" = False
expect_ok "a thin wall kept by thin cells" -- contour --initial ring.json -K 4 --out ring6
check "summary: the topology kept" test "$(json ring6/summary.json 's["kept_topology"], s["curves"]')" = "True 2"
check "no note" test ! -s err.txt
finish
