# Every rejected input of docs/errors.md: exit status 2 and exactly one line on stderr naming the
# problem. With ERRORS_TABLE=FILE set, each case also appends its row (input, message, status) to
# FILE: that is how the table in docs/errors.md is written.
source "$(dirname "$0")/lib.sh" "$1"

table="${ERRORS_TABLE:-}"
if [ -n "$table" ]; then : >"$table"; fi
section() { if [ -n "$table" ]; then printf '| **%s** | | |\n' "$1" >>"$table"; fi; }

# reject WHAT PATTERN -- ARGS...: expect_error, and the row of the table.
reject() {
    local what="$1" pattern="$2"
    local before=$failures
    expect_error "$@"
    if [ -n "$table" ] && [ "$failures" -eq "$before" ]; then
        local message
        message=$(sed 's/|/\\|/g' err.txt)
        printf '| %s | `%s` | 2 |\n' "$what" "$message" >>"$table"
    fi
}

echo '0,0' >origin.csv
square_json >square.json
interface() { printf '{"curves": [{"points": %s}]}\n' "$1"; }  # one curve from its points

section "interface files (--initial, here of slc distance)"
reject "missing file" "cannot read nowhere.json" -- distance --initial nowhere.json --points origin.csv
echo 'hello' >notjson.json
reject "not JSON" "notjson.json: not valid JSON" -- distance --initial notjson.json --points origin.csv
echo '{"curves": [{"points": [[0, 0], [1, 0],' >truncated.json
reject "truncated" "truncated.json: not valid JSON" -- distance --initial truncated.json --points origin.csv
printf '\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe' >garbage.json
reject "binary garbage" "garbage.json: not valid JSON" -- distance --initial garbage.json --points origin.csv
: >empty.json
reject "empty file" "empty.json: not valid JSON" -- distance --initial empty.json --points origin.csv
echo '[[0, 0], [1, 0], [0, 1]]' >array.json
reject "not an object" 'array.json: no "curves" array' -- distance --initial array.json --points origin.csv
echo '{"time": 0}' >nocurves.json
reject "no \"curves\" key" 'nocurves.json: no "curves" array' -- distance --initial nocurves.json --points origin.csv
echo '{"curves": {"points": []}}' >curvesobject.json
reject "\"curves\" not an array" 'curvesobject.json: no "curves" array' -- distance --initial curvesobject.json --points origin.csv
echo '{"curves": [{"pts": [[0, 0], [1, 0], [0, 1]]}]}' >nopoints.json
reject "a curve without \"points\"" 'curve 0 has no "points" array' -- distance --initial nopoints.json --points origin.csv
interface '[[0, 0], ["1", 0], [0, 1]]' >string.json
reject "a coordinate that is a string" "curve 0, point 1 is not a pair of numbers" -- distance --initial string.json --points origin.csv
interface '[[0, 0], [1, 0], [0, 1, 2]]' >triple.json
reject "a point of three numbers" "curve 0, point 2 is not a pair of numbers" -- distance --initial triple.json --points origin.csv
echo '{"time": "zero", "curves": [{"points": [[0, 0], [1, 0], [0, 1]]}]}' >timestring.json
reject "\"time\" not a number" '"time" is not a number' -- distance --initial timestring.json --points origin.csv
echo '{"time": 1e999, "curves": [{"points": [[0, 0], [1, 0], [0, 1]]}]}' >timeinf.json
reject "\"time\" not finite" '"time" is not finite' -- distance --initial timeinf.json --points origin.csv
echo '{"curves": []}' >nocurve.json
reject "no curves" "nocurve.json: no curves: the interface is empty" -- distance --initial nocurve.json --points origin.csv
interface '[[0, 0], [1, 0]]' >two.json
reject "fewer than 3 points" "two.json: curve 0 has 2 distinct points" -- distance --initial two.json --points origin.csv
interface '[[0, 0], [1, 0], [1, 0], [0, 0]]' >repeated.json
reject "3 points or more, fewer than 3 distinct" "curve 0 has 2 distinct points" -- distance --initial repeated.json --points origin.csv
interface '[[0, 0], [1, 0], [0, NaN]]' >nan.json
reject "NaN (not JSON)" "nan.json: not valid JSON" -- distance --initial nan.json --points origin.csv
interface '[[0, 0], [1, 0], [0, 1e999]]' >inf.json
reject "infinite coordinate" "curve 0, point 2 has a non-finite coordinate" -- distance --initial inf.json --points origin.csv
interface '[[0, 0], [1e300, 0], [0, 1e300]]' >huge.json
reject "huge coordinate" "curve 0, vertex 1: .* beyond the coordinate limit" -- distance --initial huge.json --points origin.csv
interface '[[0, 0], [1e-200, 0], [0, 1e-200]]' >tiny.json
reject "curves too small for doubles" "tiny.json: the curves span only 1e-200" -- distance --initial tiny.json --points origin.csv
interface '[[0, 0], [3, 0], [0, 3]]' >outside.json
reject "point outside the domain" "curve 0, vertex 1: point \(3, 0\) lies outside the domain" -- distance --initial outside.json --points origin.csv --domain 2
interface '[[0, 0], [1, 1], [1, 0], [0, 1]]' >bowtie.json
reject "self-intersecting curve" "bowtie.json: curve 0 crosses itself: segment 0 meets segment 2" -- distance --initial bowtie.json --points origin.csv
echo '{"curves": [{"points": [[0, 0], [2, 0], [2, 2], [0, 2]]}, {"points": [[1, 1], [3, 1], [3, 3]]}]}' >crossing.json
reject "curves crossing each other" "crossing.json: curve 0 crosses curve 1" -- distance --initial crossing.json --points origin.csv
echo '{"curves": [{"points": [[0, 0], [2, 0], [2, 2], [0, 2]]}, {"points": [[2, 1], [3, 1], [3, 2]]}]}' >touching.json
reject "curves touching each other" "touching.json: curve 0 crosses curve 1" -- distance --initial touching.json --points origin.csv
# 2,000,001 points: refused while counting, before the document is built.
awk 'BEGIN { printf "{\"curves\": [{\"points\": [[0, 0]"; for (i = 0; i < 2000000; ++i) printf ", [0, 0]"; print "]}]}" }' >millions.json
reject "more than 2,000,000 points" "millions.json: more than 2000000 points" -- distance --initial millions.json --points origin.csv
rm millions.json
# A unit square at 1e12, where doubles are 1.2e-4 apart: cells of depth 20 would be 4e-6 wide.
interface '[[1e12, 1e12], [1000000000001, 1e12], [1000000000001, 1000000000001], [1e12, 1000000000001]]' >far.json
reject "tree too deep for doubles (far from the origin)" "tree depth 20 is too deep for doubles" -- \
    distance --initial far.json --points origin.csv -L 20

section "points files (--points of slc distance)"
reject "missing file" "cannot read nowhere.csv" -- distance --initial square.json --points nowhere.csv
cp square.json points.csv
reject "not CSV (a JSON file)" "points.csv, line 1: expected 2 columns x,y, got 9" -- distance --initial square.json --points points.csv
printf 'x,y\n0,0\n1\n' >one.csv
reject "one column" "one.csv, line 3: expected 2 columns x,y, got 1" -- distance --initial square.json --points one.csv
printf '0,0,0\n' >three.csv
reject "three columns" "three.csv, line 1: expected 2 columns x,y, got 3" -- distance --initial square.json --points three.csv
printf '0,zero\n' >word.csv
reject "not a number" 'word.csv, line 1: y = "zero" is not a number' -- distance --initial square.json --points word.csv
printf '0,0\n\x01\x02\x1b[1m,0\n' >control.csv
reject "binary garbage (shown as ?)" 'control.csv, line 2: x = "\?\?\?\[1m" is not a number' -- distance --initial square.json --points control.csv
printf 'nan,0\n' >nan.csv
reject "NaN" 'nan.csv, line 1: x = "nan" is not finite' -- distance --initial square.json --points nan.csv
printf '0,1e400\n' >overflow.csv
reject "beyond a double" 'overflow.csv, line 1: y = "1e400" is out of the range of a double' -- distance --initial square.json --points overflow.csv
printf '1e300,0\n' >huge.csv
reject "beyond the coordinate limit" 'huge.csv, line 1: x = "1e300" is beyond the coordinate limit' -- distance --initial square.json --points huge.csv

section "parameters (slc run, and the same options of the other commands)"
reject "no subcommand" "A subcommand is required" --
reject "unknown option" "not expected: --fast" -- run --problem vortex --fast --out x
reject "unknown problem" "unknown problem 'nope'; known: " -- run --problem nope --out x
reject "unknown velocity" "unknown velocity 'warp'; known: " -- run --initial square.json --velocity warp --t-end 1 --out x
reject "unknown velocity parameter" "velocity 'rotation' has no parameter 'omeg'" -- run --initial square.json --velocity rotation --param omeg=1 --t-end 1 --out x
reject "malformed or non-finite --param" "--param expects key=value with a finite number, got 'omega=nan'" -- run --initial square.json --velocity rotation --param omega=nan --t-end 1 --out x
reject "neither --problem nor --initial" "give --problem NAME or --initial FILE" -- run --out x
reject "both --problem and --initial" "--problem excludes --initial" -- run --problem vortex --initial square.json --out x
reject "--initial without --velocity" "--initial needs --velocity" -- run --initial square.json --t-end 1 --out x
reject "--initial without --t-end" "--initial needs --t-end" -- run --initial square.json --velocity rotation --out x
reject "no --out" "--out DIR is required" -- run --problem vortex
reject "steps 0" "--steps: must be an integer from 1 to 100000000, got '0'" -- run --problem vortex -N 0 --out x
reject "steps negative" "--steps: must be an integer from 1 to 100000000, got '-5'" -- run --problem vortex -N -5 --out x
reject "steps not an integer" "--steps: must be an integer from 1 to 100000000, got '1.5'" -- run --problem vortex -N 1.5 --out x
reject "depth 0" "--depth: must be an integer from 1 to 24, got '0'" -- run --problem vortex -K 0 --out x
reject "depth 25" "--depth: must be an integer from 1 to 24, got '25'" -- run --problem vortex -K 25 --out x
reject "tree depth 31" "--tree-depth: must be an integer from 1 to 30, got '31'" -- run --problem vortex -L 31 --out x
reject "depth too deep for doubles" "tree depth 20 is too deep for doubles" -- run --initial far.json --velocity rotation --t-end 1 -K 20 -P 0 --eps 1e-9 --out x
reject "refine passes negative" "--refine: must be an integer from 0 to 64 or 'converged', got '-1'" -- run --problem vortex -P -1 --out x
reject "eps 0" "--eps: must be a positive finite number, got '0'" -- run --problem vortex --eps 0 --out x
reject "eps negative" "--eps: must be a positive finite number, got '-1e-3'" -- run --problem vortex --eps -1e-3 --out x
reject "eps NaN" "--eps: must be a positive finite number, got 'nan'" -- run --problem vortex --eps nan --out x
reject "eta infinite" "--eta: must be a positive finite number, got 'inf'" -- run --problem vortex --eta inf --out x
reject "eps below eta (both given; an η left unset is lowered to ε/10)" "--eps \(1e-12\) must not be below --eta \(1e-10\)" -- run --problem vortex --eps 1e-12 --eta 1e-10 --out x
reject "rho 1" "--rho: must be a number in \[0, 1\), got '1'" -- run --problem vortex --rho 1 --out x
reject "t-end NaN" "t-end must be finite and after the start time 0, got nan" -- run --problem vortex --t-end nan --out x
reject "t-end infinite" "t-end must be finite and after the start time 0, got inf" -- run --problem vortex --t-end inf --out x
reject "t-end before the start" "t-end must be finite and after the start time 0, got -1" -- run --problem vortex --t-end -1 --out x
reject "a motion beyond the coordinate limit (t-end)" "velocity 'unit-normal' at speed up to 1 moves the curves by up to 1e\+308 .* beyond the coordinate limit ±1e\+100, where the arithmetic overflows: lower the speed or t-end" -- run --initial square.json --velocity unit-normal --t-end 1e308 --out x
reject "a motion beyond the coordinate limit (speed)" "at speed up to 1e\+200 moves the curves by up to 1e\+200 .* overflows" -- run --initial square.json --velocity unit-normal --param speed=1e200 --t-end 1 --out x
reject "a speed that is not a number" "velocity 'speed = sqrt\(-1\)' has a speed of nan, not a finite number" -- run --initial square.json --speed "sqrt(-1)" --t-end 0.1 --out x
reject "an infinite speed" "velocity 'speed = 1/0' has a speed of inf, not a finite number" -- run --initial square.json --speed "1/0" --t-end 0.1 --out x
reject "backward curvature flow" "speed 'a - C' falls as the curvature C grows \(dv/dC = -1 at .*\): motion backward in curvature is ill-posed" -- run --initial square.json --speed "a - C" --param a=1 --t-end 0.1 --out x
reject "box of three numbers" "--box must be four numbers x0,y0,x1,y1, got '0,0,1'" -- run --problem vortex --box 0,0,1 --out x
reject "box NaN" "--box must have x0 < x1 and y0 < y1, all finite" -- run --problem vortex --box 0,0,nan,nan --out x
reject "box beyond the coordinate limit" "--box corners must lie within" -- run --problem vortex --box 0,0,1e200,1e200 --out x
reject "domain 0" "--domain must be a positive half-width up to 1e\+100, got 0" -- run --problem vortex --domain 0 --out x
reject "domain NaN" "--domain must be a positive half-width up to 1e\+100, got nan" -- run --problem vortex --domain nan --out x
reject "domain beyond the coordinate limit" "--domain must be a positive half-width up to 1e\+100, got 1e\+200" -- run --problem vortex --domain 1e200 --out x
reject "unknown extension" "--extension: bogus not in" -- run --problem vortex --extension bogus --out x
reject "unknown geometry module" "--geometry: bogus not in" -- run --problem vortex --geometry bogus --out x
reject "negative arc width" "--arc-width: must be a finite number >= 0, got '-1'" -- run --problem circle-curvature --arc-width -1 --out x
reject "arc width not a number" "--arc-width: must be a finite number >= 0, got 'wide'" -- study --problem circle-curvature --arc-width wide --out x
reject "threads negative" "--threads: must be an integer from 0 to 1024, got '-1'" -- run --problem vortex --threads -1 --out x
reject "frames negative" "--frames: must be an integer from 0 to 100000, got '-1'" -- run --problem vortex --frames -1 --out x
reject "checkpoint-every 0" "--checkpoint-every: must be an integer from 1 to 100000000, got '0'" -- run --problem vortex --checkpoint-every 0 --out x
reject "--resume without a checkpoint" "cannot read nowhere/checkpoint.json" -- run --resume nowhere
mkdir -p broken && echo '{"format": "slc run checkpoint 1"}' >broken/checkpoint.json
reject "--resume of a broken checkpoint" "broken/checkpoint.json: not a checkpoint of slc run" -- run --resume broken
reject "--resume with other options" "--steps cannot be given with it" -- run --resume broken -N 3
"$SLC" run --problem circle-curvature -N 4 -K 3 -P 0 --checkpoint-every 2 --out cut --quiet
rm cut/summary.json  # a finished run is not resumed
head -n 2 cut/history.csv >cut/history.csv.new && mv cut/history.csv.new cut/history.csv
reject "--resume with a history shorter than the checkpoint" \
    "cut/history.csv: the checkpoint after step 2 needs 3 time levels, the file has 1" -- run --resume cut
reject "contour depth 21" "--depth: must be an integer from 0 to 20, got '21'" -- contour --initial square.json -K 21 --out x
reject "study rows 6" "--rows: must be an integer from 1 to 5, got '6'" -- study --problem vortex --rows 6 --out x
reject "study of your curve with one row" "--rows must be 3 to 5 with --initial" -- \
    study --initial square.json --velocity rotation --t-end 1 --domain 2 --rows 1 --out x
reject "study of a problem and your curve" "--problem excludes --initial" -- \
    study --problem vortex --initial square.json --out x
reject "study deeper than K = 24" "the finest of 3 resolutions would have K = 25" -- \
    study --initial square.json --velocity rotation --t-end 1 --domain 2 -K 23 --eps 1e-6 --out x
reject "--estimate with one step" "--estimate compares with the run at half resolution" -- \
    run --initial square.json --velocity rotation --t-end 1 --domain 2 -N 1 --estimate --out x

section "velocity expressions and lattice files (--speed, --field, --field-file of slc run)"
law=(run --initial square.json --t-end 1 --domain 2 --out x)
reject "syntax error" "speed expression 'x \+': unexpected end of expression at position 4" -- "${law[@]}" --speed "x +"
reject "unknown name" "speed expression 'a - k': unknown name 'k' at position 4 \(the variables are x, y, t, C, nx, ny; the constants a\)" -- \
    "${law[@]}" --speed "a - k" --param a=1
reject "unbalanced parenthesis" "speed expression 'sin\(x': missing parenthesis" -- "${law[@]}" --speed "sin(x"
reject "empty expression" "speed expression is empty" -- "${law[@]}" --speed ""
reject "two values for a speed" "speed expression '1, 2': gives 2 values separated by commas; a normal speed is one" -- "${law[@]}" --speed "1, 2"
reject "one component for a field" "field expression '-y': gives 1 value; a flow field needs two, u and v" -- "${law[@]}" --field "-y"
reject "curvature in a field" "field expression 'C, 0': unknown name 'C' at position 0 \(the variables are x, y, t\)" -- "${law[@]}" --field "C, 0"
reject "constant named as a variable" "speed expression '1': the constant 'x' is a variable of the expression" -- \
    "${law[@]}" --speed 1 --param x=1
reject "constant named as a function" "speed expression '1': the constant 'sin' is a function of the expressions" -- \
    "${law[@]}" --speed 1 --param sin=1
reject "two laws" "give one velocity law of --velocity, --speed, --field and --field-file, got --velocity and --speed" -- \
    "${law[@]}" --velocity rotation --speed 1
reject "a law with a problem" "--problem excludes --speed" -- run --problem vortex --speed 1 --out x
reject "missing lattice file" "cannot read nowhere.csv: No such file or directory" -- "${law[@]}" --field-file nowhere.csv
printf 'x,y,u,v\n0,0,1,1\n1,0,1\n' >short.csv
reject "lattice line of 3 numbers" "short.csv, line 3: expected 4 numbers x,y,u,v, got '1,0,1'" -- "${law[@]}" --field-file short.csv
printf '0,0,1,1\n1,0,1,1\n0,1,1,1\n' >missing.csv
reject "lattice point missing" "missing.csv: 3 lines for a lattice of 2 x 2 points; each point needs exactly one line" -- \
    "${law[@]}" --field-file missing.csv
printf '0,0,1,1\n1,0,1,1\n3,0,1,1\n0,1,1,1\n1,1,1,1\n3,1,1,1\n' >uneven.csv
reject "lattice not uniform" "uneven.csv: the x values are not evenly spaced" -- "${law[@]}" --field-file uneven.csv
printf '0,0,1,1\n1,0,1,1\n0,1,1,1\n0,1,2,2\n' >twice.csv
reject "lattice point twice" "twice.csv, line 4: the point \(0, 1\) appears twice" -- "${law[@]}" --field-file twice.csv
printf '# vtk DataFile Version 3.0\nv\nBINARY\n' >binary.vtk
reject "binary VTK" "binary.vtk: only ASCII legacy VTK files are read, this one is 'BINARY'" -- "${law[@]}" --field-file binary.vtk
printf '# vtk DataFile Version 3.0\nv\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 1\nORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA 4\nSCALARS p float\nLOOKUP_TABLE default\n1 2 3 4\n' >scalar.vtk
reject "VTK without a vector array" "scalar.vtk: no point-data array with 2 or 3 components" -- "${law[@]}" --field-file scalar.vtk
printf -- '-3,-3,1,0\n3,-3,1,0\n-3,3,1,0\n3,3,1,0\n' >small.csv
reject "curves outside the lattice" "the initial curves leave the region where velocity 'field-file small.csv' is known, \[-3, 3\] x \[-3, 3\]" -- \
    run --initial far.json --t-end 1 --out x --field-file small.csv
section "surfaces (slc run, slc study)"
reject "an option of curves" "--vtk is for curves, not surfaces" -- run --problem sphere-rotation --vtk --out x
reject "a setting of a surface study" "-K/--depth does not apply to the study of a surface" -- \
    study --problem sphere-rotation -K 4 --out x
reject "a surface problem without a study" "problem 'enright' has no convergence study" -- \
    study --problem enright --out x
reject "--columns for curves" "--columns is for the study of a surface" -- \
    study --problem circle-curvature --columns 2 --out x

section "output folders, input sizes and memory"
echo 'not a folder' >afile
reject "--out at a file" "--out afile: a file exists and is not a folder" -- run --problem vortex -N 1 -K 3 --out afile
reject "--out where nothing can be written" "--out /proc/forbidden: cannot write in /proc: " -- run --problem vortex -N 1 --out /proc/forbidden
reject "--out at /dev/null" "--out /dev/null: it exists and is not a folder" -- contour --initial square.json -K 3 --out /dev/null
mkdir -p notes && echo 'my notes' >notes/notes.txt
reject "--out at a folder of other files" "--out notes: the folder holds files that are not results of slc" -- \
    study --problem vortex --rows 1 --out notes
reject "--initial /dev/zero (not a regular file)" "cannot read /dev/zero: not a regular file" -- distance --initial /dev/zero --points origin.csv
mkdir -p folder.json
reject "--initial a folder" "cannot read folder.json: not a regular file" -- distance --initial folder.json --points origin.csv
truncate -s 129M big.json
reject "a file above 128 MiB" "big.json: 135266304 bytes, above the limit of 134217728 bytes \(128 MiB\)" -- \
    distance --initial big.json --points origin.csv
rm big.json
# 8,000,001 values besides the curves: refused while counting, before the document is built.
awk 'BEGIN { printf "{\"curves\": [{\"points\": [[0, 0], [1, 0], [0, 1]]}], \"pad\": [0"; for (i = 0; i < 8000000; ++i) printf ",0"; print "]}" }' >padded.json
reject "a file padded with other values" "padded.json: more than 8000000 JSON values" -- distance --initial padded.json --points origin.csv
rm padded.json
reject "distance tree beyond memory" "--tree-depth 30 would need about .* GiB for its trees .* more than the .* GiB of memory this process may use; depth [0-9]+ fits" -- \
    distance --initial square.json --points origin.csv -L 30
reject "contouring tree beyond memory" "--depth 20 would need about .* GiB" -- contour --initial square.json -K 20 --out x
reject "run depth beyond memory" "--depth 24 would need about .* GiB" -- run --problem vortex -K 24 -N 1 --out x
# An eps below the rounding of G was met by rejecting every split, silently (error 3.1e-5).
reject "eps below rounding" "eps 1e-16 is below what doubles resolve in this domain" -- \
    contour --initial square.json -K 5 --refine 1000 --eps 1e-16 --eta 1e-16 --out x
reject "run eps below rounding" "eps 1e-16 is below what doubles resolve" -- \
    run --initial square.json --velocity curvature --t-end 0.1 --eps 1e-16 --out x
check "refusals wrote no folder" test ! -e x
finish
