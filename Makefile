# mcar: two entry points for a fresh machine (see README):
#   make demo   install, then build, check and render the bundled mobile car
#   make test   install (with test tools and urdfdom's check_urdf), then run the tests
# Debian packages installed here when missing: liburdfdom-tools (check_urdf, the peer
# the tests compare against); libegl1 libegl-mesa0 libgl1-mesa-dri libgl1 (headless
# OpenGL through EGL and Mesa's llvmpipe, for mcar render); graphviz (dot, which draws
# `mcar tree --graphviz x.svg`); libseccomp2 (the seccomp filter of the xacro sandbox);
# for `make bench` also time (GNU time, which measures the peak memory of each command);
# for `make test` also chromium (the browser tests/view drives through playwright).

PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
SUDO   := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
APT_PACKAGES := liburdfdom-tools graphviz libegl1 libegl-mesa0 libgl1-mesa-dri libgl1 libseccomp2

.PHONY: demo test install system-deps build bench ci clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

install: $(BIN)/python
	$(BIN)/pip install --quiet ".[test,view,sweep,usd]"

system-deps:
	@missing=""; for p in $(APT_PACKAGES); do \
	  dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

demo: install system-deps
	$(BIN)/mcar build
	$(BIN)/mcar check --strict build/mobile_robot.urdf
	$(BIN)/mcar render

test: APT_PACKAGES += chromium
test: install system-deps
	$(BIN)/pytest

ci: install system-deps
	$(BIN)/mcar ci

bench: APT_PACKAGES += time
bench: install system-deps
	$(BIN)/python bench/run.py

build: install
	$(BIN)/mcar build

clean:
	rm -rf build renders .pytest_cache
