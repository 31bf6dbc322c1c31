# slc run: a named problem and a user's curve, the files written, the summary's keys, bad input.
source "$(dirname "$0")/lib.sh" "$1"

expect_ok "merging circles" -- run --problem merging-circles -N 8 -K 4 -P 1 --frames 2 --out mc --quiet
for f in summary.json final.json final.svg final.png frames.svg frames.png frames/frame_0000.json frames/frame_0002.json; do
    check "run writes $f" test -s "mc/$f"
done
for key in problem params t_end steps status e_inf area length components segments wall_s cpu_s \
           cpu_s_per_step threads g_evals g_evals_per_vertex; do
    check "summary has $key" grep -q "\"$key\":" mc/summary.json
done
check "status ok" grep -q '"status": "ok"' mc/summary.json
check "merged into one component" grep -q '"components": 1' mc/summary.json

# The history: a header, the initial interface and one line per step; the last line is the final
# interface of the summary (area and length compared as numbers: both are shortest round-trip).
for f in history.csv history.png; do check "run writes $f" test -s "mc/$f"; done
check "history header" test "$(head -n 1 mc/history.csv)" = "t,area,length,components,segments,cpu_s"
check "history has N + 1 lines" test "$(tail -n +2 mc/history.csv | wc -l)" -eq 9
check "history starts at t = 0 with three circles and cpu_s 0" grep -qE '^0,[^,]+,[^,]+,3,[0-9]+,0$' <(sed -n 2p mc/history.csv)
summary_number() { sed -nE "s/^ *\"$2\": ([^,]+),?$/\1/p" "$1/summary.json"; }
last_field() { tail -n 1 "$1/history.csv" | cut -d, -f"$2"; }
check "history ends with the summary's area" \
    awk -v a="$(last_field mc 2)" -v b="$(summary_number mc area)" 'BEGIN { exit !(a != "" && a + 0 == b + 0) }'
check "history ends with the summary's length" \
    awk -v a="$(last_field mc 3)" -v b="$(summary_number mc length)" 'BEGIN { exit !(a != "" && a + 0 == b + 0) }'
check "history ends with the summary's segments" test "$(last_field mc 5)" = "$(summary_number mc segments)"

# Curvature flow of a circle: the area falls at 2π per unit time (to 1% here).
expect_ok "circle history" -- run --problem circle-curvature -N 12 -K 4 -P 1 --out circ --quiet
check "circle: area falls at 2 pi" awk -F, 'NR == 2 { t0 = $1; a0 = $2 } END {
    rate = (a0 - $2) / ($1 - t0); exit !(rate > 0.99 * 6.2832 && rate < 1.01 * 6.2832) }' circ/history.csv

# Resumed from a checkpoint, the history is the uninterrupted run's but for the CPU seconds of the
# steps done again. Lines after the checkpoint's step (10 of 12 here), as a run stopped later
# would have left them, are dropped and written again.
same_history() {  # same_history NAME A B: every column but cpu_s identical
    check "$1" diff <(cut -d, -f1-5 "$2/history.csv") <(cut -d, -f1-5 "$3/history.csv")
}
expect_ok "circle checkpointed" -- run --problem circle-curvature -N 12 -K 4 -P 1 --checkpoint-every 5 \
    --out circ_part --quiet
same_history "checkpointing keeps the history" circ circ_part
head -n 12 circ_part/history.csv >kept.csv
{ cat kept.csv; echo "1.8333333333333333,0,0,0,0,0"; printf "1.9"; } >circ_part/history.csv
rm circ_part/final.json circ_part/summary.json circ_part/history.png
expect_ok "circle resumed" -- run --resume circ_part --quiet
same_history "resumed history as the uninterrupted one" circ circ_part
check "resume keeps the history's lines up to the checkpoint" cmp -s kept.csv <(head -n 12 circ_part/history.csv)
check "resume draws the history" test -s circ_part/history.png
rm circ_part/summary.json  # the finished run's results are newer than its checkpoint
head -n 8 circ_part/history.csv >short.csv && mv short.csv circ_part/history.csv
expect_error "resume with a history shorter than the checkpoint" "history.csv: the checkpoint after step 10 needs 11 time levels, the file has 7" -- \
    run --resume circ_part --quiet
check "a history that cannot be continued changes nothing" test "$(wc -l <circ_part/history.csv)" -eq 8

# Many frames: the overlay's legend names a few, so the picture keeps its size (a line per frame
# made it 16220 pixels tall at 400 frames, and cairo refused it from about 1600) ...
# (The triangle at K = 5: the propeller at K = 3 and P = 0 loses its area, 99.9% by the end, and
# now ends unstable.)
expect_ok "many frames" -- run --problem triangle-normal -N 1800 -K 5 -P 0 --eps 1e-3 --frames 1800 \
    --out many --quiet
check "many frames: nothing on stderr" test ! -s err.txt
check "many frames: overlay drawn" test -s many/frames.png
png_height() { od -An -tu1 -j20 -N4 "$1" | awk '{print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4}'; }
check "many frames: overlay as tall as a one-frame picture" \
    test "$(png_height many/frames.png)" -le "$(png_height many/final.png)"
# ... and draws (and holds) every 29th of the 1801 frames and the last: 64 curves, not 1801.
check "many frames: overlay draws 64 of them" \
    test "$(grep -o '<path style="fill:none' many/frames.svg | wc -l)" -lt 100
check "many frames: all written" test -s many/frames/frame_1800.json

square_json >square.json
expect_ok "user curve and law" -- run --initial square.json --velocity rotation --param omega=2 --t-end 0.5 \
    -N 4 -K 4 -P 0 --domain 2 --out user --quiet
check "user run writes final.json" test -s user/final.json
check "user run has no exact solution" grep -q '"e_inf": null' user/summary.json
# A user's flow field takes 10 steps unless -N is given; --frames 4 raises them to 12, so that the
# frames fall at t = 0.125, 0.25, 0.375 and 0.5.
expect_ok "a flow field's frames" -- run --initial square.json --velocity rotation --t-end 0.5 \
    -K 3 -P 0 --domain 2 --frames 4 --out userframes --quiet
check "12 steps" test "$(json userframes/summary.json 's["params"]["N"]')" = 12
check "frames at evenly spaced times" test "$(python3 -c '
import json
ts = [json.load(open(f"userframes/frames/frame_{i:04d}.json"))["time"] for i in range(5)]
print(all(abs(t - 0.125 * i) < 1e-12 for i, t in enumerate(ts)))')" = True
expect_ok "a flow field's own steps" -- run --initial square.json --velocity rotation --t-end 0.5 \
    -K 3 -P 0 --domain 2 --out userten --quiet
check "10 steps" test "$(json userten/summary.json 's["params"]["N"]')" = 10

# A file's "time" is where the run starts; --t-end is where it ends.
echo '{"time": 0.5, "curves": [{"points": [[-1, -1], [1, -1], [1, 1], [-1, 1]]}]}' >late.json
expect_ok "run from the file's time" -- run --initial late.json --velocity rotation --t-end 1 -N 2 -K 3 -P 0 \
    --domain 2 --out late --quiet
check "ends at t-end" grep -q '"t": 1.0' late/summary.json
check "final.json keeps the time" grep -q '"time": 1' late/final.json
expect_error "t-end before the file's time" "t-end" -- run --initial late.json --velocity rotation --t-end 0.2 \
    --domain 2 --out early

echo '{"curves": [{"points": [[0, 0], [0.4, 0], [0, 0.4]]}]}' >small.json
expect_ok "shrinking to nothing" -- run --initial small.json --velocity unit-normal --param speed=-1 --t-end 1 \
    -N 10 -K 4 -P 0 --domain 1 --out gone --quiet
check "vanished status" grep -q '"status": "vanished"' gone/summary.json

# Curve shortening with the arclength module and arcs: the summary records them and the radius is
# right to 1e-4; a width must not be negative.
expect_ok "arclength module and arcs" -- run --problem circle-curvature --param R0=0.5 --t-end 0.1 --domain 1 \
    -N 10 -K 4 -P 2 --eps 1e-6 --geometry arclength --arcs --out arcs --quiet
check "summary records arcs" grep -q '"arcs": true' arcs/summary.json
check "summary records the width sqrt(k)" grep -q '"arc_width": 0.1' arcs/summary.json
# e_inf (Eq. 11, vertices and midpoints): 9.3e-5 here; 1.6e-3 with the embedded module and chords.
check "arcs: error below 1e-4" awk -F': ' '/"e_inf"/ { exit !($2 + 0 < 1e-4) }' arcs/summary.json
expect_error "negative arc width" "--arc-width" -- run --problem circle-curvature --arc-width -1 --out x
expect_error "unknown problem" "unknown problem 'nope'" -- run --problem nope --out x
expect_error "unknown velocity" "unknown velocity" -- run --initial square.json --velocity warp --t-end 1 --domain 2 --out x
expect_error "unknown parameter" "omeg" -- run --initial square.json --velocity rotation --param omeg=1 --t-end 1 --domain 2 --out x
expect_error "malformed parameter" "key=value" -- run --problem vortex --param period --out x
expect_error "zero steps" "steps" -- run --problem vortex -N 0 --out x
expect_error "negative eps" "eps" -- run --problem vortex --eps -1 --out x
expect_error "no input" "--problem|--initial" -- run --out x
expect_error "missing t-end" "t-end" -- run --initial square.json --velocity rotation --domain 2 --out x
# A user's curve with nothing set gets the law's defaults (docs/defaults.md): curvature laws the
# arclength module with arcs and P = 2; normal laws and flow fields the law itself off the curve,
# with arcs, refined until converged; eps and eta relative to the curves' half-width (here 1).
echo '{"curves": [{"points": [[1, 0], [0.5, 0.866], [-0.5, 0.866], [-1, 0], [-0.5, -0.866], [0.5, -0.866]]}]}' >hexagon.json
expect_ok "default curvature run" -- run --initial hexagon.json --velocity curvature --t-end 0.05 --out dcurv --quiet
check "curvature: arcs by default" grep -q '"arcs": true' dcurv/summary.json
check "curvature: two passes" grep -q '"P": 2' dcurv/summary.json
check "curvature: eps relative to the curve" grep -q '"eps": 1e-05' dcurv/summary.json
expect_ok "no arcs" -- run --initial hexagon.json --velocity curvature --t-end 0.05 --no-arcs --out nocurv --quiet
check "--no-arcs turns them off" grep -q '"arcs": false' nocurv/summary.json
expect_ok "default normal-speed run" -- run --initial hexagon.json --velocity unit-normal --t-end 0.2 -N 10 \
    --out dgrow --quiet
check "normal law: direct" grep -q '"extension": "direct"' dgrow/summary.json
check "normal law: refined until converged" grep -q '"P": "converged"' dgrow/summary.json
check "normal law: arcs" grep -q '"arcs": true' dgrow/summary.json
expect_ok "-P converged on a named problem" -- run --problem triangle-normal -N 4 -K 4 -P converged --out pconv --quiet
check "named problem keeps the nearest-point extension" grep -q '"extension": "nearest"' pconv/summary.json
# Growing past the default domain (1.5 times the hexagon's half-width) doubles it, once, saying so.
expect_ok "domain grows" -- run --initial hexagon.json --velocity unit-normal --t-end 1 -N 10 --out big --quiet
check "domain grows: one note on stderr" test "$(grep -c "domain grew" err.txt)" -eq 1
check "domain grows: summary says so" grep -q '"domain_grown"' big/summary.json
check "domain grows: status ok" grep -q '"status": "ok"' big/summary.json
# A drop 4e-3 across carried round LeVeque's vortex moves 0.2 in its first step, 50 times its
# size: the domain doubles 8 times (of the 10 a user's run allows) and the drop keeps its area.
awk 'BEGIN { printf "{\"curves\": [{\"points\": ["; for (i = 0; i < 128; i++)
    printf "%s[%.17g, %.17g]", (i ? ", " : ""), 0.76 + 0.002 * cos(2 * 3.141592653589793 * i / 128), 0.61 + 0.002 * sin(2 * 3.141592653589793 * i / 128)
    print "]}]}" }' >drop.json
expect_ok "a drop in the vortex" -- run --initial drop.json --velocity vortex --t-end 2 --out drop --quiet
check "a drop in the vortex: the domain doubled 8 times, status ok" test "$(json drop/summary.json 's["status"], s["domain_grown"]["doublings"]')" = "ok 8"
check "a drop in the vortex: area within 1e-4 of the circle's" json drop/summary.json '1 if abs(s["area"] / (3.141592653589793 * 0.002 ** 2) - 1) < 1e-4 else exit(1)'
# A named problem keeps the paper's fixed domain: leaving it is an error that names the setting.
expect_status "named problem leaves its domain" 3 -- run --problem triangle-normal --t-end 3 -N 10 -K 4 -P 0 --out out3 --quiet
# A rectangular box is taken as the square around it.
expect_ok "rectangular box" -- run --initial hexagon.json --velocity rotation --t-end 0.1 -N 2 --box -2,-1.5,2,1.5 \
    --out rect --quiet
check "rectangular box: the square around it" grep -q '"domain": \[' rect/summary.json
expect_ok "help lists the problems" -- run --help
check "help names zalesak" grep -q "zalesak" out.txt
tr -s ' \n' ' ' <out.txt >help_joined.txt  # the help is wrapped to 100 columns
check "help says --initial reads surfaces too" grep -q "a closed triangle surface (.obj, .stl, .ply; or .vdb, an OpenVDB file" help_joined.txt
check "help is wrapped to 100 columns" test -z "$(awk 'length($0) > 100' out.txt)"

# --estimate: one more run at half resolution; summary.json gets the distance between the two.
expect_ok "user run with --estimate" -- run --initial square.json --velocity rotation --t-end 0.5 -N 4 -K 4 \
    --domain 2 --threads 1 --estimate --out est --quiet
for key in error_estimate distance coarse estimate note coarse_status; do
    check "estimate: summary has $key" grep -q "\"$key\":" est/summary.json
done
check "estimate: the coarse run is N/2, K - 1, 4 eps (eps = 1e-4 from -K 4)" grep -q '"coarse": "2/0/3/converged/4e-04"' est/summary.json
check "estimate: a positive distance" grep -qE '"distance": [0-9.]+(e-?[0-9]+)?,' est/summary.json
expect_ok "named problem with --estimate" -- run --problem circle-curvature -N 8 -K 4 -P 1 --threads 1 \
    --estimate --out est_named --quiet
check "estimate of a named problem" grep -q '"error_estimate":' est_named/summary.json
check "without --estimate, no estimate" test -z "$(grep error_estimate user/summary.json)"
expect_error "--estimate with one step" "--estimate .* N >= 2" -- run --initial square.json --velocity rotation \
    --t-end 0.5 -N 1 --domain 2 --estimate --out est_bad
# The area correction keeps the area of the area-preserving flow at every step: the spiral's
# thin turns, where shifting every vertex by the same amount would fold the curve, included.
expect_ok "spiral with the area correction" -- run --problem spiral-nonlocal -N 40 --t-end 0.2 \
    --area-correction --out spiral_kept --quiet
check "spiral: area kept to 1e-10 at every step" awk -F, 'NR == 2 { a0 = $2 }
    NR > 2 && ($2 - a0 > 1e-10 * a0 || a0 - $2 > 1e-10 * a0) { bad = 1 } END { exit bad }' spiral_kept/history.csv
check "spiral: the correction reported" grep -q '"area_corrected"' spiral_kept/summary.json
# Without it the law's mean, fixed on the curve each step produces, keeps it to 1e-3 (5.6e-5
# here; 1.6e-2 with the mean over the curve the step starts from).
expect_ok "spiral without it" -- run --problem spiral-nonlocal -N 40 --t-end 0.2 --no-area-correction \
    --out spiral_free --quiet
check "spiral without it: the area kept to 1e-3" awk -F, 'NR == 2 { a0 = $2 }
    NR > 2 && ($2 - a0 > 1e-3 * a0 || a0 - $2 > 1e-3 * a0) { moved = 1 } END { exit moved }' spiral_free/history.csv
check "spiral without it: no correction reported" test -z "$(grep area_corrected spiral_free/summary.json)"
expect_ok "help documents --estimate" -- run --help
check "help names --estimate" grep -q -- "--estimate" out.txt
# Threads: OMP_NUM_THREADS sets the default, and a count beyond the cores this process may use
# runs on those cores (more threads would only wait on each other).
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)
OMP_NUM_THREADS=1 expect_ok "OMP_NUM_THREADS=1" -- run --problem circle-curvature -N 4 -K 4 --out omp1 --quiet
check "OMP_NUM_THREADS=1: one thread" test "$(json omp1/summary.json 's["threads"]')" = 1
expect_ok "--threads 1024" -- run --problem circle-curvature -N 4 -K 4 --threads 1024 --out t1024 --quiet
check "--threads 1024: the $cores cores there are" test "$(json t1024/summary.json 's["threads"]')" = "$cores"
check "--threads 1024: the same result" cmp -s omp1/final.json t1024/final.json

# --until-components: the coarsening of six particles stops when three are left, before t_end; its
# frames end with where it stopped (frame 1 of --frames 10, every 50 of the 500 steps).
expect_ok "coarsening until three" -- run --problem coarsening --param count=6 --param left=3 \
    --frames 10 --out co --quiet
check "coarsening: three left" test "$(json co/summary.json 's["components"]')" = 3
check "coarsening: stopped before t_end" json co/summary.json '1 if s["t"] < s["params"]["t_end"] else exit(1)'
check "coarsening: the last frame is where it stopped" test \
    "$(json co/frames/frame_0001.json 's["time"]')" = "$(json co/summary.json 's["t"]')"
check "coarsening: no frame beyond it" test ! -e co/frames/frame_0002.json

finish
