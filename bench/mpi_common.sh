# Sourced by the MPI benchmarks (mpi_speedup.sh, mpi_frames.sh) after they set $build: the glint
# binary, a scratch folder $out removed on exit, the tools checked, and mpirun allowed as root.
glint=$build/apps/glint/glint
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
command -v mpirun >/dev/null || { echo "missing mpirun: run scripts/install-deps.sh" >&2; exit 1; }
command -v idiff >/dev/null || { echo "missing idiff (openimageio-tools)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
