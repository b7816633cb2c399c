#!/bin/sh
# `pip install .` and the wheel, as a Python user on Debian 13 installs glint (issue 46;
# docs/python.md): in a fresh venv with Debian's build backend (scikit-build-core, numpy and
# pybind11 from Debian's packages: nothing from PyPI), then `python3 -m build --wheel`, the
# wheel installed into another fresh venv, and the pytest suite run there against it.
# Skipped (exit 77) where the release does not package the backend: Debian 12.
#   pip_test.sh SOURCE_DIR OUT_DIR GLINT_COMMAND
set -eu
src="$1" out="$2" glint="$3"
python3 -c "import scikit_build_core" 2>/dev/null ||
  { echo "skipped: python3-scikit-build-core is not packaged here (Debian 12): pip install needs Debian 13; cmake --install is the way here"; exit 77; }
python3 -m build --version >/dev/null 2>&1 || { echo "skipped: python3-build is not installed (scripts/setup --test installs it)"; exit 77; }
rm -rf "$out" && mkdir -p "$out"
# The compiled libraries are kept in one build folder for both builds.
settings="--config-settings=build-dir=$out/wheel-build"

echo "== pip install . (a fresh venv, Debian's backend, no build isolation)"
python3 -m venv --system-site-packages "$out/venv-pip"
"$out/venv-pip/bin/pip" install --no-build-isolation --no-deps --no-index $settings "$src"
"$out/venv-pip/bin/python" -c "
import glint, os, sys
assert glint.__file__.startswith('$out/venv-pip/'), glint.__file__
print('installed:', glint.__version__, os.path.dirname(glint.__file__))
assert os.path.exists(os.environ['GLINT_OIIO_MODULE']), 'the image module beside the package'
"

echo "== python3 -m build --wheel, installed into another fresh venv"
python3 -m build --wheel --no-isolation -C build-dir="$out/wheel-build" --outdir "$out/dist" "$src"
wheel="$(ls "$out"/dist/glint-*.whl)"
python3 -m venv --system-site-packages "$out/venv-wheel"
"$out/venv-wheel/bin/pip" install --no-deps --no-index "$wheel"

echo "== the pytest suite against the wheel"
cd "$out"
PYTHONPATH= "$out/venv-wheel/bin/python" -c "
import glint
assert glint.__file__.startswith('$out/venv-wheel/'), glint.__file__
print('the suite imports', glint.__file__)
"
GLINT="$glint" PYTHONPATH= "$out/venv-wheel/bin/python" -m pytest -q -p no:cacheprovider \
  "$src/tests/python/test_glint.py" "$src/tests/python/test_frontends.py" --basetemp="$out/pytest"
