# Manipulator Jacobians: the two commands are `make book` and `make test`.
# Each sets up what it needs (a virtual environment with pinned packages, the
# npm front-end files, Chromium for the browser tests) and then does its job.

SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
BIN := $(VENV)/bin
PY_STAMP := $(VENV)/.installed-stamp
NPM_STAMP := node_modules/.installed-stamp
JB_FLAGS := -W -n --keep-going
# (MPLBACKEND=Agg only for the library tests: the notebooks' kernels need the
# inline backend, or plt.show() draws nothing into the book and the slides)
export PYDEVD_DISABLE_FILE_VALIDATION := 1
# make book SOLUTIONS=0: publish the book without the solutions (_ext/course_solutions.py)
SOLUTIONS ?= 1
export COURSE_SOLUTIONS := $(SOLUTIONS)
# The publishing PDFs (Chromium prints; minutes of CPU on a cold build). make book BOOK_PDF=0: no whole-book PDF
# (tools/book_pdf.py). SLIDES_PDF=0: no PDF of a deck or lecture; SLIDES_PDF="<deck> ...": only these decks' PDFs,
# and those of the lectures made of them alone (tools/build_slides.py --pdf-only). make test builds the book with
# BOOK_PDF=0 SLIDES_PDF=$(TEST_SLIDES_PDF) and prints a sample of each instead (tests/browser/test_publishing_pdf.py,
# tests/slides/test_pdf.py); the tests read both variables to know what this build printed.
BOOK_PDF ?= 1
SLIDES_PDF ?= 1
export BOOK_PDF SLIDES_PDF
SLIDES_PDF_ARGS = $(if $(filter 0,$(SLIDES_PDF)),--no-pdf,$(if $(filter-out 1,$(SLIDES_PDF)),--pdf-only $(SLIDES_PDF)))
#: the deck make test prints (with its lecture, lecture 4: the one lecture of a single deck), math, live views and
#: animations included
TEST_SLIDES_PDF := 05_geometric_jacobian

# STAGE_CPU=tools/stage_cpu.sh: each stage of make test (the book's steps, each test run) in a cgroup of its own,
# its wall time and CPU seconds printed when it ends (for measuring where make test's time goes; empty: nothing)
STAGE_CPU ?=
export STAGE_RUN ?= $(shell date +%s)
stage = $(if $(STAGE_CPU),$(STAGE_CPU) $(1))

.PHONY: help setup book site test test-site lint test-lib coverage test-js test-live test-notebooks test-browser test-pages test-slides test-install test-targets test-numerics bench lab slides slides-pdf exercises clean distclean vendor browser grade sandbox

help:
	@echo "make book       build the book into _build/html"
	@echo "make site       the book, with a .gz and a .br copy of each text file for a static host (nginx, Netlify)"
	@echo "make test       run every test (static checks, library, notebooks, book build, browser, decks)"
	@echo "make lab        JupyterLab on the chapters, live widgets"
	@echo "make slides     reveal.js decks, their PDFs and handouts into _build/html/slides (after make book)"
	@echo "make slides-pdf the decks again from the last revealjs build, with their PDFs and handouts"
	@echo "make exercises  student notebooks into _build/exercises"
	@echo "make bench      speed benchmark against modern_robotics and Pinocchio, and the book on a slow phone"
	@echo "make test-install  a student's install from a wheel in a fresh venv: notebooks, a live view, size"
	@echo "make grade SUBMISSIONS=<dir>  grade every student notebook under <dir> (gradebook.csv, reports/), as root"
	@echo "make book SOLUTIONS=0         the book without the solutions"
	@echo "make book BOOK_PDF=0 SLIDES_PDF=0  the book without the whole-book PDF and the decks' PDFs"
	@echo "make test-numerics  the float comparisons on two other OpenBLAS kernels, in reverse order"
	@echo "make coverage   the library tests (test-lib) with the line coverage of jacobians and course"

# ------------------------------------------------------------------ set-up
$(PY_STAMP): requirements.txt requirements-book.txt constraints.txt pyproject.toml
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -r requirements.txt -c constraints.txt
	$(PY) -m pip install -q --no-deps --no-build-isolation -e .
	@touch $@

$(NPM_STAMP): package.json package-lock.json
	npm ci --no-audit --no-fund --loglevel=error
	@touch $@

setup: $(PY_STAMP) $(NPM_STAMP)

vendor: setup
	$(PY) -m tools.vendor

# Debian's Chromium for the browser tests (never `playwright install`).
browser:
	@command -v chromium >/dev/null 2>&1 || { \
	  echo "Installing Debian's chromium for the browser tests"; \
	  if [ "$$(id -u)" = 0 ]; then SUDO=; else SUDO=sudo; fi; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq chromium >/dev/null; }

# Debian's bubblewrap, the sandbox of make grade (and of the grading tests)
sandbox:
	@command -v bwrap >/dev/null 2>&1 || { \
	  echo "Installing Debian's bubblewrap for the grading sandbox"; \
	  if [ "$$(id -u)" = 0 ]; then SUDO=; else SUDO=sudo; fi; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq bubblewrap >/dev/null; }

# ------------------------------------------------------------------ the book
# The notebooks are executed first, on every core, into the execution cache (tools/preexecute.py): Sphinx reads
# the pages one at a time and would execute them one after the other; it then finds each one in the cache.
book: vendor browser
	$(call stage,book-preexecute) $(PY) -m tools.preexecute
	$(call stage,book-sphinx) $(BIN)/jupyter-book build . $(JB_FLAGS)
	$(call stage,book-exercises) $(PY) -m tools.make_exercises _build/html/exercises/student
	$(call stage,book-slides) $(PY) -m tools.build_slides $(SLIDES_PDF_ARGS)
	$(if $(filter 0,$(BOOK_PDF)),@echo "No whole-book PDF (BOOK_PDF=0)",$(PY) -m tools.book_pdf _build/html)
	@$(REFRESH_COMPRESSED)
	@echo "The book is in _build/html/index.html (student notebooks in exercises/student/, lecture slides in slides/)"

# The .gz/.br copies of the site's text files (tools/precompress.cjs, brotli at quality 11: minutes of CPU) are
# for hosts that serve them as they are (nginx gzip_static/brotli_static, Netlify, Cloudflare); a reader of the
# built book, GitHub Pages and the tests need none. `make site` writes them; after that, `make book` and
# `make slides` bring them up to date (only the files they rewrote), so no copy is ever older than its original.
REFRESH_COMPRESSED = if [ -f _build/html/index.html.gz ]; then node tools/precompress.cjs _build/html; fi
site: book
	node tools/precompress.cjs _build/html

# ------------------------------------------------------------------ tests
# make test runs two chains side by side (-j2: one job each on the 2 cores): the book, then the tests that
# read the built site, then the targets that rewrite it; and the stages that need no built site (static
# checks, library, JavaScript, a student's install). The book executes its notebooks one at a time, so the
# other chain fills the second core. Each stage's output is printed whole when it ends (--output-sync); a
# failing stage fails the run. Before them, the Python packages and the npm ones install side by side (the two
# apt-get installs, when needed, one after the other: they share dpkg's lock).
test:
	$(MAKE) -j2 --output-sync=target setup
	$(MAKE) browser sandbox
	$(MAKE) -j2 --output-sync=target test-site lint test-lib test-js test-live test-install

# the book, the browser tests on it (without the pages' screenshots, which are for a person: `make test-browser`
# takes them), the targets after it (in this order: the last rewrites the site). The book without its publishing
# PDFs but one deck's (BOOK_PDF, SLIDES_PDF above): the tests print a sample of the book and check that deck.
test-site: BOOK_PDF = 0
test-site: SLIDES_PDF = $(TEST_SLIDES_PDF)
test-site: setup
	$(MAKE) book
	BOOK_SHOTS=0 $(MAKE) test-browser
	$(MAKE) test-targets

lint: setup
	$(call stage,lint) $(BIN)/ruff check lib tools _ext tests
	$(call stage,lint) $(BIN)/mypy
	$(call stage,lint) $(BIN)/mypy _ext
	$(call stage,lint) node_modules/.bin/eslint lib/jacobians/widgets/live tests/js _ext/exercise_checks tools
	node_modules/.bin/tsc -p jsconfig.json

# every test not marked `browser` (tests/conftest.py: a test under tests/browser, tests/install or tests/site,
# or one that uses a browser or built-site fixture, or marked by hand), on every core. Without coverage: the
# tracer costs 30-50 % more CPU on these tests (measured, CPU seconds: tests/test_jacobian.py 11.5 -> 15.0,
# tests/test_exercise_properties.py 160 -> 244), and coverage is a report that no test reads; `make coverage`
# runs the same tests with it.
LIB_TESTS := -m "not browser" -q lib/jacobians lib/course tests
test-lib: setup sandbox
	MPLBACKEND=Agg $(call stage,test-lib) $(BIN)/pytest -n auto $(LIB_TESTS)

# test-lib's tests with the library's line coverage (jacobians, course), printed per file (not part of make test)
coverage: setup sandbox
	MPLBACKEND=Agg $(BIN)/pytest -n auto --cov=jacobians --cov=course --cov-report=term:skip-covered $(LIB_TESTS)

# the live views' numeric modules under Node, against values the library writes (no browser)
test-js: setup
	$(call stage,test-js) $(PY) -m tools.js_fixtures _build/js-fixtures.json
	JS_FIXTURES=_build/js-fixtures.json $(call stage,test-js) node --test tests/js/

# nbval on every notebook, without building the book. Not part of make test: the book build runs the same
# cells and fails on any error (tests/test_book_executes_notebooks.py keeps that true).
test-notebooks: setup
	rm -rf _build/nbval && mkdir -p _build/nbval
	$(PY) -m tools.to_ipynb _build/nbval
	cd _build/nbval && ../../$(BIN)/pytest --nbval-lax -n 2 --dist loadscope -p no:cacheprovider -q .

# the built site and the decks in Chromium: tests/browser (test-pages), and the tests of tests/slides that open a
# deck (test-slides; the others run in test-lib), each run on both cores (a module stays whole in one worker, with
# its browser). Two runs, because the decks' tests start their own Playwright and one pytest process can hold only
# one; they run side by side, since their tests spend much of their time waiting on the browser: two runs of two
# workers keep the two cores busier than one run after the other (each prints whole when it ends).
# (the browser tests that need no built book are test-live's)
test-browser: setup browser
	$(MAKE) -j2 --output-sync=target test-pages test-slides

# the built book's pages in Chromium (part of test-browser)
test-pages: setup browser
	$(call stage,test-pages) $(BIN)/pytest tests/browser -m browser -q -n 2 --dist loadscope \
	  $(addprefix --ignore=,$(BOOKLESS_BROWSER))

# The browser tests that need no built book: the live views on the test harness pages (numbers against the
# library, keyboard, contrast in both modes) and in a real JupyterLab. In make test they run on the chain without
# the book, while the book builds. BOOK_HTML points at no book, so a test of these that comes to need the built
# site fails with "The built book is missing" instead of reading a half-built one; their screenshots and page
# summaries go to their own folder (test-browser's are left alone).
BOOKLESS_BROWSER := tests/browser/test_live_kinematics.py tests/browser/test_live_story.py \
  tests/browser/test_live_theme.py tests/browser/test_live_lab.py
test-live: setup browser
	BOOK_HTML=_build/no-book-for-test-live BOOK_ARTIFACTS=_build/test-artifacts/live \
	  $(call stage,test-live) $(BIN)/pytest $(BOOKLESS_BROWSER) -m browser -q -p no:xdist -p no:cacheprovider

# the deck tests alone (part of test-browser)
test-slides: setup browser
	$(call stage,test-slides) $(BIN)/pytest tests/slides -m browser -q -n 2 --dist loadscope

# A student's install: a wheel of the checkout into a fresh venv with [student] (from the pip cache), every
# student notebook run there, a live view mounted in its JupyterLab; prints the time, size and package count.
test-install: setup browser
	$(call stage,test-install) $(BIN)/pytest tests/install -q -p no:cacheprovider

# After make book: make slides, exercises, vendor and slides-pdf in turn, the site crawled for missing files after
# each (SITE_TARGETS_PDF=0 leaves slides-pdf out). Rewrites the built site, so it runs after the tests that read it.
test-targets: setup
	$(call stage,test-targets) $(BIN)/pytest tests/site -q -p no:xdist

# The floating-point comparisons (library vs JavaScript, Pinocchio, Modern Robotics) on two other OpenBLAS
# kernels than the one this CPU picks, each run in reverse order (pytest-reverse): a tolerance that only held
# by luck of one machine's rounding fails here. Not part of make test (about 2 x 4 min).
NUMERIC_TESTS := tests/test_interop.py tests/test_jacobian.py tests/test_velocity.py tests/test_ik.py \
  tests/test_analysis.py tests/test_lie.py tests/test_chain.py tests/test_representations.py \
  tests/test_redundancy.py tests/test_statics.py tests/test_dynamics.py tests/test_jacobian_derivative.py \
  tests/browser/test_live_kinematics.py tests/browser/test_live_gimbal.py tests/browser/test_live_columns.py \
  tests/browser/test_live_story.py tests/browser/test_live_views.py
BLAS_KERNELS ?= Prescott Sandybridge
test-numerics: setup browser
	@for core in $(BLAS_KERNELS); do \
	  echo "== OPENBLAS_CORETYPE=$$core, tests in reverse order"; \
	  OPENBLAS_CORETYPE=$$core $(PY) -m tools.blas_kernel --expect $$core || exit 1; \
	  OPENBLAS_CORETYPE=$$core MPLBACKEND=Agg $(BIN)/pytest -q -p no:xdist -p no:cacheprovider --reverse \
	    $(NUMERIC_TESTS) -k "not on_the_built_chapter_page" || exit 1; \
	done

bench: setup
	$(PY) -m tools.bench
	$(PY) -m tools.bench_live
	$(PY) -m tools.bench_live_spatial
	$(PY) -m tools.bench_grade
	$(PY) -m tools.bench_exercise_checks
	$(PY) -m tools.bench_ik_check
	$(PY) -m tools.bench_phone

# JupyterLab opens the MyST sources as notebooks (jupytext), not as text
LAB_OVERRIDES := $(VENV)/share/jupyter/lab/settings/overrides.json
lab: setup
	@mkdir -p $(dir $(LAB_OVERRIDES))
	@echo '{"@jupyterlab/docmanager-extension:plugin": {"defaultViewers": {"markdown": "Jupytext Notebook", "myst": "Jupytext Notebook"}}}' > $(LAB_OVERRIDES)
	$(BIN)/jupyter lab --notebook-dir=. $$( [ "$$(id -u)" = 0 ] && echo --allow-root ) chapters

clean:
	rm -rf _build _vendor

distclean: clean
	rm -rf $(VENV) node_modules

# ------------------------------------------------------------------ grading a class (chapters/teaching.md)
grade: setup sandbox
	@test -n "$(SUBMISSIONS)" || { echo "Usage: make grade SUBMISSIONS=<folder of student notebooks>" >&2; exit 2; }
	JACOBIANS_GRADE_UNSAFE=$(UNSAFE) $(PY) -m course.classroom.grade "$(SUBMISSIONS)" $(if $(ROSTER),--roster "$(ROSTER)") $(if $(STUDENT),--student "$(STUDENT)")

# ------------------------------------------------------------------ exercises and slides
exercises: setup
	$(PY) -m tools.make_exercises _build/exercises

slides: vendor browser
	$(PY) -m tools.build_slides $(SLIDES_PDF_ARGS)
	@$(REFRESH_COMPRESSED)

# the decks' PDFs (a page a slide) and handouts (with the speaker notes), with Debian's Chromium, into
# _build/html/slides/pdf (make book and make slides print them too)
slides-pdf: setup browser
	@test -f _build/html/slides/decks.json || $(MAKE) book
	$(PY) -m tools.build_slides --no-build $(if $(filter-out 0 1,$(SLIDES_PDF)),--pdf-only $(SLIDES_PDF))
