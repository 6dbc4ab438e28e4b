# leaks.awk - finds solution lines in a handout.
#
#   awk -f leaks.awk pass=known FILE... pass=solution REGIONS pass=handout FILE...
#
# known:    files whose lines a handout may contain (the stage outside its
#           LAB NN regions, the common core, the tests, ...)
# solution: the body lines of the LAB NN regions, as "FILE<tab>LINE<tab>text"
#           (markers.awk -v mode=inside)
# handout:  the handout's files, searched
# A solution line is a region line, compared with blanks squeezed, that is
# in no known file and is not trivial (fewer than `min` = 16 non-blank
# characters, such as "}" or "return false;").  Each handout line equal to
# one is printed as "FILE:LINE: text"; the exit status is then 1.

function norm(s) {
    gsub(/[ \t\r]+/, " ", s)
    sub(/^ /, "", s)
    sub(/ $/, "", s)
    return s
}

function trivial(s,    t) {
    t = s
    gsub(/ /, "", t)
    return length(t) < min
}

BEGIN {
    if (min == "") min = 16
    found = 0
}

pass == "known" {
    known[norm($0)] = 1
    next
}

pass == "solution" {
    text = $0
    sub(/^[^\t]*\t[^\t]*\t/, "", text)
    text = norm(text)
    if (!trivial(text) && !(text in known)) secret[text] = 1
    next
}

pass == "handout" {
    text = norm($0)
    if (text in secret) {
        printf "%s:%d: %s\n", FILENAME, FNR, text
        found++
    }
}

END { exit found > 0 ? 1 : 0 }
