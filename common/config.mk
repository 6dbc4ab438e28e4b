# config.mk - toolchain, warnings, precision and optional dependencies.
# Included by every Makefile of the project, after it has set ROOT.
#
# User knobs (GNU conventions: CFLAGS is yours to set):
#   CC CXX CFLAGS CXXFLAGS CPPFLAGS LDFLAGS LDLIBS
#   REAL=float      single-precision build (outputs in build/float/)
#   SANITIZE=1      AddressSanitizer + UBSan (outputs in build/sanitize/)
#   NATIVE=1        built for this processor, -march=native (build/native/)
#   FUZZ=1          clang's libFuzzer instrumentation + ASan + UBSan, for the
#                   harnesses of tests/fuzz (outputs in build/fuzz/; CC=clang)
#   WERROR=1        warnings are errors
#   OPENEXR=0|1     override the pkg-config detection of OpenEXR
#   TINYGLTF=0|1    override the detection of tinygltf (glTF meshes)

# GNU make 4 or newer ($(file) in the flags stamps below); macOS ships 3.81.
ifneq ($(filter 3.%,$(MAKE_VERSION)),)
$(error stagelight needs GNU make 4 or newer, this is $(MAKE_VERSION): on macOS, brew install make and run gmake, or open the devcontainer)
endif

CC ?= cc
CXX ?= c++
# -O3: the same results bit for bit as -O2 (no fast-math), and 16% fewer
# instructions for stage 07 on the Cornell boxes (callgrind; more inlining
# of the intersection loops), 3.5% on the bunny.
CFLAGS ?= -O3 -g
CXXFLAGS ?= -O2 -g
PKG_CONFIG ?= pkg-config

# -std=c11 also keeps GCC's floating-point contraction off (no fused
# multiply-add behind our back), so results are the same at every
# optimisation level; clang contracts within an expression by default where
# the processor has FMA (arm64, or x86-64 with NATIVE=1), so ARCH_FLAGS
# below says -ffp-contract=off to both.
WARN := -std=c11 -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes \
        -Wmissing-prototypes -Wvla -Wformat=2 -Wundef -Wwrite-strings
# clang's -Wstatic-in-inline takes the stages' `inline` intersection routines
# (geometry.c) for inline definitions, which may not call static functions;
# geometry.h declares them without `inline`, which makes them external
# definitions, to which that rule does not apply (C11 6.7.4p3, p7).
ifneq ($(findstring clang,$(shell $(CC) --version 2>/dev/null | head -n 1)),)
WARN += -Wno-static-in-inline
endif
ifeq ($(WERROR),1)
WARN += -Werror
endif

# common/ in layers, each using only those before it (tests/common/
# layers.sh): core (vectors, random numbers, diagnostics, counters, atomic
# files), image (the image and its formats), gltf (tinygltf behind a C API),
# scene (the model, then the loader), inspect (the path recorder), render
# (tiles on threads, stop signals, AOV passes), app (command line, run,
# outputs).  Each folder is on the include path: a file names a header, not
# its folder.
COMMON_LAYERS := core image gltf scene inspect render app
BASE_CPPFLAGS := -D_POSIX_C_SOURCE=200809L $(COMMON_LAYERS:%=-I$(ROOT)/common/%)

REAL ?= double
VARIANT :=
ifeq ($(REAL),float)
BASE_CPPFLAGS += -DREAL_IS_FLOAT=1
VARIANT := $(VARIANT)float/
else ifneq ($(REAL),double)
$(error REAL must be double or float, got '$(REAL)')
endif

SANITIZE ?= 0
SAN_FLAGS :=
ifeq ($(SANITIZE),1)
SAN_FLAGS := -O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
VARIANT := $(VARIANT)sanitize/
endif

# Coverage-guided fuzzing (make fuzz, tests/fuzz/Makefile): every object is
# instrumented for libFuzzer; only the harnesses link its main.
FUZZ ?= 0
ifeq ($(FUZZ),1)
SAN_FLAGS := -O1 -g -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer \
             -fno-sanitize-recover=undefined
VARIANT := $(VARIANT)fuzz/
endif

# A build for this machine's processor (make NATIVE=1: outputs in
# build/native/): -march=native lets the compiler use every vector
# instruction it has (AVX2 on most x86-64 processors since 2013, as Embree
# picks at run time); the results are the same bit for bit, since
# contraction stays off and no other floating-point rule changes.  Stage 09
# then takes eight children a node where AVX2 holds eight floats a
# register (bvh.h).
NATIVE ?= 0
ARCH_FLAGS := -ffp-contract=off
ifeq ($(NATIVE),1)
ARCH_FLAGS += -march=native
VARIANT := $(VARIANT)native/
endif

# Where things are built follows from the knobs above alone: a variable of
# the same name on the command line (or from an enclosing make) cannot move it.
override BUILDROOT := $(ROOT)/build/$(VARIANT)
override COMMON_LIB := $(BUILDROOT)common/libcommon.a

OPENEXR ?= $(shell $(PKG_CONFIG) --exists OpenEXR 2>/dev/null && echo 1 || echo 0)
ifeq ($(OPENEXR),1)
EXR_CPPFLAGS := -DHAVE_OPENEXR=1 $(shell $(PKG_CONFIG) --cflags OpenEXR)
EXR_LDLIBS := $(shell $(PKG_CONFIG) --libs OpenEXR)
endif

TINYGLTF ?= $(shell ($(PKG_CONFIG) --exists tinygltf 2>/dev/null || test -f /usr/include/tiny_gltf.h) && echo 1 || echo 0)
ifeq ($(TINYGLTF),1)
GLTF_LDLIBS := $(shell $(PKG_CONFIG) --libs tinygltf 2>/dev/null || echo -ltinygltf)
LINK := $(CXX)
LINK_LDLIBS := $(GLTF_LDLIBS) -lstdc++
else
LINK := $(CC)
endif

ALL_CPPFLAGS = $(BASE_CPPFLAGS) $(CPPFLAGS)
ALL_CFLAGS = $(WARN) $(CFLAGS) $(ARCH_FLAGS) $(SAN_FLAGS)
ALL_LDFLAGS = $(LDFLAGS) $(SAN_FLAGS) -pthread
ALL_LDLIBS = $(EXR_LDLIBS) $(LINK_LDLIBS) $(LDLIBS) -lm

# Flags stamps.  $(call flags_stamp,DIR,FLAGS) makes DIR/flags.stamp hold
# FLAGS (the compilers and flags that build DIR's files) and names it; the
# file is rewritten only when FLAGS differ from what it holds, so objects that
# depend on it are rebuilt exactly when their flags change, and a build
# directory never holds objects of two flag sets.  -Werror is left out: it
# changes no object (`make WERROR=1` recompiles only what is out of date);
# the project's path is written as @ROOT@, so that copies of one tree that
# share a build directory (the lab handouts' common core) agree.  The file's
# text is compared stripped: $(file <) of GNU make 4.3 may keep its final
# newline, and then every make rewrote the stamp of build/tools/ and rebuilt
# every tool.
flags_stamp = $(strip $(if $(call same_text,$(strip $(file <$(1)/flags.stamp)),$(call stamp_text,$(2))),,\
    $(shell mkdir -p '$(1)')$(file >$(1)/flags.stamp,$(call stamp_text,$(2))))$(1)/flags.stamp)
stamp_text = $(strip $(filter-out -Werror,$(subst $(ROOT),@ROOT@,$(1))))
same_text = $(and $(findstring x$(1)x,x$(2)x),$(findstring x$(2)x,x$(1)x))

# Dependency files.  $(call include_deps,FILES) includes the .d files
# (gcc -MMD -MP) among FILES that exist, each only while the source it was
# made from (its first prerequisite) still exists.  -MP keeps a header that
# has gone from stopping make, but not the source itself: after a source
# moves (the tests/ layout move put tests/meshgen.c in tests/lib/), an
# earlier build's .d file would stop every make of that directory with "No
# rule to make target 'meshgen.c'".  Such a .d file and its target are
# removed instead, so the target is built again from the source where it is
# now, which writes a fresh .d file.
include_deps = $(foreach d,$(wildcard $(1)),$(call dep_file,$(d),$(filter-out \,$(file <$(d)))))
dep_file = $(if $(wildcard $(word 2,$(2))),$(eval -include $(1)),$(shell rm -f '$(1)' '$(patsubst %:,%,$(firstword $(2)))'))
