#!/usr/bin/env python3
"""scripts/test_docs.py - the documentation against the code.

Usage: python3 scripts/test_docs.py [REPOSITORY_ROOT]     (scripts/test_users.sh runs it)
       python3 scripts/test_docs.py --write-decks GAPBEAM [REPOSITORY_ROOT]

Checks (one `PASS  docs: ...` or `FAIL  docs: ...` line each):
  * every group of the deck table -- every `begin_group('name', ...)` of
    src/core/gapbeam_deck_table*.f90, where each deck variable is declared once -- has a section
    in docs/decks.md (a heading that names `&group`) holding its generated table (between the
    lines `<!-- deck table &group: ... -->` and `<!-- end of deck table &group -->`), and no
    section holds a table of a group the deck does not have. test/test_input.f90 checks that each
    table is exactly what `gapbeam --help-deck --markdown` prints (the table's units, defaults,
    ranges and meanings); `--write-decks GAPBEAM` rewrites the tables from that output;
  * the front door: README.md is at most 220 lines, shows ./scripts/run.sh and ./scripts/test.sh,
    and the command of .ci/run; every docs/*.md file README.md links to exists.
The output datasets are checked against docs/outputs.md by python/tests/test_reader.py, on the
files every analysis writes (they need a run of the program).
Exit status 1 if a check failed.
"""

import re
import subprocess
import sys
from pathlib import Path


TABLE_BEGIN = re.compile(r"^<!-- deck table &(\w+): .*-->$")
TABLE_END = "<!-- end of deck table &{} -->"


def table_groups(src):
    """The groups of the deck table, in order: `begin_group('name'` in gapbeam_deck_table*.f90
    (or `call walk_end(v, 'name'`, the walk shared by &root and &tip)."""
    groups = []
    for f in sorted((src / "core").glob("gapbeam_deck_table*.f90")):
        text = f.read_text(encoding="utf-8", errors="replace")
        for m in re.finditer(r"(?:begin_group|walk_end)\((?:v, )?'(\w+)'", text):
            if m.group(1) not in groups:
                groups.append(m.group(1))
    return groups


def write_decks(exe, md_path):
    """Replace every generated table of docs/decks.md by `exe --help-deck --markdown`'s."""
    out = subprocess.run([exe, "--help-deck", "--markdown"], capture_output=True, text=True,
                         check=True).stdout.splitlines()
    tables, current = {}, None
    for line in out:
        m = TABLE_BEGIN.match(line)
        if m:
            current = m.group(1)
            tables[current] = [line]
        elif current:
            tables[current].append(line)
            if line == TABLE_END.format(current):
                current = None
    lines, result, skip = md_path.read_text(encoding="utf-8").splitlines(), [], None
    for line in lines:
        m = TABLE_BEGIN.match(line)
        if m and m.group(1) in tables:
            result.extend(tables[m.group(1)])
            skip = m.group(1)
            continue
        if skip:
            if line == TABLE_END.format(skip):
                skip = None
            continue
        result.append(line)
    md_path.write_text("\n".join(result) + "\n", encoding="utf-8")
    return len(tables)


def sections(md):
    """{group: text of its section} of docs/decks.md: a heading (###) naming `&group`."""
    out, current, buf = {}, None, []
    for line in md.splitlines():
        if line.startswith("#"):
            if current:
                out[current] = "\n".join(buf)
            m = re.search(r"`&(\w+)`", line)
            current = m.group(1).lower() if m else None
            buf = []
        elif current:
            buf.append(line)
    if current:
        out[current] = "\n".join(buf)
    return out


def main(argv):
    if len(argv) > 2 and argv[1] == "--write-decks":
        root = Path(argv[3]) if len(argv) > 3 else Path(__file__).resolve().parents[1]
        n = write_decks(argv[2], root / "docs" / "decks.md")
        print("test_docs.py: {} tables of docs/decks.md written from {} --help-deck "
              "--markdown".format(n, argv[2]))
        return 0
    root = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parents[1]
    n, failed = 0, 0

    def check(name, ok, why=""):
        nonlocal n, failed
        n += 1
        if ok:
            print("PASS  docs: " + name)
        else:
            failed += 1
            print("FAIL  docs: {}{}".format(name, " ({})".format(why) if why else ""))

    groups = table_groups(root / "src")
    check("the deck table declares the deck's groups ({} found)".format(len(groups)),
          len(groups) >= 10, str(groups))
    decks = root / "docs" / "decks.md"
    md = decks.read_text(encoding="utf-8") if decks.exists() else ""
    check("docs/decks.md exists", bool(md))
    secs = sections(md)
    for group in groups:
        text = secs.get(group)
        if text is None:
            check("docs/decks.md has a section for &{}".format(group), False)
            continue
        lines = text.splitlines()
        begin = [l for l in lines if TABLE_BEGIN.match(l) and TABLE_BEGIN.match(l).group(1) == group]
        check("docs/decks.md: the section of &{} holds its generated table".format(group),
              len(begin) == 1 and TABLE_END.format(group) in lines,
              "no table between '<!-- deck table &{0}: ...' and '{1}'".format(
                  group, TABLE_END.format(group)))
    stale = sorted(set(m.group(1) for m in map(TABLE_BEGIN.match, md.splitlines()) if m)
                   - set(groups))
    check("docs/decks.md holds no table of a group the deck does not have", not stale,
          "stale: {}".format(", ".join(stale)))

    readme = root / "README.md"
    text = readme.read_text(encoding="utf-8") if readme.exists() else ""
    lines = text.count("\n")
    check("README.md is a front door: at most 220 lines ({})".format(lines), 0 < lines <= 220)
    for cmd in ("./scripts/run.sh", "./scripts/test.sh"):
        check("README.md shows {}".format(cmd), cmd in text)
    ci = root / ".ci" / "run"
    if ci.exists():
        m = re.search(r"exec\s+(\./scripts/\S+)", ci.read_text(encoding="utf-8"))
        check("README.md shows the command of .ci/run", m is not None and m.group(1) in text,
              m.group(1) if m else "no exec line in .ci/run")
    links = sorted(set(re.findall(r"\]\((docs/[^)#\s]+)", text)))
    bad = [l for l in links if not (root / l).exists()]
    check("every docs/ file README.md links to exists ({} links)".format(len(links)),
          links and not bad, "missing: {}".format(bad))
    print("test_docs.py: {} checks, {} failed".format(n, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
