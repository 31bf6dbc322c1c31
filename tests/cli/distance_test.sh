# slc distance: exact answers for a square, full precision, input order, and its bad input.
source "$(dirname "$0")/lib.sh" "$1"

square_json >square.json
printf 'x,y\n0,0\n3,0\n2,2\n0.5,-1\n' >points.csv
expect_ok "distance runs" -- distance --initial square.json --points points.csv --domain 4
cat >want.csv <<'CSV'
x,y,distance,nearest_x,nearest_y
0,0,-1,0,-1
3,0,2,1,0
2,2,1.4142135623730951,1,1
0.5,-1,0,0.5,-1
CSV
check "distances of a square are exact, in input order" diff -u want.csv out.txt

# (0, 0) is equally near all four sides: the lowest-numbered segment, the bottom, wins.
# Clockwise input is reoriented with a note on stderr, and gives the same answers.
echo '{"curves": [{"points": [[-1, -1], [-1, 1], [1, 1], [1, -1]]}]}' >cw.json
expect_ok "clockwise input accepted" -- distance --initial cw.json --points points.csv --domain 4
# The same answers but at (0, 0), where reversal renumbers the tied segments.
check "clockwise input gives the same distances" diff -u <(grep -v '^0,0,' want.csv) <(grep -v '^0,0,' out.txt)
check "reorientation is reported" grep -q "reoriented" err.txt

expect_error "missing file" "nope.json" -- distance --initial nope.json --points points.csv
echo '{"curves": [' >bad.json
expect_error "not JSON" "bad.json" -- distance --initial bad.json --points points.csv
printf 'x,y\n1,2,3\n' >cols.csv
expect_error "wrong column count" "cols.csv.*line 2" -- distance --initial square.json --points cols.csv
printf '1,abc\n' >nan.csv
expect_error "non-number" "nan.csv.*line 1" -- distance --initial square.json --points nan.csv
echo '{"curves": [{"points": [[0, 0], [1, 1], [1, 0], [0, 1]]}]}' >bowtie.json
expect_error "self-intersection" "curve 0" -- distance --initial bowtie.json --points points.csv
echo '{"curves": [{"points": [[0, 0], [1, 0]]}]}' >short.json
expect_error "too few points" "curve 0" -- distance --initial short.json --points points.csv
expect_error "point outside the domain" "outside" -- distance --initial square.json --points points.csv --domain 0.5
expect_ok "non-square box: the square around it" -- distance --initial square.json --points points.csv --box -2,-2,2,3
expect_error "unknown option" "--frobnicate" -- distance --initial square.json --points points.csv --frobnicate
expect_ok "help" -- distance --help
check "help names the output columns" grep -q "nearest_x" out.txt
finish
