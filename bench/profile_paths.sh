#!/usr/bin/env bash
# Where a path's time goes: `perf record` of one render on one thread, its samples summed by
# what the code does (sample generation, traversal and intersection, light sampling, BSDFs,
# the integrator's own loop, camera and film, surface set-up, libm, the rest). Prints a Markdown
# table, then the 15 hottest functions. perf is Debian's linux-perf (on this VM it samples
# cpu-clock: no hardware counters).
#
#   bench/profile_paths.sh GLINT_BINARY SCENE [SPP=8] [extra render arguments...]
set -euo pipefail
if [[ $# -lt 2 ]]; then sed -n '2,8p' "$0"; exit 2; fi
bin=$1 scene=$2 spp=${3:-8}
shift $(( $# < 3 ? $# : 3 ))
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
perf record -q -o "$tmp/perf.data" "$bin" render "$scene" --spp "$spp" --threads 1 -o "$tmp/out.exr" "$@" 2>&1 |
  grep '^rendered' || true
perf report -i "$tmp/perf.data" --no-children --stdio --sort symbol 2>/dev/null |
  sed -n 's/^ *\([0-9.]*\)%  *\[[.k]\] *\(.*\)$/\1\t\2/p' > "$tmp/symbols.tsv"
python3 - "$tmp/symbols.tsv" <<'PY'
import re, sys
# First match wins; patterns are on the demangled name, without its argument list.
groups = [
    ("sample generation", r"PixelSampler|permute_index|SampleStream|sobol|owen"),
    ("traversal and intersection", r"Scene::intersect|Scene::occluded|intersect_triangle|WatertightRay|"
                                   r"::intersect\b|mesh_closest|mesh_any|spheres_|Bvh|closest_instance|any_instance"),
    ("light sampling", r"LightSampler|LightBvh|light_radiance|emission_of|Distribution|EnvironmentMap|evaluate\b"),
    ("BSDF evaluation and sampling", r"Bsdf|make_bsdf|Lobe|sample_cosine|ggx|Ggx|fresnel|Fresnel|surface_material"),
    ("surface set-up (hit to interaction, textures)", r"interaction|Triangle::normal|texture|Texture|spawn_ray|uv"),
    ("the integrator's own loop", r"PathIntegrator"),
    ("camera, filter and film", r"ProgressiveRender|Camera|Filter|Film"),
    ("libm", r"sincos|atan|expf|logf|powf|__ieee754"),
]
total = {name: 0.0 for name, _ in groups}
other = 0.0
rows = []
for line in open(sys.argv[1]):
    pct, sym = line.rstrip("\n").split("\t", 1)
    pct = float(pct)
    rows.append((pct, sym))
    name_only = sym.split("(")[0]  # a lambda's symbol carries its function's argument types
    for name, pat in groups:
        if re.search(pat, name_only):
            total[name] += pct
            break
    else:
        other += pct
print("| share of the samples | what |\n|---|---|")
for name, _ in sorted(groups, key=lambda g: -total[g[0]]):
    print(f"| {total[name]:.1f} % | {name} |")
print(f"| {other:.1f} % | everything else (start-up, kernel, threads) |\n")
print("hottest functions:")
for pct, sym in sorted(rows, reverse=True)[:15]:
    print(f"  {pct:5.2f} %  {sym[:110]}")
PY
