# aggregate.awk - trade.csv (one row per render) to settings.csv (one row per
# stage, scene, curve and knob set: the seeds of a setting summarised).
#
#   awk -F, -f tests/trade/aggregate.awk docs/trade/trade.csv > settings.csv
#
# Per setting: seeds (renders), seconds = the MEDIAN of seconds_render (or,
# with -v timebase=cpu, of cpu_seconds / threads; a time is noisy: one slow
# run must not move it), relmse_* = the MEAN over the
# seeds (an estimate of the expected error, E[relMSE]), rays and counters =
# means, efficiency = 1 / (relmse x seconds) from those, relMSE against the
# own reference where there is one, else against the GI reference.  main is
# 1 for the curve holding the stage's default knobs on that scene (the first
# such curve), the one plots use to stand for the stage.
# POSIX awk (mawk): no gawk extensions.

function median(list,    v, n, i, j, t) {
    n = split(list, v, " ")
    for (i = 2; i <= n; i++) {
        t = v[i] + 0
        for (j = i - 1; j >= 1 && v[j] + 0 > t; j--) v[j + 1] = v[j]
        v[j + 1] = t
    }
    if (n == 0) return ""
    return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
}

function mean(sum, count) { return count ? sum / count : "" }

function num(x) { return x == "" ? "" : sprintf("%.6g", x) }

NR == 1 {
    for (i = 1; i <= NF; i++) col[$i] = i
    split("stage scene knobs family value default seconds_render relmse_own relmse_gi frac5_own frac5_gi", need, " ")
    for (i in need) if (!(need[i] in col)) { print "aggregate.awk: no column " need[i] > "/dev/stderr"; exit 1 }
    next
}

{
    k = $col["stage"] SUBSEP $col["scene"] SUBSEP $col["family"] SUBSEP $col["knobs"]
    if (!(k in n)) {
        order[++nkeys] = k
        sk = $col["stage"] SUBSEP $col["scene"]
    }
    n[k]++
    # The time: seconds_render, or with timebase=cpu (TRADE_TIME=cpu) the
    # render's CPU seconds / threads, which other work on the machine inflates less.
    t = (timebase == "cpu" && ("cpu_seconds" in col)) ? $col["cpu_seconds"] / $col["threads"] : $col["seconds_render"]
    times[k] = times[k] " " t
    times_build[k] = times_build[k] " " (t + $col["seconds_build"])
    if ($col["relmse_own"] != "") { own[k] += $col["relmse_own"]; nown[k]++; f5own[k] += $col["frac5_own"] }
    if ($col["relmse_gi"] != "") { gi[k] += $col["relmse_gi"]; ngi[k]++; f5gi[k] += $col["frac5_gi"] }
    rays = $col["rays_camera"] + $col["rays_shadow"] + $col["rays_secondary"]
    rsum[k] += rays; rcam[k] += $col["rays_camera"]; rsh[k] += $col["rays_shadow"]; rsec[k] += $col["rays_secondary"]
    spp[k] += $col["spp"]; build[k] += $col["seconds_build"]
    ptests[k] += $col["prim_tests"]; nvisits[k] += $col["node_visits"]
    if (rays > 0) { tpr[k] += $col["prim_tests"] / rays; npr[k] += $col["node_visits"] / rays }
    pen[k] += $col["penumbra_pixels"]; aar[k] += $col["aa_refined_pixels"]
    value[k] = $col["value"]; ownref[k] = $col["own_ref"]; limit[k] = $col["own_is_limit"]
    tri[k] = $col["triangles"]; width[k] = $col["width"]
    if ($col["default"] == 1) {
        isdef[k] = 1
        sk = $col["stage"] SUBSEP $col["scene"]
        if (!(sk in mainfam)) mainfam[sk] = $col["family"]
    }
}

END {
    print "stage,scene,family,knobs,value,main,default,seeds,seconds,relmse_own,relmse_gi,frac5_own,frac5_gi,efficiency,rays,rays_camera,rays_shadow,rays_secondary,own_ref,own_is_limit,spp,seconds_build,seconds_render_build,prim_tests,node_visits,prim_tests_per_ray,node_visits_per_ray,penumbra_pixels,aa_refined_pixels,triangles,width"
    for (i = 1; i <= nkeys; i++) {
        k = order[i]
        split(k, p, SUBSEP)
        sk = p[1] SUBSEP p[2]
        m = n[k]
        t = median(times[k])
        o = mean(own[k], nown[k]); g = mean(gi[k], ngi[k])
        e = (o != "" ? o : g)
        eff = (e != "" && e > 0 && t > 0) ? 1 / (e * t) : ""
        printf "%s,%s,%s,%s,%s,%d,%d,%d,%s,%s,%s,%s,%s,%s,%.0f,%.0f,%.0f,%.0f,%s,%s,%.0f,%s,%s,%.0f,%.0f,%s,%s,%.0f,%.0f,%s,%s\n",
            p[1], p[2], p[3], p[4], value[k], (sk in mainfam && mainfam[sk] == p[3]), (k in isdef), m,
            num(t), num(o), num(g), num(mean(f5own[k], nown[k])), num(mean(f5gi[k], ngi[k])), num(eff),
            rsum[k] / m, rcam[k] / m, rsh[k] / m, rsec[k] / m, ownref[k], limit[k], spp[k] / m,
            num(build[k] / m), num(median(times_build[k])), ptests[k] / m, nvisits[k] / m, num(tpr[k] / m), num(npr[k] / m),
            pen[k] / m, aar[k] / m, tri[k], width[k]
    }
}
