# BirdsEye for QGIS — every target installs what it needs first (scripts/setup.sh: Debian packages
# and .venv, only when something is missing). `make help` lists the targets.
SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := help
.PHONY: help setup lint test test-unit test-integration test-qgis-lts test-qgis-sid demo demo-loop bench package qgis-process chain-model translations clean \
	distclean

VENV := .venv
PYTHON := $(VENV)/bin/python
# The pytest script, not `python -m pytest`: -m would put the repository root on sys.path, where
# our processing/ package shadows QGIS's own `processing`.
PYTEST := $(VENV)/bin/pytest
# Exit status 5 means "no tests collected": not a failure while a suite folder is still empty.
ALLOW_EMPTY := || { rc=$$?; [[ $$rc == 5 ]] || exit $$rc; }

help:
	@echo "make demo          set up, then run the whole chain on a simulated campaign -> birdseye-demo/"
	@echo "make demo-loop     set up, then one round of review -> labels -> retraining -> comparison -> birdseye-demo-loop/"
	@echo "make test          set up, then run every test suite (unit, QGIS, desktop under Xvfb, qgis_process)"
	@echo "make test-qgis-lts the QGIS suites on QGIS 3.40 LTR, in a Debian 13 chroot (root; CI runs it too)"
	@echo "make test-qgis-sid the QGIS suites on Debian unstable's QGIS (3.44), in a chroot (root)"
	@echo "make setup         install missing Debian packages and the pinned Python packages into $(VENV)"
	@echo "make lint          ruff, flake8-qgis and the Qt 6 / QGIS API name check (run by make test)"
	@echo "make bench         run each benchmarks/bench_*.py and print its figures and ratios"
	@echo "make package       build/birdseye.<version>.zip (QGIS's 'Install from ZIP') and build/plugins.xml (a plugin repository)"
	@echo "make qgis-process ARGS='run birdseye:<id> -- PARAM=value'   run qgis_process with the plugin loaded"
	@echo "make chain-model   regenerate resources/models/birdseye_chain.model3 (Graphical Modeler model)"
	@echo "make translations  update i18n/birdseye_en.ts from the tr() strings and help texts; compile other i18n/*.ts to .qm"
	@echo "make clean         remove build/, birdseye-demo/ and caches (keeps $(VENV)); distclean also $(VENV)"

setup:
	@scripts/setup.sh

test: setup
	@$(MAKE) --no-print-directory lint test-unit test-integration

# ruff (pyproject.toml), flake8-qgis on what ships (.flake8), and every Qt name checked against PyQt6 and
# every Qgis enum name against qgis-stubs (scripts/check_qt6.py in .venv-qt6): QGIS 4 runs Qt 6, this
# machine only QGIS 3.22.
lint: setup
	$(VENV)/bin/ruff check .
	$(VENV)/bin/flake8 birdseye_qgis processing __init__.py
	.venv-qt6/bin/python scripts/check_qt6.py

test-unit:
	$(PYTEST) -p no:qgis -q tests/unit $(ALLOW_EMPTY)

# tests/gui starts its own Xvfb for the real desktop; everything else is headless.
test-integration:
	QT_QPA_PLATFORM=offscreen $(PYTEST) -q tests/qgis tests/gui tests/e2e $(ALLOW_EMPTY)

# The same QGIS suites on the QGIS releases users run (scripts/qgis_chroot.sh builds the chroot under
# build/chroots once, from the Debian archive in this machine's apt sources); needs root.
test-qgis-lts:
	scripts/qgis_chroot.sh trixie

test-qgis-sid:
	scripts/qgis_chroot.sh sid

# DEMO_ARGS, e.g. "--size small" for a quick check or "--out elsewhere" (see scripts/demo.py --help).
demo: setup
	QT_QPA_PLATFORM=offscreen $(PYTHON) scripts/demo.py $(DEMO_ARGS)

# DEMO_ARGS as for demo, e.g. "--size small --minutes 0.5" (scripts/demo_loop.py --help).
demo-loop: setup
	QT_QPA_PLATFORM=offscreen $(PYTHON) scripts/demo_loop.py $(DEMO_ARGS)

bench: setup
	@shopt -s nullglob; benches=(benchmarks/bench_*.py); \
	(($${#benches[@]})) || { echo "no benchmarks/bench_*.py yet"; exit 0; }; \
	for bench in "$${benches[@]}"; do \
		echo "== $$bench"; \
		QT_QPA_PLATFORM=offscreen $(PYTHON) "$$bench"; \
	done

# build/birdseye.<version>.zip and build/plugins.xml, the plugin repository file a user adds in QGIS's
# Plugin Manager. PLUGIN_BASE_URL: the web folder the two files will be served from (for plugins.xml's
# download_url), e.g. make package PLUGIN_BASE_URL=https://example.org/qgis/; empty: build/ as a file:// URL.
package:
	@/usr/bin/python3 scripts/package.py --out build $(if $(PLUGIN_BASE_URL),--base-url '$(PLUGIN_BASE_URL)')

qgis-process: setup
	@scripts/qgis_process.sh $(ARGS)

chain-model: setup
	QT_QPA_PLATFORM=offscreen $(PYTHON) scripts/make_chain_model.py

# Every file with tr() strings (core/ has none: it never imports Qt), then every block of the help texts
# (scripts/help_catalogue.py; one recipe line, so the catalogue is never left without them). English is
# the source language: birdseye_en.ts lists the strings; a translator copies it to birdseye_<locale>.ts
# and fills it in (Qt Linguist), and this target compiles it to the .qm the plugin loads for that QGIS locale.
TR_SOURCES = $(sort __init__.py $(shell find birdseye_qgis processing -name '*.py' -not -path '*/core/*'))
translations: setup
	@PYTHONWARNINGS=ignore::DeprecationWarning pylupdate5 -noobsolete $(TR_SOURCES) -ts i18n/birdseye_en.ts && /usr/bin/python3 scripts/help_catalogue.py i18n/birdseye_en.ts
	@echo "i18n/birdseye_en.ts: $$(grep -c '<source>' i18n/birdseye_en.ts) strings from $(words $(TR_SOURCES)) files and $$(ls resources/help/*.md | wc -l) help texts"
	@shopt -s nullglob; for ts in i18n/birdseye_*.ts; do \
		[[ $$ts == i18n/birdseye_en.ts ]] || lrelease -silent "$$ts" -qm "$${ts%.ts}.qm"; \
	done

# While scripts/qgis_chroot.sh runs, this tree and /dev are mounted inside build/chroots: removing build
# then would reach them.
clean:
	@! awk '{print $$2}' /proc/self/mounts | grep -q '^$(CURDIR)/build/' || \
		{ echo "make clean: build/chroots is in use (scripts/qgis_chroot.sh); try again once it ends" >&2; exit 1; }
	rm -rf --one-file-system build birdseye-demo birdseye-demo-loop .pytest_cache .hypothesis .qgis-settings
	find . -path ./$(VENV) -prune -o \( -name __pycache__ -o -name '*.pyc' \) -exec rm -rf {} +

distclean: clean
	rm -rf $(VENV)
