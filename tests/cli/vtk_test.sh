# slc run --vtk: a .vtp per frame (initial, frames, final) and a .pvd listing them with their times;
# the final .vtp holds the points of final.json. When Python's VTK is installed (Debian
# python3-vtk9), VTK's own readers read every file too; otherwise that part is skipped.
source "$(dirname "$0")/lib.sh" "$1"

# number_of DIR/FILE.vtp ATTRIBUTE: an attribute of the Piece element
number_of() { grep -o "$2=\"[0-9]*\"" "$1" | head -1 | tr -dc '0-9'; }
# The x, y of every point of a .vtp, one "x y" per line.
vtp_points() { awk '/<Points>/ {p = 1; next} /<\/Points>/ {p = 0} p && !/DataArray/ {print $1, $2}' "$1"; }
# The x, y of every point of an interface file, one "x y" per line.
json_points() { grep -o '\[-\?[0-9][^][]*\]' "$1" | tr -d '[],' ; }
# Same numbers (compared as doubles by awk) in the same order.
same_points() {
    paste -d ' ' <(vtp_points "$1") <(json_points "$2") |
        awk 'NF != 4 || $1 != $3 || $2 != $4 {bad = 1} END {exit bad || NR == 0}'
}

expect_ok "frames and vtk" -- run --problem merging-circles -N 8 -K 4 -P 1 --frames 4 --vtk --out mc --quiet
check "collection written" test -s mc/frames.pvd
check "five datasets: initial and four frames" test "$(grep -c '<DataSet' mc/frames.pvd)" -eq 5
for i in 0 1 2 3 4; do
    check "frame $i written" test -s "mc/frames/frame_000$i.vtp"
    check "frame $i listed" grep -q "file=\"frames/frame_000$i.vtp\"" mc/frames.pvd
done
check "no sixth frame: the last frame is the final interface" test ! -e mc/frames/frame_0005.vtp
check "times from 0 to t_end" test "$(grep -o 'timestep="[^"]*"' mc/frames.pvd | tr -dc '0-9.\n' | tr '\n' ' ')" \
    = "0 0.125 0.25 0.375 0.5 "
check "last frame has the final segments" \
    test "$(number_of mc/frames/frame_0004.vtp NumberOfPoints)" -eq "$(grep -o '"segments": [0-9]*' mc/summary.json | tr -dc '0-9')"
check "one line per component" test "$(number_of mc/frames/frame_0004.vtp NumberOfLines)" -eq 1
check "three circles at first" test "$(number_of mc/frames/frame_0000.vtp NumberOfLines)" -eq 3
check "final points are final.json's" same_points mc/frames/frame_0004.vtp mc/final.json
check "initial points are frame_0000.json's" same_points mc/frames/frame_0000.vtp mc/frames/frame_0000.json

# Without --frames: the initial and the final interface.
echo '{"curves": [{"points": [[0, 0], [0.4, 0], [0, 0.4]]}]}' >small.json
expect_ok "vtk alone" -- run --initial small.json --velocity unit-normal --param speed=0.5 --t-end 0.2 \
    -N 4 -K 4 -P 0 --domain 1 --vtk --out grow --quiet
check "two datasets" test "$(grep -c '<DataSet' grow/frames.pvd)" -eq 2
check "final listed at t_end" grep -q 'timestep="0.2" group="" part="0" file="frames/frame_0001.vtp"' grow/frames.pvd
check "final vtp is final.json" same_points grow/frames/frame_0001.vtp grow/final.json

# A curve that shrinks away: the last frame is empty, and still a valid file.
expect_ok "vanishing" -- run --initial small.json --velocity unit-normal --param speed=-1 --t-end 1 \
    -N 10 -K 4 -P 0 --domain 1 --vtk --out gone --quiet
check "vanished status" grep -q '"status": "vanished"' gone/summary.json
last=$(grep -o 'file="[^"]*"' gone/frames.pvd | tail -1 | cut -d'"' -f2)
check "empty last frame" test "$(number_of "gone/$last" NumberOfPoints)" -eq 0

# A folder of other files (here one in the way of the frames' folder) is not replaced: status 2,
# one line naming it.
mkdir blocked && touch blocked/frames
expect_error "frames folder blocked" "--out blocked: the folder holds files that are not results of slc" -- run --initial small.json --velocity unit-normal \
    --t-end 0.1 -N 1 -K 3 -P 0 --domain 1 --vtk --out blocked --quiet

# VTK's own readers, when installed: every dataset of each collection, with its points and lines.
# Debian's python3-vtk9 serves Debian's Python, which may not be the first python3 on the PATH.
vtk_python=""
for py in python3 /usr/bin/python3; do
    if "$py" -c 'import vtk' 2>/dev/null; then vtk_python="$py"; break; fi
done
if [ -n "$vtk_python" ]; then
    check "VTK reads the collections" "$vtk_python" - mc/frames.pvd grow/frames.pvd gone/frames.pvd <<'EOF'
import os, re, sys, vtk
for pvd in sys.argv[1:]:
    base = os.path.dirname(pvd)
    for t, f in re.findall(r'timestep="([^"]*)"[^>]*file="([^"]*)"', open(pvd).read()):
        r = vtk.vtkXMLPolyDataReader()
        r.SetFileName(os.path.join(base, f))
        r.Update()
        d = r.GetOutput()
        text = open(os.path.join(base, f)).read()
        n = int(re.search(r'NumberOfPoints="(\d+)"', text).group(1))
        c = int(re.search(r'NumberOfLines="(\d+)"', text).group(1))
        assert r.GetErrorCode() == 0, f
        assert d.GetNumberOfPoints() == n and d.GetNumberOfLines() == c, (f, n, c)
        body = text.split("<Points>")[1].split(">", 1)[1].split("<")[0].split()
        xyz = [float(v) for v in body]
        assert all(d.GetPoint(i) == tuple(xyz[3 * i:3 * i + 3]) for i in range(n)), f
        if c:
            assert d.GetPointData().GetArray("curve").GetNumberOfTuples() == n, f
            assert d.GetCellData().GetArray("length").GetValue(0) > 0, f
            line = d.GetCell(0)
            assert line.GetPointId(0) == line.GetPointId(line.GetNumberOfPoints() - 1), f
        assert abs(d.GetFieldData().GetArray("TimeValue").GetValue(0) - float(t)) == 0, f
EOF
else
    echo "skipped: Python's VTK is not installed (Debian python3-vtk9)"
fi
finish
