#!/usr/bin/env bash
# The Python package's tests (issue 32): a virtual environment in target/python-venv with
# pytest, NumPy, Dask's `distributed` and matplotlib (the session example's plots) from PyPI;
# the package installed into it the way the README installs it, `pip install ./python`
# (maturin builds the wheel), but in the workspace's dev profile (MATURIN_PEP517_ARGS) so the
# crates `cargo test --workspace` built are reused; then pytest against the CLI of the same
# build (target/debug/reconfig).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv=$root/target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
pip=("$venv/bin/pip" -q --disable-pip-version-check)
"${pip[@]}" install pytest numpy "dask[distributed]" matplotlib
# --force-reinstall --no-deps: the same version number, rebuilt from this tree every run.
MATURIN_PEP517_ARGS="--profile dev" "${pip[@]}" install --force-reinstall --no-deps ./python
cargo build -q -p reconfig-host --bin reconfig
# From the repository's root, where no `reconfig` directory shadows the installed package.
RECONFIG_BIN=$root/target/debug/reconfig "$venv/bin/python" -m pytest -q python/tests
