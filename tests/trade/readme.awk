# readme.awk - docs/trade/README.md from settings.csv (see aggregate.awk):
# the cheapest setting per stage and scene that reaches relMSE 0.01, and the
# answers, with this sweep's numbers, to the questions of the trade study.
#
#   awk -F, -v mode=full -v sweep=docs/trade/sweep.txt -v pairs=docs/trade/pairs.csv \
#       -v plots=LIST -f tests/trade/readme.awk docs/trade/settings.csv
#
# sweep: the sweep's command file, whose "# key=value" lines describe it;
# pairs: bvh=off renders compared with their bvh=on twins (may not exist);
# plots: "file|caption" lines of the SVGs report.sh drew.
# POSIX awk (mawk): no gawk extensions.

function g3(x) { return x == "" ? "-" : sprintf("%.3g", x) }
function g2(x) { return x == "" ? "-" : sprintf("%.2g", x) }

function secs(x) {
    if (x == "") return "-"
    if (x < 0.01) return sprintf("%.2g ms", x * 1000)
    if (x < 1) return sprintf("%.0f ms", x * 1000)
    return sprintf("%.3g s", x)
}

function count(x) {
    if (x >= 1e9) return sprintf("%.3gG", x / 1e9)
    if (x >= 1e6) return sprintf("%.3gM", x / 1e6)
    if (x >= 1e4) return sprintf("%.3gk", x / 1e3)
    return sprintf("%d", x)
}

function times(r) {
    if (r >= 1.05) return sprintf("%.3gx", r)
    return sprintf("%.2gx", r)
}

# A count that may be fractional (tests per ray): grouped when large.
function nice(x) { return x == "" ? "-" : x >= 1000 ? grouped(int(x + 0.5)) : sprintf("%.3g", x) }

function stage_num(s) { return substr(s, 1, 2) + 0 }

# Thousands separators for integers.
function grouped(n,    s, out) {
    s = sprintf("%d", n)
    out = ""
    while (length(s) > 3) { out = "," substr(s, length(s) - 2) out; s = substr(s, 1, length(s) - 3) }
    return s out
}

# The relMSE a setting is judged by: against its own reference, else GI.
function err(i) { return OWN[i] != "" ? OWN[i] : GI[i] }
function errname(i) { return OREF[i] == "direct" ? "direct" : "GI" }

# Row of a stage/scene/family/value, 0 if none.
function find(st, sc, fam, val,    i) {
    for (i = 1; i <= N; i++)
        if (S[i] == st && SC[i] == sc && F[i] == fam && V[i] == val) return i
    return 0
}

# The default row of a stage on a scene (its main curve first), 0 if none.
function default_row(st, sc,    i, any) {
    any = 0
    for (i = 1; i <= N; i++) {
        if (S[i] != st || SC[i] != sc || !DEF[i]) continue
        if (MAIN[i]) return i
        if (!any) any = i
    }
    return any
}

# Least-squares slope of ln(y) against ln(x) over the rows of a curve
# (x = the spp, or the swept value when xcol is "value"); sets FIT_N,
# FIT_X0, FIT_X1, FIT_Y0, FIT_Y1 (first and last points by x).
function fit(st, sc, fam, useown, xcol,    i, x, y, n, sx, sy, sxx, sxy) {
    n = sx = sy = sxx = sxy = 0
    FIT_X0 = FIT_X1 = ""
    for (i = 1; i <= N; i++) {
        if (S[i] != st || SC[i] != sc || F[i] != fam) continue
        x = (xcol == "value" ? V[i] : SPP[i]) + 0
        y = (useown ? OWN[i] : GI[i])
        if (x <= 0 || y == "" || y <= 0) continue
        n++
        sx += log(x); sy += log(y); sxx += log(x) * log(x); sxy += log(x) * log(y)
        if (FIT_X0 == "" || x < FIT_X0) { FIT_X0 = x; FIT_Y0 = y }
        if (FIT_X1 == "" || x > FIT_X1) { FIT_X1 = x; FIT_Y1 = y }
    }
    FIT_N = n
    if (n < 2 || n * sxx - sx * sx <= 0) return ""
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)
}

function plot_link(file) { return (file in PLOTFILE) ? "[" file "](" file ")" : "" }

BEGIN {
    while ((getline line < sweep) > 0) {
        if (line ~ /^# [a-z_]+=/) {
            sub(/^# /, "", line)
            k = line; sub(/=.*/, "", k)
            v = line; sub(/^[^=]*=/, "", v)
            INFO[k] = v
        }
    }
    close(sweep)
    NPAIRS = NZERO = 0
    while ((getline line < pairs) > 0) {
        if (line ~ /^pair,/) continue
        NPAIRS++
        n = split(line, p, ",")
        if (p[n] + 0 == 0 && p[n] != "") NZERO++
        else PAIRBAD = PAIRBAD " " p[2] "/" p[3] "/" p[4]
    }
    close(pairs)
    NPLOTS = 0
    while ((getline line < plots) > 0) {
        if (line == "") continue
        f = line; sub(/\|.*/, "", f)
        c = line; sub(/^[^|]*\|/, "", c)
        PLOT[++NPLOTS] = f; PLOTFILE[f] = c
    }
    close(plots)
}

NR == 1 { for (i = 1; i <= NF; i++) C[$i] = i; next }

{
    N++
    S[N] = $C["stage"]; SC[N] = $C["scene"]; F[N] = $C["family"]; K[N] = $C["knobs"]
    V[N] = $C["value"]; MAIN[N] = $C["main"] + 0; DEF[N] = $C["default"] + 0
    SEEDS[N] = $C["seeds"]; T[N] = $C["seconds"]; OWN[N] = $C["relmse_own"]; GI[N] = $C["relmse_gi"]
    EFF[N] = $C["efficiency"]; RAYS[N] = $C["rays"]; RCAM[N] = $C["rays_camera"]
    OREF[N] = $C["own_ref"]; LIM[N] = $C["own_is_limit"]; SPP[N] = $C["spp"]
    TRB[N] = $C["seconds_render_build"]; TPR[N] = $C["prim_tests_per_ray"]; NPR[N] = $C["node_visits_per_ray"]
    PEN[N] = $C["penumbra_pixels"]; TRI[N] = $C["triangles"] + 0
    if (!(S[N] in SEEN)) { SEEN[S[N]] = 1; STAGE[++NST] = S[N] }
}

END {
    NSC = split("cornell_diffuse_point cornell_diffuse_area cornell_specular_area", SCENE, " ")
    header()
    cheapest()
    q_stages()
    q_adaptive()
    q_nee_rr()
    q_bvh()
    q_spp()
    plots_section()
}

function header() {
    print "# Speed against accuracy, measured"
    print ""
    print "*Generated by `make trade` (`tests/trade/`) from this sweep's renders; do not edit:"
    print "change the generator and run it again.*"
    print ""
    printf "Sweep: **%s**, %s renders of %sx%s pixels, each with `-t %s` (%s threads), one render at a\n",
        INFO["mode"], grouped(INFO["runs"]), INFO["width"], INFO["width"], INFO["threads"], INFO["threads"]
    printf "time: %s s of wall-clock time on %s cores (%s); load average before and after: %s / %s.\n",
        INFO["wall_seconds"], INFO["cores"], INFO["cpu"] == "" ? "CPU not reported" : INFO["cpu"],
        INFO["load_before"], INFO["load_after"]
    if (INFO["mode"] == "quick") {
        print "The references are shrunk 4x4 by a box filter to match (exact for box-filtered pixels), but the"
        print "errors of a quick sweep are not comparable with a full one's: a bigger pixel averages more."
    }
    print "Stages: " INFO["stages"] "."
    if (INFO["cpu_seconds"] != "") {
        printf "Timing hygiene: a render whose seconds_render x threads exceeded 1.4x its CPU seconds (the\n"
        printf "cores were shared with other work) was run once more, within %s s per sweep, and its faster\n", "60"
        printf "attempt kept (the image is the same every time): %d renders were retried, for %s s. In all the\n", INFO["retried_runs"], INFO["retry_seconds"]
        printf "renders took %s s (`seconds_render`, summed) for %s CPU seconds: seconds_render x threads / CPU\n", INFO["render_seconds"], INFO["cpu_seconds"]
        printf "seconds = **%s** (a little above 1 with both cores free, as two threads are never quite evenly\n", INFO["wall_over_cpu"]
        printf "busy), and %d renders still took over 1.5x the time their CPU seconds imply (their times are\n", INFO["contended_runs"]
        printf "inflated; their errors are not). Each row's `cpu_seconds` and `attempts` are in `trade.csv`.\n"
        if (INFO["wall_over_cpu"] + 0 > 1.25)
            printf "**This sweep ran on a shared machine: its times, and the efficiencies and speed-ups computed\nfrom them, are inflated unevenly (up to about 2x). Run `make trade` on an idle machine for clean times.**\n"
    }
    if (timebase == "cpu")
        print "**Times below are CPU seconds / threads (TRADE_TIME=cpu), not seconds_render.**"
    print "Times are `seconds_render` from `--stats` (the median over the seeds of a setting); errors are the"
    print "mean over the seeds. Every number but the times (and the efficiencies, which divide by a time) is"
    print "reproduced exactly by running the sweep again: the seeds are fixed."
    if (INFO["nonfinite_runs"] + 0 > 0)
        printf "\n**%d renders had NaN/Inf pixels** (left out of their errors; see `trade.csv`).\n", INFO["nonfinite_runs"]
    print ""
    if ("summary.svg" in PLOTFILE) {
        print "![error against time, every stage](summary.svg)"
        print ""
        print "*" PLOTFILE["summary.svg"] "*"
        print ""
    }
    print "**Reading the numbers.**"
    print "relMSE = mean over pixels and channels of (x - r)^2 / (r^2 + 0.01), x the render, r the reference."
    print "Each render is compared with two references from Mitsuba 3 (`tests/reference/`): the stage's **own**"
    print "limit (`_direct`, direct light only, for the direct-light stages 01-06; the specular scene has none;"
    print "`_gi` for 07), which says how far this setting is from what the stage can ever compute, and **GI**"
    print "(full global illumination, the truth), which says how much of the truth the stage captures at all."
    print "Efficiency = 1 / (relMSE x seconds), relMSE against the own reference (GI where there is none):"
    print "higher is better, and for an unbiased estimator it does not depend on the sample count."
    print ""
    print "Files: `trade.csv`, one row per render: stage, scene, knobs, seed, seconds_render, seconds_total,"
    print "rays_camera, rays_shadow, rays_secondary, relmse/rmse/mae/frac5 against the own reference (`_own`)"
    print "and the GI one (`_gi`), efficiency; then own_ref (direct, gi or empty), own_is_limit (1 if the stage"
    print "converges to it), family (the curve) and value (its swept knob), default (1: the stage's defaults),"
    print "and from `--stats` spp, width, height, threads, seconds_build, prim_tests, node_visits,"
    print "penumbra_pixels, aa_refined_pixels; triangles (mesh scenes) and cpu_seconds (the render's user +"
    print "system time). `settings.csv`: one row per setting, seeds summarised (median time, mean errors)."
    print "`sweep.txt`: the sweep's parameters and every command line, in the order of the CSV's rows."
    if (NPAIRS > 0) print "`pairs.csv`: each render without the BVH against the same render with it (relMSE; 0: identical)."
    print ""
}

function cheapest(    s, j, st, sc, i, best, bi, bt, slope, need, reason, main_fam) {
    print "## Cheapest setting that reaches relMSE 0.01"
    print ""
    print "Per stage and scene: the fastest setting of the sweep whose mean relMSE against the stage's own"
    print "reference (GI where it has none) is at most 0.01, its time and its rays (camera + shadow +"
    print "secondary, per render)."
    print ""
    print "| stage | scene | against | cheapest setting | relMSE | seconds | rays |"
    print "|---|---|---|---|---|---|---|"
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        for (j = 1; j <= NSC; j++) {
            sc = SCENE[j]
            bi = 0; best = ""
            for (i = 1; i <= N; i++) {
                if (S[i] != st || SC[i] != sc || err(i) == "") continue
                if (err(i) <= 0.01 && (bi == 0 || T[i] < T[bi])) bi = i
                if (best == "" || err(i) < err(best)) best = i
            }
            if (best == "") continue
            if (bi) {
                printf "| %s | %s | %s | `%s` | %s | %s | %s |\n", st, sc, errname(bi), K[bi], g3(err(bi)), secs(T[bi]), count(RAYS[bi])
                continue
            }
            reason = ""
            if (OREF[best] == "" && stage_num(st) < 7)
                reason = "direct light only: the indirect light it never computes is a floor"
            else if (LIM[best] == 0 && stage_num(st) == 1)
                reason = "no shadows: this reference is not its limit"
            else if (LIM[best] == 0)
                reason = "it lights the area light as a point: this reference is not its limit"
            else if (F[best] ~ /^nee=/) {
                slope = fit(st, sc, F[best], OREF[best] == "direct", "spp")
                if (slope != "" && slope < -0.5) {
                    need = SPP[best] * exp(log(err(best) / 0.01) / -slope)
                    reason = sprintf("not within the sweep; at the fitted rate (relMSE ~ spp^%.2f) about %s spp, about %s", slope, grouped(need), secs(T[best] * need / SPP[best]))
                }
            }
            if (reason == "") reason = "not within the sweep"
            printf "| %s | %s | %s | **none** (%s); best: `%s` | %s | %s | %s |\n", st, sc, errname(best), reason, K[best], g3(err(best)), secs(T[best]), count(RAYS[best])
        }
    }
    print ""
}

function q_stages(    j, sc, s, st, i, p, pi, y, ya, yb, what, fl) {
    print "## 1. What does each stage buy, in error, and what does it cost, in time?"
    print ""
    print "Each stage at its default knobs (`render` without options), per scene. relMSE against the"
    print "direct-light reference (the limit of 02+ for the point light, of 03+ for the area light) and"
    print "against the GI truth; `-` where there is no such reference."
    print ""
    for (j = 1; j <= NSC; j++) {
        sc = SCENE[j]
        print "**" sc "**"
        print ""
        print "| stage | default knobs | seconds | rays | relMSE vs direct | relMSE vs GI |"
        print "|---|---|---|---|---|---|"
        for (s = 1; s <= NST; s++) {
            i = default_row(STAGE[s], sc)
            if (!i) continue
            printf "| %s | `%s` | %s | %s | %s | %s |\n", S[i], K[i], secs(T[i]), count(RAYS[i]),
                OREF[i] == "direct" ? g3(OWN[i]) : "-", g3(GI[i])
        }
        print ""
    }
    print "Each stage against the one before it, on the scene that shows its idea (defaults):"
    print ""
    p = ""
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        sc = (stage_num(st) <= 2 ? "cornell_diffuse_point" : stage_num(st) == 4 ? "cornell_specular_area" : "cornell_diffuse_area")
        i = default_row(st, sc)
        pi = (p != "" ? default_row(p, sc) : 0)
        if (i && pi) {
            # Compare against the direct reference when both have it, else GI.
            if (OREF[i] == "direct" && OREF[pi] == "direct") { ya = OWN[pi]; yb = OWN[i]; what = "vs direct" }
            else { ya = GI[pi]; yb = GI[i]; what = "vs GI" }
            if (ya == yb)
                printf "- **%s** on %s: the same image error (relMSE %s %s) in %s the time (%s -> %s), with %s the rays.\n",
                    st, sc, what, g3(yb), times(T[i] / T[pi]), secs(T[pi]), secs(T[i]), times(RAYS[i] / RAYS[pi])
            else
                printf "- **%s** on %s: relMSE %s %s -> %s (%s lower) for %s the time (%s -> %s) and %s the rays.\n",
                    st, sc, what, g3(ya), g3(yb), times(ya / yb), times(T[i] / T[pi]), secs(T[pi]), secs(T[i]),
                    times(RAYS[i] / RAYS[pi])
        } else if (i) {
            printf "- **%s** on %s: relMSE vs %s %s in %s.\n", st, sc, errname(i), g3(err(i)), secs(T[i])
        }
        p = st
    }
    print ""
    fl = ""
    for (j = 1; j <= NSC; j++)
        if (("floor_" SCENE[j]) in INFO)
            fl = fl (fl == "" ? "" : ", ") g3(INFO["floor_" SCENE[j]]) " on " SCENE[j]
    print "How much of the truth a direct-light stage (01-06) can ever capture: at best it converges to the"
    print "direct-light reference, whose own relMSE against the GI reference is " fl "."
    print "No knob of theirs goes below that: the light that bounced off a wall first is missing."
    print "Only 07 does, given time (see the summary plot)."
    aliasing()
    print ""
}

function q_adaptive(    i, u, st, sc, ratio, n, pay, npay, tpay_max, tnot_min, line, best, worst, bi, wi, pfrac) {
    print "## 2. Where does adaptive penumbra sampling pay off, and where not?"
    print ""
    print "`--adaptive K,M` shoots K probe shadow rays per area light; only where they disagree (a penumbra)"
    print "does it shoot M more. It is compared with `--shadow-samples K+M` (the same rays where it refines)."
    print "Penumbra share: shading points that took the refined path, per camera ray."
    print ""
    print "| stage | scene | adaptive K:M | vs uniform | relMSE adaptive / uniform | seconds adaptive / uniform | efficiency gain | penumbra share |"
    print "|---|---|---|---|---|---|---|---|"
    n = npay = 0
    tpay_max = 0; tnot_min = 1e30; best = worst = ""
    for (i = 1; i <= N; i++) {
        if (F[i] !~ /^adaptive=/) continue
        u = find(S[i], SC[i], "shadow", V[i])
        if (!u || EFF[i] == "" || EFF[u] == "") continue
        ratio = EFF[i] / EFF[u]
        n++
        if (ratio > 1) { npay++; if (V[i] + 0 > tpay_max) tpay_max = V[i] + 0 }
        else if (V[i] + 0 < tnot_min) tnot_min = V[i] + 0
        if (best == "" || ratio > best) { best = ratio; bi = i }
        if (worst == "" || ratio < worst) { worst = ratio; wi = i }
        pfrac = RCAM[i] > 0 ? PEN[i] / RCAM[i] : 0
        printf "| %s | %s | %s | `%s` | %s / %s | %s / %s | **%s** | %.1f%% |\n", S[i], SC[i], substr(K[i], 10),
            K[u], g3(err(i)), g3(err(u)), secs(T[i]), secs(T[u]), times(ratio), 100 * pfrac
    }
    print ""
    if (n == 0) {
        print "No stage with `--adaptive` was swept on an area-light scene."
        print ""
        return
    }
    printf "Adaptive sampling pays off (efficiency gain > 1) in %d of %d settings. ", npay, n
    printf "Best: `%s` on %s (%s) at %s the efficiency of `%s`; worst: `%s` on %s (%s) at %s.\n",
        K[bi], SC[bi], S[bi], times(best), "shadow-samples " V[bi], K[wi], SC[wi], S[wi], times(worst)
    if (npay > 0 && npay < n && tpay_max < tnot_min)
        printf "In this sweep it pays off up to %d shadow rays per point and not from %d on.\n", tpay_max, tnot_min
    print "It saves rays where the probes agree (fully lit or fully shadowed points, most of these scenes) and"
    print "spends them where they do not. Its price is bias: a point whose K probes agree by chance although"
    print "it sees part of the light is never refined, so past some budget its error stops falling, while"
    print "uniform sampling keeps converging. Per probe count, relMSE over the budgets swept:"
    print ""
    adaptive_floors()
    print ""
}

# Per stage, scene and probe count K: relMSE at the smallest and largest
# budget, against uniform sampling at the same budgets.
function adaptive_floors(    i, j, key, lo, hi, ulo, uhi, seen) {
    for (i = 1; i <= N; i++) {
        if (F[i] !~ /^adaptive=/) continue
        key = S[i] SUBSEP SC[i] SUBSEP F[i]
        if (key in seen) continue
        seen[key] = 1
        lo = hi = 0
        for (j = 1; j <= N; j++) {
            if (S[j] != S[i] || SC[j] != SC[i] || F[j] != F[i] || err(j) == "") continue
            if (!lo || V[j] + 0 < V[lo] + 0) lo = j
            if (!hi || V[j] + 0 > V[hi] + 0) hi = j
        }
        ulo = find(S[i], SC[i], "shadow", V[lo])
        uhi = find(S[i], SC[i], "shadow", V[hi])
        if (V[lo] == V[hi]) {
            printf "- %s, %s, K = %s: %s at %s rays per point%s%s.\n", S[i], SC[i], substr(F[i], 10), g3(err(lo)), V[lo],
                ulo ? sprintf(" (uniform: %s)", g3(err(ulo))) : "",
                OREF[lo] == "" ? "; against GI, whose error the missing indirect light dominates: only the time differs" : ""
            continue
        }
        printf "- %s, %s, K = %s: %s -> %s from %s to %s rays per point%s%s.\n", S[i], SC[i], substr(F[i], 10),
            g3(err(lo)), g3(err(hi)), V[lo], V[hi],
            (ulo && uhi) ? sprintf(" (uniform: %s -> %s)", g3(err(ulo)), g3(err(uhi))) : "",
            OREF[lo] == "" ? "; against GI, whose error the missing indirect light dominates: only the time differs" : ""
    }
}

function q_nee_rr(    j, sc, st, s, v, a, b, c, d, found, r, any) {
    print "## 3. How much do NEE and RR each change efficiency?"
    print ""
    print "Efficiency = 1 / (relMSE vs GI x seconds), at the largest spp every variant ran (same seeds)."
    print "With `--no-nee` paths must hit the area light by chance; a point light is always sampled, so NEE"
    print "is only toggled on the area-light scenes. `--no-rr` keeps every path until it leaves the box."
    print ""
    any = 0
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        for (j = 1; j <= NSC; j++) {
            sc = SCENE[j]
            # The largest spp at which nee=on rr=on and the others exist.
            found = ""
            for (r = 1; r <= N; r++) {
                if (S[r] != st || SC[r] != sc || F[r] != "nee=on rr=on") continue
                if (!find(st, sc, "nee=on rr=off", V[r]) && !find(st, sc, "nee=off rr=on", V[r])) continue
                if (found == "" || V[r] + 0 > found + 0) found = V[r]
            }
            if (found == "") continue
            if (!any) {
                print "| stage | scene | spp | variant | relMSE | seconds | efficiency | vs NEE+RR |"
                print "|---|---|---|---|---|---|---|---|"
                any = 1
            }
            a = find(st, sc, "nee=on rr=on", found)
            split("nee=on rr=on|nee=off rr=on|nee=on rr=off|nee=off rr=off", VAR, "|")
            for (v = 1; v <= 4; v++) {
                b = find(st, sc, VAR[v], found)
                if (!b) continue
                printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", st, sc, found, VAR[v], g3(GI[b]), secs(T[b]), g3(EFF[b]),
                    v == 1 ? "1" : times(EFF[b] / EFF[a])
            }
            SPPQ[st, sc] = found
        }
    }
    if (!any) {
        print "No stage with `--no-nee`/`--no-rr` was swept."
        print ""
        return
    }
    print ""
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        for (j = 1; j <= NSC; j++) {
            sc = SCENE[j]
            if (!((st, sc) in SPPQ)) continue
            found = SPPQ[st, sc]
            a = find(st, sc, "nee=on rr=on", found)
            b = find(st, sc, "nee=off rr=on", found)
            c = find(st, sc, "nee=on rr=off", found)
            d = find(st, sc, "nee=off rr=off", found)
            if (b) printf "- NEE %s efficiency on %s by **%s** at %s spp (relMSE %s -> %s, %s -> %s).\n",
                (EFF[a] >= EFF[b] ? "improves" : "lowers"), sc, times((EFF[a] >= EFF[b]) ? EFF[a] / EFF[b] : EFF[b] / EFF[a]),
                found, g3(GI[b]), g3(GI[a]), secs(T[b]), secs(T[a])
            if (c) printf "- RR %s efficiency on %s by **%s** at %s spp with NEE (time %s -> %s, relMSE %s -> %s)%s.\n",
                (EFF[a] >= EFF[c] ? "improves" : "lowers"), sc, times((EFF[a] >= EFF[c]) ? EFF[a] / EFF[c] : EFF[c] / EFF[a]),
                found, secs(T[c]), secs(T[a]), g3(GI[c]), g3(GI[a]),
                (b && d) ? sprintf("; without NEE by %s", times(EFF[b] / EFF[d])) : ""
        }
    }
    print ""
    levers()
    print "RR ends a path with a probability and reweights the survivors: it cuts time and adds variance."
    print "It pays when the saved time outweighs the added noise; the time saved is largest where paths"
    print "are long (bright walls, open glass), the added noise largest where rare long paths carry the light."
    print ""
    roulette()
    print "Path length: `--max-depth N` keeps paths of at most N segments, the camera ray included; relMSE"
    print "against GI at 16 spp for each N, then unbounded (with RR), then the direct-light floor (the"
    print "direct reference against the GI one), which the shortest paths that still see light converge to:"
    print ""
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        for (j = 1; j <= NSC; j++) {
            sc = SCENE[j]
            depth_line(st, sc)
        }
    }
    print ""
}

# The other knobs of a path tracer (sampler, MIS, light sampling): every
# family "nee=on rr=on KNOB..." against "nee=on rr=on" (the defaults) at the
# largest spp both ran, with the efficiency gain.
function levers(    s, st, j, sc, r, fam, best, a, b, any, seen) {
    any = 0
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        for (j = 1; j <= NSC; j++) {
            sc = SCENE[j]
            delete seen
            for (r = 1; r <= N; r++) {
                fam = F[r]
                if (S[r] != st || SC[r] != sc || index(fam, "nee=on rr=on ") != 1 || (fam in seen)) continue
                seen[fam] = 1
                best = ""
                for (b = 1; b <= N; b++) {
                    if (S[b] != st || SC[b] != sc || F[b] != fam || !find(st, sc, "nee=on rr=on", V[b])) continue
                    if (best == "" || V[b] + 0 > best + 0) best = V[b]
                }
                if (best == "") continue
                if (!any) {
                    print "The other levers of the path tracer, each against the defaults (`nee=on rr=on`) at the largest"
                    print "spp both ran; efficiency gain = efficiency / the defaults' efficiency:"
                    print ""
                    print "| stage | scene | spp | knobs | relMSE | seconds | efficiency | gain |"
                    print "|---|---|---|---|---|---|---|---|"
                    any = 1
                }
                a = find(st, sc, "nee=on rr=on", best)
                b = find(st, sc, fam, best)
                printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", st, sc, best, substr(fam, 14), g3(GI[b]), secs(T[b]),
                    g3(EFF[b]), times(EFF[b] / EFF[a])
            }
        }
    }
    if (any) print ""
}

function q_bvh(    i, j, st, nt, tri, on, off, n, sp, cross, nrow, last_off, k, nsp, p0, p1) {
    print "## 4. What does the BVH change, and from how many primitives on?"
    print ""
    nt = 0
    for (i = 1; i <= N; i++)
        if (SC[i] ~ /^mesh_/ && !((TRI[i] + 0) in HAVE)) { HAVE[TRI[i] + 0] = 1; TRIS[++nt] = TRI[i] + 0; st = S[i] }
    if (nt == 0) {
        print "Not measured: no stage with `--no-bvh` was built when this sweep ran (05_bvh adds it)."
        print "Run `make trade` again once it is."
        print ""
        return
    }
    for (i = 2; i <= nt; i++) { k = TRIS[i]; for (j = i - 1; j >= 1 && TRIS[j] > k; j--) TRIS[j + 1] = TRIS[j]; TRIS[j + 1] = k }
    printf "%s on the Cornell box (5 quads, point light) holding a sphere of N triangles (N = 0: the box\n", st
    printf "alone), %sx%s pixels. Time = render + BVH build (median of the repeats); brute force (`--no-bvh`)\n", INFO["mesh_width"], INFO["mesh_width"]
    printf "tests every primitive for every ray, so it grows as pixels x primitives and is run only up to\n"
    printf "%s triangles.\n", grouped(INFO["mesh_brute_max"])
    print ""
    print "| primitives | BVH: seconds | BVH: tests + node visits per ray | brute force: seconds | brute force: tests per ray | speed-up |"
    print "|---|---|---|---|---|---|"
    cross = ""; last_off = 0; nsp = 0
    for (j = 1; j <= nt; j++) {
        tri = TRIS[j]
        on = off = 0
        for (i = 1; i <= N; i++) {
            if (SC[i] !~ /^mesh_/ || TRI[i] != tri) continue
            if (F[i] == "bvh=on") on = i
            if (F[i] == "bvh=off") off = i
        }
        sp = (on && off && TRB[on] > 0) ? TRB[off] / TRB[on] : ""
        if (sp != "") {
            if (sp > 1 && cross == "") cross = tri
            if (sp <= 1) cross = ""
            last_off = off
            SPN[++nsp] = tri + 5; SPV[nsp] = sp
        }
        printf "| %s | %s | %s | %s | %s | %s |\n", grouped(tri + 5), on ? secs(TRB[on]) : "-", on ? nice(TPR[on]) " + " nice(NPR[on]) : "-",
            off ? secs(TRB[off]) : "not run", off ? nice(TPR[off]) : "-", sp == "" ? "-" : "**" times(sp) "**"
        LASTON = on; LASTTRI = tri
    }
    print ""
    if (cross != "" && SPN[1] == cross + 5)
        printf "The BVH is faster at every size measured, from the smallest (%s primitives) on. ", grouped(cross + 5)
    else if (cross != "") {
        for (k = 1; SPN[k] != cross + 5; k++) ;
        # Where the speed-up crosses 1, interpolated on log-log axes.
        n = exp(log(SPN[k - 1]) + (log(SPN[k]) - log(SPN[k - 1])) * (0 - log(SPV[k - 1])) / (log(SPV[k]) - log(SPV[k - 1])))
        printf "The BVH pays off from about **%s primitives** on: brute force is faster at %s (%s), the BVH at %s (%s) and every larger size (interpolated on log-log axes). ",
            grouped(n), grouped(SPN[k - 1]), times(SPV[k - 1]), grouped(SPN[k]), times(SPV[k])
    } else
        printf "The BVH was not faster at any brute-forced size of this sweep. "
    if (last_off && LASTON && TRI[last_off] < LASTTRI) {
        p0 = TRI[last_off] + 5; p1 = LASTTRI + 5
        k = TRB[last_off] * p1 / p0
        printf "Brute force at %s primitives would take about %s (linear extrapolation from %s), %s the BVH's %s.",
            grouped(p1), secs(k), grouped(p0), times(k / TRB[LASTON]), secs(TRB[LASTON])
    }
    print ""
    print ""
    # The reference scenes: 7 primitives.
    nrow = 0
    for (i = 1; i <= N; i++) {
        if (SC[i] ~ /^mesh_/ || F[i] != "bvh=off") continue
        on = 0
        for (j = 1; j <= N; j++)
            if (S[j] == S[i] && SC[j] == SC[i] && F[j] == "bvh=on" && SPP[j] == SPP[i]) on = j
        if (!on) continue
        if (!nrow++) print "On the reference scenes (7 primitives: 2 spheres, 5 quads) at the stages' default knobs, " INFO["width"] "x" INFO["width"] " pixels:"
        printf "- %s, %s: %s with the BVH, %s without (speed-up %s).\n", S[i], SC[i], secs(TRB[on]), secs(TRB[i]), times(TRB[i] / TRB[on])
    }
    if (nrow) print ""
    if (NPAIRS > 0)
        printf "The image does not change: %d of %d renders without the BVH are identical (relMSE 0) to the same render with it.\n\n",
            NZERO, NPAIRS
    if (NPAIRS > NZERO)
        printf "**Differing:**%s.\n\n", PAIRBAD
}

function q_spp(    s, st, j, sc, i, fam, slope, any, useown, theory, done) {
    print "## 5. Error against spp: does relMSE fall as 1/spp?"
    print ""
    print "Monte Carlo theory: for an unbiased estimator with independent samples relMSE falls as 1/spp"
    print "(slope -1 on log-log axes); stratified samples (a jittered grid) can fall faster, between"
    print "spp^-2 and spp^-1, where a pixel holds an edge (Mitchell 1996). A slope flatter than -1 means"
    print "bias (or the reference's own noise floor) has started to dominate. Least-squares slopes of"
    print "ln relMSE against ln spp over each curve (own reference; GI where there is none), seeds averaged:"
    print ""
    print "| stage | scene | curve | against | spp | relMSE at lowest -> highest spp | slope |"
    print "|---|---|---|---|---|---|---|"
    any = 0
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        if (stage_num(st) < 6) continue
        for (j = 1; j <= NSC; j++) {
            sc = SCENE[j]
            delete done
            for (i = 1; i <= N; i++) {
                fam = F[i]
                if (S[i] != st || SC[i] != sc || (fam in done)) continue
                if (fam !~ /^nee=/ && fam !~ /^aa=/) continue
                done[fam] = 1
                useown = (OREF[i] != "")
                slope = fit(st, sc, fam, useown, "spp")
                if (slope == "" || FIT_N < 3) continue
                any++
                printf "| %s | %s | %s | %s | %s-%s | %s -> %s | **%.2f** |\n", st, sc, fam, (useown ? errname(i) : "GI"), FIT_X0, FIT_X1, g3(FIT_Y0), g3(FIT_Y1), slope
                if (fam == "nee=on rr=on") MAINSLOPE[sc] = slope
            }
        }
    }
    # 03's shadow rays: the same question for the light's samples.
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        if (stage_num(st) != 3) continue
        for (j = 1; j <= NSC; j++) {
            slope = fit(st, SCENE[j], "shadow", 1, "value")
            if (slope == "" || FIT_N < 3) continue
            printf "| %s | %s | shadow rays per point (not spp) | direct | %s-%s | %s -> %s | **%.2f** |\n", st, SCENE[j], FIT_X0, FIT_X1, g3(FIT_Y0), g3(FIT_Y1), slope
            if (slope > -0.8) { FLAT03 = sprintf("- %s on %s: the error against its limit falls with shadow rays only to about %s (slope %.2f): what remains is the pixel-centre aliasing floor of question 1, which more shadow rays cannot remove.", st, SCENE[j], g3(FIT_Y1), slope) }
        }
    }
    print ""
    if (!any) { print "No stage that samples pixels was swept."; print ""; return }
    for (j = 1; j <= NSC; j++)
        if (SCENE[j] in MAINSLOPE)
            printf "- 07 with NEE and RR on %s: relMSE ~ spp^%.2f (theory: -1)%s.\n", SCENE[j], MAINSLOPE[SCENE[j]],
                (MAINSLOPE[SCENE[j]] > -0.8 ? ": flatter than 1/spp, rare bright paths (fireflies) dominate the mean at low spp" : "")
    if (FLAT03 != "") print FLAT03
    print "- 06's curves mix two sources of error: the pixel's area (aliasing at edges, which the grid and"
    print "  jitter patterns stratify) and the light's area (one shadow ray per camera sample with"
    print "  `shadow=1`); see the slopes above and the `*_spp_*.svg` plots."
    print ""
}

function plots_section(    i) {
    print "## Plots"
    print ""
    for (i = 1; i <= NPLOTS; i++)
        printf "- [%s](%s): %s\n", PLOT[i], PLOT[i], PLOTFILE[PLOT[i]]
    print ""
    print "To embed a stage's plot in its page (`docs/stages/NN_name.md`): `![trade-off](../trade/NN_name.svg)`."
}

# Stages 01-05 trace one ray through each pixel's centre; the references are
# pixel averages, so edges alias.  06 removes that: compare on the point
# light, where nothing else is random.
function aliasing(    i, a, b, s) {
    a = b = 0
    for (s = 1; s <= NST; s++) {
        i = default_row(STAGE[s], "cornell_diffuse_point")
        if (i && stage_num(STAGE[s]) >= 2 && stage_num(STAGE[s]) <= 5 && OREF[i] == "direct") a = i
    }
    for (i = 1; i <= N; i++)
        if (stage_num(S[i]) == 6 && SC[i] == "cornell_diffuse_point" && OWN[i] != "" && (!b || OWN[i] < OWN[b])) b = i
    if (!a || !b) return
    printf "Stages 01-05 trace one ray through each pixel's centre, while a reference pixel is the average over\n"
    printf "its area: edges alias, and that sets a floor too. On cornell_diffuse_point %s reaches relMSE %s\n", S[a], g3(OWN[a])
    printf "against its limit and stops; %s with `%s` reaches %s in %s.\n", S[b], K[b], g3(OWN[b]), secs(T[b])
}

# Sort rows d[1..n] by their swept value (insertion sort: a handful).
function sort_by_value(d, n,    r, k, a) {
    for (r = 2; r <= n; r++) { a = d[r]; for (k = r - 1; k >= 1 && V[d[k]] + 0 > V[a] + 0; k--) d[k + 1] = d[k]; d[k + 1] = a }
}

# relMSE vs GI along the max-depth curve of a stage on a scene.
function depth_line(st, sc,    r, k, n, d, line, a, spp) {
    n = 0
    for (r = 1; r <= N; r++) {
        if (S[r] != st || SC[r] != sc || F[r] !~ /^depth \(/) continue
        d[++n] = r
        spp = SPP[r]
    }
    if (!n) return
    sort_by_value(d, n)
    line = ""
    for (k = 1; k <= n; k++) line = line (k > 1 ? ", " : "") V[d[k]] ": " g3(GI[d[k]])
    a = find(st, sc, "nee=on rr=on", spp)
    printf "- %s, %s spp: max-depth %s; unbounded: %s; direct-light floor: %s.\n", sc, spp, line,
        a ? g3(GI[a]) : "-", (("floor_" sc) in INFO) ? g3(INFO["floor_" sc]) : "-"
}

# Russian roulette's two settings, each swept at 16 spp with the other at
# its default: where it starts (--rr-depth, with each sampler) and the
# throughput a survivor carries (--rr-threshold); the gain is against the
# sweep's row at the stage's default (RR_MIN_DEPTH 3, RR_THRESHOLD 0.4).
function roulette(    s, st, j, sc, f, fam, r, k, n, d, a, base, any, fams) {
    fams[1] = "rr start (spp=16)"; fams[2] = "rr start independent (spp=16)"; fams[3] = "rr threshold (spp=16)"
    any = 0
    for (s = 1; s <= NST; s++) {
        st = STAGE[s]
        for (j = 1; j <= NSC; j++) {
            sc = SCENE[j]
            for (f = 1; f <= 3; f++) {
                fam = fams[f]
                n = 0
                for (r = 1; r <= N; r++) if (S[r] == st && SC[r] == sc && F[r] == fam) d[++n] = r
                if (!n) continue
                sort_by_value(d, n)
                base = find(st, sc, fam, f == 3 ? "0.4" : "3")
                if (!any) {
                    print "Russian roulette, its two settings swept at 16 spp (the other at its default): the ray it"
                    print "starts at (`--rr-depth`, camera ray = 1; with the Sobol sampler, the default, and with the"
                    print "independent one) and the throughput T a survivor carries (`--rr-threshold`, survival"
                    print "min(max beta / T, 0.95)); gain = efficiency / that of the sweep's row at the defaults (3, 0.4):"
                    print ""
                    print "| stage | scene | sweep | value | relMSE | seconds | efficiency | gain |"
                    print "|---|---|---|---|---|---|---|---|"
                    any = 1
                }
                for (k = 1; k <= n; k++) {
                    r = d[k]
                    printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", st, sc, substr(fam, 1, length(fam) - 9), V[r],
                        g3(GI[r]), secs(T[r]), g3(EFF[r]), base ? times(EFF[r] / EFF[base]) : "-"
                }
            }
        }
    }
    if (any) print ""
}
