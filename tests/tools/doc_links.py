#!/usr/bin/env python3
"""Check the relative links of Markdown files.

usage: doc_links.py ROOT   (checks ROOT/README.md and ROOT/docs/**/*.md)

Every link or image [text](target) outside code must name an existing file
or folder, relative to the Markdown file; a #anchor must name a heading of
the target Markdown file (GitHub's anchors: lower case, punctuation other
than - and _ dropped, spaces as -, a repeated heading gets -1, -2, ...).
Links with a scheme (https:, mailto:) are not checked.
"""
import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(`{3,}|~{3,})")
INLINE_CODE = re.compile(r"(`+)(?:(?!\1).)+?\1")


def outside_fences(path):
    """(number, line) of the lines outside fenced code blocks."""
    fence = None
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            m = FENCE.match(line)
            if fence:
                if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence):
                    fence = None
                continue
            if m:
                fence = m.group(1)
                continue
            yield n, line


def prose_lines(path):
    """(number, line) of the lines outside fenced code, inline code removed."""
    for n, line in outside_fences(path):
        yield n, INLINE_CODE.sub("", line)


def slug(heading):
    text = re.sub(r"`([^`]*)`", r"\1", heading.strip()).lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def heading_anchors(path):
    found, seen = set(), {}
    for _, line in outside_fences(path):
        h = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not h:
            continue
        s = slug(h.group(1))
        if s in seen:
            seen[s] += 1
            s = "%s-%d" % (s, seen[s])
        else:
            seen[s] = 0
        found.add(s)
    return found


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    files = [os.path.join(root, "README.md")]
    for folder, _, names in os.walk(os.path.join(root, "docs")):
        files += [os.path.join(folder, n) for n in sorted(names) if n.endswith(".md")]
    failures, links, with_anchor = [], 0, 0
    cache = {}
    for path in files:
        for n, line in prose_lines(path):
            for m in LINK.finditer(line):
                target = m.group(1)
                if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                    continue
                links += 1
                where = "%s:%d" % (os.path.relpath(path, root), n)
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                if not os.path.exists(dest):
                    failures.append("%s: link to %s: no such file %s" % (where, target, os.path.relpath(dest, root)))
                    continue
                if anchor and dest.endswith(".md"):
                    with_anchor += 1
                    if dest not in cache:
                        cache[dest] = heading_anchors(dest)
                    if anchor not in cache[dest]:
                        failures.append("%s: link to %s: no heading with anchor #%s in %s"
                                        % (where, target, anchor, os.path.relpath(dest, root)))
    print("%d relative links checked in %d files (%d anchors)" % (links, len(files), with_anchor))
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
