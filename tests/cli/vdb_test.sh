# OpenVDB files on the command line: slc run --vdb writes final.vdb, which --initial (and
# slc distance) read back as a surface; files that are missing, truncated, not OpenVDB, or hold
# no level set (a fog volume, a vec3s grid: data/*.vdb, written by OpenVDB) or no zero crossing
# exit 2 with one line naming the file; a vec3s grid moves a surface (--field-file), which may
# not start or go outside its active voxels.
DATA="$(cd "$(dirname "$0")" && pwd)/data"
source "$(dirname "$0")/lib.sh" "$1"

expect_ok "a run writes final.vdb" -- run --problem sphere-curvature -N 2 -K 4 --t-end 0.01 --vdb --quiet --out a
check "final.vdb is there" test -s a/final.vdb
# K = 4 in the cube [-1, 1]^3: half a cell is 1/16, coarser than 1/128 of the domain.
check "its voxel is 1/128 of the domain" test "$(json a/summary.json "s['vdb_voxel']")" = "0.015625"

expect_ok "--vdb-voxel sets the voxel" -- run --problem sphere-curvature -N 2 -K 4 --t-end 0.01 --vdb-voxel 0.05 --frames 2 --quiet --out b
check "its voxel is 0.05" test "$(json b/summary.json "s['vdb_voxel']")" = "0.05"
check "each frame is a level set too" test -s b/frames/frame_0000.vdb -a -s b/frames/frame_0001.vdb -a -s b/frames/frame_0002.vdb

# The level set read back: the same sphere, R^2 = 0.25 - 4t at t = 0.01.
echo "0,0,0" >origin.csv
expect_ok "distance reads the first frame's level set" -- distance --initial b/frames/frame_0000.vdb --points origin.csv
cp out.txt d0.csv
check "the first frame is the sphere at t = 0, radius 0.5 to 0.01" python3 -c "
import csv
row = next(csv.DictReader(open('d0.csv')))
assert abs(-float(row['distance']) - 0.5) < 0.01, row"
expect_ok "distance reads final.vdb" -- distance --initial a/final.vdb --points origin.csv
cp out.txt d.csv
check "the sphere read back has radius sqrt(0.21) to 0.005" python3 -c "
import csv, math
row = next(csv.DictReader(open('d.csv')))
assert abs(-float(row['distance']) - math.sqrt(0.21)) < 0.005, row"
expect_ok "a run starts from final.vdb" -- run --initial a/final.vdb --velocity unit-normal -N 1 -K 4 --t-end 0.01 --quiet --out e
check "it starts from the volume the first run ended with, to 1%" python3 -c "
import csv
first = list(csv.DictReader(open('a/history.csv')))[-1]
second = list(csv.DictReader(open('e/history.csv')))[0]
assert abs(float(second['volume']) / float(first['volume']) - 1) < 0.01, (first, second)"
check "without --vdb no final.vdb" test ! -e e/final.vdb

# Bad files: exit 2, one line naming the file.
expect_error "a missing file" "cannot read nothing.vdb" -- run --initial nothing.vdb --velocity unit-normal --t-end 0.1 --out f
head -c 3000 a/final.vdb >cut.vdb
expect_error "a truncated file" "cut.vdb: not a readable OpenVDB file: its 3000 bytes end before" -- run --initial cut.vdb --velocity unit-normal --t-end 0.1 --out f
echo "v 0 0 0" >text.vdb
expect_error "a text file" "text.vdb: not a readable OpenVDB file" -- run --initial text.vdb --velocity unit-normal --t-end 0.1 --out f
expect_error "a fog volume" "fog.vdb: no level-set grid of float or double values \(grids: 'density' \(class fog volume, float values\)\)" -- run --initial "$DATA/fog.vdb" --velocity unit-normal --t-end 0.1 --out f
expect_error "a vec3s grid" "velocity.vdb: no level-set grid .*'velocity' \(class unknown, vec3s values\)" -- run --initial "$DATA/velocity.vdb" --velocity unit-normal --t-end 0.1 --out f
expect_error "a level set without zero crossing" "outside.vdb: level set 'outside' has no zero crossing" -- run --initial "$DATA/outside.vdb" --velocity unit-normal --t-end 0.1 --out f
expect_error "distance refuses it too" "fog.vdb: no level-set grid" -- distance --initial "$DATA/fog.vdb" --points origin.csv
check "nothing was written for them" test ! -e f

echo '{"time": 0, "curves": [{"points": [[-1, -1], [1, -1], [1, 1], [-1, 1]]}]}' >square.json

# A vec3s grid as a flow field: data/velocity.vdb holds (-y, x, 0) on the voxels of [0, 2]^3.
python3 - <<'PY'
import math
n, m, c, r = 12, 24, (1.0, 1.0, 1.0), 0.3
V = [(c[0], c[1], c[2] + r)]
for i in range(1, n):
    t = math.pi * i / n
    V += [(c[0] + r * math.sin(t) * math.cos(2 * math.pi * j / m),
           c[1] + r * math.sin(t) * math.sin(2 * math.pi * j / m), c[2] + r * math.cos(t))
          for j in range(m)]
V.append((c[0], c[1], c[2] - r))
k = lambda i, j: 1 + (i - 1) * m + j % m
F = [(0, k(1, j), k(1, j + 1)) for j in range(m)]
for i in range(1, n - 1):
    for j in range(m):
        F += [(k(i, j), k(i + 1, j), k(i + 1, j + 1)), (k(i, j), k(i + 1, j + 1), k(i, j + 1))]
F += [(k(n - 1, j), len(V) - 1, k(n - 1, j + 1)) for j in range(m)]
with open("ball.obj", "w") as f:
    f.writelines("v %.9g %.9g %.9g\n" % v for v in V)
    f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in F)
PY
expect_ok "a vec3s field moves a surface" -- run --initial ball.obj --field-file "$DATA/velocity.vdb" --t-end 0.2 -N 2 -K 4 --quiet --out g
check "it turns the ball about the z axis by 0.2" python3 -c "
import math
V = [list(map(float, l.split()[1:4])) for l in open('g/final.obj') if l.startswith('v ')]
c = [sum(v[a] for v in V) / len(V) for a in range(3)]
want = (math.cos(0.2) - math.sin(0.2), math.sin(0.2) + math.cos(0.2), 1.0)
assert max(abs(c[a] - want[a]) for a in range(3)) < 0.02, (c, want)"
expect_status "leaving the field's voxels is an error naming time and place" 3 -- run --initial ball.obj --field-file "$DATA/velocity.vdb" --t-end 0.8 -N 2 -K 3 --quiet --out h
check "  the message" grep -qE "at t = .* the surface left the region where velocity 'field-file .*velocity.vdb' is known, \[0, 2\] x \[0, 2\] x \[0, 2\], at \(" err.txt
expect_ok "--field-outside zero: what leaves the voxels stops there" -- run --initial ball.obj --field-file "$DATA/velocity.vdb" --field-outside zero --t-end 0.8 -N 2 -K 3 --quiet --out h0
check "  no vertex beyond the voxels' box [0, 2]^3 by more than 0.01" python3 -c "
V = [list(map(float, l.split()[1:4])) for l in open('h0/final.obj') if l.startswith('v ')]
assert all(-0.01 < c < 2.01 for v in V for c in v), (min(min(v) for v in V), max(max(v) for v in V))"
expect_error "a surface outside the field" "the initial surface leaves the region where velocity 'field-file .*velocity.vdb' is known" -- run --initial a/final.vdb --field-file "$DATA/velocity.vdb" --t-end 0.1 --out f
expect_error "a fog volume is no field" "fog.vdb: no vector grid of vec3s or vec3d values" -- run --initial ball.obj --field-file "$DATA/fog.vdb" --t-end 0.1 --out f
echo "0,0,1,0" >field.csv
expect_error "a lattice file for a surface" "--field-file for a surface takes an OpenVDB vector grid \(.vdb\), got 'field.csv'" -- run --initial ball.obj --field-file field.csv --t-end 0.1 --out f
expect_error "an OpenVDB field for curves" "--field-file: an OpenVDB field \(.vdb\) moves surfaces, not curves" -- run --initial square.json --field-file "$DATA/velocity.vdb" --t-end 0.1 --out f

# The options' own errors.
expect_error "--vdb with curves" "^slc: --vdb is for surfaces, not curves" -- run --initial square.json --velocity unit-normal --t-end 0.1 --vdb --out f
expect_error "--vdb-voxel with curves" "^slc: --vdb-voxel is for surfaces, not curves" -- run --initial square.json --velocity unit-normal --t-end 0.1 --vdb-voxel 0.1 --out f
expect_error "--vdb-voxel 0" "--vdb-voxel" -- run --problem sphere-curvature --vdb-voxel 0 --out f
expect_error "--vdb-voxel too fine" "--vdb-voxel 1e-05 is too fine for the domain, 2 wide" -- run --problem sphere-curvature --vdb-voxel 1e-5 --out f

finish
