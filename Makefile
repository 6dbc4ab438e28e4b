# stagelight - top-level Makefile.
#
#   make            build the common core, every stage (build/NN_name/render)
#                   and the tools (build/tools/: imgcmp, plotcsv, gen_meshes,
#                   subdivide_glb) and the generated models (make models)
#   make models     build/models/happy_res3_subdiv16.glb, the 1.08M-triangle
#                   Buddha, made from scenes/models/happy_res3.glb
#   make test       every test of common/ and of every stage; last line "N passed, N failed"
#   make test STAGE=03   only stage 03's tests (also STAGE=03_soft_shadows)
#   make sanitize   the same tests built with AddressSanitizer + UBSan (build/sanitize/);
#                   make sanitize STAGE=03 for one stage
#   make fuzz       every parser under libFuzzer for FUZZ_SECONDS (60) each (clang)
#   make demo       render the showcase scenes through the stages into out/ (and
#                   the mesh scenes through the stages with a BVH)
#   make gallery    scenes/README.md: every scene, its first correct stage and the last
#   make config     what the build found (OpenEXR, tinygltf, emscripten)
#   make web        every stage in the browser: build/web/, a static page
#                   (docs/web.md; needs emscripten's emcc)
#   make lab STAGE=05 OUT=dir   a lab handout; make grade LAB=dir grades one
#   make autograder STAGE=05 OUT=dir   Gradescope's autograder of a lab;
#                   make grade-class SUBMISSIONS=dir a whole class (CSV, HTML;
#                   SCHEDULER=slurm); make farm-render a render over Slurm tasks
#   make diffs      docs/diffs/*.diff and the diff table; make branches OUT=dir
#   make check-labs every check of every handout (make test runs the quick ones;
#                   CHECK_LABS_FLAGS=--no-earlier: all but the earlier stages' tests)
#   make clean
#   make help       one line per target
# Knobs: REAL=float (single precision, build/float/), NATIVE=1 (for this
# processor, build/native/), CFLAGS=..., WERROR=1,
# OPENEXR=0|1, TINYGLTF=0|1.  See common/config.mk.
override ROOT := $(abspath .)
include common/config.mk

STAGES := $(notdir $(wildcard stages/[0-9][0-9]_*))
LOGS := $(BUILDROOT)test-logs

all: $(STAGES) tools models

common:
	@$(MAKE) --no-print-directory -C common

# The generated models (build/models/), made after the common core.
include scenes/models/models.mk
# The model's rule builds its tool through tests/Makefile, as `tools` does:
# after it, so that under make -j the two never write the test-support
# archive (build/tests/libtestsupport.a) at once.  Here and not in models.mk:
# the lab handouts include models.mk and have no `tools` target.
$(MODELS): | common tools

# Each stage after the common core, so parallel stage builds never race on it.
$(STAGES): common
	@$(MAKE) --no-print-directory -C stages/$@

# The command-line tools of tests/tools/ (image comparison, plots, meshes).
tools: common
	@$(MAKE) --no-print-directory -C tests tools

# Every test program prints its own results; harness/test-all.sh runs the
# parts, prints one line per part and the total last, and exits non-zero when
# anything failed.  STAGE=NN (or a stage's name) runs only that stage's tests.
test:
	@MAKE='$(MAKE)' tests/harness/test-all.sh --logs $(LOGS) $(if $(STAGE),--stage '$(STAGE)')

sanitize:
	@$(MAKE) --no-print-directory SANITIZE=1 test

# Coverage-guided fuzzing of the scene, glTF, PFM and command-line parsers
# (tests/fuzz, docs/robustness.md); needs clang.  FUZZ_SECONDS per harness.
fuzz: common
	@$(MAKE) --no-print-directory -C tests/fuzz fuzz

config:
	@echo "compiler:  $(CC) ($(REAL) precision)"
	@echo "OpenEXR:   $(if $(filter 1,$(OPENEXR)),yes,no (apt-get install libopenexr-dev))"
	@echo "tinygltf:  $(if $(filter 1,$(TINYGLTF)),yes,no (apt-get install libtinygltf-dev))"
	@echo "emscripten: $(if $(EMCC_PATH),yes (make web),no (apt-get install emscripten, for make web))"

# The browser version: every stage compiled to WebAssembly, with the page,
# the scenes and the references, in build/web/ (common/web/, docs/web.md).
EMCC_PATH := $(shell command -v $${EMCC:-emcc} 2>/dev/null)
web:
ifeq ($(EMCC_PATH),)
	@echo "make web: needs emscripten's emcc, which is not installed: apt-get install emscripten" >&2
	@exit 1
else
	@$(MAKE) --no-print-directory -C common/web
endif

DEMO_SCENES := scenes/cornell_diffuse_point.scene scenes/cornell_diffuse_area.scene \
	scenes/cornell_specular_area.scene $(wildcard scenes/showcase*.scene)
# Scenes with meshes, through the stages with a BVH: the ones before it test
# every triangle for every ray (correct, but minutes to hours at full size).
ifeq ($(TINYGLTF),1)
DEMO_MESH_SCENES := scenes/bunny_cornell.scene scenes/glass_bunny.scene scenes/buddha.scene
endif
BVH_STAGES := $(filter-out 01_% 02_% 03_% 04_%,$(STAGES))

demo: all
	@mkdir -p out
	@for s in $(STAGES); do \
		for scene in $(DEMO_SCENES); do \
			name=$$(basename $$scene .scene); \
			echo "$$s: $$name"; \
			$(BUILDROOT)$$s/render -q -o out/$${s}_$$name.png $$scene || exit 1; \
		done; \
	done
	@for s in $(BVH_STAGES); do \
		for scene in $(DEMO_MESH_SCENES); do \
			name=$$(basename $$scene .scene); \
			echo "$$s: $$name"; \
			$(BUILDROOT)$$s/render -q -o out/$${s}_$$name.png $$scene || exit 1; \
		done; \
	done
	@echo "wrote out/*.png$(if $(DEMO_MESH_SCENES), (the mesh scenes from 05_bvh on), (no mesh scenes: no glTF support, apt-get install libtinygltf-dev))"

# The gallery of every scene (scenes/README.md, scenes/gallery/): each from
# the first stage that renders it correctly and from the last stage, with render times.
gallery: all
	@scenes/make-gallery.sh

# make trade: speed against accuracy for every stage -> docs/trade/ (< 15 min
# on 2 cores); make trade QUICK=1: reduced sweep -> build/trade/quick/ (< 1 min).
trade: all
	@$(MAKE) --no-print-directory -C tests/trade

# Speed: BVH build and trace rates, against brute force and Embree (tests/bench).
bench: all
	@$(MAKE) --no-print-directory -C tests/bench run

# Every verdict of every lab's default grade: how often it fails correct
# work, how often its paired pages find a 2% bias, the bug catalogue
# (tests/calibrate/grades.sh; about 0.75 processor-hours, the table into
# docs/calibration/README.md).  QUICK=1: 4 sets a lab, a check (CI).
calibrate: all
	@tests/calibrate/grades.sh $(if $(filter 1,$(QUICK)),--quick,--write) $(if $(SETS),--sets $(SETS))

# How often compare's verdicts (compare, its regions, the Mitsuba pages of
# make grade SPP=N|auto, check-planted's controls) call correct work
# biased, and how often they find planted biases -> docs/calibration/
# (tests/calibrate/calibrate.sh; hours).  CALIBRATE_FLAGS: the script's
# options, e.g. --size 256 --sets 50.
calibrate-compare: all
	@tests/calibrate/calibrate.sh $(CALIBRATE_FLAGS)

# The statistical stage tests under SEEDS other seeds each (TESTING.md):
# a line per test program: "PROGRAM RUNS FAILED_RUNS SECONDS".
SEEDS ?= 20
test-seeds: all
	@tests/calibrate/seed-offsets.sh $(SEEDS)

# The labs' statistical function tests on correct code under SEEDS (2000)
# seed offsets each: their false-alarm rates (docs/calibration/README.md).
calibrate-functions: all
	@tests/calibrate/functions.sh $(or $(SEEDS),2000)

# Every stage on random scenes nobody tuned it to, at random scales, and the
# path tracers against Mitsuba 3 on them (tests/unseen/, docs/unseen.md).
# UNSEEN_FLAGS: the script's options, e.g. --count 40 --first 100.
unseen: all
	@tests/unseen/unseen.sh $(UNSEEN_FLAGS)

# The lessons' pictures (docs/images/), rendered by the stages.
docs-images: all
	@docs/make-images.sh

# Coursework: lab handouts, grading, stage diffs (tests/lab/README.md).
lab:
	@if [ -z "$(STAGE)" ] || [ -z "$(OUT)" ]; then echo "usage: make lab STAGE=05 OUT=path [SOLUTION=1] [FORCE=1]" >&2; exit 2; fi
	@tests/lab/make-lab.sh $(if $(filter 1,$(SOLUTION)),--solution) $(if $(filter 1,$(FORCE)),--force) "$(STAGE)" "$(OUT)"

grade:
	@if [ -z "$(LAB)" ]; then echo "usage: make grade LAB=path [FULL=1] [SPP=N|auto]" >&2; exit 2; fi
	@tests/lab/grade.sh --pristine $(if $(filter 1,$(FULL)),--full) $(if $(SPP),--spp "$(SPP)") "$(LAB)"

# A course at scale (tests/course/README.md): Gradescope's autograder, a
# whole class graded (locally or as a Slurm job array), a render split over
# a Slurm cluster.
autograder:
	@if [ -z "$(STAGE)" ] || [ -z "$(OUT)" ]; then echo "usage: make autograder STAGE=05 OUT=path [SPP=N|auto]" >&2; exit 2; fi
	@tests/course/autograder.sh $(if $(SPP),--spp "$(SPP)") "$(STAGE)" "$(OUT)"

grade-class:
	@if [ -z "$(SUBMISSIONS)" ]; then echo "usage: make grade-class SUBMISSIONS=dir [STAGE=05] [OUT=dir] [SCHEDULER=local|slurm] [JOBS=N] [SPP=N|auto]" >&2; exit 2; fi
	@tests/course/grade-class.sh $(if $(STAGE),--stage "$(STAGE)") $(if $(OUT),--out "$(OUT)") \
		$(if $(SCHEDULER),--scheduler "$(SCHEDULER)") $(if $(JOBS),--jobs "$(JOBS)") $(if $(SPP),--spp "$(SPP)") "$(SUBMISSIONS)"

farm-render: all
	@if [ -z "$(SCENE)" ] || [ -z "$(SPP)" ] || [ -z "$(TASKS)" ]; then echo "usage: make farm-render SCENE=file SPP=N TASKS=N [STAGE=07] [OUT=dir]" >&2; exit 2; fi
	@tests/course/farm-render.sh $(if $(STAGE),--stage "$(STAGE)") $(if $(OUT),--out "$(OUT)") "$(SCENE)" "$(SPP)" "$(TASKS)"

diffs:
	@tests/lab/make-diffs.sh

# The SHA-256 of every stage's image of every scene, rendered small
# (tests/tools/image-hashes.sh): a change that must move no pixel runs it
# before (OUT=file) and after (COMPARE=file).
image-hashes: all
	@tests/tools/image-hashes.sh $(if $(OUT),--out "$(OUT)") $(if $(COMPARE),--compare "$(COMPARE)")

branches:
	@if [ -z "$(OUT)" ]; then echo "usage: make branches OUT=path [FORCE=1]" >&2; exit 2; fi
	@tests/lab/make-branches.sh $(if $(filter 1,$(FORCE)),--force) "$(OUT)"

# What make grade costs in each lab's handout, first and again, and its
# score beside busy loops (tests/lab/grade-cost.sh; LABS="07 08" for some).
grade-cost:
	@tests/lab/grade-cost.sh $(LABS)

check-labs: all
	@tests/lab/check-labs.sh --full $(CHECK_LABS_FLAGS)

# The reference scenes' feature masks, by which make grade breaks the error
# down (tests/reference/NAME.feature.pfm, docs/aov.md).
reference-masks: 07_pathtrace
	@tests/lab/reference-masks.sh

clean:
	rm -rf build

# make help: one line per target (tests/lab/test-lab-tools.sh checks that
# every target of .PHONY has its line).
help:
	@printf '%s\n' \
	'make                  build everything: common core, stages (build/NN_name/render), tools, models' \
	'make all              the same' \
	'make NN_name          one stage, e.g. make 05_bvh' \
	'make common           the common core (build/common/libcommon.a)' \
	'make tools            the command-line tools of tests/tools/ (build/tools/)' \
	'make models           the generated 1.08M-triangle Buddha (build/models/, needs tinygltf)' \
	'make test             every test; the last line is "N passed, N failed, N skipped"' \
	'make test STAGE=NN    only stage NN'"'"'s tests (STAGE=03 or STAGE=03_soft_shadows; sanitize too)' \
	'make sanitize         the tests built with AddressSanitizer and UBSan' \
	'make fuzz             every parser under libFuzzer for FUZZ_SECONDS each (clang)' \
	'make config           what the build found (OpenEXR, tinygltf, emscripten)' \
	'make web              every stage in the browser: build/web/, a static page (needs emcc)' \
	'make demo             the showcase and reference scenes through every stage into out/' \
	'make gallery          scenes/README.md: every scene of the library, rendered (scenes/make-gallery.sh)' \
	'make trade            speed against accuracy of every stage (docs/trade/; QUICK=1: short)' \
	'make bench            BVH build and trace rates, against brute force and Embree' \
	'make calibrate        every lab grade'\''s false alarms and detections, about 0.75 processor-hours (QUICK=1: CI'\''s check)' \
	'make calibrate-compare  false-alarm and detection rates of compare'\''s verdicts (docs/calibration/; hours)' \
	'make calibrate-functions  false-alarm rates of the labs'\'' statistical function tests (SEEDS=2000)' \
	'make test-seeds       the statistical stage tests under SEEDS (20) other seeds: failure rates' \
	'make unseen           every stage on random scenes at random scales; the path tracers against Mitsuba 3' \
	'make docs-images      the lessons'"'"' pictures (docs/images/)' \
	'make lab STAGE=NN OUT=dir   a lab handout (SOLUTION=1 the instructor'"'"'s; FORCE=1 moves a changed one aside)' \
	'make grade LAB=dir    build a handout, run its tests, score them, paired pages included (SPP=auto or N: the Mitsuba pages'"'"' samples)' \
	'make autograder STAGE=NN OUT=dir   the Gradescope autograder of a lab (OUT/autograder.zip)' \
	'make grade-class SUBMISSIONS=dir   grade every submission: a CSV and an HTML summary (SCHEDULER=slurm: a job array)' \
	'make farm-render SCENE=f SPP=N TASKS=N   one render split over N Slurm tasks by seed, merged' \
	'make diffs            docs/diffs/*.diff and the diff table of docs/README.md' \
	'make image-hashes     every stage'"'"'s image of every scene, hashed (OUT=file, then COMPARE=file)' \
	'make branches OUT=dir the stages as a git repository, one commit per stage (FORCE=1 replaces)' \
	'make check-labs       every check of every lab handout' \
	'make grade-cost       what make grade costs in each lab (processor s), idle and loaded' \
	'make reference-masks  tests/reference/*.feature.pfm: the reference scenes'"'"' regions, for make grade' \
	'make clean            remove build/' \
	'make help             this list' \
	'' \
	'Knobs, with any target: REAL=float (single precision, in build/float/: make REAL=float test),' \
	'NATIVE=1 (built for this processor: -march=native, in build/native/),' \
	'WERROR=1 (warnings are errors), OPENEXR=0|1, TINYGLTF=0|1, CFLAGS=... (common/config.mk)'

.PHONY: all models common tools test sanitize fuzz config web demo gallery trade bench calibrate calibrate-compare calibrate-functions test-seeds unseen docs-images clean lab grade autograder grade-class farm-render diffs image-hashes branches check-labs grade-cost reference-masks help $(STAGES)
