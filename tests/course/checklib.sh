# checklib.sh - the result lines of the course tools' tests (test-course.sh,
# test-slurm.sh) and of tests/unseen/test-unseen.sh.  Sourced; the caller
# sets CHECKS (its prefix: course, slurm, unseen).  ok NAME, fail NAME [DETAIL...], skip NAME count; finish prints
# "N passed, N failed, N skipped" and exits 1 when a check failed.
passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok   $CHECKS/$1"; }
fail() {
    failed=$((failed + 1))
    echo "FAIL $CHECKS/$1"
    shift
    for fail_d in "$@"; do printf '%s\n' "$fail_d" | tail -n 30 | sed 's/^/    /'; done
}
skip() { skipped=$((skipped + 1)); echo "skip $CHECKS/$1"; }
finish() {
    echo "$passed passed, $failed failed, $skipped skipped"
    [ "$failed" -eq 0 ]
    exit
}
