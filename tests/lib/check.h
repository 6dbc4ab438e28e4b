/*
 * check.h - the project's test harness, header-only.
 *
 * A test program defines its tests with TEST(name) { ... } and lists them in
 * a TEST_LIST; main() comes from TEST_MAIN().  Checks print
 *     file:line: check failed: expression
 * and mark the test failed; a test counts once, passed or failed.  The last
 * line is "N passed, N failed, N skipped", the line make test sums.
 *
 *     ./test_vec3            run every test
 *     ./test_vec3 NAME ...   run only the named tests
 *
 * SKIP("why") ends a test as skipped (a missing optional dependency).
 */
#ifndef CHECK_H
#define CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

struct check_state {
    int failed_checks; /* in the current test */
    int skipped; /* the current test called SKIP */
};

static struct check_state check_current;

#define CHECK(cond) \
    do { \
        if (!(cond)) { \
            printf("%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            check_current.failed_checks++; \
        } \
    } while (0)

/* CHECK with a printf-style explanation printed on failure. */
#define CHECK_MSG(cond, ...) \
    do { \
        if (!(cond)) { \
            printf("%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond); \
            printf(__VA_ARGS__); \
            printf("\n"); \
            check_current.failed_checks++; \
        } \
    } while (0)

/* A failed check that is all explanation: the function tests' messages
 * (tests/stage/NN_lab_functions.c), which a student reads. */
#define CHECK_FAIL(...) \
    do { \
        printf("%s:%d: check failed: ", __FILE__, __LINE__); \
        printf(__VA_ARGS__); \
        printf("\n"); \
        check_current.failed_checks++; \
    } while (0)

/* |a - b| <= tol, with both values printed on failure; NaN always fails. */
#define CHECK_NEAR(a, b, tol) \
    do { \
        double check_a_ = (double)(a); \
        double check_b_ = (double)(b); \
        if (!(fabs(check_a_ - check_b_) <= (double)(tol))) { \
            printf( \
                "%s:%d: check failed: %s = %.17g, %s = %.17g, tolerance %g\n", \
                __FILE__, \
                __LINE__, \
                #a, \
                check_a_, \
                #b, \
                check_b_, \
                (double)(tol)); \
            check_current.failed_checks++; \
        } \
    } while (0)

/* |a - b| <= rel |b|: a relative tolerance, each argument evaluated once. */
#define CHECK_REL(a, b, rel) \
    do { \
        double check_b_rel_ = (double)(b); \
        CHECK_NEAR((a), check_b_rel_, (rel) * fabs(check_b_rel_)); \
    } while (0)

#define SKIP(why) \
    do { \
        printf("%s:%d: skipped: %s\n", __FILE__, __LINE__, why); \
        check_current.skipped = 1; \
        return; \
    } while (0)

#define TEST(name) static void test_##name(void)

struct check_test {
    const char *name;
    void (*fn)(void);
};

#define TEST_ENTRY(name) \
    { \
#name, test_##name \
    }

/* Usage: TEST_MAIN(TEST_ENTRY(a), TEST_ENTRY(b), ...) */
#define TEST_MAIN(...) \
    int main(int argc, char **argv) \
    { \
        static const struct check_test tests[] = {__VA_ARGS__}; \
        return check_run(tests, sizeof tests / sizeof tests[0], argc, argv); \
    }

static int
check_selected(const char *name, int argc, char **argv)
{
    if (argc <= 1) {
        return 1;
    }
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], name) == 0) {
            return 1;
        }
    }
    return 0;
}

static int
check_run(const struct check_test *tests, size_t n, int argc, char **argv)
{
    int passed = 0;
    int failed = 0;
    int skipped = 0;
    for (size_t i = 0; i < n; i++) {
        if (!check_selected(tests[i].name, argc, argv)) {
            continue;
        }
        check_current.failed_checks = 0;
        check_current.skipped = 0;
        fflush(stdout);
        tests[i].fn();
        if (check_current.failed_checks > 0) {
            printf("FAIL %s\n", tests[i].name);
            failed++;
        } else if (check_current.skipped) {
            printf("skip %s\n", tests[i].name);
            skipped++;
        } else {
            printf("ok   %s\n", tests[i].name);
            passed++;
        }
        fflush(stdout);
    }
    printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    return failed > 0 ? 1 : 0;
}

#endif /* CHECK_H */
