/*
 * fuzz_cli_stage.c - one stage's main.c, compiled for the CLI harness.
 *
 * Built once per stage (tests/fuzz/Makefile) with STAGE_MAIN naming the
 * stage's main.c, STAGE_NAME its name and FUZZ_CLI_ENTRY the name its
 * main() takes here.  The stage's own source is included as it is, so the
 * harness runs the stage's real option table and every check main() makes
 * before it loads the scene (run_parse, the output and identity checks,
 * the stage's own checks such as --aa grid's square --spp).
 *
 * Two calls are redirected to the harness (fuzz_cli.c): run_parse, which
 * it wraps to check the values against the table main() passed, and
 * run_load_scene, where the command-line path ends: the harness checks
 * what was parsed and stops the run there, so no scene is read and
 * nothing is rendered or written.
 *
 * The Makefile links this object with the stage's other objects into one
 * relocatable object and keeps only FUZZ_CLI_ENTRY global: eight stages
 * define the same functions and live side by side in one harness.
 */
#define main FUZZ_CLI_ENTRY
#define run_parse fuzz_cli_run_parse
#define run_load_scene fuzz_cli_load_scene

/* The prototype the harness calls main() by (main.c defines it). */
int FUZZ_CLI_ENTRY(int argc, char **argv);

#include STAGE_MAIN
