# slc render --frames: the frames of a run as one animated SVG, one group per frame; bad input.
source "$(dirname "$0")/lib.sh" "$1"

expect_ok "a run with frames" -- run --problem merging-circles -N 8 -K 4 -P 1 --frames 4 --out mc --quiet
expect_ok "animation" -- render --frames mc --out mc/run.svg --title "merging circles"
check "svg written" test -s mc/run.svg
check "five frames" test "$(grep -c '<g id="frame' mc/run.svg)" -eq 5
check "five animations" test "$(grep -c '<animate attributeName="visibility"' mc/run.svg)" -eq 5
check "loop of 5 x 0.25 s" grep -q 'dur="1.25s"' mc/run.svg
check "times shown" grep -q 't = 0.5<' mc/run.svg
check "trail of five" test "$(sed -n '/<g id="trail"/,/<\/g>/p' mc/run.svg | grep -c '<path')" -eq 5
expect_ok "frames folder itself, slower" -- render --frames mc/frames --seconds-per-frame 1 --out slow.svg
check "loop of 5 x 1 s" grep -q 'dur="5s"' slow.svg

echo '{"curves": [{"points": [[0, 0], [0.4, 0], [0, 0.4]]}]}' >small.json
expect_ok "vanishing run" -- run --initial small.json --velocity unit-normal --param speed=-1 --t-end 1 \
    -N 10 -K 4 -P 0 --domain 1 --frames 10 --out gone --quiet
expect_ok "animation of a vanishing run" -- render --frames gone --out gone.svg
check "nothing left at the end" grep -q "nothing left" gone.svg

mkdir empty
expect_error "no frames" "no frames in empty" -- render --frames empty --out x.svg
expect_error "png animation" "must end in .svg" -- render --frames mc --out x.png
expect_error "frames and files" "excludes|frames" -- render small.json --frames mc --out x.svg
expect_error "nothing to draw" "files|--frames" -- render --out x.svg
expect_error "zero seconds per frame" "seconds-per-frame" -- render --frames mc --seconds-per-frame 0 --out x.svg
expect_error "nan seconds per frame" "--seconds-per-frame: must be a positive finite number, got 'nan'" -- render --frames mc --seconds-per-frame nan --out x.svg
expect_error "infinite seconds per frame" "--seconds-per-frame: must be a positive finite number, got 'inf'" -- render --frames mc --seconds-per-frame inf --out x.svg
finish
