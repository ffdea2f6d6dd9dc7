# Sourced by the bench scripts: image error by oiiotool's arithmetic, over R, G, B.
# relative_rmse X REF: sqrt of the mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01).
# rmse X REF: sqrt of the mean over pixels and channels of (x - ref)^2.
# mean_rgb X: the mean over pixels and channels.

# The three channel averages from oiiotool --printstats output on stdin, reduced by awk program $1.
stats_avg() {
  sed -n 's/.*Stats Avg: \([0-9.e+-]*\) \([0-9.e+-]*\) \([0-9.e+-]*\).*/\1 \2 \3/p' | awk "$1"
}
relative_rmse() {
  oiiotool "$1" --ch R,G,B "$2" --ch R,G,B --sub --dup --mul "$2" --ch R,G,B --dup --mul --addc 0.01 --div --printstats 2>&1 |
    stats_avg '{printf "%.4f", sqrt(($1 + $2 + $3) / 3)}'
}
rmse() {
  oiiotool "$1" --ch R,G,B "$2" --ch R,G,B --sub --dup --mul --printstats 2>&1 |
    stats_avg '{printf "%.4f", sqrt(($1 + $2 + $3) / 3)}'
}
mean_rgb() {
  oiiotool "$1" --ch R,G,B --printstats 2>&1 | stats_avg '{printf "%.4f", ($1 + $2 + $3) / 3}'
}
