#!/usr/bin/env bash
# The README's first command: installs what is missing, builds oceanref and renders the default
# scene (reference/scenes/default.json) to build/default.exr (linear, cd/m²) and
# build/default.png (tone-mapped preview); prints where the Python module is (build/python).
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/build.sh build
# The Python module (OCEANREF_PYTHON, on when pybind11 and NumPy are installed): import-checked.
if [ -d build/python/oceanref ]; then
  /usr/bin/python3 -c "import sys; sys.path.insert(0, 'build/python'); import oceanref"
  echo "Python module: import oceanref with PYTHONPATH=$PWD/build/python /usr/bin/python3"
fi
echo
echo "== oceanref render reference/scenes/default.json -o build/default.exr --png build/default.png"
build/src/oceanref render reference/scenes/default.json -o build/default.exr --png build/default.png
echo "wrote build/default.exr and build/default.png"
