# scenes/models/models.mk - the models made at build time (scenes/models/
# CREDITS.md).  Included by the top-level Makefile and by lab handouts'
# Makefiles, after ROOT is set and common/config.mk is included.
#
# build/models/happy_res3_subdiv16.glb: the 1,075,840-triangle Happy Buddha,
# happy_res3 with every triangle split into four at its edge midpoints,
# twice.  Too big for the repository (25 MB) and made in a second, so it is
# generated.  It does not depend on the build variant (REAL, SANITIZE): the
# same bytes from any of them, made once.  It needs the glTF loader.

MODELS := $(ROOT)/build/models/happy_res3_subdiv16.glb
STANFORD_CREDIT := Stanford 3D Scanning Repository, Stanford University Computer Graphics \
	Laboratory (Happy Buddha, happy_vrip_res3), subdivided twice by stagelight

ifeq ($(TINYGLTF),1)
models: $(MODELS)
else
models:
	@echo "models: not generated (no glTF support: apt-get install libtinygltf-dev)"
endif

# The tool is built by tests/Makefile (with the common core it needs).
$(ROOT)/build/models/happy_res3_subdiv16.glb: $(ROOT)/scenes/models/happy_res3.glb \
		$(ROOT)/tests/tools/subdivide_glb.c $(ROOT)/tests/lib/meshgen.c
	@$(MAKE) --no-print-directory -C $(ROOT)/tests $(BUILDROOT)tools/subdivide_glb
	@mkdir -p $(@D)
	@tmp=$@.tmp-$$$$; \
	$(BUILDROOT)tools/subdivide_glb $< 2 $$tmp "$(STANFORD_CREDIT)" && mv -f $$tmp $@ \
		|| { rm -f $$tmp; exit 1; }

.PHONY: models
