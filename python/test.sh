#!/usr/bin/env bash
# The Python package's tests (issue 32): a virtual environment in target/python-venv with
# maturin, pytest and NumPy from PyPI, the extension built into it (`maturin develop`, the
# workspace's dev profile, so the crates `cargo test --workspace` built are reused), then
# pytest against the CLI of the same build (target/debug/reconfig).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv=$root/target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/pip" install -q --disable-pip-version-check "maturin>=1.5,<2" pytest numpy
(cd python && VIRTUAL_ENV=$venv PATH=$venv/bin:$PATH maturin develop -q)
cargo build -q -p reconfig-host --bin reconfig
RECONFIG_BIN=$root/target/debug/reconfig "$venv/bin/python" -m pytest -q python/tests
