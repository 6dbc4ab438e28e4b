# diffstat.awk - the numbers of one stage's diff for the table in docs/README.md.
#
#   awk -v lab=NN -f diffstat.awk pass=regions REGIONS pass=diff DIFF
#
# REGIONS: markers.awk -v mode=regions output for the new stage, with paths
# as the diff names them (NN_name/file.c).  DIFF: a unified diff from
# git diff --no-index --no-prefix.  Prints one line:
#   files new deleted added removed in_lab
# files: files touched (new and deleted included); added/removed: lines;
# in_lab: added lines inside LAB NN regions (their marker lines included).

function in_region(file, line,    i) {
    for (i = 1; i <= nr; i++)
        if (rf[i] == file && line >= ro[i] && line <= re[i]) return 1
    return 0
}

BEGIN { nr = 0; files = 0; added = 0; removed = 0; in_lab = 0; newf = 0; deleted = 0; hunk = 0 }

pass == "regions" {
    split($0, f, "\t")
    if (f[4] == lab) {
        nr++
        rf[nr] = f[1]
        ro[nr] = f[2] + 0
        re[nr] = f[3] + 0
    }
    next
}

/^diff --git / { files++; hunk = 0; cur = ""; next }

!hunk && /^new file mode/ { newf++; next }
!hunk && /^deleted file mode/ { deleted++; next }
!hunk && /^\+\+\+ / { cur = substr($0, 5); sub(/\t.*/, "", cur); next }

/^@@ / {
    hunk = 1
    s = $3
    sub(/^\+/, "", s)
    sub(/,.*/, "", s)
    line = s + 0
    next
}

hunk && /^\+/ {
    added++
    if (in_region(cur, line)) in_lab++
    line++
    next
}
hunk && /^-/ { removed++; next }
hunk && /^ / { line++; next }

END { print files, newf, deleted, added, removed, in_lab }
