#!/usr/bin/env python3
"""scripts/test_docs.py - the documentation against the code.

Usage: python3 scripts/test_docs.py [REPOSITORY_ROOT]     (scripts/test_users.sh runs it)

Checks (one `PASS  docs: ...` or `FAIL  docs: ...` line each):
  * every deck variable -- every name of every `namelist /group/ ...` statement in the sources
    (src/**/*.f90) -- is documented in docs/decks.md, in the section of its group (a heading that
    names `&group`), written as `name` (in backquotes) in that section;
  * no section of docs/decks.md documents a variable its group does not have (a stale name);
  * the front door: README.md is at most 220 lines, shows ./scripts/run.sh and ./scripts/test.sh,
    and the command of .ci/run; every docs/*.md file README.md links to exists.
The output datasets are checked against docs/outputs.md by python/tests/test_reader.py, on the
files every analysis writes (they need a run of the program).
Exit status 1 if a check failed.
"""

import re
import sys
from pathlib import Path


def namelists(src):
    """{group: [variables]} of every namelist statement under src/ (continuation lines joined)."""
    groups = {}
    for f in sorted(src.rglob("*.f90")):
        text = f.read_text(encoding="utf-8", errors="replace")
        text = re.sub(r"&[ \t]*\n[ \t]*&?", " ", text)          # join continued lines
        for m in re.finditer(r"^\s*namelist\s*/\s*(\w+)\s*/\s*([^\n!]*)", text, re.M | re.I):
            names = [v.strip().lower() for v in m.group(2).split(",") if v.strip()]
            groups.setdefault(m.group(1).lower(), []).extend(names)
    return groups


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

    groups = namelists(root / "src")
    check("the sources declare the deck's namelist groups ({} found)".format(len(groups)),
          len(groups) >= 10, str(sorted(groups)))
    decks = root / "docs" / "decks.md"
    md = decks.read_text(encoding="utf-8") if decks.exists() else ""
    check("docs/decks.md exists", bool(md))
    secs = sections(md)
    for group in sorted(groups):
        text = secs.get(group)
        if text is None:
            check("docs/decks.md has a section for &{}".format(group), False)
            continue
        missing = [v for v in groups[group] if "`{}`".format(v) not in text]
        check("docs/decks.md documents every variable of &{} ({})".format(
            group, len(groups[group])), not missing, "missing: {}".format(", ".join(missing)))
        # first column of the section's tables: the variables documented
        documented = set()
        for line in text.splitlines():
            m = re.match(r"\|\s*((?:`\w+`(?:,\s*)?)+)\s*\|", line)
            if m:
                documented.update(re.findall(r"`(\w+)`", m.group(1)))
        stale = sorted(documented - set(groups[group]))
        check("docs/decks.md documents no variable &{} does not have".format(group), not stale,
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
