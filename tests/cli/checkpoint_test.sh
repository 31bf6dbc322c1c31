# slc run --checkpoint-every and --resume: a run stopped and resumed ends with the same final
# interface, byte for byte (17 significant digits: the same doubles), as a run never stopped.
source "$(dirname "$0")/lib.sh" "$1"

same_run() {  # same_run NAME A B: final.json identical, the history and the summaries but for clocks and memory
    check "$1: final.json identical" cmp -s "$2/final.json" "$3/final.json"
    check "$1: history identical but cpu_s" diff <(cut -d, -f1-5 "$2/history.csv") <(cut -d, -f1-5 "$3/history.csv")
    check "$1: summary identical but clocks and memory" diff <(grep -vE '"(wall_s|cpu_s|cpu_s_per_step|peak_rss_mib)"' "$2/summary.json") \
        <(grep -vE '"(wall_s|cpu_s|cpu_s_per_step|peak_rss_mib)"' "$3/summary.json")
}

# Uninterrupted, then the same run checkpointed every 6 steps and resumed from its last checkpoint
# (step 18 of 20): steps 19 and 20 again, with the frames written before (and their VTK series).
run_args=(run --problem zalesak -N 20 -K 6 -P 1 --frames 4 --vtk --quiet)
expect_ok "uninterrupted" -- "${run_args[@]}" --out full
expect_ok "checkpointed" -- "${run_args[@]}" --checkpoint-every 6 --out part
check "checkpoint written" test -s part/checkpoint.json
check "last checkpoint after step 18" grep -q '"steps_done":18' part/checkpoint.json
same_run "checkpointing changes nothing" full part
rm part/final.json part/summary.json part/frames.png part/frames.pvd part/frames/frame_0000.vtp
expect_ok "resume" -- run --resume part --quiet
same_run "resumed from step 18" full part
check "resume redraws the frames" test -s part/frames.png
check "resume writes the VTK series again" cmp -s full/frames.pvd part/frames.pvd
check "resume rewrites the VTK frames" cmp -s full/frames/frame_0000.vtp part/frames/frame_0000.vtp
check "VTK series of 4 frames and the initial one" test "$(grep -c '<DataSet' part/frames.pvd)" -eq 5

# The arclength module, arcs and a width are options of the run like the others: the checkpoint
# keeps them (a resume without them would end elsewhere).
arc_args=(run --problem circle-curvature --param R0=0.5 --t-end 0.1 --domain 1 -N 10 -K 4 -P 2
          --geometry arclength --arcs --arc-width 0.08 --quiet)
expect_ok "arcs" -- "${arc_args[@]}" --out arcs_full
expect_ok "arcs checkpointed" -- "${arc_args[@]}" --checkpoint-every 3 --out arcs_part
rm arcs_part/final.json arcs_part/summary.json
expect_ok "arcs resumed" -- run --resume arcs_part --quiet
same_run "arcs resumed from step 9" arcs_full arcs_part

# A user's curve under a law: the checkpoint keeps a copy of the file, so that resuming does not
# depend on the original staying where it was.
echo '{"curves": [{"points": [[-1, -1], [1, -1], [1, 1], [-1, 1]]}]}' >square.json
user_args=(run --initial square.json --velocity rotation --param omega=2 --t-end 0.5 -N 5 -K 4 -P 1
           --domain 2 --quiet)
expect_ok "user curve" -- "${user_args[@]}" --out user_full
expect_ok "user curve checkpointed" -- "${user_args[@]}" --checkpoint-every 2 --out user_part
rm square.json user_part/final.json user_part/summary.json
expect_ok "user curve resumed" -- run --resume user_part --quiet
same_run "user curve resumed from step 4" user_full user_part

# Under curvature flow a user's run holds its area to the law's change (area_lag,
# area_law_change), which the checkpoint keeps: the resumed run splits the same steps.
echo '{"curves": [{"points": [[1.0, 0.0], [0.450484, 0.216942], [0.62349, 0.781831], [0.11126, 0.487464], [-0.222521, 0.974928], [-0.311745, 0.390916], [-0.900969, 0.433884], [-0.5, 0.0], [-0.900969, -0.433884], [-0.311745, -0.390916], [-0.222521, -0.974928], [0.11126, -0.487464], [0.62349, -0.781831], [0.450484, -0.216942]]}]}' >star.json
star_args=(run --initial star.json --velocity curvature --t-end 0.02 --quiet)
expect_ok "star under curvature" -- "${star_args[@]}" --out star_full
expect_ok "star checkpointed" -- "${star_args[@]}" --checkpoint-every 10 --out star_part
check "star checkpoint keeps the law's area change" grep -q '"area_law_change":-0.0942' star_part/checkpoint.json
rm star_part/final.json star_part/summary.json
expect_ok "star resumed" -- run --resume star_part --quiet
same_run "star resumed from step 30" star_full star_part

# A surface: final.obj, history.csv, the frames (.vtp, .pvd) and the summary as the run never
# stopped; a user's surface file is copied into the folder as a curve file is.
surface_args=(run --problem sphere-rotation --t-end 1.5 -N 6 -K 4 --eps 2e-3 --frames 3 --quiet)
expect_ok "surface" -- "${surface_args[@]}" --out surface_full
expect_ok "surface checkpointed" -- "${surface_args[@]}" --checkpoint-every 2 --out surface_part
check "surface checkpoint after step 4" grep -q '"steps_done":4' surface_part/checkpoint.json
rm surface_part/final.obj surface_part/summary.json surface_part/frames.pvd
expect_ok "surface resumed" -- run --resume surface_part --quiet
for f in final.obj history.csv frames.pvd frames/frame_0003.vtp; do
    check "surface resumed from step 4: $f identical" cmp -s "surface_full/$f" "surface_part/$f"
done
check "surface resumed: summary identical but clocks" \
    diff <(grep -vE '"(wall_s|cpu_s)"' surface_full/summary.json) <(grep -vE '"(wall_s|cpu_s)"' surface_part/summary.json)
cp surface_full/initial.obj ball.obj
ball_args=(run --initial ball.obj --velocity rotation --param omega=2 --t-end 0.5 -N 4 -K 4 --eps 2e-3 --domain 1 --quiet)
expect_ok "user surface" -- "${ball_args[@]}" --out ball_full
expect_ok "user surface checkpointed" -- "${ball_args[@]}" --checkpoint-every 3 --out ball_part
rm ball.obj ball_part/final.obj ball_part/summary.json
expect_ok "user surface resumed" -- run --resume ball_part --quiet
check "user surface resumed from step 3: final.obj identical" cmp -s ball_full/final.obj ball_part/final.obj
# A run whose domain grew resumes in the grown domain.
cp surface_full/initial.obj ball.obj
away_args=(run --initial ball.obj --velocity translation --param ux=1 --param uy=0 --param uz=0 --t-end 1.5 -N 6 -K 4 --eps 2e-3 --quiet)
expect_ok "surface leaving its domain" -- "${away_args[@]}" --out away_full
expect_ok "surface leaving its domain, checkpointed" -- "${away_args[@]}" --checkpoint-every 4 --out away_part
rm away_part/final.obj away_part/summary.json
expect_ok "surface in a grown domain resumed" -- run --resume away_part --quiet
check "resumed in the grown domain: final.obj identical" cmp -s away_full/final.obj away_part/final.obj
expect_error "resume refuses a finished surface run" "after the checkpoint's step 3" -- run --resume ball_part --quiet

# Stopped by SIGTERM while running: status interrupted, a checkpoint at the step it stopped after,
# and the resumed run ends as the uninterrupted one. (Should the run finish before the signal,
# the last regular checkpoint is resumed: the comparison holds either way.)
long_args=(run --problem zalesak -N 100 -K 6 -P 1 --quiet)
expect_ok "long run" -- "${long_args[@]}" --out long_full
"$SLC" "${long_args[@]}" --checkpoint-every 1 --out long_part 2>err.txt &
pid=$!
for _ in $(seq 200); do [ -s long_part/checkpoint.json ] && break; sleep 0.05; done
kill -TERM "$pid"
wait "$pid"
status=$?
check "SIGTERM: exit status 143 (0 had it finished)" test "$status" -eq 143 -o "$status" -eq 0
check "SIGTERM: status interrupted (or ok had it finished)" \
    grep -qE '"status": "(interrupted|ok)"' long_part/summary.json
check "SIGTERM: one line on stderr" test "$(wc -l <err.txt)" -le 1
# A run that finished has results newer than its last checkpoint, which --resume refuses.
if grep -q '"status": "ok"' long_part/summary.json; then rm long_part/summary.json; fi
expect_ok "resume after SIGTERM" -- run --resume long_part --quiet
same_run "resumed after SIGTERM" long_full long_part

# SIGTERM within a long step of a surface (here the contour at K = 7 that reads the surface, some
# 20 s and more): the run stops at the next stage of the step, not at its end, and says so in
# one line with status 143 (before, a 60 s step ran to its end first).
"$SLC" run --initial ball.obj --velocity unit-normal --t-end 0.01 -N 1 -K 7 --out slow --quiet 2>err.txt &
pid=$!
for _ in $(seq 200); do ls -d slow.slc-* >/dev/null 2>&1 && break; sleep 0.05; done
sleep 1
kill -TERM "$pid"
stopped=0
for _ in $(seq 600); do kill -0 "$pid" 2>/dev/null || { stopped=1; break; }; sleep 0.05; done
check "SIGTERM within a step: the process ends within 30 s" test "$stopped" -eq 1
[ "$stopped" -eq 1 ] || kill -KILL "$pid"
wait "$pid"
status=$?
check "SIGTERM within a step: exit status 143" test "$status" -eq 143
check "SIGTERM within a step: one line naming it" \
    sh -c 'test "$(wc -l <err.txt)" -eq 1 && grep -q "interrupted by SIGTERM" err.txt'

# SIGTERM during the final writes (here during --estimate's second run, which follows
# final.json): the writes are finished, then exit 143. (Should the run finish before the
# signal, it exits 0 with the same files.)
"$SLC" run --problem zalesak -N 20 -K 6 --estimate --out late --quiet 2>err.txt &
pid=$!
seen=0
for _ in $(seq 3000); do ls late.slc-*/final.json >/dev/null 2>&1 && { seen=1; break; }; sleep 0.02; done
check "SIGTERM in the final writes: final.json seen within 60 s" test "$seen" -eq 1
kill -TERM "$pid"
wait "$pid"
status=$?
check "SIGTERM in the final writes: exit 143 (0 had it finished)" test "$status" -eq 143 -o "$status" -eq 0
for f in final.json final.png final.svg history.csv history.png summary.json; do
    check "SIGTERM in the final writes: $f written" test -s "late/$f"
done
check "SIGTERM in the final writes: status ok" grep -q '"status": "ok"' late/summary.json
if [ "$status" -eq 143 ]; then
    check "SIGTERM in the final writes: one line saying so" grep -q "SIGTERM came after the last step; the results in late are written whole" err.txt
    check "SIGTERM in the final writes: one line" test "$(wc -l <err.txt)" -eq 1
fi
check "SIGTERM in the final writes: no working folder left" test -z "$(ls -d late.slc-* late.lock 2>/dev/null)"

# Ctrl-C (SIGINT) the same way: the results written whole, exit status 130.
"$SLC" "${long_args[@]}" --checkpoint-every 1 --out int_part 2>err.txt &
pid=$!
for _ in $(seq 200); do [ -s int_part/checkpoint.json ] && break; sleep 0.05; done
kill -INT "$pid"
wait "$pid"
status=$?
check "SIGINT: exit status 130 (0 had it finished)" test "$status" -eq 130 -o "$status" -eq 0
check "SIGINT: a whole summary" grep -qE '"status": "(interrupted|ok)"' int_part/summary.json
check "SIGINT: no working folder left" test -z "$(ls -d int_part.slc-* int_part.lock 2>/dev/null)"

# Output folders are replaced whole: a run without checkpoints into the folder of a run with
# them leaves no frame, checkpoint or history of the first.
expect_ok "run A, checkpointed, 4 frames" -- run --problem zalesak -N 8 -K 6 -P 1 --frames 4 --checkpoint-every 2 --quiet --out mixed
expect_ok "run B into the same folder" -- run --problem circle-curvature -N 2 -K 3 -P 0 --quiet --out mixed
check "run B left no frame of A" test ! -e mixed/frames
check "run B left no checkpoint of A" test ! -e mixed/checkpoint.json
check "run B's summary" grep -q '"problem": "circle-curvature"' mixed/summary.json
check "no working folder left" test -z "$(ls -d mixed.slc-* mixed.lock 2>/dev/null)"
expect_error "resume B (no checkpoint)" "cannot read mixed/checkpoint.json" -- run --resume mixed

# A checkpoint carries its run's identity: beside the results of another run it is refused, as
# it is when the results are newer than it (the run finished after it).
expect_ok "run C, checkpointed" -- run --problem circle-curvature -N 6 -K 4 -P 0 --checkpoint-every 2 --quiet --out other
cp other/checkpoint.json mixed/checkpoint.json
expect_error "resume a checkpoint beside another run's results" "mixed/summary.json: the results in the folder belong to another run" -- run --resume mixed
expect_error "resume a finished run" "other/summary.json: the results are of step 6, after the checkpoint's step 4" -- run --resume other
check "the refused resume left the results" grep -q '"steps_done": 6' other/summary.json

# A checkpoint is read as an interface file is: crossing curves are bad input, not an internal error.
rm other/summary.json
sed -E 's/"curves":[^"]*,"domain/"curves":[[0.2,0.2,0.8,0.8,0.8,0.2,0.2,0.8]],"domain/' other/checkpoint.json >crossed.json
mv crossed.json other/checkpoint.json
expect_error "resume a checkpoint of crossing curves" "other/checkpoint.json: curve 0 crosses itself" -- run --resume other

# A second writer of a folder is refused at once (here the lock is held by this shell).
exec 9>busy.lock
flock 9
expect_error "a second writer" "--out busy: another slc is writing this folder" -- run --problem vortex -N 2 -K 3 --quiet --out busy
exec 9>&-
check "the refused writer wrote nothing" test ! -e busy

# A full disk (here a file size limit) leaves the earlier results whole and no working folder.
expect_ok "earlier run" -- run --problem circle-curvature -N 2 -K 3 -P 0 --quiet --out kept
cp kept/summary.json kept_summary.json
(trap '' XFSZ; ulimit -f 4; "$SLC" run --problem vortex -N 2 -K 5 -P 0 --frames 2 --quiet --out kept >out.txt 2>err.txt)
check "disk full: exit status 2" test $? -eq 2
check "disk full: one line naming the file" grep -q "cannot write .*File too large" err.txt
check "disk full: earlier summary kept" cmp -s kept/summary.json kept_summary.json
check "disk full: no frames of the failed run" test ! -e kept/frames
check "disk full: no working folder left" test -z "$(ls -d kept.slc-* 2>/dev/null)"

# Bad use of --resume.
expect_error "resume with other options" "--steps cannot be given" -- run --resume part --steps 3
expect_error "resume without checkpoint" "cannot read" -- run --resume nowhere
echo '{"format": "slc run checkpoint 2"}' >part/checkpoint.json
expect_error "resume a broken checkpoint" "not a checkpoint" -- run --resume part
expect_error "checkpoint-every 0" "checkpoint-every" -- run --problem vortex --checkpoint-every 0 --out x
finish
