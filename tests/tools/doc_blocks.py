#!/usr/bin/env python3
"""Run the ```lua code blocks of Markdown files and compare their output.

usage: doc_blocks.py --host build/bin/ashlar [--lua lua5.4 --module-dir DIR]
                     [--work DIR] file.md ...

Conventions (docs/development.md, "Documentation tests"):
- Every block fenced ```lua is a script: it runs in the ashlar host, in a
  working folder of its own for each Markdown file, the file's blocks one
  after another (a block may read what an earlier one wrote). It must end
  without error.
- A block fenced ```lua fragment is a piece of a script: it is not run.
- A block fenced ```text output that follows a lua block (blank lines
  between them only) is that block's expected output: what the block
  prints must match it line by line (trailing spaces ignored).
- A lua block whose first line is `local ashlar = require "ashlar"` claims
  to work in stock Lua: it is run with --lua too (the C module found in
  --module-dir), and its output compared the same way.
Exit status 0 when every block passed; the failures are printed.
With --update, each output block is rewritten with what the block printed
in the host (review the diff before committing it).
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

FENCE = re.compile(r"^(`{3,}|~{3,})\s*([^\s`]*)\s*(.*?)\s*$")
STOCK_LINE = 'local ashlar = require "ashlar"'


def blocks(path):
    """Yield (line, language, qualifier, text) of each fenced block."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, lang, rest = m.group(1), m.group(2).lower(), m.group(3).lower()
        start = i + 1
        j = start
        while j < len(lines) and not lines[j].startswith(fence[0] * len(fence)):
            j += 1
        yield start, lang, rest, "\n".join(lines[start:j]) + "\n", j
        i = j + 1


def pairs(path):
    """The lua blocks of a file, each with its expected output or None."""
    found = list(blocks(path))
    result = []
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    for k, (line, lang, rest, text, end) in enumerate(found):
        if lang != "lua":
            continue
        expected = None
        if k + 1 < len(found):
            nline, nlang, nrest, ntext, _ = found[k + 1]
            between = lines[end + 1:nline - 1]
            if nlang == "text" and nrest == "output" and all(not s.strip() for s in between):
                expected = ntext
        result.append((line, rest, text, expected, found[k + 1][0] if expected is not None else None))
    return result


def normalise(text):
    out = [s.rstrip() for s in text.replace("\r\n", "\n").split("\n")]
    while out and not out[-1]:
        out.pop()
    return out


def run(command, cwd, env, timeout):
    try:
        p = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "", "timed out after %d s" % timeout
    return p.returncode, p.stdout, p.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--host", required=True)
    ap.add_argument("--lua")
    ap.add_argument("--module-dir")
    ap.add_argument("--work")
    ap.add_argument("--timeout", type=int, default=60)
    ap.add_argument("--update", action="store_true")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()

    work = a.work or tempfile.mkdtemp(prefix="ashlar-doc-blocks-")
    counts = {"host": 0, "stock": 0, "compared": 0, "fragments": 0}
    failures = []
    for path in a.files:
        name = os.path.basename(path)
        here = os.path.abspath(path)
        label = os.path.basename(os.path.dirname(here)) + "_" + os.path.basename(here)
        folder = os.path.join(work, re.sub(r"[^A-Za-z0-9_.-]", "_", label))
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        updates = {}
        for line, rest, text, expected, output_line in pairs(path):
            where = "%s:%d" % (path, line)
            if rest == "fragment":
                counts["fragments"] += 1
                continue
            if rest:
                failures.append("%s: unknown qualifier 'lua %s' (use 'lua' or 'lua fragment')" % (where, rest))
                continue
            script = os.path.join(folder, "block_%d.lua" % line)
            with open(script, "w", encoding="utf-8") as f:
                f.write(text)
            hosts = [("host", [os.path.abspath(a.host), script], dict(os.environ))]
            if text.split("\n", 1)[0].strip() == STOCK_LINE:
                if not (a.lua and a.module_dir):
                    failures.append("%s: a stock-Lua block, but no --lua and --module-dir given" % where)
                else:
                    env = dict(os.environ)
                    cpath = os.path.abspath(a.module_dir) + "/?.so;;"
                    env["LUA_CPATH_5_4"] = cpath
                    hosts.append(("stock", [a.lua, script], env))
            for kind, command, env in hosts:
                counts[kind] += 1
                code, out, err = run(command, folder, env, a.timeout)
                label = "%s (%s)" % (where, "ashlar host" if kind == "host" else "stock " + a.lua)
                if code != 0:
                    failures.append("%s: the block failed (exit %s):\n%s" % (label, code, err.strip()))
                    continue
                if expected is not None and a.update and kind == "host":
                    updates[output_line] = normalise(out)
                elif expected is not None:
                    counts["compared"] += 1
                    want, got = normalise(expected), normalise(out)
                    if want != got:
                        diff = []
                        for n in range(max(len(want), len(got))):
                            w = want[n] if n < len(want) else "<no line>"
                            g = got[n] if n < len(got) else "<no line>"
                            if w != g:
                                diff.append("  line %d: documented %r, printed %r" % (n + 1, w, g))
                        failures.append("%s: printed output differs from the output block:\n%s"
                                        % (label, "\n".join(diff[:10])))
        if updates:
            with open(path, encoding="utf-8") as f:
                lines = f.read().split("\n")
            for start in sorted(updates, reverse=True):
                end = start
                while not lines[end].startswith("```"):
                    end += 1
                lines[start:end] = updates[start]
            with open(path, "w", encoding="utf-8") as f:
                f.write("\n".join(lines))
    print("%d blocks run in the ashlar host, %d in stock Lua, %d outputs compared, %d fragments skipped"
          % (counts["host"], counts["stock"], counts["compared"], counts["fragments"]))
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
