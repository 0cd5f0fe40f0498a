# stack.awk -- the worst-case stack of each public entry point, from the
# frames of -fstack-usage and the call graph of -fcallgraph-info=su (the
# .ci files on the command line), with calls through pointers resolved by
# embedded/indirect.txt.  Frames of functions outside the library (libc,
# libgcc's soft-float routines) are not known and count as 0.  Fails
# (exit 1) when any function of the library can reach itself (the
# library must not recurse), or calls through a pointer and is not in
# indirect.txt.
#   awk -v kind=irr|irrg|sh -v map=embedded/indirect.txt -v entries="irc_a irc_b" -f stack.awk *.ci
function base(t,   b) {
    b = t
    sub(/^.*:/, "", b)
    sub(/\..*$/, "", b)
    return b
}
function quoted(s, key,   i, r) {
    i = index(s, key ": \"")
    if (!i) return ""
    r = substr(s, i + length(key) + 3)
    return substr(r, 1, index(r, "\"") - 1)
}
BEGIN {
    while ((getline line < map) > 0) {
        sub(/#.*/, "", line)
        n = split(line, w, /[ \t]+/)
        caller = ""
        for (i = 1; i <= n; i++) {
            if (w[i] == "") continue
            if (caller == "") { caller = w[i]; mapped[caller] = 1; continue }
            t = w[i]
            if (t ~ /^irrg:/) { if (kind != "irrg") continue; t = substr(t, 6) }
            else if (t ~ /^irr:/) { if (kind != "irr" && kind != "irrg") continue; t = substr(t, 5) }
            else if (t ~ /^sh:/) { if (kind != "sh") continue; t = substr(t, 4) }
            if (t != "-" && t != "port") targets[caller] = targets[caller] " " t
        }
    }
}
/^node:/ {
    t = quoted($0, "title")
    l = quoted($0, "label")
    if (match(l, /[0-9]+ bytes/)) {
        frame[t] = substr(l, RSTART, RLENGTH) + 0
        titles[base(t)] = titles[base(t)] " " t
        known[t] = 1
        if (FILENAME ~ /irc_port/) portmax = frame[t] > portmax ? frame[t] : portmax
    }
}
/^edge:/ {
    s = quoted($0, "sourcename")
    t = quoted($0, "targetname")
    if (t == "__indirect_call") indirect[s] = 1
    else calls[s] = calls[s] " " t
}
function depth(f,   best, n, i, list, d, m, j, names) {
    if (f in memo) return memo[f]
    if (f in active) {
        if (!(f in reported)) print "recursion: " base(f) " reaches itself"
        reported[f] = 1
        recursion = 1
        return 0
    }
    active[f] = 1
    best = 0
    n = split(calls[f], list, " ")
    for (i = 1; i <= n; i++)
        if ((d = depth(list[i])) > best) { best = d; via[f] = list[i] }
    if (f in indirect) {
        if (portmax > best) { best = portmax; via[f] = "(port)" }
        n = split(targets[base(f)], list, " ")
        for (i = 1; i <= n; i++) {
            m = split(titles[list[i]], names, " ")
            if (m == 0) print "indirect.txt: " list[i] " is not a library function"
            for (j = 1; j <= m; j++)
                if ((d = depth(names[j])) > best) { best = d; via[f] = names[j] }
        }
    }
    delete active[f]
    memo[f] = (f in frame ? frame[f] : 0) + best
    return memo[f]
}
END {
    for (t in known) depth(t)
    # Every function that calls through a pointer is listed: an unlisted
    # one would be counted as calling the port only, and its kind's frames
    # left out of the bound without a word.
    for (t in indirect)
        if (!(base(t) in mapped)) {
            print "indirect.txt: " base(t) " calls through a pointer and is not listed"
            recursion = 1
        }
    n = split(entries, e, " ")
    for (i = 1; i <= n; i++) {
        m = split(titles[e[i]], names, " ")
        worst = 0
        for (j = 1; j <= m; j++) if ((d = depth(names[j])) > worst) { worst = d; top = names[j] }
        printf "%-32s %6d\n", e[i], worst
        # -v path=1: the deepest chain, frame by frame
        for (f = top; path && f != ""; f = via[f])
            printf "    %-40s %6d\n", base(f), f in frame ? frame[f] : 0
    }
    exit recursion
}
