# Sourced by scripts/test.sh, fuzz.sh and ompl2.sh from the repository root: sets `launcher` to
# the CMake arguments that compile through ccache when it is present (scripts/install-deps.sh
# installs it), empty otherwise. Paths are hashed relative to the clone's parent, so later runs,
# other clones and the OMPL 2 stage reuse objects compiled alike.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
fi
