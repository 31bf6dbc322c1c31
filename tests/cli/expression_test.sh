# slc run --speed, --field and --field-file: the laws typed as expressions or read from a lattice
# against the built-in laws and exact solutions, summary.json, checkpoints, and bad input.
source "$(dirname "$0")/lib.sh" "$1"

circle_json() {  # circle_json R N: a circle of radius R about the origin as an N-gon
    awk -v r="$1" -v n="$2" 'BEGIN { pi = atan2(0, -1); printf "{\"time\": 0, \"curves\": [{\"points\": [";
        for (i = 0; i < n; i++) printf "%s[%.17g, %.17g]", (i ? ", " : ""), r * cos(2 * pi * i / n), r * sin(2 * pi * i / n);
        print "]}]}" }'
}
points_of() { sed -nE 's/^ *\[([^],]+), ([^]]+)\],?$/\1,\2/p' "$1"; }  # final.json -> x,y lines
summary_number() { sed -nE "s/^ *\"$2\": ([^,]+),?$/\1/p" "$1/summary.json"; }
# max_distance CURVES.json POINTS.csv OFFSET [slc distance options]: max |F(p) - OFFSET| over the
# points p, F the signed distance to CURVES.
max_distance() {
    local curves="$1" points="$2" offset="$3"
    shift 3
    "$SLC" distance --initial "$curves" --points "$points" "$@" |
        awk -F, -v o="$offset" 'NR > 1 { d = $3 - o; d = d < 0 ? -d : d; if (d > m) m = d } END { printf "%.17g\n", m }'
}
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a + 0 < b + 0) }'; }

circle_json 1 200 >circle.json

# --speed 1 is unit normal motion: the built-in law's run exactly, and Huygens' offset of the
# initial polygon, F0 = t, to 1e-3 at every vertex (measured 2.0e-4 at the defaults, N = 40,
# K = 5: the contour's resolution at the polygon's 200 corners).
expect_ok "speed 1" -- run --initial circle.json --speed 1 --t-end 0.5 --out speed1 --quiet
expect_ok "unit-normal" -- run --initial circle.json --velocity unit-normal --t-end 0.5 --out unit --quiet
check "speed 1: the unit-normal run, bit for bit" cmp -s speed1/final.json unit/final.json
points_of speed1/final.json >speed1.csv
check "speed 1: the offset circle, radius 1 + t" below "$(max_distance circle.json speed1.csv 0.5 --domain 3)" 1e-3
check "summary: velocity speed" grep -q '"velocity": "speed"' speed1/summary.json
check "summary: the expression" grep -q '"velocity_expression": "1"' speed1/summary.json
check "summary: direct extension of a normal law" grep -q '"extension": "direct"' speed1/summary.json

# --speed C is curvature flow (C = -1/R on a circle): the built-in curvature run exactly, and
# the area pi (R0^2 - 2t) of the exact shrinking circle to a relative 1e-4 (measured 2.6e-5).
expect_ok "speed C" -- run --initial circle.json --speed C --t-end 0.25 --out speedC --quiet
expect_ok "curvature" -- run --initial circle.json --velocity curvature --t-end 0.25 --out curv --quiet
check "speed C: the curvature run, bit for bit" cmp -s speedC/final.json curv/final.json
check "speed C: area lost at 2 pi" awk -v a="$(summary_number speedC area)" 'BEGIN {
    pi = atan2(0, -1); want = pi * (1 - 2 * 0.25); e = (a - want) / want; exit !(a != "" && e < 1e-4 && e > -1e-4) }'
check "speed C: the curvature defaults (P = 2, arcs)" grep -qE '"P": 2,' speedC/summary.json
check "speed C: arcs" grep -q '"arcs": true' speedC/summary.json

# A constant from --param, and the same run on 1 and 2 threads: identical.
expect_ok "speed with a constant" -- run --initial circle.json --speed "a + C + 0.1*x*ny" --param a=0.5 \
    --t-end 0.1 -N 10 --threads 1 --out const1 --quiet
expect_ok "speed on two threads" -- run --initial circle.json --speed "a + C + 0.1*x*ny" --param a=0.5 \
    --t-end 0.1 -N 10 --threads 2 --out const2 --quiet
check "thread count changes nothing" cmp -s const1/final.json const2/final.json
check "summary: the constants" grep -qE '"a": 0.5' const1/summary.json

# --field "-y, x" is the rigid rotation: the built-in run exactly, and after t = 2 pi the shape is
# back where it started, every vertex within 2e-4 of the initial triangle (measured 5.6e-5; its
# corners are where the contour is least accurate).
echo '{"time": 0, "curves": [{"points": [[0.2, 0.1], [1.0, 0.3], [0.5, 0.9]]}]}' >tri.json
two_pi=6.283185307179586
box=(--box -1.5,-1.5,1.5,1.5)
expect_ok "field rotation" -- run --initial tri.json --field "-y, x" --t-end $two_pi "${box[@]}" --out rot --quiet
expect_ok "rotation" -- run --initial tri.json --velocity rotation --t-end $two_pi "${box[@]}" --out rotb --quiet
check "field -y, x: the rotation run, bit for bit" cmp -s rot/final.json rotb/final.json
points_of rot/final.json >rot.csv
check "field -y, x: back at the start after 2 pi" below "$(max_distance tri.json rot.csv 0 --domain 2)" 2e-4
check "summary: velocity field" grep -q '"velocity": "field"' rot/summary.json

# The rotation on a lattice (CSV, and VTK with 3-component vectors): bilinear interpolation is
# exact for a linear field, so the run is the --field run but for rounding: within 1e-12
# (measured 5e-14).
awk 'BEGIN { print "x,y,u,v"; for (j = 30; j >= 0; j--) for (i = 0; i <= 30; i++) {
    x = -1.5 + 0.1 * i; y = -1.5 + 0.1 * j; printf "%.17g,%.17g,%.17g,%.17g\n", x, y, -y, x } }' >rot_field.csv
{ printf '# vtk DataFile Version 3.0\nrotation\nASCII\nDATASET STRUCTURED_POINTS\n'
  printf 'DIMENSIONS 31 31 1\nORIGIN -1.5 -1.5 0\nSPACING 0.1 0.1 1\nPOINT_DATA 961\nVECTORS u double\n'
  awk 'BEGIN { for (j = 0; j <= 30; j++) for (i = 0; i <= 30; i++) {
      x = -1.5 + 0.1 * i; y = -1.5 + 0.1 * j; printf "%.17g %.17g 0\n", -y, x } }'; } >rot_field.vtk
same_curves() {  # same_curves A B TOL: the vertices of two final.json files pairwise within TOL
    paste -d, <(points_of "$1/final.json") <(points_of "$2/final.json") | awk -F, -v tol="$3" '
        { n++; d = ($1 - $3) ^ 2 + ($2 - $4) ^ 2; if (d > m) m = d; if ($3 == "") bad = 1 }
        END { exit !(n > 0 && !bad && sqrt(m) < tol) }'
}
# Compared with chords: arcs through nearly collinear vertices carry the rounding of their
# curvature into the next step. Over a fifth of a turn: corners found where the sides' lines meet
# pass rounding on from step to step (3.5e-6 apart after the whole turn, 1.6e-13 after a fifth).
fifth=$(awk 'BEGIN { printf "%.17g", 2 * atan2(0, -1) / 5 }')
expect_ok "field rotation, chords" -- run --initial tri.json --field "-y, x" --t-end $fifth -N 8 "${box[@]}" \
    --no-arcs --out rot_chords --quiet
for ext in csv vtk; do
    expect_ok "field file $ext" -- run --initial tri.json --field-file rot_field.$ext --t-end $fifth -N 8 \
        "${box[@]}" --no-arcs --out rotf_$ext --quiet
    check "field file $ext: the --field run to rounding" same_curves rotf_$ext rot_chords 1e-12
done
check "summary: the file" grep -q '"velocity_file": "rot_field.csv"' rotf_csv/summary.json

# A field that is not linear: the single vortex on lattices of spacing 1/32 and 1/64 against the
# built-in vortex (steady: period 1e300) at t = 0.5. Bilinear interpolation is second order, so
# halving h divides the distance between the final curves by about 4 (measured 1.9e-3, 4.8e-4:
# 4.04); asserted: a ratio above 3 and 1e-3 at h = 1/64.
awk 'BEGIN { pi = atan2(0, -1); printf "{\"time\": 0, \"curves\": [{\"points\": [";
    for (i = 0; i < 100; i++) printf "%s[%.17g, %.17g]", (i ? ", " : ""), 0.5 + 0.15 * cos(2 * pi * i / 100), 0.75 + 0.15 * sin(2 * pi * i / 100);
    print "]}]}" }' >disk.json
vortex_args=(--initial disk.json --t-end 0.5 --box 0,0,1,1 --quiet)
expect_ok "vortex" -- run "${vortex_args[@]}" --velocity vortex --param period=1e300 --out vortex
expect_ok "vortex as --field" -- run "${vortex_args[@]}" \
    --field "sin(_pi*x)^2 * sin(2*_pi*y), -sin(_pi*y)^2 * sin(2*_pi*x)" --out vortex_field
points_of vortex_field/final.json >vortex_field.csv
check "vortex as --field: the built-in run to rounding" \
    below "$(max_distance vortex/final.json vortex_field.csv 0 --box 0,0,1,1)" 1e-10
for n in 32 64; do
    awk -v n=$n 'BEGIN { pi = atan2(0, -1); for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) {
        x = i / n; y = j / n; printf "%.17g,%.17g,%.17g,%.17g\n", x, y, sin(pi * x) ^ 2 * sin(2 * pi * y), -sin(pi * y) ^ 2 * sin(2 * pi * x) } }' >vortex_$n.csv
    expect_ok "vortex on a lattice of $n" -- run "${vortex_args[@]}" --field-file vortex_$n.csv --out vortex_$n
    points_of vortex_$n/final.json >vortex_$n.points.csv
done
e32=$(max_distance vortex/final.json vortex_32.points.csv 0 --box 0,0,1,1)
e64=$(max_distance vortex/final.json vortex_64.points.csv 0 --box 0,0,1,1)
check "vortex lattice: within 1e-3 at h = 1/64" below "$e64" 1e-3
check "vortex lattice: second order in h" awk -v a="$e32" -v b="$e64" 'BEGIN { exit !(b > 0 && a / b > 3) }'

# Checkpoints keep the expression and a copy of the lattice: the resumed run is the uninterrupted
# one even after the file has gone.
cp rot_field.csv moved.csv
ck_args=(run --initial tri.json --field-file moved.csv --t-end 1 -N 10 "${box[@]}" --quiet)
expect_ok "lattice run" -- "${ck_args[@]}" --out ck_full
expect_ok "lattice run checkpointed" -- "${ck_args[@]}" --checkpoint-every 4 --out ck_part
rm moved.csv ck_part/final.json ck_part/summary.json  # results newer than the checkpoint are not resumed
expect_ok "lattice run resumed without its file" -- run --resume ck_part --quiet
check "lattice run resumed: the same final curves" cmp -s ck_full/final.json ck_part/final.json
# Backward in curvature (the sign of C the wrong way round) is ill-posed: refused, not run.
expect_error "speed falling as C grows" "speed 'a - C' falls as the curvature C grows" -- \
    run --initial circle.json --speed "a - C" --param a=0.25 --t-end 0.1 -N 10 --out backward
sp_args=(run --initial circle.json --speed "a + C" --param a=0.25 --t-end 0.1 -N 10 --quiet)
expect_ok "speed run" -- "${sp_args[@]}" --out sp_full
expect_ok "speed run checkpointed" -- "${sp_args[@]}" --checkpoint-every 4 --out sp_part
rm sp_part/final.json sp_part/summary.json
expect_ok "speed run resumed" -- run --resume sp_part --quiet
check "speed run resumed: the same final curves" cmp -s sp_full/final.json sp_part/final.json

# Curves must stay on the lattice: outside at the start is bad input (2, nothing written), leaving
# it during the run a numerical failure (3) that names the time and what to change.
awk 'BEGIN { for (j = 0; j <= 10; j++) for (i = 0; i <= 10; i++) printf "%g,%g,1,0\n", -1 + 0.2 * i, -1 + 0.2 * j }' >right.csv
echo '{"time": 0, "curves": [{"points": [[-0.6, -0.3], [0.2, -0.1], [-0.3, 0.5]]}]}' >inside.json
expect_status "leaving the lattice" 3 -- run --initial inside.json --field-file right.csv --t-end 2 --box -3,-3,3,3 \
    --out leave --quiet
check "leaving the lattice: says when and what to change" \
    grep -qE "at t = 0\.[0-9]+ the curves left the region where velocity 'field-file right.csv' is known, \[-1, 1\] x \[-1, 1\].*larger grid.*t-end" err.txt
check "leaving the lattice: status error" grep -q '"status": "error"' leave/summary.json
echo '{"time": 0, "curves": [{"points": [[2.2, 0.1], [3.0, 0.3], [2.5, 0.9]]}]}' >far.json
expect_error "initial curves off the lattice" "the initial curves leave the region where velocity 'field-file right.csv' is known, \[-1, 1\] x \[-1, 1\]: vertex 0 at \(2.2, 0.1\)" -- \
    run --initial far.json --field-file right.csv --t-end 1 --out far --quiet
check "initial curves off the lattice: nothing written" test ! -e far
expect_status "speed not finite" 3 -- run --initial tri.json --speed "1/(x-0.6)" --t-end 1 --out inf --quiet
check "speed not finite: names the law" grep -q "velocity 'speed = 1/(x-0.6)' is not finite" err.txt

# Bad expressions and files: status 2 and one line naming what is wrong.
run_tri=(run --initial tri.json --t-end 1 --out bad --quiet)
expect_error "syntax error" "speed expression 'x \+': unexpected end of expression" -- "${run_tri[@]}" --speed "x +"
expect_error "unknown variable" "speed expression 'z': unknown name 'z' at position 0 \(the variables are x, y, t, C, nx, ny\)" -- \
    "${run_tri[@]}" --speed z
expect_error "curvature in a field" "field expression 'C, x': unknown name 'C'" -- "${run_tri[@]}" --field "C, x"
expect_error "one component" "field expression '-y': gives 1 value; a flow field needs two" -- "${run_tri[@]}" --field "-y"
expect_error "two speeds" "a normal speed is one" -- "${run_tri[@]}" --speed "1, 2"
expect_error "empty speed" "speed expression is empty" -- "${run_tri[@]}" --speed ""
expect_error "speed and velocity" "give one velocity law of --velocity, --speed, --field and --field-file, got --velocity and --speed" -- \
    "${run_tri[@]}" --speed 1 --velocity rotation
expect_error "field and field file" "got --field and --field-file" -- "${run_tri[@]}" --field "-y, x" --field-file right.csv
expect_error "speed with a problem" "--problem excludes --speed" -- run --problem vortex --speed 1 --out bad
expect_error "constant named as a variable" "the constant 'x' is a variable" -- "${run_tri[@]}" --speed 1 --param x=2
expect_error "missing lattice file" "cannot read nope.csv" -- "${run_tri[@]}" --field-file nope.csv
printf '0,0,1,1\n1,0,1,1\n3,0,1,1\n0,1,1,1\n1,1,1,1\n3,1,1,1\n' >uneven.csv
expect_error "uneven lattice" "uneven.csv: the x values are not evenly spaced" -- "${run_tri[@]}" --field-file uneven.csv
printf '0,0,1,1\n1,0,1\n' >short.csv
expect_error "short line" "short.csv, line 2: expected 4 numbers x,y,u,v" -- "${run_tri[@]}" --field-file short.csv
printf '# vtk DataFile Version 3.0\nt\nBINARY\n' >binary.vtk
expect_error "binary VTK" "binary.vtk: only ASCII legacy VTK files are read" -- "${run_tri[@]}" --field-file binary.vtk
check "bad input writes nothing" test ! -e bad

# Zero outside the lattice when asked (--field-outside zero): a circle of radius 0.25 carried
# right at unit speed stops at the lattice's edge x = 1 instead of ending with an error.
circle_json 0.25 64 >disk.json
expect_status "leaving the lattice is an error by default" 3 -- run --initial disk.json --field-file right.csv --t-end 0.9 -N 9 --quiet --out wall_error
expect_ok "--field-outside zero" -- run --initial disk.json --field-file right.csv --field-outside zero --t-end 0.9 -N 9 --quiet --out wall
check "  recorded in summary.json" test "$(json wall/summary.json 's["params"]["field_outside"]')" = zero
check "  what reached the edge x = 1 stopped there, the rest went on" python3 -c "
import json
x = [p[0] for c in json.load(open('wall/final.json'))['curves'] for p in c['points']]
assert 0.99 < max(x) < 1.01 and abs(min(x) - 0.65) < 0.01, (min(x), max(x))"
expect_error "--field-outside needs --field-file" "--field-outside requires --field-file" -- run --initial disk.json --velocity rotation --field-outside zero --t-end 0.1 --out f
expect_error "--field-outside is error or zero" "--field-outside: none not in \{error,zero\}" -- run --initial disk.json --field-file right.csv --field-outside none --t-end 0.1 --out f

finish
