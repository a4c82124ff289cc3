# mcar: two entry points for a fresh machine (see README):
#   make demo   install, then build, check and render the bundled mobile car
#   make test   install (with test tools and urdfdom's check_urdf), then run the tests
# Debian packages installed here when missing: liburdfdom-tools (check_urdf, the peer
# the tests compare against); libegl1 libegl-mesa0 libgl1-mesa-dri libgl1 (headless
# OpenGL through EGL and Mesa's llvmpipe, for mcar render); graphviz (dot, which draws
# `mcar tree --graphviz x.svg`); libseccomp2 (the seccomp filter of the xacro sandbox);
# for `make bench` also time (GNU time, which measures the peak memory of each command);
# for `make test` also chromium (the browser tests/view drives through playwright), and
# ROS 1 from Debian (ROS_APT_PACKAGES: roslaunch, the state publishers, RViz) with xvfb,
# catkin and ament-cmake (tests/ros: the RViz launch, catkin and ament builds), strace
# (tests/untrusted: the system calls the confined Gazebo helper is refused);
# for `make rviz` also ROS_APT_PACKAGES (mcar itself needs none of ROS).
# g++ pkg-config libsdformat-dev (sdformat 12): the Gazebo helper mcar-sdformat (mcar check
# --gazebo, build --format sdf), built beside mcar in $(BIN) whenever they are there.

PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
SUDO   := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
APT_PACKAGES := liburdfdom-tools graphviz libegl1 libegl-mesa0 libgl1-mesa-dri libgl1 libseccomp2
ROS_APT_PACKAGES := python3-roslaunch rosbash ros-robot-state-publisher joint-state-publisher \
	joint-state-publisher-gui rviz python3-rostopic python3-rostest python3-tf2-ros tf-tools

APT_PACKAGES += g++ pkg-config libsdformat-dev
# The Gazebo helper: its path (tests build it elsewhere with GAZEBO_HELPER=...) and
# libsdformat's pkg-config name.
GAZEBO_HELPER ?= $(BIN)/mcar-sdformat
SDFORMAT_PC ?= sdformat12

.PHONY: demo test test-quick install system-deps build bench ci rviz clean gazebo-helper

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

install: $(BIN)/python
	$(BIN)/pip install --quiet ".[test,view,sweep,usd]"
	@$(MAKE) --no-print-directory gazebo-helper

# Built only where g++, pkg-config and libsdformat are there; elsewhere mcar check --gazebo
# says how to get it, and nothing else changes.
gazebo-helper:
	@if command -v g++ >/dev/null && command -v pkg-config >/dev/null && \
	    pkg-config --exists $(SDFORMAT_PC); then $(MAKE) --no-print-directory $(GAZEBO_HELPER); \
	else echo "mcar-sdformat not built: it needs g++, pkg-config and libsdformat-dev"; fi

$(GAZEBO_HELPER): helpers/mcar-sdformat.cc
	@mkdir -p $(dir $@)
	g++ -O2 -std=c++17 -Wall -Wextra $$(pkg-config --cflags $(SDFORMAT_PC)) $< -o $@.tmp \
	    $$(pkg-config --libs $(SDFORMAT_PC)) && mv $@.tmp $@

system-deps:
	@missing=""; for p in $(APT_PACKAGES); do \
	  dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

demo: install system-deps gazebo-helper
	$(BIN)/mcar build
	$(BIN)/mcar check --strict build/mobile_robot.urdf
	$(BIN)/mcar render

# Parallel workers (pytest-xdist): one per core, at least 2, at most 8. --dist loadgroup
# keeps a module that shares a module fixture on one worker, and tests/conftest.py starts
# the slowest first (tests/durations.txt). Not more workers than cores, though many tests
# wait on processes: the suite keeps the cores busy anyway (idle 3 % with 2 workers on
# 2 cores), and each more worker costs CPU (its own collection and launcher, and tests
# slowing each other down): measured on 2 cores, 4 workers 362 s, 3 workers 326 s,
# 2 workers 314 s.
TEST_WORKERS ?= $(shell n=$$(nproc 2>/dev/null || echo 2); \
	[ $$n -lt 2 ] && n=2; [ $$n -gt 8 ] && n=8; echo $$n)

test: APT_PACKAGES += chromium $(ROS_APT_PACKAGES) xvfb catkin ament-cmake strace
test: install system-deps gazebo-helper
	$(BIN)/pytest -n $(TEST_WORKERS) --dist loadgroup

# The inner loop: every test but those of over ~5 s (tests/durations.txt, the slow mark);
# `make test` still runs them all. Installs nothing: run `make test` once first.
test-quick:
	$(BIN)/pytest -n $(TEST_WORKERS) --dist loadgroup -m "not slow"

ci: install system-deps gazebo-helper
	$(BIN)/mcar ci

# The car in RViz, by the seed's command (docs/rviz.md); the venv's mcar builds it.
rviz: APT_PACKAGES += $(ROS_APT_PACKAGES)
rviz: install system-deps
	ROS_PACKAGE_PATH=$(CURDIR) roslaunch mobile_car_description display.launch \
	  model:='$$(find mobile_car_description)/urdf/mobile_robot.xacro'

bench: APT_PACKAGES += time
bench: install system-deps
	$(BIN)/python bench/run.py

build: install
	$(BIN)/mcar build

clean:
	rm -rf build renders .pytest_cache
