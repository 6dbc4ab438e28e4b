# table.awk - the Markdown tables of make calibrate-compare, from its CSV.
#
#   awk -F, -v size=64 -v spp=64 -f table.awk calibration.csv
#
# Columns: verdict,scene,bias,bias_pct,sets,biased,rate,low,high,renders,
# seconds (calibrate.sh).  Two tables: the false alarms (bias "none": the
# rate at which correct work is called biased; the target is a rate at most
# alpha = 0.01 with the upper end of its interval at most 0.02) and the
# detections (a planted bias; the target for a 2% bias in a 32x32 region
# is at least 0.9).  Then the stage tests under other seeds (verdict
# "test:PROGRAM"), when run.
NR == 1 { next }
$1 == "grade-auto" { auto = 1 }
{
    row = sprintf("| %s | %s | %s | %d of %d | %.3f | %.3f-%.3f | %d | %.0f |", $1, $2, $3, $6, $5, $7, $8, $9, $10, $11)
    if ($1 ~ /^test:/) {
        tests[++nt] = sprintf("| %s | %d of %d | %.3f | %.3f-%.3f | %.0f | %s |", substr($1, 6), $6, $5, $7, $8, $9, $11, ($9 <= 0.02 ? "yes" : "no"))
    } else if ($3 == "none") {
        fa[++nf] = row " " ($7 <= 0.01 && $9 <= 0.02 ? "yes" : "no") " |"
    } else {
        target = ($3 == "region2" ? ($7 >= 0.9 ? "yes" : "no") : "")
        det[++nd] = row " " target " |"
    }
}
END {
    printf "Measured with %dx%d renders of %d spp (stage 07's defaults).\n\n", size, size, spp
    if (auto)
        printf "grade-auto: each set's two renders of %d spp are its pilot; the two renders judged have the spp it asks for.\n\n", spp
    print "False alarms: correct renders called \"biased\" (target: rate <= 0.01, upper end <= 0.02)."
    print ""
    print "| verdict | scene | bias | biased | rate | 95% interval | renders | processor s | meets |"
    print "|---|---|---|---|---|---|---|---|---|"
    for (i = 1; i <= nf; i++) print fa[i]
    print ""
    print "Detections: renders with a planted bias called \"biased\" (target for region2: rate >= 0.9)."
    print ""
    print "| verdict | scene | bias | biased | rate | 95% interval | renders | processor s | meets |"
    print "|---|---|---|---|---|---|---|---|---|"
    for (i = 1; i <= nd; i++) print det[i]
    if (nt) {
        print ""
        print "Statistical stage tests under other seeds (PATHCHECK_SEED): runs with a failure."
        print ""
        print "| test program | failed runs | rate | 95% interval | processor s | upper end <= 0.02 |"
        print "|---|---|---|---|---|---|"
        for (i = 1; i <= nt; i++) print tests[i]
    }
    print ""
    print "Intervals: Wilson's score interval at 95%."
}
