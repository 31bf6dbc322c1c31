# slc study: the convergence table of a problem, here with the arclength module and arcs, which
# the table names; the same first row with the paper's method beside it.
source "$(dirname "$0")/lib.sh" "$1"

expect_ok "study with the arclength module and arcs" -- study --problem circle-curvature --rows 1 \
    --geometry arclength --arcs --out arcs --quiet
expect_ok "study with the paper's method" -- study --problem circle-curvature --rows 1 --out paper --quiet
for f in table.md table.csv table.json error_vs_time.png; do
    check "study writes $f" test -s "arcs/$f"
done
check "table names the module" grep -q "arclength geometry module" arcs/table.md
check "table names the arcs" grep -q "(--arcs)" arcs/table.md
check "the paper's method's table names neither" test -z "$(grep -E 'arclength|--arcs' paper/table.md)"
# Row 1 at P = 4 (20/1/3/1e-3): E_inf 3.3e-4 against 2.6e-2 (the paper's Table 7: 0.057).
e_inf() { awk -F, '$1 == 1 && $6 == 4 { print $8 }' "$1/table.csv"; }
check "arcs and the arclength module: E_inf at least 10 times smaller" \
    awk -v a="$(e_inf arcs)" -v b="$(e_inf paper)" 'BEGIN { exit !(a > 0 && 10 * a < b) }'
finish
