# One table row from a scripts/paired_timing.py report of ramap (A) against a peer (B):
#   | first | second | A's median wall | B's median wall | B / A (median of the pairs) | min-max |
# The report's rows are "<command> <figure> min median max", the ratio taken as A/B.
#   awk -v first=NAME -v second=WHAT -f scripts/paired_ratio.awk REPORT
$1 == "A" && $2 == "wall" { a = $4 }
$1 == "B" && $2 == "wall" { b = $4 }
$1 == "A/B" && $2 == "wall" { lo = 1 / $5; mid = 1 / $4; hi = 1 / $3 }
END { printf "| %s | %s | %.2f | %.2f | %.1fx | %.1f-%.1fx |\n", first, second, a, b, mid, lo, hi }
