#!/usr/bin/env python3
"""Code metrics of gapbeam's Fortran sources, for before/after figures of a restructuring.

Usage:
    python3 scripts/code_metrics.py [--root DIR] [--top N] [--all-procedures] [--dot]
    python3 scripts/code_metrics.py --check [--root DIR]
    python3 scripts/code_metrics.py > metrics.txt

    --root DIR        repository to measure (default: the one holding this script)
    --top N           length of the longest-procedure lists (default 10)
    --all-procedures  list every procedure of src/, app/, bench/ (longest first)
    --dot             print the module `use` graph in Graphviz DOT instead of the report
    --check           check the house rules instead of the report: the folder rule (a layer folder
                      of src/ uses only itself and the folders below it: core < model <
                      integrators < analyses; io uses only core and io; jobs uses any folder of
                      src/; app and bench use src/), no source file over 1,000 lines and no
                      procedure over 150 lines (own lines: internal procedures apart); one line per breach, exit status 1 when
                      there is one, else 0 and one line 'rules kept'

Python 3 standard library only. Reads every .f90 file under src/, app/ and bench/ (the code)
and test/ (reported separately). Output, plain text:

  1. Lines per folder (src/core, src/model, src/integrators, src/analyses, src/io, any other
     src/ folder, app, bench; then test): files, total lines, code lines (not blank, not only a
     comment), comment-only lines, blank lines.
  2. Module `use` graph of the code (modules, submodules and programs of src/, app/, bench/;
     intrinsic modules (`use, intrinsic ::`, iso_*, ieee_*), hdf5* / h5* and omp_lib are left
     out and listed as external): number of modules and edges; the dependency depth, the longest
     chain of `use` from gapbeam_kinds up to the program in app/main.f90, counted in modules
     (both ends included; edges = modules - 1), with the chain printed; and the level of every
     module (its longest chain down to gapbeam_kinds, 1 for gapbeam_kinds itself; a unit that
     does not reach it gets 0), by folder.
  3. The N longest procedures (subroutines and functions, module procedures and internal ones;
     interface bodies are not procedures): name, host (the enclosing procedure for an internal
     one, else the module or program), file, start line and lengths:
        span   physical lines from the subroutine/function statement to its end statement,
               both included (an internal procedure's lines also count in its host's span);
        own    span less the spans of its internal procedures (ranking key);
        code   own lines that are neither blank nor only a comment.
     Two lists: ranked by own lines and ranked by span.
  4. Internal procedures per host procedure (every host that has a `contains`): number of
     internal procedures, the host's own/span lines, and what host association lets them see:
     the host's dummy arguments and its locals (entities declared in the host's specification
     part, between its header and its `contains`: every name on a type-declaration line with
     `::` (real, integer, logical, complex, character, type(...), class(...), procedure(...)),
     parameters included; names in the header's argument list count as dummies, the result
     variable of a function as a local); and `used`: how many different host locals (and
     dummies) occur as identifiers in the internal procedures' bodies without being declared
     there again. This is a token-level approximation (no scoping beyond one level, no
     `associate`/`block` handling, a local shadowed by a component name `%x` is not counted
     because `%name` tokens are skipped).
  5. test/: the same line counts (section 1), the N longest test procedures by own lines, and
     the modules test/ uses.

Parsing: comments (`!` outside strings) removed, continuation lines (`&`) joined, statements
split at `;`, case folded. Procedure statements are recognised by
`[prefixes] [type-spec] subroutine|function NAME` (prefixes pure, impure, elemental,
recursive, non_recursive, module) and closed by `end [subroutine|function|procedure] [NAME]`
or a bare `end`; `module procedure NAME` (separate module procedure) bodies are counted too,
`module procedure a, b` inside an interface is not.
"""

import argparse
import os
import re
import subprocess
import sys
from collections import defaultdict

LAYERS = ['src/core', 'src/model', 'src/integrators', 'src/analyses', 'src/io', 'src/jobs']
# the folder rule: which folders the modules of a folder may use
BELOW = {'src/core': ['src/core'],
         'src/model': ['src/core', 'src/model'],
         'src/integrators': ['src/core', 'src/model', 'src/integrators'],
         'src/analyses': ['src/core', 'src/model', 'src/integrators', 'src/analyses'],
         'src/io': ['src/core', 'src/io'],
         'src/jobs': LAYERS,
         'app': LAYERS + ['app'],
         'bench': LAYERS + ['bench']}
MAX_FILE_LINES = 1000
MAX_PROC_LINES = 150
EXTERNAL = re.compile(r'^(iso_\w+|ieee_\w+|omp_lib(_kinds)?|hdf5|h5\w*|mpi\w*|openacc)$')
PREFIX = r'(?:(?:pure|impure|elemental|recursive|non_recursive|module)\s+)'
TYPESPEC = (r'(?:(?:real|integer|logical|complex|character|double\s+precision|type|class)'
            r'\s*(?:\*\s*\d+|\((?:[^()]|\([^()]*\))*\))?\s+)')
PROC_RE = re.compile(r'^' + PREFIX + r'*' + TYPESPEC + r'?' + PREFIX + r'*'
                     r'(subroutine|function)\s+(\w+)\s*(\((.*?)\))?', re.I)
MODPROC_RE = re.compile(r'^module\s+procedure\s+(\w+)\s*$', re.I)
END_RE = re.compile(r'^end\s*(subroutine|function|procedure|module|submodule|program|'
                    r'interface|type|block\s*data)\b\s*(\w+)?\s*$', re.I)
BARE_END = re.compile(r'^end\s*$', re.I)
UNIT_RE = re.compile(r'^(module|program|submodule)\b\s*(\([^)]*\))?\s*(\w+)?\s*$', re.I)
IFACE_RE = re.compile(r'^(abstract\s+)?interface\b', re.I)
USE_RE = re.compile(r'^use\b\s*(,\s*(intrinsic|non_intrinsic)\s*)?(::)?\s*(\w+)', re.I)
DECL_RE = re.compile(r'^(real|integer|logical|complex|character|double\s+precision|type\s*\(|'
                     r'class\s*\(|procedure\s*\()', re.I)
IDENT_RE = re.compile(r'(?<![%\w])([a-z_]\w*)', re.I)


def strip_comment(line):
    """Remove a `!` comment outside strings; return (code, had_comment)."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in '\'"':
            quote = ch
        elif ch == '!':
            return line[:i], True
    return line, False


def strip_strings(code):
    return re.sub(r"'[^']*'|\"[^\"]*\"", "''", code)


class Source:
    """One .f90 file: physical line classes and logical statements with their line numbers."""

    def __init__(self, path, rel):
        self.path, self.rel = path, rel
        with open(path, errors='replace') as f:
            self.lines = f.read().split('\n')
        if self.lines and self.lines[-1] == '':
            self.lines.pop()
        self.kind = []          # 'blank' | 'comment' | 'code' per physical line
        self.statements = []    # (first line, last line, text)
        pending, first = '', None
        for no, raw in enumerate(self.lines, start=1):
            code, had = strip_comment(raw)
            s = code.strip()
            if not s:
                self.kind.append('comment' if had or raw.strip().startswith('!') else 'blank')
                if not raw.strip():
                    self.kind[-1] = 'blank'
                if pending:      # a comment line inside a continued statement
                    continue
                continue
            self.kind.append('code')
            if s.startswith('&'):
                s = s[1:].lstrip()
            cont = s.endswith('&')
            if cont:
                s = s[:-1].rstrip()
            if first is None:
                first = no
            pending = (pending + ' ' + s) if pending else s
            if not cont:
                for part in split_semicolons(pending):
                    if part.strip():
                        self.statements.append((first, no, part.strip()))
                pending, first = '', None
        if pending:
            self.statements.append((first, len(self.lines), pending.strip()))

    def count(self, a, b, kind=None):
        ks = self.kind[a - 1:b]
        return len(ks) if kind is None else sum(1 for k in ks if k == kind)


def split_semicolons(s):
    out, quote, cur = [], None, ''
    for ch in s:
        if quote:
            if ch == quote:
                quote = None
        elif ch in '\'"':
            quote = ch
        elif ch == ';':
            out.append(cur)
            cur = ''
            continue
        cur += ch
    out.append(cur)
    return out


class Proc:
    def __init__(self, name, kind, host, unit, src, start, args):
        self.name, self.kind, self.host, self.unit, self.src = name, kind, host, unit, src
        self.start, self.end = start, None
        self.args = args            # dummy argument names
        self.result = None
        self.children = []          # internal procedures
        self.parent = None          # host Proc, if internal
        self.contains_line = None   # line of this procedure's `contains`
        self.decls = []             # (line, names) declared in this procedure's own part

    @property
    def span(self):
        return self.end - self.start + 1

    @property
    def own(self):
        return self.span - sum(c.span for c in self.children)

    def own_code(self):
        n = self.src.count(self.start, self.end, 'code')
        return n - sum(self.src.count(c.start, c.end, 'code') for c in self.children)


class Unit:
    def __init__(self, name, kind, src, line):
        self.name, self.kind, self.src, self.line = name, kind, src, line
        self.uses = []          # (module name, intrinsic?)


def decl_names(text):
    """Entity names of a type-declaration statement with `::`."""
    if '::' not in text:
        return []
    rest = strip_strings(text.split('::', 1)[1])
    names, depth, cur = [], 0, ''
    for ch in rest:
        if ch in '([':
            depth += 1
        elif ch in ')]':
            depth -= 1
        elif ch == ',' and depth == 0:
            names.append(cur)
            cur = ''
            continue
        cur += ch
    names.append(cur)
    out = []
    for n in names:
        m = re.match(r'\s*([a-z_]\w*)', n, re.I)
        if m:
            out.append(m.group(1).lower())
    return out


def parse(src, units, procs):
    """Fill units (list) and procs (list) from one Source."""
    stack = []          # entries: ('unit', Unit) | ('proc', Proc) | ('iface', None) | ('type', None)
    for first, last, text in src.statements:
        low = text.lower()
        cur_proc = next((o for k, o in reversed(stack) if k == 'proc'), None)
        in_iface = any(k == 'iface' for k, _ in stack)
        # end statements
        if END_RE.match(low) or BARE_END.match(low):
            m = END_RE.match(low)
            what = (m.group(1) or '').replace(' ', '') if m else ''
            if not stack:
                continue
            if what in ('subroutine', 'function', 'procedure', ''):
                # close the innermost procedure-like entry (interface bodies are 'ibody')
                for idx in range(len(stack) - 1, -1, -1):
                    if stack[idx][0] in ('proc', 'ibody') or (what == '' and stack[idx][0] == 'unit'):
                        break
                else:
                    continue
                kind, obj = stack[idx]
                del stack[idx:]
                if kind == 'proc':
                    obj.end = last
                elif kind == 'unit' and obj.kind == 'program':
                    obj.end = last
                continue
            if what == 'interface':
                while stack and stack[-1][0] != 'iface':
                    stack.pop()
                if stack:
                    stack.pop()
                continue
            if what == 'type':
                if stack and stack[-1][0] == 'type':
                    stack.pop()
                continue
            if what in ('module', 'submodule', 'program'):
                while stack and stack[-1][0] != 'unit':
                    stack.pop()
                if stack:
                    stack[-1][1].end = last
                    stack.pop()
                continue
            continue
        if IFACE_RE.match(low):
            stack.append(('iface', None))
            continue
        if re.match(r'^type\b\s*(,[^:]*)?(::)?\s*\w+\s*(\(.*\))?$', low) and \
                not re.match(r'^type\s*\(', low):
            stack.append(('type', None))
            continue
        if low == 'contains':
            if cur_proc is not None and stack[-1][0] == 'proc':
                cur_proc.contains_line = first
            continue
        m = UNIT_RE.match(low)
        if m and not low.startswith('module procedure') and not PROC_RE.match(low):
            kind, name = m.group(1), (m.group(3) or '?')
            u = Unit(name, kind, src, first)
            units.append(u)
            stack.append(('unit', u))
            continue
        m = PROC_RE.match(low) if '::' not in low else None
        mp = MODPROC_RE.match(low)
        if m or (mp and not in_iface):
            if in_iface:
                stack.append(('ibody', None))
                continue
            unit = next((o for k, o in reversed(stack) if k == 'unit'), None)
            if m:
                kind, name = m.group(1), m.group(2)
                args = [a.strip() for a in (m.group(4) or '').split(',') if a.strip()]
                rm = re.search(r'\bresult\s*\(\s*(\w+)\s*\)', low)
            else:
                kind, name, args, rm = 'procedure', mp.group(1), [], None
            host = cur_proc.name if cur_proc else (unit.name if unit else '?')
            p = Proc(name, kind, host, unit, src, first, args)
            p.result = rm.group(1) if rm else (name if kind == 'function' else None)
            if cur_proc is not None:
                p.parent = cur_proc
                cur_proc.children.append(p)
            procs.append(p)
            stack.append(('proc', p))
            continue
        m = USE_RE.match(low)
        if m:
            unit = next((o for k, o in reversed(stack) if k == 'unit'), None)
            if unit is not None:
                unit.uses.append((m.group(4), m.group(2) == 'intrinsic'))
            continue
        if cur_proc is not None and stack[-1][0] == 'proc' and cur_proc.contains_line is None \
                and DECL_RE.match(low):
            cur_proc.decls.append((first, decl_names(text)))
    for k, o in stack:
        if k == 'proc' and o.end is None:
            o.end = len(src.lines)


def identifiers(src, a, b):
    """Set of identifiers (lower case) in the statements of lines a..b, strings removed."""
    out = set()
    for first, last, text in src.statements:
        if first >= a and last <= b:
            out.update(x.lower() for x in IDENT_RE.findall(strip_strings(text)))
    return out


def folder_of(rel):
    parts = rel.split('/')
    if parts[0] == 'src' and len(parts) > 2:
        return 'src/' + parts[1]
    return parts[0]


def collect(root, tops):
    files = []
    for top in tops:
        base = os.path.join(root, top)
        for dp, dn, fn in os.walk(base):
            dn.sort()
            for f in sorted(fn):
                if f.lower().endswith('.f90'):
                    p = os.path.join(dp, f)
                    files.append(Source(p, os.path.relpath(p, root)))
    return files


def line_table(files, order):
    rows = defaultdict(lambda: [0, 0, 0, 0, 0])
    for s in files:
        r = rows[folder_of(s.rel)]
        r[0] += 1
        r[1] += len(s.kind)
        r[2] += s.kind.count('code')
        r[3] += s.kind.count('comment')
        r[4] += s.kind.count('blank')
    keys = [k for k in order if k in rows] + sorted(k for k in rows if k not in order)
    out = [f'  {"folder":<18} {"files":>5} {"lines":>7} {"code":>7} {"comment":>8} {"blank":>6}']
    tot = [0, 0, 0, 0, 0]
    for k in keys:
        r = rows[k]
        tot = [a + b for a, b in zip(tot, r)]
        out.append(f'  {k:<18} {r[0]:>5} {r[1]:>7} {r[2]:>7} {r[3]:>8} {r[4]:>6}')
    if len(keys) > 1:
        out.append(f'  {"total":<18} {tot[0]:>5} {tot[1]:>7} {tot[2]:>7} {tot[3]:>8} {tot[4]:>6}')
    return out


def proc_table(procs, n, key):
    ps = sorted(procs, key=lambda p: (-key(p), p.src.rel, p.start))[:n]
    out = [f'  {"#":>2} {"own":>5} {"span":>5} {"code":>5}  {"procedure":<34} {"host":<30} file:line']
    for i, p in enumerate(ps, 1):
        host = p.host + (' (internal)' if p.parent else '')
        out.append(f'  {i:>2} {p.own:>5} {p.span:>5} {p.own_code():>5}  {p.name:<34} {host:<30} '
                   f'{p.src.rel}:{p.start}')
    return out


def check_rules(code_files, units, procs, by_name, graph):
    """The folder rule and the size limits; one line per breach; 1 when there is one."""
    breaches = []
    for u in units:
        folder = folder_of(u.src.rel)
        if folder not in BELOW:
            breaches.append(f'{u.src.rel}: folder {folder} has no place in the folder rule '
                            '(scripts/code_metrics.py BELOW, docs/architecture.md)')
            continue
        for d in graph[u.name]:
            dfolder = folder_of(by_name[d].src.rel)
            if dfolder not in BELOW[folder]:
                breaches.append(f'{u.src.rel}: {u.name} uses {d} ({dfolder}): {folder} may use '
                                f'only {", ".join(BELOW[folder])}')
    for f in code_files:
        if len(f.lines) > MAX_FILE_LINES:
            breaches.append(f'{f.rel}: {len(f.lines)} lines (at most {MAX_FILE_LINES})')
    for p in procs:
        if p.own > MAX_PROC_LINES:
            breaches.append(f'{p.src.rel}:{p.start}: procedure {p.name}: {p.own} lines of '
                            f'its own (at most {MAX_PROC_LINES})')
    for b in breaches:
        print(b)
    if not breaches:
        print(f'rules kept: the folder rule ({len(units)} units), files <= {MAX_FILE_LINES} '
              f'lines ({len(code_files)} files), procedures <= {MAX_PROC_LINES} lines '
              f'({len(procs)} procedures)')
    return 1 if breaches else 0


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description='gapbeam code metrics (see the module docstring).')
    ap.add_argument('--root', default=os.path.dirname(here))
    ap.add_argument('--top', type=int, default=10)
    ap.add_argument('--all-procedures', action='store_true')
    ap.add_argument('--dot', action='store_true')
    ap.add_argument('--check', action='store_true')
    if len(sys.argv) > 1 and sys.argv[1] in ('-h', '--help'):
        print(__doc__)
        return 0
    opts = ap.parse_args()
    root = os.path.abspath(opts.root)
    code_files = collect(root, ['src', 'app', 'bench'])
    test_files = collect(root, ['test'])
    if not code_files:
        print(f'code_metrics: no .f90 files under {root}/src, app, bench', file=sys.stderr)
        return 1
    units, procs = [], []
    for s in code_files:
        parse(s, units, procs)
    t_units, t_procs = [], []
    for s in test_files:
        parse(s, t_units, t_procs)

    # ---- use graph
    by_name = {u.name: u for u in units}
    graph = {}
    external = defaultdict(set)
    for u in units:
        deps = []
        for name, intrinsic in u.uses:
            if intrinsic or EXTERNAL.match(name) or name not in by_name:
                external[name].add(u.name)
            elif name not in deps:
                deps.append(name)
        graph[u.name] = deps
    if opts.check:
        return check_rules(code_files, units, procs, by_name, graph)
    if opts.dot:
        print('digraph gapbeam_use {')
        print('  rankdir=BT; node [shape=box, fontsize=10];')
        for a in sorted(graph):
            for b in graph[a]:
                print(f'  "{a}" -> "{b}";')
        print('}')
        return 0

    memo = {}

    def chain(name, seen=()):
        """Longest chain of use from `name` down to gapbeam_kinds (list of names) or None."""
        if name in memo:
            return memo[name]
        if name in seen:
            return None   # a cycle (not legal Fortran): ignore
        if name == 'gapbeam_kinds':
            memo[name] = [name]
            return memo[name]
        best = None
        for d in graph.get(name, []):
            c = chain(d, seen + (name,))
            if c is not None and (best is None or len(c) > len(best)):
                best = c
        memo[name] = [name] + best if best is not None else None
        return memo[name]

    program = next((u for u in units if u.kind == 'program' and u.src.rel == 'app/main.f90'),
                   None)
    try:
        git_head = subprocess.run(['git', '-C', root, 'log', '-1', '--format=%h %s', '--',
                                   'src', 'app', 'bench', 'test'],
                                  capture_output=True, text=True, check=True).stdout.strip()
        if subprocess.run(['git', '-C', root, 'diff', '--quiet', 'HEAD', '--', 'src', 'app',
                           'bench', 'test']).returncode != 0:
            git_head += ' + uncommitted changes'
    except (OSError, subprocess.CalledProcessError):
        git_head = ''

    print(f'gapbeam code metrics: {root}' + (f'\n  sources (src/ app/ bench/ test/) last changed in {git_head}'
                                                   if git_head else ''))
    print()
    print('1. Lines per folder (code: not blank and not only a comment)')
    for ln in line_table(code_files, LAYERS + ['app', 'bench']):
        print(ln)
    print()

    n_edges = sum(len(v) for v in graph.values())
    print(f'2. Module use graph: {len(units)} units ({sum(u.kind == "module" for u in units)} '
          f'modules, {sum(u.kind == "program" for u in units)} programs, '
          f'{sum(u.kind == "submodule" for u in units)} submodules), {n_edges} use edges')
    if program is not None:
        c = chain(program.name)
        if c:
            print(f'   dependency depth: {len(c)} modules ({len(c) - 1} use edges) from '
                  'gapbeam_kinds up to the program '
                  f'"{program.name}" (app/main.f90); the longest chain:')
            for i, n in enumerate(reversed(c)):
                u = by_name[n]
                print(f'     {i + 1:>2}. {n:<26} {u.src.rel}')
            # how many different longest chains are there?
        else:
            print(f'   the program {program.name} does not reach gapbeam_kinds')
    else:
        print('   no program in app/main.f90')
    print('   level of each unit (longest chain down to gapbeam_kinds, in modules):')
    rows = []
    for u in units:
        c = chain(u.name)
        rows.append((folder_of(u.src.rel), -(len(c) if c else 0), u.name,
                     len(c) if c else 0, len(graph[u.name])))
    cur = None
    for folder, _, name, level, nuse in sorted(rows):
        if folder != cur:
            print(f'     {folder}:')
            cur = folder
        print(f'       {level:>2}  {name:<28} uses {nuse}')
    print('   external modules (not in the graph): ' +
          ', '.join(f'{k} ({len(v)})' for k, v in sorted(external.items())))
    print()

    print(f'3. The {opts.top} longest procedures of src/, app/, bench/ ({len(procs)} procedures, '
          f'{sum(1 for p in procs if p.parent)} of them internal)')
    print('   own = span less internal procedures; span = statement to end statement; '
          'code = own non-blank, non-comment lines')
    print('   ranked by own lines:')
    for ln in proc_table(procs, opts.top, lambda p: p.own):
        print(ln)
    print('   ranked by span:')
    for ln in proc_table(procs, opts.top, lambda p: p.span):
        print(ln)
    print()

    hosts = [p for p in procs if p.children]
    print(f'4. Internal procedures per host procedure ({len(hosts)} hosts, '
          f'{sum(len(h.children) for h in hosts)} internal procedures)')
    print('   dummies/locals: declared in the host before its contains (host association makes '
          'them all visible inside);')
    print('   used: different host dummies/locals named in the internal bodies and not '
          'redeclared there (token approximation)')
    print(f'   {"host":<32} {"internal":>8} {"own":>5} {"span":>5} {"dummies":>7} {"locals":>6} '
          f'{"used d/l":>8}  file:line')
    for h in sorted(hosts, key=lambda h: (-len(h.children), -h.span)):
        args = set(a.lower() for a in h.args)
        declared = set()
        for _, names in h.decls:
            declared.update(names)
        dummies = args
        locals_ = (declared - args) | ({h.result} if h.result and h.result not in args else set())
        used_d, used_l = set(), set()
        for c in h.children:
            ids = identifiers(h.src, c.start, c.end)
            own = set(a.lower() for a in c.args)
            for _, names in c.decls:
                own.update(names)
            for g in c.children:   # nested deeper: their own declarations
                for _, names in g.decls:
                    own.update(names)
            used_d |= (ids & dummies) - own
            used_l |= (ids & locals_) - own - {h.name}
        print(f'   {h.name:<32} {len(h.children):>8} {h.own:>5} {h.span:>5} {len(dummies):>7} '
              f'{len(locals_):>6} {len(used_d):>3}/{len(used_l):<4}  {h.src.rel}:{h.start}')
        print('      ' + ', '.join(c.name for c in h.children))
    print()

    if opts.all_procedures:
        print('All procedures (by own lines):')
        for ln in proc_table(procs, len(procs), lambda p: p.own):
            print(ln)
        print()

    print('5. test/ (reported separately)')
    for ln in line_table(test_files, []):
        print(ln)
    print(f'   {len(t_procs)} procedures, {len(t_units)} units; the {opts.top} longest by own '
          'lines:')
    for ln in proc_table(t_procs, opts.top, lambda p: p.own):
        print(ln)
    used = defaultdict(int)
    for u in t_units:
        for name, intrinsic in u.uses:
            if name in by_name:
                used[name] += 1
    print('   project modules used by test/ (units using each): ' +
          ', '.join(f'{k} ({v})' for k, v in sorted(used.items(), key=lambda kv: (-kv[1], kv[0]))))
    return 0


if __name__ == '__main__':
    sys.exit(main())
