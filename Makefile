# The two commands of the README:
#   make run    set up .venv from the lock (what the run needs) and run `shaftfem design`:
#               the paper's shaft hanging free (its Table 2), then in its bearings under
#               its duty (modes, whirl and strength)
#   make test   set up .venv from the lock (plus test tools and the cross-check programs)
#               and run the tests, one worker per core (.ci/run calls this)
# And for developers:
#   make test-all     the tests with the long cases marked slow too (about an hour)
#   make lint         ruff and mypy, as CI runs them
#   make lock         upgrade the lock to the newest versions the ranges admit, then test
#   make test-latest  the tests against the newest versions, in .venv-latest, lock untouched
#   make docs         regenerate the pages made from the code, then build the docs site
#                     strictly (warnings are errors) into out/docs
.PHONY: run test test-all lint lock test-latest docs
run:
	bash scripts/setup.sh run
	.venv/bin/shaftfem design
	.venv/bin/shaftfem design paper2018_installed
test:
	bash scripts/setup.sh test
	.venv/bin/python -m pytest -q -n auto --dist worksteal
test-all:
	bash scripts/setup.sh test
	.venv/bin/python -m pytest -q -n auto --dist worksteal -m "slow or not slow"
lint:
	bash scripts/setup.sh test
	.venv/bin/ruff check src tests benchmarks scripts examples docs
	.venv/bin/mypy
lock:
	bash scripts/setup.sh test
	bash scripts/lock.sh --upgrade
	$(MAKE) test
test-latest:
	bash scripts/setup.sh test
	bash scripts/test_latest.sh
docs:
	bash scripts/setup.sh test
	.venv/bin/python scripts/write_docs.py
	.venv/bin/sphinx-build -W --keep-going -q -b html docs out/docs
	@echo "docs: out/docs/index.html"
