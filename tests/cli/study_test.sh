# slc study: the convergence table of a problem, here with the arclength module and arcs, which
# the table names; the same first row with the paper's method beside it.
source "$(dirname "$0")/lib.sh" "$1"

expect_ok "study with the arclength module and arcs" -- study --problem circle-curvature --rows 1 \
    --geometry arclength --arcs --out arcs --quiet
expect_ok "study with the paper's method" -- study --problem circle-curvature --rows 1 --out paper --quiet
for f in table.md table.csv table.json error_vs_time.png; do
    check "study writes $f" test -s "arcs/$f"
done
check "table names the module" grep -q "arclength geometry module" arcs/table.md
check "table names the arcs" grep -q "(--arcs)" arcs/table.md
check "the paper's method's table names neither" test -z "$(grep -E 'arclength|--arcs' paper/table.md)"
# Row 1 at P = 4 (20/1/3/1e-3): E_inf 3.3e-4 against 2.6e-2 (the paper's Table 7: 0.057).
e_inf() { awk -F, '$1 == 1 && $6 == 4 { print $8 }' "$1/table.csv"; }
check "arcs and the arclength module: E_inf at least 10 times smaller" \
    awk -v a="$(e_inf arcs)" -v b="$(e_inf paper)" 'BEGIN { exit !(a > 0 && 10 * a < b) }'

# Self-convergence of a user's curve (no exact solution): three resolutions of a square turned
# by rotation, each final interface compared with the next.
square_json >square.json
expect_ok "self-convergence study" -- study --initial square.json --velocity rotation --t-end 0.5 \
    -N 4 -K 3 --domain 2 --threads 1 --out self --quiet
for f in table.md table.csv table.json convergence.png convergence.svg final_0.json final_2.json; do
    check "self-convergence writes $f" test -s "self/$f"
done
check "self-convergence csv header" test "$(head -n 1 self/table.csv)" = \
    "r,N,S,K,P,eps,status,t,segments,components,area,length,cpu_s,distance_to_next,order,error_estimate"
check "self-convergence csv has three resolutions" test "$(tail -n +2 self/table.csv | wc -l)" -eq 3
check "resolutions refine N, K and eps (/4)" \
    test "$(cut -d, -f2,4,6 self/table.csv | tail -n +2 | tr '\n' ' ')" = "4,3,0.001 8,4,0.00025 16,5,6.25e-05 "
for key in resolutions pairs estimate N K eps P status segments components area length cpu_s \
           distance order error order_observed note; do
    check "table.json has $key" grep -q "\"$key\":" self/table.json
done
check "the finest row holds the estimate" awk -F, 'END { exit !($16 > 0) }' self/table.csv
check "the table states the estimate" grep -q "Estimated error of the finest run" self/table.md

# Runs that cannot be compared (all vanish before t-end) are reported, not a failure.
python3 -c "import json, math; json.dump({'time': 0, 'curves': [{'points': [[0.3 * math.cos(2 * math.pi * i / 64), 0.3 * math.sin(2 * math.pi * i / 64)] for i in range(64)]}]}, open('small.json', 'w'))"
expect_ok "self-convergence of vanishing curves" -- study --initial small.json --velocity curvature \
    --t-end 0.1 -N 4 -K 3 --threads 1 --out vanish --quiet
check "vanished runs: distance infinite in the csv" awk -F, 'NR == 2 { exit !($14 == "inf") }' vanish/table.csv
check "vanished runs: no estimate" grep -q '"estimate": null' vanish/table.json
check "vanished runs: the note says why" grep -q "cannot be compared" vanish/table.json

expect_error "--rows 1 with --initial" "--rows must be 3 to 5 with --initial" -- \
    study --initial square.json --velocity rotation --t-end 0.5 --rows 1 --out bad
expect_error "--rows 6" "--rows" -- study --initial square.json --velocity rotation --t-end 0.5 --rows 6 --out bad
expect_error "--problem and --initial" "excludes" -- \
    study --problem circle-curvature --initial square.json --velocity rotation --t-end 0.5 --out bad
expect_error "--initial without --velocity" "--initial needs --velocity" -- \
    study --initial square.json --t-end 0.5 --out bad
expect_error "neither --problem nor --initial" "give --problem NAME or --initial FILE" -- study --out bad
expect_error "finest K too deep" "must not exceed 24" -- \
    study --initial square.json --velocity rotation --t-end 0.5 -K 23 --eps 1e-6 --out bad
# A study of surfaces: sphere-rotation's first column (P = 0) at two resolutions, N 16 K 5
# eps 4e-4 and N 32 K 6 eps 1e-4. Measured: E_inf 2.26e-3 and 4.55e-4, order 2.31.
expect_ok "study of a surface" -- study --problem sphere-rotation --rows 2 --columns 1 --out sphere --quiet
for f in table.md table.csv table.json error_vs_time.png; do
    check "surface study writes $f" test -s "sphere/$f"
done
check "surface csv header" test "$(head -n 1 sphere/table.csv)" = \
    "row,N,K,eps,P,status,E_inf,T_cpu_s_per_step,wall_s,initial_triangles,triangles"
check "surface rows refine N, K and eps (/4)" \
    test "$(cut -d, -f2-4 sphere/table.csv | tail -n +2 | tr '\n' ' ')" = "16,5,0.0004 32,6,0.0001 "
check "both surface runs ok" test "$(cut -d, -f6 sphere/table.csv | tail -n +2 | sort -u)" = ok
check "surface study: second order down the column" python3 -c "
import json, sys
t = json.load(open('sphere/table.json'))
e = [c['e_inf'] for c in t['cells']]
q = t['orders']['down_columns'][0][0]
sys.exit(not (e[1] < 1e-3 and q > 1.8))"
expect_error "a surface study refuses -K" "-K/--depth does not apply to the study of a surface" -- \
    study --problem sphere-rotation -K 4 --out bad
expect_error "a surface problem without a study" "problem 'enright' has no convergence study" -- \
    study --problem enright --out bad
expect_error "--columns for curves" "--columns is for the study of a surface" -- \
    study --problem circle-curvature --columns 2 --out bad
# Self-convergence of a surface of one's own: a sphere of radius 0.6 grown at unit speed to 0.7
# at N 1, K 2, eps 1.6e-2 and two finer resolutions. Measured: d 1.41e-2 and 3.37e-3, order 2.06;
# the finest run's estimate 1.06e-3 against its error 9.83e-4 (vertices and centroids).
expect_ok "a sphere to grow" -- contour --function sphere -K 4 --refine 100 --eps 1e-3 --out ball
expect_ok "self-convergence of a surface" -- study --initial ball/final.obj --velocity unit-normal \
    --t-end 0.1 -N 1 -K 2 --eps 1.6e-2 --out grown --quiet
for f in table.md table.csv table.json convergence.png final_0.obj final_1.obj final_2.obj; do
    check "surface self-convergence writes $f" test -s "grown/$f"
done
check "surface self-convergence: three runs, ok, refined N, K and eps (/4)" python3 -c "
import json, sys
t = json.load(open('grown/table.json'))
runs = [(r['status'], r['N'], r['K'], r['eps']) for r in t['resolutions']]
sys.exit(runs != [('ok', 1, 2, 1.6e-2), ('ok', 2, 3, 4e-3), ('ok', 4, 4, 1e-3)])"
check "surface self-convergence: second order, an estimate within 0.5 to 3 times the error" python3 -c "
import json, math, sys
t = json.load(open('grown/table.json'))
v, f = [], []
for line in open('grown/final_2.obj'):
    w = line.split()
    if w and w[0] == 'v': v.append([float(x) for x in w[1:4]])
    if w and w[0] == 'f': f.append([int(x.split('/')[0]) - 1 for x in w[1:4]])
points = v + [[sum(v[i][k] for i in tri) / 3 for k in range(3)] for tri in f]
error = max(abs(math.dist(p, (0.03, -0.02, 0.01)) - 0.7) for p in points)
order, estimate = t['pairs'][0]['order'], t['estimate']['error']
sys.exit(not (1.5 < order < 2.5 and 0.5 * error < estimate < 3 * error))"
# A cube turned: its sharp edges leave every run beyond eps, which the table and its note say
# (measured: run 0 unstable at K = 2, runs 1 and 2 beyond eps in every step, 0.0246 and 0.0123).
printf 'v -0.3 -0.3 -0.3\nv 0.3 -0.3 -0.3\nv 0.3 0.3 -0.3\nv -0.3 0.3 -0.3\nv -0.3 -0.3 0.3\nv 0.3 -0.3 0.3\nv 0.3 0.3 0.3\nv -0.3 0.3 0.3\n' >cube.obj
printf 'f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n' >>cube.obj
expect_ok "self-convergence of a cube turned" -- study --initial cube.obj --velocity rotation \
    --t-end 0.5 -N 1 -K 2 --eps 1.6e-2 --out cube --quiet
check "cube: the runs beyond eps counted and named in the note" python3 -c "
import json, sys
t = json.load(open('cube/table.json'))
r = t['resolutions']
sys.exit(not (all(x['unconverged_steps'] == x['N'] and x['largest_residual'] > x['eps'] for x in r[1:])
              and 'Run 2 left 4 of 4 steps beyond' in t['note']))"
check "cube: the table's beyond-eps column" grep -q '| 2 of 2 (' cube/table.md
expect_error "surface self-convergence: --rows 2" "--rows must be 3 to 5 with --initial" -- \
    study --initial ball/final.obj --velocity unit-normal --t-end 0.1 --rows 2 --out bad
expect_error "surface self-convergence: --mesh" \
    "--mesh is for curves, not surfaces" -- \
    study --initial ball/final.obj --velocity unit-normal --t-end 0.1 --mesh 16 --out bad
expect_error "surface self-convergence: no law" "--initial with a surface needs --velocity" -- \
    study --initial ball/final.obj --t-end 0.1 --out bad
check "bad input writes nothing" test ! -e bad
finish
