# stage.mk - the rules every stage Makefile includes after setting SRCS.
# The stage's name and build directory come from its directory alone, so no
# stage file names itself and no STAGE= or OUT= of a caller can redirect the
# build (`override`).
override ROOT := $(abspath ../..)
include $(ROOT)/common/config.mk

override STAGE := $(notdir $(CURDIR))
override OUT := $(BUILDROOT)$(STAGE)
# Every stage links the course's table (stages/course.c: which stage
# models which scene feature), which lives beside the stages, not in common/.
override OBJS := $(SRCS:%.c=$(OUT)/%.o) $(OUT)/course.o
override STAGE_CPPFLAGS := -DSTAGE_NAME=\"$(STAGE)\" -I$(ROOT)/stages
FLAGS_STAMP := $(call flags_stamp,$(OUT),$(CC) $(ALL_CPPFLAGS) $(STAGE_CPPFLAGS) $(ALL_CFLAGS) \
    | $(LINK) $(ALL_LDFLAGS) $(ALL_LDLIBS) | $(SRCS))

all: $(OUT)/render

$(OUT)/render: $(OBJS) $(COMMON_LIB) $(FLAGS_STAMP)
	$(LINK) $(ALL_LDFLAGS) -o $@ $(OBJS) $(COMMON_LIB) $(ALL_LDLIBS)

$(OUT)/%.o: %.c $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(CC) $(ALL_CPPFLAGS) $(STAGE_CPPFLAGS) $(ALL_CFLAGS) -MMD -MP -c -o $@ $<

$(OUT)/course.o: $(ROOT)/stages/course.c $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(CC) $(ALL_CPPFLAGS) $(STAGE_CPPFLAGS) $(ALL_CFLAGS) -MMD -MP -c -o $@ $<

# The common core is built by its own Makefile (the top level builds it
# once before the stages, so parallel stage builds never race on it).
$(COMMON_LIB): FORCE
	@$(MAKE) --no-print-directory -C $(ROOT)/common

# The stage's tests (tests/Makefile builds the stage, in double and float,
# and its test programs, then runs them; a program that does not build
# counts as failed).
test:
	@$(MAKE) --no-print-directory -C $(ROOT)/tests stage STAGE=$(STAGE)

clean:
	rm -rf $(OUT)

FORCE:
.PHONY: all test clean FORCE
$(call include_deps,$(OBJS:.o=.d))
