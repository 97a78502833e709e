# The two commands of the README:
#   make run    set up (.venv) and run `shaftfem design` on the default scene
#   make test   set up and run the test suite (what .ci/run calls)
.PHONY: run test setup
setup:
	bash scripts/setup.sh
run: setup
	.venv/bin/shaftfem design
test: setup
	.venv/bin/python -m pytest -q
