# class.awk - the CSV and the HTML summary of grade-class.sh.
#
#   awk -v lab=05_bvh -v csv=FILE -v html=FILE -v pages=FILE -f class.awk TESTS RESULTS
#
# pages: "STUDENT NAME" lines, the report pages (students/STUDENT/pages/
# NAME.html) the summary links to.
# TESTS: "STUDENT KIND FROM PROGRAM TEST STATUS NOTE" lines (tab-separated:
# each student's grade.awk tests= file); RESULTS: one line per student, in
# the class's order, "STUDENT KEY SCORE LAB_PASSED LAB_TOTAL BUILD SECONDS
# REASON" (grade-class.sh's result files; score empty when not graded).
# The columns of the lab's tests are those of the lab (KIND lab, control or
# skipped), in the order the gradings list them.
BEGIN {
    FS = "\t"
    while ((getline l < pages) > 0) {
        split(l, w, "\t")
        page[w[1], ++npage[w[1]]] = w[2]
    }
}

FNR == NR {
    if ($2 == "lab" || $2 == "control" || $2 == "skipped") {
        t = $4 "/" $5
        if (!(t in col)) { col[t] = ++ncol; cname[ncol] = t; ctrl[ncol] = 0 }
        if ($2 == "control") ctrl[col[t]] = 1
        st[$1, t] = $6
        if ($2 == "lab" && $6 == "FAIL") nfail[t]++
        if ($2 == "lab") nrun[t]++
    }
    next
}

{
    n++
    who[n] = $1; score[n] = $3; passed[n] = $4; total[n] = $5; build[n] = $6; secs[n] = $7; why[n] = $8
}

function csvq(s) {
    if (s ~ /[",\n]/) { gsub(/"/, "\"\"", s); return "\"" s "\"" }
    return s
}

function esc(s) {
    gsub(/&/, "\\&amp;", s); gsub(/</, "\\&lt;", s); gsub(/>/, "\\&gt;", s); gsub(/"/, "\\&quot;", s)
    return s
}

END {
    printf "student,score,lab_passed,lab_total,build,seconds,reason" > csv
    for (c = 1; c <= ncol; c++) printf ",%s", csvq(cname[c] (ctrl[c] ? " (control)" : "")) > csv
    printf "\n" > csv
    for (i = 1; i <= n; i++) {
        printf "%s,%s,%s,%s,%s,%s,%s", csvq(who[i]), score[i], passed[i], total[i], build[i], secs[i], csvq(why[i]) > csv
        for (c = 1; c <= ncol; c++) printf ",%s", st[who[i], cname[c]] > csv
        printf "\n" > csv
    }
    close(csv)

    # The histogram: ten bins of 10 points (100 in the last), and the
    # submissions that could not be graded apart.
    for (i = 1; i <= n; i++) {
        if (score[i] == "") { ungraded++; continue }
        b = int(score[i] / 10); if (b > 9) b = 9
        bin[b]++; if (bin[b] > top) top = bin[b]
        sum += score[i]; graded++
    }
    print "<!DOCTYPE html>" > html
    print "<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" esc(lab) ": the class</title>" > html
    print "<style>body{font-family:sans-serif;margin:2em;max-width:60em}table{border-collapse:collapse}" > html
    print "td,th{padding:2px 8px;border-bottom:1px solid #ddd;text-align:left}td.n{text-align:right}" > html
    print ".bar{background:#4a7;height:1em;display:inline-block}.bad{color:#b00}</style></head><body>" > html
    printf "<h1>Lab %s: %d submission(s)</h1>\n", esc(lab), n > html
    printf "<p>Graded: %d, mean score %.1f%%; not graded: %d (rerun make grade-class to grade them).</p>\n",
        graded, (graded ? sum / graded : 0), ungraded + 0 > html
    print "<h2>Scores</h2><table><tr><th>score</th><th>students</th><th></th></tr>" > html
    for (b = 0; b < 10; b++)
        printf "<tr><td>%d-%d%%</td><td class=\"n\">%d</td><td><span class=\"bar\" style=\"width:%dem\"></span></td></tr>\n",
            10 * b, (b == 9 ? 100 : 10 * b + 9), bin[b] + 0, (top ? int(20 * bin[b] / top + 0.5) : 0) > html
    print "</table>" > html
    print "<h2>Tests most failed</h2><table><tr><th>test</th><th>failed by</th></tr>" > html
    for (c = 1; c <= ncol; c++) order[c] = c
    for (i = 2; i <= ncol; i++) for (j = i; j > 1 && nfail[cname[order[j - 1]]] < nfail[cname[order[j]]]; j--) {
        x = order[j]; order[j] = order[j - 1]; order[j - 1] = x
    }
    for (k = 1; k <= ncol && k <= 15; k++) {
        c = order[k]
        if (ctrl[c] || nfail[cname[c]] == 0) continue
        printf "<tr><td>%s</td><td class=\"n\">%d of %d</td></tr>\n", esc(cname[c]), nfail[cname[c]], nrun[cname[c]] > html
    }
    print "</table>" > html
    print "<h2>Students</h2><table><tr><th>student</th><th>score</th><th>tests</th><th>build</th><th>seconds</th><th>reason</th><th>report</th></tr>" > html
    for (i = 1; i <= n; i++) {
        d = "students/" who[i]
        printf "<tr><td>%s</td><td class=\"n\">%s</td><td class=\"n\">%s/%s</td><td%s>%s</td><td class=\"n\">%s</td><td>%s</td><td>",
            esc(who[i]), (score[i] == "" ? "-" : score[i] "%"), passed[i], total[i],
            (build[i] == "ok" ? "" : " class=\"bad\""), build[i], secs[i], esc(why[i]) > html
        if (score[i] != "") printf "<a href=\"%s/report.txt\">report</a>", esc(d) > html
        for (k = 1; k <= npage[who[i]]; k++)
            printf " <a href=\"%s/pages/%s.html\">%s</a>", esc(d), esc(page[who[i], k]), esc(page[who[i], k]) > html
        printf "</td></tr>\n" > html
    }
    print "</table></body></html>" > html
    close(html)
}
