"""results-check.py - check a results.json against Gradescope's autograder
specification: the top-level fields and each test's, with their types.

    python3 results-check.py RESULTS.json [SCORE]

SCORE: the score it must have ("full": the sum of the tests' max_score).
Prints "ok SCORE MAX" or what is wrong; exit status 0 or 1.
(Used by test-course.sh and test-slurm.sh.)"""
import json
import sys

TOP = {"score", "execution_time", "output", "output_format", "test_output_format",
       "test_name_format", "visibility", "stdout_visibility", "extra_data", "tests", "leaderboard"}
TEST = {"score", "max_score", "status", "name", "name_format", "number", "output",
        "output_format", "tags", "visibility", "extra_data"}
VISIBILITY = {"visible", "hidden", "after_due_date", "after_published"}
FORMATS = {"text", "html", "simple_format", "md", "ansi"}


def check(d):
    assert isinstance(d, dict), "not an object"
    assert set(d) <= TOP, "unknown fields: %s" % (set(d) - TOP)
    assert isinstance(d["score"], (int, float)), "score is not a number"
    assert isinstance(d.get("execution_time", 0), int), "execution_time is not an integer"
    assert d.get("visibility", "visible") in VISIBILITY and d.get("stdout_visibility", "visible") in VISIBILITY
    assert isinstance(d.get("output", ""), str)
    assert isinstance(d["tests"], list) and d["tests"], "no tests"
    for t in d["tests"]:
        assert set(t) <= TEST, "unknown test fields: %s" % (set(t) - TEST)
        assert isinstance(t["name"], str) and t["name"], t
        assert isinstance(t["output"], str), t["name"]
        assert isinstance(t["score"], (int, float)) and isinstance(t["max_score"], (int, float)), t["name"]
        assert 0 <= t["score"] <= t["max_score"], t["name"]
        assert t["status"] in ("passed", "failed"), t["name"]
        assert t.get("visibility", "visible") in VISIBILITY, t["name"]
        assert t.get("output_format", "text") in FORMATS, t["name"]
        assert (t["status"] == "passed") == (t["score"] == t["max_score"]) or t["max_score"] == 0, t["name"]
    total = sum(t["score"] for t in d["tests"])
    assert d["score"] == total, "score %s is not the tests' sum %s" % (d["score"], total)
    return total, sum(t["max_score"] for t in d["tests"])


def main():
    try:
        with open(sys.argv[1]) as f:
            score, most = check(json.load(f))
        if len(sys.argv) > 2:
            want = most if sys.argv[2] == "full" else float(sys.argv[2])
            assert score == want, "score %s, expected %s" % (score, want)
    except (AssertionError, KeyError, ValueError, OSError) as e:
        print("%s: %s" % (sys.argv[1], e))
        return 1
    print("ok %s %s" % (score, most))
    return 0


if __name__ == "__main__":
    sys.exit(main())
