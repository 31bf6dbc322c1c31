# slc distance on surfaces (DESIGN §8): exact answers for a cube in OBJ, STL (ASCII and binary)
# and PLY, full precision, input order; inward orientation fixed with a note; bad input.
source "$(dirname "$0")/lib.sh" "$1"

cat >cube.obj <<'OBJ'
# the cube [-1, 1]^3, outward; quads fanned into triangles
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
f 1 4 3 2
f 5/1 6/1 7/1 8/1
f 1//1 2//1 6//1 5//1
f 2 3 7 6
f -6 -5 -1 -2
f 4 1 5 8
OBJ
printf 'x,y,z\n0,0,0\n3,0,0\n2,2,2\n0.5,-1,0\n0.25,0.5,-0.75\n' >points.csv
expect_ok "distance runs on a surface" -- distance --initial cube.obj --points points.csv --domain 4
cat >want.csv <<'CSV'
x,y,z,distance,nearest_x,nearest_y,nearest_z
0,0,0,-1,0,0,-1
3,0,0,2,1,0,0
2,2,2,1.7320508075688772,1,1,1
0.5,-1,0,0,0.5,-1,0
0.25,0.5,-0.75,-0.25,0.25,0.5,-1
CSV
check "distances to a cube are exact, in input order" diff -u want.csv out.txt
expect_ok "default domain" -- distance --initial cube.obj --points points.csv
check "the default domain gives the same answers" diff -u want.csv out.txt

# The same cube as ASCII STL, binary STL and PLY: the same answers (corners merged in STL).
{
    echo "solid cube"
    for f in "1 4 3" "1 3 2" "5 6 7" "5 7 8" "1 2 6" "1 6 5" "2 3 7" "2 7 6" "3 4 8" "3 8 7" "4 1 5" "4 5 8"; do
        echo " facet normal 0 0 0"
        echo "  outer loop"
        for i in $f; do echo "   vertex $(sed -n "$((i + 1))p" cube.obj | cut -d' ' -f2-)"; done
        echo "  endloop"
        echo " endfacet"
    done
    echo "endsolid cube"
} >cube.stl
expect_ok "ASCII STL" -- distance --initial cube.stl --points points.csv --domain 4
check "ASCII STL gives the same answers" diff -u want.csv out.txt
python3 - <<'PY'
import struct
v = [(-1,-1,-1),(1,-1,-1),(1,1,-1),(-1,1,-1),(-1,-1,1),(1,-1,1),(1,1,1),(-1,1,1)]
f = [(1,4,3),(1,3,2),(5,6,7),(5,7,8),(1,2,6),(1,6,5),(2,3,7),(2,7,6),(3,4,8),(3,8,7),(4,1,5),(4,5,8)]
with open("binary.stl", "wb") as out:
    out.write(b"solid but binary".ljust(80, b" ") + struct.pack("<I", len(f)))
    for t in f:
        out.write(struct.pack("<3f", 0, 0, 0))
        for i in t: out.write(struct.pack("<3f", *v[i - 1]))
        out.write(b"\0\0")
with open("cube.ply", "w") as out:
    out.write("ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
              "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n")
    for p in v: out.write("%d %d %d\n" % p)
    for q in [(1,4,3,2),(5,6,7,8),(1,2,6,5),(2,3,7,6),(3,4,8,7),(4,1,5,8)]:
        out.write("4 %d %d %d %d\n" % tuple(i - 1 for i in q))
PY
expect_ok "binary STL" -- distance --initial binary.stl --points points.csv --domain 4
check "binary STL gives the same answers" diff -u want.csv out.txt
expect_ok "PLY" -- distance --initial cube.ply --points points.csv --domain 4
check "PLY gives the same answers" diff -u want.csv out.txt

# The cube scaled by 2^-250 (6e-76), 2^250 and 2^330 (2e99, near the coordinate limit): the
# answers of the unit cube scaled, exactly (a power of two scales every rounding with them).
for e in -250 250 330; do
    python3 - "$e" <<'PY'
import sys
s = 2.0 ** int(sys.argv[1])
with open("cube.obj") as src, open("scaled.obj", "w") as out:
    for line in src:
        w = line.split()
        out.write("v %r %r %r\n" % tuple(s * float(c) for c in w[1:]) if w and w[0] == "v" else line)
with open("points.csv") as src, open("scaled.csv", "w") as out:
    out.write(next(src))
    for line in src: out.write(",".join(repr(s * float(c)) for c in line.split(",")) + "\n")
PY
    expect_ok "a cube scaled by 2^$e" -- distance --initial scaled.obj --points scaled.csv
    check "a cube scaled by 2^$e gives the unit cube's answers scaled" python3 - "$e" <<'PY'
import csv, sys
s = 2.0 ** int(sys.argv[1])
want = list(csv.reader(open("want.csv")))[1:]
got = list(csv.reader(open("out.txt")))[1:]
assert len(got) == len(want), got
for w, g in zip(want, got):
    assert [s * float(c) for c in w] == [float(c) for c in g], (w, g)
PY
done

# Inward orientation is reversed with a note on stderr, and gives the same distances.
sed 's/^f \([^ ]*\) \([^ ]*\) \([^ ]*\) \([^ ]*\)$/f \4 \3 \2 \1/' cube.obj >inward.obj
expect_ok "inward surface accepted" -- distance --initial inward.obj --points points.csv --domain 4
check "inward surface gives the same distances" diff -u <(cut -d, -f1-4 want.csv) <(cut -d, -f1-4 out.txt)
check "reversal is reported" grep -q "oriented inward; reversed" err.txt

# Bad input: one line, status 2.
expect_error "missing surface" "cannot read nowhere.obj" -- distance --initial nowhere.obj --points points.csv
printf 'v 0 0 0\nv 1 0 zero\n' >bad.obj
expect_error "bad OBJ number" "bad.obj, line 2: \"zero\" is not a finite number" -- distance --initial bad.obj --points points.csv
head -n 14 cube.obj >open.obj
expect_error "open surface" "open.obj: triangle [0-9]+ has an open edge" -- distance --initial open.obj --points points.csv
sed 's/^v \(.*\)/v \1/' cube.obj >two.obj
awk '/^v /{print "v", $2 + 1, $3 + 0.5, $4 + 0.25}' cube.obj >>two.obj
echo "f 9 12 11 10" >>two.obj
echo "f 13 14 15 16" >>two.obj
echo "f 9 10 14 13" >>two.obj
echo "f 10 11 15 14" >>two.obj
echo "f 11 12 16 15" >>two.obj
echo "f 12 9 13 16" >>two.obj
expect_error "intersecting cubes" "two.obj: triangles [0-9]+ and [0-9]+ intersect" -- distance --initial two.obj --points points.csv
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n' >flat.obj
expect_error "degenerate triangle" "flat.obj: triangle 0 is degenerate" -- distance --initial flat.obj --points points.csv
printf 'solid x\nfacet\nvertex 0 0 0\n' >cut.stl
expect_error "truncated STL" "cut.stl: the file ends inside a facet" -- distance --initial cut.stl --points points.csv
printf 'x,y,z\n1,2\n' >cols.csv
expect_error "two columns for a surface" "cols.csv, line 2: expected 3 columns x,y,z, got 2" -- distance --initial cube.obj --points cols.csv
expect_error "surface outside the domain" "cube.obj: vertex 0 \(-1, -1, -1\) lies outside the domain" -- distance --initial cube.obj --points points.csv --domain 0.5
expect_error "a 2D box for a surface" "--box must be six numbers" -- distance --initial cube.obj --points points.csv --box 0,0,1,1
expect_ok "a box for a surface" -- distance --initial cube.obj --points points.csv --box -2,-2,-2,2,2,3
check "a box gives the same answers" diff -u want.csv out.txt
# slc tree on a surface: the octree in a slice, checked against brute force.
expect_ok "tree of a surface" -- tree --initial cube.obj --out tree --slice 0.25
for f in tree.svg tree.png distance.svg distance.png surface.vtp summary.json; do
    check "tree writes $f" test -s "tree/$f"
done
check "the tree agrees with brute force" grep -q '"max_abs_difference": 0.0' tree/summary.json
check "the summary has the surface's genus" grep -q '"genus": 0' tree/summary.json
expect_error "slice outside the domain" "--slice must lie in the domain" -- tree --initial cube.obj --out tree2 --slice 9
expect_ok "help names the 3D columns" -- distance --help
check "help names nearest_z" grep -q "nearest_z" out.txt
finish
