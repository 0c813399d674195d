# SPDX-License-Identifier: MIT
# The phase seconds of one hp run (kind = 'eigen' or 'threshold', progress = .true.) per
# step, from its progress lines: each level, the check one degree higher, the report of the
# last level. Columns: step, dofs, assembly, ordering + factor, the contact blocks, the
# pencil's thresholds and round-off bounds, the p x p solves of the boundary search (count,
# p, seconds), eigen (c_n: ARPACK or dense at each level and in its check; thresholds: the
# spectrum at lambda of the report), the rest (the threshold check's blocks, pencil and
# onsets; output), the step's sum and the sum so far. Used by bench_thresholds.sh (PHASES).
# The seconds are what the executable's timers read: wall seconds, or CPU seconds from a
# build configured with -DNCEIG_CPU_TIMERS=ON.
# solves S: "N at p = P, SECONDS" from the text "SECONDS s (N p x p solves at p = P" in S
function solves(text,    w) {
    if (!match(text, /[0-9.]+ s \([0-9]+ p x p solves at p = [0-9]+/)) return ""
    split(substr(text, RSTART, RLENGTH), w, " ")
    seconds = w[1]
    return substr(w[3], 2) " at p = " w[11] ", " w[1]
}
# the step read so far, as a row
function flush() {
    if (name == "") return
    step = a + f + b + pen + seconds + e + o
    total += step
    printf "| %s | %s | %.3f | %.3f | %.3f | %.3f | %s | %.3f | %.3f | %.3f | %.3f |\n", name,
        dofs, a, f, b, pen, searched, e, o, step, total
    name = dofs = searched = ""
    a = f = b = pen = seconds = e = o = 0
}
!/^  \.\. / { next }
{ sub(/^  \.\. /, "") }
/^assembly .*hp space/ { flush(); checked = 0; a = $2; next }   # a level or check begins
/^(ordering|factor) / { f += $2; next }
/^hp level [0-9]+: [0-9]+ cells/ { name = "level " $3; sub(/:$/, "", name); dofs = $(NF - 1); next }
/^hp check of level [0-9]+: [0-9]+ cells/ { name = "check"; dofs = $(NF - 1); next }
/^reduction / {
    match($0, /contact blocks [0-9.]+/); b = substr($0, RSTART + 15, RLENGTH - 15)
    match($0, /thresholds [0-9.]+/); pen = substr($0, RSTART + 11, RLENGTH - 11)
    searched = solves($0)
    next
}
# after a threshold run's check, the eigen line is the report's (its spectrum at lambda)
/^eigen / { if (!checked) e += $2; next }
# the check's seconds in all (a threshold run says them once per side)
/^hp check of level .* [0-9.]+ s$/ { o = $(NF - 1) - a - f - e; checked = 1; next }
/^thresholds of the last level/ {
    flush()
    name = "report"
    match($0, /lambda [0-9.]+ s/); e = substr($0, RSTART + 7, RLENGTH - 9)
    searched = solves($0)
    next
}
/^output / { if (name == "") name = "report"; o += $2; next }
END { flush() }
