/*
 * fuzz.h - what the fuzzing harnesses of tests/fuzz share.
 *
 * Each harness fuzz_NAME.c defines the libFuzzer entry point
 * LLVMFuzzerTestOneInput and checks, besides "no crash", what its API
 * promises (a failure carries a message; a success is internally
 * consistent).  A broken promise calls fuzz_fail, which aborts: libFuzzer
 * records the input, the replay driver (replay.c) reports a crash.
 *
 * The same sources serve two builds:
 *   - make fuzz: clang, -fsanitize=fuzzer,address,undefined, libFuzzer's main;
 *   - make test: the ordinary compiler, each entry point renamed
 *     (-DLLVMFuzzerTestOneInput=fuzz_NAME_input) and called by replay.c on
 *     every file of tests/fuzz/regressions/NAME and tests/fuzz/seeds/NAME.
 */
#ifndef FUZZ_H
#define FUZZ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "diag.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A private directory for the files a harness hands to path-based loaders:
 * created on first use under $TMPDIR, removed (with the files fuzz_write put
 * there) when the process exits normally. */
const char *fuzz_dir(void);

/* Write data to fuzz_dir()/name, replacing an older file; returns the full
 * path (a static buffer per name slot: at most FUZZ_MAX_FILES names). */
#define FUZZ_MAX_FILES 8
const char *fuzz_write(const char *name, const uint8_t *data, size_t size);

/* Remove fuzz_dir()/name if it exists (a file an earlier input wrote). */
void fuzz_remove(const char *name);

/* Print "fuzz harness: broken promise: WHY" and abort. */
void fuzz_fail(const char *fmt, ...) DIAG_PRINTF(1, 2);

/* A failed load must say why: a non-empty message. */
void fuzz_require_message(const struct diag *err, const char *what);

#endif /* FUZZ_H */
