# stage.mk - the rules every stage Makefile includes after setting SRCS.
# The stage's name comes from its directory, so no stage file names itself.
ROOT := $(abspath ../..)
include $(ROOT)/common/config.mk

STAGE := $(notdir $(CURDIR))
OUT := $(BUILDROOT)$(STAGE)
OBJS := $(SRCS:%.c=$(OUT)/%.o)
STAGE_CPPFLAGS := -DSTAGE_NAME=\"$(STAGE)\"

all: $(OUT)/render

$(OUT)/render: $(OBJS) $(COMMON_LIB)
	$(LINK) $(ALL_LDFLAGS) -o $@ $(OBJS) $(COMMON_LIB) $(ALL_LDLIBS)

$(OUT)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(ALL_CPPFLAGS) $(STAGE_CPPFLAGS) $(ALL_CFLAGS) -MMD -MP -c -o $@ $<

# The common core is built by its own Makefile (the top level builds it
# once before the stages, so parallel stage builds never race on it).
$(COMMON_LIB): FORCE
	@$(MAKE) --no-print-directory -C $(ROOT)/common

# The double build's tests also run the float build of the stage (the
# extremes battery compares the two).
test: all
	@$(if $(filter double0,$(REAL)$(SANITIZE)),$(MAKE) --no-print-directory REAL=float all)
	@$(MAKE) --no-print-directory -C $(ROOT)/tests stage STAGE=$(STAGE)

clean:
	rm -rf $(OUT)

FORCE:
.PHONY: all test clean FORCE
-include $(OBJS:.o=.d)
