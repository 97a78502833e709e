#!/usr/bin/env bash
# The test suite against the newest versions pyproject.toml's ranges admit today, in
# .venv-latest (the lock is not touched): what would move if the lock were upgraded.
# Prints which packages differ from the lock, then runs pytest; exits as pytest does.
set -euo pipefail
cd "$(dirname "$0")/.."
uv=.venv/bin/uv
latest=.venv-latest/requirements.txt
rm -rf .venv-latest
"${PYTHON:-python3}" -m venv .venv-latest
"$uv" pip compile pyproject.toml --group dev --upgrade --quiet -o "$latest"
"$uv" pip install --quiet --python .venv-latest/bin/python -r "$latest"
"$uv" pip install --quiet --python .venv-latest/bin/python --no-deps -e .
echo "test-latest: packages at other versions than the lock:"
.venv-latest/bin/python scripts/check_lock.py requirements/dev.txt 2>&1 | sed 's/^check_lock: /  /' || true
.venv-latest/bin/python -m pytest -q -n auto --dist worksteal "$@"
