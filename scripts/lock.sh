#!/usr/bin/env bash
# Write the lock: every package shaftfem and its tools need, pinned with hashes, for
# every platform and Python >= 3.11 (universal), by uv.
#   scripts/lock.sh            keep the pins there are; add or drop only what pyproject changed
#   scripts/lock.sh --upgrade  the newest versions pyproject.toml's ranges admit
# requirements/dev.txt holds the dependencies and the dependency group `dev` (tests,
# lint, uv); requirements/run.txt the dependencies alone, at dev.txt's versions.
set -euo pipefail
cd "$(dirname "$0")/.."
uv=${UV:-.venv/bin/uv}
common=(--universal --generate-hashes --python-version 3.11 --quiet --custom-compile-command "make lock")
"$uv" pip compile pyproject.toml --group dev "${common[@]}" "$@" -o requirements/dev.txt
"$uv" pip compile pyproject.toml -c requirements/dev.txt "${common[@]}" -o requirements/run.txt
grep -cE '^[a-z0-9]' requirements/run.txt requirements/dev.txt | sed 's/^/lock: pins in /'
