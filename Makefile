# glint — the two commands a new user needs:
#   make gallery   install what is missing, build, render every variant into out/gallery/index.html
#   make test      install what is missing, build, run the whole test suite (ctest)
# Both are idempotent and quick when everything is already there.

BUILD ?= build
JOBS  ?= $(shell nproc)
GLINT := $(BUILD)/app/glint

.PHONY: all setup setup-test configure build gallery test view accept-golden clean

all: build

setup:
	@scripts/setup

setup-test:
	@scripts/setup --test

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo

configure: $(BUILD)/build.ninja

build: setup configure
	cmake --build $(BUILD) -j $(JOBS)

gallery: build
	$(GLINT) gallery -o out/gallery
	@echo "open out/gallery/index.html"

test: setup-test configure
	cmake --build $(BUILD) -j $(JOBS)
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600

view: build
	$(GLINT) view

# After looking at build/test-output/golden/**/*.actual.png: make accept-golden [FILTER=scene]
accept-golden:
	scripts/accept-golden $(FILTER)

clean:
	rm -rf $(BUILD) out
