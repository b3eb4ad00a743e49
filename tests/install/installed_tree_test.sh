#!/usr/bin/env bash
# The installed tree works (issue 38, README "Install"): `cmake --install` into a temporary prefix,
# then examples/ configured and built against it alone through find_package(jellysim) and one example
# run; the installed CLI runs; the installed Python module imports from the prefix's site directory.
#   installed_tree_test.sh BUILD_DIR EXAMPLES_DIR CMAKE PYTHON
set -euo pipefail
build=$1 examples=$2 cmake=$3 python=$4
work=$(mktemp -d "${TMPDIR:-/tmp}/jellysim-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

"$cmake" --install "$build" --prefix "$prefix" > "$work/install.log"
for f in bin/jellysim lib/cmake/jellysim/jellysimConfig.cmake lib/cmake/jellysim/jellysimTargets.cmake \
         lib/libjellysim_jellyfish.a include/jellysim/jellyfish/swim_simulation.hpp \
         share/jellysim/scenes/jellyfish.toml share/jellysim/jellysim_blender.zip share/jellysim/web/jellyfish-viewer.js; do
  [[ -e "$prefix/$f" ]] || { echo "FAIL: $f is not installed"; exit 1; }
done
"$prefix/bin/jellysim" --version

# The examples as a project of their own: only the prefix on CMake's path, not the build tree.
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
"$cmake" -S "$examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  -DBUILD_TESTING=OFF "${launcher[@]}" > "$work/configure.log" || { cat "$work/configure.log"; exit 1; }
"$cmake" --build "$work/examples" --target swim_in_a_tank -j2 > "$work/build.log" || { cat "$work/build.log"; exit 1; }
grep -q "$prefix/include" "$work/examples/CMakeFiles/swim_in_a_tank.dir/flags.make" \
  || { echo "FAIL: the example does not compile against the installed headers"; exit 1; }
"$work/examples/swim_in_a_tank"

# The Python module, from the prefix's Debian site directory (on sys.path itself under /usr).
site="$prefix/lib/python3/dist-packages"
PYTHONPATH="$site" "$python" -c "
import jellysim, sys
assert jellysim.__file__.startswith('$site'), jellysim.__file__
print('installed module', jellysim.__version__, jellysim.__file__)
assert '/usr/lib/python3/dist-packages' in sys.path, sys.path
"
echo "installed tree OK"
