# Sourced by the bench scripts: image error by oiiotool's arithmetic, over R, G, B.
# relative_rmse X REF: sqrt of the mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01).
relative_rmse() {
  oiiotool "$1" --ch R,G,B "$2" --ch R,G,B --sub --dup --mul "$2" --ch R,G,B --dup --mul --addc 0.01 --div --printstats 2>&1 |
    sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p' |
    awk '{printf "%.4f", sqrt(($1 + $2 + $3) / 3)}'
}
