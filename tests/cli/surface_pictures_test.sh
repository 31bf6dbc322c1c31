# The shaded pictures of surfaces: written by slc contour and slc run (final.png, frames/*.png)
# at 800 x 800 pixels, with guides and, for a run, the colour bar of the distance moved; a y-up
# model and --view with an up axis. The pictures are not compared pixel by pixel.
source "$(dirname "$0")/lib.sh" "$1"

png_size() {  # png_size FILE: "width height" from the PNG's header
    python3 -c "import struct, sys; d = open(sys.argv[1], 'rb').read(24); \
assert d[:8] == b'\x89PNG\r\n\x1a\n' and d[12:16] == b'IHDR'; print(*struct.unpack('>II', d[16:24]))" "$1"
}

expect_ok "torus contours" -- contour --function torus -K 4 --out torus
check "contour's final.png is 800 x 800" test "$(png_size torus/final.png)" = "800 800"

# An ellipsoid long along y (semi-axes 0.3, 0.7, 0.3), as a y-up scan would be: a UV sphere
# scaled, poles on the y axis.
python3 - <<'PY'
import math
n, m = 16, 32
V = [(0.0, 0.7, 0.0)]
for i in range(1, n):
    t = math.pi * i / n
    for j in range(m):
        p = 2 * math.pi * j / m
        V.append((0.3 * math.sin(t) * math.sin(p), 0.7 * math.cos(t), 0.3 * math.sin(t) * math.cos(p)))
V.append((0.0, -0.7, 0.0))
k = lambda i, j: 1 + (i - 1) * m + j % m
F = [(0, k(1, j), k(1, j + 1)) for j in range(m)]
for i in range(1, n - 1):
    for j in range(m):
        F += [(k(i, j), k(i + 1, j), k(i + 1, j + 1)), (k(i, j), k(i + 1, j + 1), k(i, j + 1))]
F += [(k(n - 1, j), len(V) - 1, k(n - 1, j + 1)) for j in range(m)]
with open("tall.obj", "w") as f:
    f.writelines("v %.9g %.9g %.9g\n" % v for v in V)
    f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in F)
PY
expect_ok "a y-up ellipsoid contours" -- contour --initial tall.obj -K 4 --out tall
check "its final.png is 800 x 800" test "$(png_size tall/final.png)" = "800 800"

expect_ok "a run with frames" -- run --initial tall.obj --velocity unit-normal --t-end 0.05 -K 4 -N 2 --frames 2 --quiet --out grown
check "run's final.png is 800 x 800" test "$(png_size grown/final.png)" = "800 800"
check "frame pictures are 800 x 800" test "$(png_size grown/frames/frame_0000.png) $(png_size grown/frames/frame_0002.png)" = "800 800 800 800"

# The up axis chosen (y, the ellipsoid standing) and z asked for draw different pictures; --view
# with y as up draws the chosen one.
expect_ok "--view with z up" -- run --initial tall.obj --velocity unit-normal --t-end 0.05 -K 4 -N 1 --view 35,25,z --quiet --out z_up
expect_ok "--view with y up" -- run --initial tall.obj --velocity unit-normal --t-end 0.05 -K 4 -N 2 --view 35,25,y --quiet --out y_up
check "z up differs from the chosen view" test "$(cmp -s grown/final.png z_up/final.png && echo same)" != same
check "y up is the chosen view" cmp -s grown/final.png y_up/final.png
expect_ok "--view AZ,EL" -- run --initial tall.obj --velocity unit-normal --t-end 0.05 -K 4 -N 1 --view 35,25 --quiet --out plain
check "--view AZ,EL is z up" cmp -s plain/final.png z_up/final.png
expect_error "a bad up axis" "--view must be two finite numbers AZ,EL in degrees, got '35,25,w'" -- run --initial tall.obj --velocity unit-normal --t-end 0.05 --view 35,25,w --out x

finish
