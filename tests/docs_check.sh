#!/bin/sh
# SPDX-License-Identifier: MIT
# The documentation's shape: README.md is the front door (under 8 KB, the rest by topic
# in docs/), every relative link and #anchor in README.md and docs/*.md resolves, and
# the bench markers, between which rad_bench writes its report, are in docs/bench.md
# alone (so `make bench` never rewrites the README).
# Run by tests/run_tests.sh as `sh tests/docs_check.sh BUILDDIR` (cwd: the tree);
# prints a CMocka-style line per check.
set -u
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rad_docs.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM

. tests/check_lib.sh

# The front door stays a front door: what rad is, the two commands, the pictures, the
# library example, the house and the links. 8 KB is the bound (#33).
readme_small() {
    size=$(wc -c <README.md)
    echo "README.md: $size bytes (bound 8192)"
    test "$size" -lt 8192
}

# Every link [text](target) and image ![alt](target) outside code, whose target is not
# a URL: the file (relative to the linking file's folder) exists, and a #anchor names
# a heading of it (GitHub's anchors: the heading's text lower-cased, every character
# but letters, digits, spaces, '-' and '_' dropped, spaces made '-', a repeated one
# given -1, -2, ...; the headings here are ASCII but for the title's dash, which is
# dropped as GitHub drops it). A link may span lines, as Markdown allows.
links_resolve() {
    awk '
    function slugs(f,    line, fence, h, s, n) {
        if (f in done) return
        done[f] = 1
        fence = 0
        while ((getline line < f) > 0) {
            if (line ~ /^```/) { fence = !fence; continue }
            if (fence || line !~ /^#+ /) continue
            h = line
            sub(/^#+ +/, "", h)
            s = tolower(h)
            gsub(/[^a-z0-9 _-]/, "", s)
            gsub(/ /, "-", s)
            n = seen[f, s]++
            anchor[f, n ? s "-" n : s] = 1
        }
        close(f)
    }
    function norm(p,    parts, n, i, out, k) {
        n = split(p, parts, "/")
        k = 0
        for (i = 1; i <= n; i++) {
            if (parts[i] == "." || parts[i] == "") continue
            if (parts[i] == ".." && k > 0 && stack[k] != "..") { k--; continue }
            stack[++k] = parts[i]
        }
        out = ""
        for (i = 1; i <= k; i++) out = out (i > 1 ? "/" : "") stack[i]
        return out
    }
    FNR == 1 { if (prev != "") scan(prev, text); prev = FILENAME; text = ""; fence = 0 }
    /^```/ { fence = !fence; text = text "\n"; next }
    { text = text (fence ? "" : $0) "\n" }
    END { if (prev != "") scan(prev, text); printf "%d links checked, %d broken\n", total, bad; exit bad > 0 }
    function scan(f, t,    dir, m, target, path, a, i) {
        gsub(/`[^`]*`/, "", t)           # code spans hold no links
        dir = f
        if (!sub(/\/[^\/]*$/, "", dir)) dir = "."
        while (match(t, /\]\([^()[:space:]]+\)/)) {
            target = substr(t, RSTART + 2, RLENGTH - 3)
            t = substr(t, RSTART + RLENGTH)
            if (target ~ /^[a-z]+:/) continue
            total++
            i = index(target, "#")
            path = i ? substr(target, 1, i - 1) : target
            a = i ? substr(target, i + 1) : ""
            path = path == "" ? f : norm(dir "/" path)
            if (system("test -e \"" path "\"") != 0) {
                printf "%s: broken link %s (no file %s)\n", f, target, path; bad++; continue
            }
            if (a == "") continue
            slugs(path)
            if (!((path, a) in anchor)) {
                printf "%s: broken link %s (no heading of %s has the anchor #%s)\n", f, target, path, a; bad++
            }
        }
    }' README.md docs/*.md
}

# rad_bench replaces what lies between the markers of docs/bench.md; any other file
# that held them would be rewritten too, or rather instead.
bench_markers() {
    others=$(grep -l -e '<!-- bench:begin -->' -e '<!-- bench:end -->' README.md docs/*.md | grep -vx docs/bench.md)
    test -z "$others" || { echo "bench markers outside docs/bench.md: $others"; return 1; }
    awk '/^<!-- bench:begin -->$/ { b++; if (!e) ok = 1 } /^<!-- bench:end -->$/ { e++ }
         END { printf "docs/bench.md: %d begin and %d end markers (expected 1 each, begin first)\n", b, e
               exit !(b == 1 && e == 1 && ok) }' docs/bench.md
}

check docs_readme_small "README.md is 8 KB or more: move the rest into docs/" readme_small
check docs_links_resolve "a relative link or #anchor in README.md or docs/*.md leads nowhere" links_resolve
check docs_bench_markers "the bench markers are not in docs/bench.md alone" bench_markers
