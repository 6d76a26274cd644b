#!/usr/bin/env python3
"""scripts/fuzz_decks.py - deterministic fuzz test of the gapbeam deck reader, through the real
executable.

Usage:
    scripts/fuzz_decks.py GAPBEAM_EXE [--seed N] [--per-class N] [--jobs N] [--timeout S]
                          [--limit S] [--only CLASS[,CLASS...]] [--keep DIR] [--json FILE]
                          [--details N] [--list]

What it does
------------
1. Reads every deck in inputs/*.nml (sorted) and makes it cheap to run ("cheapening", done on the
   deck text before any mutation, so a mutation can still hit the variables it sets): 2 + 4
   forcing periods for transient, sweep and model-size runs, a Lyapunov exponent over 2 periods
   (no adaptive average: lyapunov_max_periods = 2) and at most 6 transient periods (no settling
   extension: transient_max_periods = 6),
   2 history periods; sweeps: progress lines off (output under the deck's own prefix, in a
   directory the sweep creates), a 3-frequency line given as a list, a 3 x 2 grid;
   work-precision studies of 2 levels over 1 period without rk45 (see cheapen) and stability
   charts of 11 points, on 6 elements instead of 15; a model-size ladder of 2 and 3 elements
   and 1 and 2 modes; continuations: a 100-period transient taken as a period-1 orbit, 4 points
   a branch, no doubled branches, 3 points a curve. These cheap decks run unmutated as the
   `baseline` class
   (each must end with exit 0 and finite results).
2. Mutates them with a random.Random(seed) (default seed 20240611): --per-class decks (default
   24) for each mutation class below, the base deck taken in turn (deck i of class c is base deck
   (i + c) mod n), the variant of a class in turn (drawn for value_negative), the rest (which
   group, variable, position, value) drawn from the generator. The same seed always gives the same decks, byte for byte.
3. Runs every deck (2 workers by default) in its own temporary directory, with the deck's file
   name as the path (`gapbeam NAME.nml [OVERRIDE]`, cwd = that directory, so the decks' relative
   output prefixes land there), OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1, an address-space limit
   of 2 GiB and a time-out per deck (default 5 s; the slowest cheap deck takes about 1 s).
4. Classifies each run (below) and prints one `PASS  fuzz: CLASS ...` or `FAIL  fuzz: CLASS ...`
   line per mutation class (plus indented lines for the first --details failing decks of each
   class), one line for the total run time against --limit (default 60 s), and two tables:
   decks by outcome and class, and every issue found (a deck can have several).
   Exit status 1 if any check failed, else 0.

Mutation classes
----------------
    delete_chars      1 to 4 characters deleted (mostly inside groups)
    value_string      a value replaced by text: 'fuzz', fuzz, 'x y z', "quoted", .true., 1.0.0,
                      0x1F, abc123, or a lone quote
    value_negative    one of: a number negated (-1 for a word); a value (a `node` one time in
                      two) replaced by -1; ', -1' appended to a list of numbers (a sweep axis or
                      a model-size ladder where the deck has one, else `node`)
    value_zero        a value replaced by 0 or 0.0
    value_nan         NaN, nan, -NaN
    value_inf         Inf, -Inf, Infinity, +inf
    value_huge        1e308, -1e308, 1.7976931348623157e308, 1e309, 2147483647, -2147483648,
                      9999999999
    value_empty       the value removed: `name = ,`
    group_misspelt    a group name with one typo (letter dropped, doubled, swapped or replaced)
    group_duplicated  a whole group repeated right after itself
    truncated         the file cut at a random byte, just before its last '/', or to 0 bytes
    line_crlf         CRLF line ends (all lines, or every other line)
    line_cr           CR-only line ends (old Mac)
    line_bom          a UTF-8 byte-order mark first (with LF or CRLF line ends)
    long_line         a 100 000-character comment line; a value padded with 20 000 blanks; a
                      300-character title; a 288-character output prefix; a 100-entry &stops
                      node list; the whole deck on one line (comments removed); a 5000-character
                      override (a valid override padded with blanks)
    group_char        a character around a group name: after it ('.', '-', ':', '='), after the
                      '&' ('-', '.', '=', '!', a blank), or its first letter replaced by '-'
                      (`&-tops`): once dropped whole and silently (issue 25)
    text_outside      ' junk' after a closing '/', a line of stray text between groups, a '/'
                      after a group's first assignment (a second '/'), an assignment repeated in
                      its group, a group's '/' removed (it runs into the next group)
    lone_sign         a numeric value replaced by '+' or '-' (once: the old value kept)
    extreme_value     frequency_hz = 1e308 or 1e10, amplitude_pp = 1e-300 or 1e200 (overrides),
                      a value 1e309 or -1e309 (overflow), 1e-400 (underflow: any outcome), an
                      &initial displacement of 1e300
    count_2_31        a count (transient_periods, record_periods, steps_per_period, n_elem, ...,
                      random_seed) set to 2^31 - 1, 2^31, 2^32 or -(2^31 + 1) by an override

Outcomes
--------
    ok           exit 0; stdout ends with `output: PREFIX`; PREFIX.h5 exists; no NaN, Infinity,
                 -Infinity or '****' (overflowed Fortran field) in stdout (the title line aside)
                 nor in the data lines (not '#' comments) of the text files written (every file
                 but the deck, *.h5 and *.checkpoint; the HDF5 file is not read: stdlib only);
                 where the mutation set the title or the output prefix, stdout shows it whole
                 and the files are under that prefix.
    clean_error  exit 1; stderr is exactly one line, starting `error: `, naming the deck path as
                 given, a group `&name` (the mutated group where the mutation targets one) and,
                 where the mutation targets a variable, that variable; no file but the deck left
                 in the run's directory (no result under its final name, no .part file).
    failures     timeout, signal N, runtime_error (`At line`, `Fortran runtime error` or
                 `warning`, `Program received signal`, `HDF5-DIAG`), nonfinite_output, unexpected_ok (a
                 mutation that must be rejected ran), unexpected_error (a mutation that must run,
                 e.g. CR line ends, was rejected), file_left_after_error, part_file_left,
                 missing_output, output_misplaced, title_truncated, multi_line_error,
                 no_error_prefix, deck_not_named, group_not_named, var_not_named, bad_status N,
                 backtrace (`ERROR STOP`, `Backtrace`, `#0 ...` lines). A deck's outcome is its
                 first issue in that order.
Expectations: encoding-only mutations (line_*, long comment, blank padding, one-line deck, long
override) must give `ok`; value_empty, group_misspelt, group_duplicated, a negative node, a list
with -1 appended, a 100-entry list, an empty file and every deck of group_char, text_outside,
lone_sign, extreme_value (but the underflow) and count_2_31 (but random_seed = 2^31 - 1) must give
`clean_error`, naming the group (and the variable where the mutation targets one); all others
may give either.

--keep DIR keeps every run's directory (deck, outputs, stdout.txt, stderr.txt, case.json) under
DIR; --json FILE writes every deck's result; --list prints the decks without running them;
--only runs some classes (the others are still generated, so the decks stay the same).
Standard library only.
"""

import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEED = 20240611
CLASSES = ['delete_chars', 'value_string', 'value_negative', 'value_zero', 'value_nan',
           'value_inf', 'value_huge', 'value_empty', 'group_misspelt', 'group_duplicated',
           'truncated', 'line_crlf', 'line_cr', 'line_bom', 'long_line',
           # appended (later classes draw after the earlier ones: their decks stay the same)
           'group_char', 'text_outside', 'lone_sign', 'extreme_value', 'count_2_31']
KNOWN_GROUPS = ('job beam root springs masses modes calibrate stops damping forcing solver '
                'initial output diagnostics sweep reduction study model_size').split()
ISSUE_ORDER = ['timeout', 'signal', 'runtime_error', 'nonfinite_output', 'unexpected_ok',
               'unexpected_error', 'file_left_after_error', 'part_file_left', 'missing_output',
               'output_misplaced', 'title_truncated', 'multi_line_error', 'no_error_prefix',
               'deck_not_named', 'group_not_named', 'var_not_named', 'bad_status', 'backtrace']
MEMORY_LIMIT = 2 << 30

# ------------------------------------------------------------------------------ deck text


def mask(text):
    """Copy of `text` with comments blanked and quoted strings replaced by 'q' (same length).

    Quotes carry over line ends, as in gapbeam's group scanner; a '!' outside quotes starts a
    comment to the end of the line (CR or LF)."""
    out = list(text)
    quote = None
    comment = False
    for i, c in enumerate(text):
        if comment:
            if c in '\n\r':
                comment = False
            else:
                out[i] = ' '
        elif quote:
            if c == quote:
                quote = None
            if c not in '\n\r':
                out[i] = 'q'
        elif c in '\'"':
            quote = c
            out[i] = 'q'
        elif c == '!':
            comment = True
            out[i] = ' '
    return ''.join(out)


GROUP_RE = re.compile(r'[&$]([A-Za-z_][A-Za-z0-9_]*)')
ASSIGN_RE = re.compile(r'(?<![^\s,])([A-Za-z_][A-Za-z0-9_]*)\s*(\([^)=]*\))?\s*=')


def scan(text):
    """Groups of a deck: [{name, start, name_end, end, assigns: [{var, index, var_start,
    val_start, val_end, is_list}]}]; `end` is the index of the closing '/' (len(text) if none)."""
    m = mask(text)
    groups = []
    pos = 0
    while True:
        g = GROUP_RE.search(m, pos)
        if not g:
            break
        start, name_end = g.start(), g.end()
        end = m.find('/', name_end)
        if end < 0:
            end = len(m)
        body = m[name_end:end]
        found = list(ASSIGN_RE.finditer(body))
        assigns = []
        for k, a in enumerate(found):
            v0 = name_end + a.end()
            v1 = name_end + (found[k + 1].start() if k + 1 < len(found) else len(body))
            while v0 < v1 and m[v0].isspace():
                v0 += 1
            while v1 > v0 and (m[v1 - 1].isspace() or m[v1 - 1] == ','):
                v1 -= 1
            assigns.append({'var': a.group(1).lower(), 'index': a.group(2) or '',
                            'var_start': name_end + a.start(1), 'val_start': v0, 'val_end': v1,
                            'is_list': ',' in m[v0:v1]})
        groups.append({'name': g.group(1).lower(), 'start': start, 'name_end': name_end,
                       'end': end, 'assigns': assigns})
        pos = end + 1
    return groups


def find_group(text, name):
    for g in scan(text):
        if g['name'] == name:
            return g
    return None


def get_value(text, group, var):
    g = find_group(text, group)
    if g:
        for a in g['assigns']:
            if a['var'] == var and not a['index']:
                return text[a['val_start']:a['val_end']]
    return None


def set_value(text, group, var, value):
    """Set `var = value` in &group: replace the value, or add the assignment first in the group,
    or add the group at the end of the deck."""
    g = find_group(text, group)
    if g is None:
        return text.rstrip('\n') + '\n&%s %s = %s /\n' % (group, var, value)
    for a in g['assigns']:
        if a['var'] == var and not a['index']:
            return text[:a['val_start']] + value + text[a['val_end']:]
    return text[:g['name_end']] + ' %s = %s,' % (var, value) + text[g['name_end']:]


def remove_var(text, group, var):
    g = find_group(text, group)
    if g is None:
        return text
    for a in g['assigns']:
        if a['var'] == var:
            end = a['val_end']
            rest = text[end:]
            stripped = rest.lstrip(' ')
            if stripped.startswith(','):
                end += len(rest) - len(stripped) + 1
            return text[:a['var_start']] + text[end:]
    return text


def cheapen(text):
    """Make a deck run in well under a second with the debug build."""
    analysis = (get_value(text, 'job', 'analysis') or "'modes'").strip('\'"').lower()
    two_planes = (get_value(text, 'beam', 'planes') or '1').strip() == '2'
    if analysis in ('transient', 'sweep', 'model_size'):
        text = set_value(text, 'solver', 'transient_periods', '2')
        text = set_value(text, 'solver', 'record_periods', '4')
        # ring supports refuse an exponent (a two-plane deck's default is lyapunov_periods = 0)
        if not two_planes and (get_value(text, 'diagnostics', 'lyapunov_periods') or '') \
                .strip() != '0':
            text = set_value(text, 'diagnostics', 'lyapunov_periods', '2')
        # the exponent's adaptive average and the settling extensions bounded as tightly
        text = set_value(text, 'diagnostics', 'lyapunov_max_periods', '2')
        text = set_value(text, 'diagnostics', 'transient_max_periods', '6')
    if two_planes and analysis in ('transient', 'sweep'):
        # the tube deck (24 elements, two planes, impacts with stick-slip): one period at a
        # loose tolerance, no settling test and no certificate, about 1 s with the debug build
        text = set_value(text, 'solver', 'transient_periods', '0')
        text = set_value(text, 'solver', 'record_periods', '1')
        text = set_value(text, 'solver', 'tolerance', '1.0e-2')
        text = set_value(text, 'diagnostics', 'settle_windows', '0')
        text = set_value(text, 'diagnostics', 'certify', '.false.')
    if analysis == 'transient':
        text = set_value(text, 'output', 'history_periods', '1' if two_planes else '2')
    if analysis == 'sweep':
        # the deck's own prefix ('results/...'): the sweep makes the missing directory
        text = set_value(text, 'sweep', 'progress', '.false.')
        x_var = (get_value(text, 'sweep', 'x_variable') or '').strip().strip('\'"')
        if x_var and x_var != '&forcing frequency_hz':
            # axes of deck variables given as lists (the cross-flow map): their first values
            for var in ('x_values', 'y_values'):
                value = get_value(text, 'sweep', var)
                if value is not None:
                    text = set_value(text, 'sweep', var, value.split(',')[0].strip())
        elif two_planes and (get_value(text, 'sweep', 'n_amplitude') is not None
                           or get_value(text, 'sweep', 'n_y') is not None):
            text = set_value(text, 'sweep', 'n_frequency', '1')     # 1 point, about 2 s
            for var in ('n_amplitude', 'n_y'):
                if get_value(text, 'sweep', var) is not None:
                    text = set_value(text, 'sweep', var, '1')
        elif get_value(text, 'sweep', 'n_amplitude') is not None:
            text = set_value(text, 'sweep', 'n_frequency', '3')
            text = set_value(text, 'sweep', 'n_amplitude', '2')
        else:   # a line: given as a list, so that list mutations reach the sweep axes
            for var in ('frequency_start_hz', 'frequency_end_hz', 'n_frequency'):
                text = remove_var(text, 'sweep', var)
            text = set_value(text, 'sweep', 'frequency_hz', '9.5, 10.0, 10.5')
    if analysis in ('work_precision', 'stability') and \
            int(get_value(text, 'beam', 'n_elem') or '4') > 8:
        text = set_value(text, 'beam', 'n_elem', '6')     # 15 elements: a few seconds
        text = set_value(text, 'stops', 'node', '7')
    if analysis == 'work_precision':
        text = set_value(text, 'study', 'levels', '2')
        text = set_value(text, 'study', 'periods', '1')
        # no rk45: its cost grows with the stiffest mode, and a mutation that makes the root
        # spring 10^4 times stiffer (k_theta 0.0912 -> 912) makes it run for 20 s, correctly.
        # The speed of the methods is not what this test is about (issue 12, item 14).
        series = get_value(text, 'study', 'series')
        if series is not None:
            kept = [x for x in series.split(',') if x.strip().strip('\'"').lower() != 'rk45']
            text = set_value(text, 'study', 'series', ','.join(kept))
    if analysis == 'stability':
        text = set_value(text, 'study', 'n_omega_dt', '11')
    if analysis == 'model_size':
        text = set_value(text, 'model_size', 'elements', '2, 3')
        text = set_value(text, 'model_size', 'modes', '1, 2')
    if analysis == 'continuation':
        # a short transient taken as a period-1 orbit, 4 points a branch, no doubled branch,
        # 3 points a curve (issue 14)
        text = set_value(text, 'continuation', 'transient_periods', '100')
        text = set_value(text, 'continuation', 'period', '1')
        text = set_value(text, 'continuation', 'max_points', '4')
        text = set_value(text, 'continuation', 'switch_period_doubling', '.false.')
        text = set_value(text, 'continuation', 'curve_max_points', '3')
    return text


# ------------------------------------------------------------------------------ mutations

NUMBER_RE = re.compile(r'[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$')


class Case:
    """One fuzz deck: the text (bytes) and what is expected of its run."""

    def __init__(self, cls, base, variant, data, expect='any', group=None, var=None, args=(),
                 detail='', want_title=None, want_output=None):
        self.cls = cls                  # mutation class
        self.base = base                # base deck file name
        self.variant = variant          # variant of the class
        self.data = data                # deck bytes
        self.expect = expect            # 'ok', 'error' or 'any'
        self.group = group              # group the error must name (None: any group)
        self.var = var                  # variable the error must name (None: none required)
        self.args = list(args)          # overrides after the deck
        self.detail = detail            # what was done, for the report
        self.want_title = want_title    # title stdout must show whole on success
        self.want_output = want_output  # output prefix that must hold the results on success
        self.id = ''

    def describe(self):
        return '%s %s [%s] %s' % (self.id, self.base, self.variant, self.detail)


def enc(text):
    return text.encode('utf-8')


def is_numeric(text, a):
    return all(NUMBER_RE.match(v.strip())
               for v in mask(text)[a['val_start']:a['val_end']].split(','))


def pick_assign(rng, text, numeric=False):
    """A random assignment (group, assignment); with `numeric`, 4 times in 5 one with a number
    (or list of numbers) as value, and then 1 time in 4 a `node` one where the deck has it."""
    choices = [(g, a) for g in scan(text) for a in g['assigns'] if a['val_end'] > a['val_start']]
    if numeric and rng.random() < 0.8:
        numbers = [(g, a) for g, a in choices if is_numeric(text, a)]
        nodes = [(g, a) for g, a in numbers if a['var'] == 'node']
        if nodes and rng.random() < 0.25:
            return rng.choice(nodes)
        if numbers:
            return rng.choice(numbers)
    return rng.choice(choices)


def short(s, n=60):
    s = s.replace('\n', '\\n').replace('\r', '\\r')
    return s if len(s) <= n else s[:n] + '...'


def value_case(cls, rng, base, text, i):
    g, a = pick_assign(rng, text, numeric=cls != 'value_string')
    old = text[a['val_start']:a['val_end']]
    var = a['var']
    expect = 'any'
    variant = cls
    if cls == 'value_string':
        new = rng.choice(["'fuzz'", 'fuzz', "'x y z'", '"quoted"', '.true.', '1.0.0', '0x1F',
                          'abc123', "'"])
    elif cls == 'value_negative':
        variant = rng.choice(['negated', 'minus_one', 'list_trailing_-1'])
        if variant == 'minus_one' and rng.random() < 0.5:
            nodes = [(gg, aa) for gg in scan(text) for aa in gg['assigns'] if aa['var'] == 'node']
            if nodes:
                g, a = rng.choice(nodes)
        if variant == 'list_trailing_-1':
            lists = [(gg, aa) for gg in scan(text) for aa in gg['assigns']
                     if aa['is_list'] and is_numeric(text, aa)]
            nodes = [(gg, aa) for gg in scan(text) for aa in gg['assigns'] if aa['var'] == 'node']
            if lists or nodes:      # a list of the deck first (sweep axis, model-size ladder)
                g, a = rng.choice(lists or nodes)
            else:
                variant = 'negated'
        old = text[a['val_start']:a['val_end']]
        var = a['var']
        if variant == 'list_trailing_-1':
            new = old + ', -1'     # -1 is the readers' 'not given' marker of list entries
            expect = 'error'
        elif variant == 'minus_one':
            new = '-1'
        elif NUMBER_RE.match(old.strip()):
            s = old.strip()
            new = s[1:] if s.startswith('-') else '-' + s.lstrip('+')
        else:
            new = '-1'
        if var == 'node' and new.strip().startswith('-'):
            expect = 'error'
    elif cls == 'value_zero':
        new = rng.choice(['0', '0.0'])
    elif cls == 'value_nan':
        new = rng.choice(['NaN', 'nan', '-NaN'])
    elif cls == 'value_inf':
        new = rng.choice(['Inf', '-Inf', 'Infinity', '+inf'])
    elif cls == 'value_huge':
        new = ['1e308', '-1e308', '1.7976931348623157e308', '1e309', '2147483647',
               '-2147483648', '9999999999'][i % 7]
    elif cls == 'value_empty':
        new = ''
        expect = 'error'
        # `name = ,` even when the assignment was the group's last
        rest = text[a['val_end']:].lstrip(' ')
        if not rest.startswith(','):
            new = ','
    else:
        raise ValueError(cls)
    mutated = text[:a['val_start']] + new + text[a['val_end']:]
    return Case(cls, base, variant, enc(mutated), expect, g['name'], var,
                detail='&%s %s%s = %s (was %s)' % (g['name'], var, a['index'], short(new),
                                                  short(old)))


def typo(rng, name):
    letters = 'abcdefghijklmnopqrstuvwxyz'
    for _ in range(100):
        k = rng.randrange(4)
        p = rng.randrange(len(name))
        if k == 0 and len(name) > 2:
            new = name[:p] + name[p + 1:]
        elif k == 1:
            new = name[:p] + name[p] + name[p:]
        elif k == 2 and p + 1 < len(name) and name[p] != name[p + 1]:
            new = name[:p] + name[p + 1] + name[p] + name[p + 2:]
        else:
            new = name[:p] + rng.choice(letters.replace(name[p].lower(), '')) + name[p + 1:]
        if new.lower() != name.lower() and new.lower() not in KNOWN_GROUPS:
            return new
    raise RuntimeError('no typo for ' + name)


COUNTS = [('solver', 'transient_periods'), ('solver', 'record_periods'),
          ('solver', 'steps_per_period'), ('diagnostics', 'lyapunov_periods'),
          ('diagnostics', 'transient_max_periods'), ('output', 'history_periods'),
          ('output', 'samples_per_period'), ('beam', 'n_elem'), ('diagnostics', 'period_points'),
          ('sweep', 'n_frequency'), ('sweep', 'chunk'), ('continuation', 'max_points'),
          ('study', 'periods'), ('diagnostics', 'random_seed')]


def strict_case(cls, i, rng, base, text):
    """The classes that found the reader's silent faults (issue 25): characters around group
    names, text outside groups, lone signs, extreme magnitudes, 2^31 counts."""
    groups = scan(text)
    if cls == 'group_char':
        g = rng.choice(groups)
        name = text[g['start'] + 1:g['name_end']]
        v = ['after_dot', 'after_dash', 'after_colon', 'after_equals', 'amp_dash', 'amp_dot',
             'amp_equals', 'amp_bang', 'amp_blank', 'letter_dash'][i % 10]
        if v.startswith('after_'):
            new = '&' + name + {'after_dot': '.', 'after_dash': '-', 'after_colon': ':',
                                'after_equals': '='}[v]
        elif v == 'letter_dash':                       # '&stops' -> '&-tops'
            new = '&-' + name[1:]
        else:
            new = '&' + {'amp_dash': '-', 'amp_dot': '.', 'amp_equals': '=', 'amp_bang': '!',
                         'amp_blank': ' '}[v] + name
        mutated = text[:g['start']] + new + text[g['name_end']:]
        return Case(cls, base, v, enc(mutated), 'error',
                    None if v == 'letter_dash' else g['name'], None,
                    detail='&%s -> %s' % (name, new))
    if cls == 'text_outside':
        v = ['after_slash', 'between_groups', 'second_slash', 'repeated', 'missing_slash'][i % 5]
        closed = [g for g in groups if g['end'] < len(text)]
        g = rng.choice(closed or groups)
        if v == 'after_slash':
            mutated = text[:g['end'] + 1] + ' junk' + text[g['end'] + 1:]
            return Case(cls, base, v, enc(mutated), 'error', g['name'], None,
                        detail="' junk' after the '/' of &%s" % g['name'])
        if v == 'between_groups':
            mutated = text[:g['end'] + 1] + '\nstray text\n' + text[g['end'] + 1:]
            return Case(cls, base, v, enc(mutated), 'error', g['name'], None,
                        detail="a line 'stray text' after &%s" % g['name'])
        with_values = [gg for gg in groups if len(gg['assigns']) >= 2] or groups
        g = rng.choice(with_values)
        if v == 'second_slash' and len(g['assigns']) >= 2:
            a = g['assigns'][0]
            mutated = text[:a['val_end']] + ' /' + text[a['val_end']:]
            return Case(cls, base, v, enc(mutated), 'error', g['name'], None,
                        detail="a '/' after the first assignment of &%s" % g['name'])
        if v == 'missing_slash' and g is not groups[-1]:
            mutated = text[:g['end']] + text[g['end'] + 1:]
            return Case(cls, base, v, enc(mutated), 'error', g['name'], None,
                        detail="the '/' of &%s removed (the next group follows)" % g['name'])
        a = rng.choice(g['assigns'])
        item = text[a['var_start']:a['val_end']]
        mutated = text[:a['val_end']] + ', ' + item + text[a['val_end']:]
        return Case(cls, base, 'repeated', enc(mutated), 'error', g['name'], a['var'],
                    detail='&%s %s assigned twice' % (g['name'], a['var']))
    if cls == 'lone_sign':
        numbers = [(g, a) for g in groups for a in g['assigns']
                   if a['val_end'] > a['val_start'] and is_numeric(text, a)]
        g, a = rng.choice(numbers)
        new = ['+', '-'][i % 2]
        mutated = text[:a['val_start']] + new + text[a['val_end']:]
        return Case(cls, base, new, enc(mutated), 'error', g['name'], a['var'],
                    detail='&%s %s = %s (was %s)' % (g['name'], a['var'], new,
                                                    short(text[a['val_start']:a['val_end']])))
    if cls == 'extreme_value':
        v = ['frequency_1e308', 'amplitude_1e-300', 'overflow_1e309', 'overflow_-1e309',
             'initial_1e300', 'amplitude_1e200', 'underflow_1e-400', 'frequency_1e10'][i % 8]
        if v.startswith('overflow_'):
            numbers = [(g, a) for g in groups for a in g['assigns']
                       if a['val_end'] > a['val_start'] and is_numeric(text, a)]
            g, a = rng.choice(numbers)
            new = v.split('_')[1]
            mutated = text[:a['val_start']] + new + text[a['val_end']:]
            return Case(cls, base, v, enc(mutated), 'error', g['name'], a['var'],
                        detail='&%s %s = %s' % (g['name'], a['var'], new))
        if v == 'underflow_1e-400':       # reads as 0 (or a subnormal): either outcome
            numbers = [(g, a) for g in groups for a in g['assigns']
                       if a['val_end'] > a['val_start'] and is_numeric(text, a)]
            g, a = rng.choice(numbers)
            mutated = text[:a['val_start']] + '1e-400' + text[a['val_end']:]
            return Case(cls, base, v, enc(mutated), 'any', g['name'], None,
                        detail='&%s %s = 1e-400' % (g['name'], a['var']))
        if v == 'initial_1e300':
            n_elem = int((get_value(text, 'beam', 'n_elem') or '4').strip())
            override = ("&initial kind = 'given', node = %d, dof = 'w', displacement = 1e300 /"
                        % (n_elem + 1))
            return Case(cls, base, v, enc(text), 'error', 'initial', 'displacement',
                        args=[override], detail='override ' + override)
        group, var, new = {'frequency_1e308': ('forcing', 'frequency_hz', '1e308'),
                           'frequency_1e10': ('forcing', 'frequency_hz', '1e10'),
                           'amplitude_1e-300': ('forcing', 'amplitude_pp', '1e-300'),
                           'amplitude_1e200': ('forcing', 'amplitude_pp', '1e200')}[v]
        override = '&%s %s = %s /' % (group, var, new)
        return Case(cls, base, v, enc(text), 'error', group, var, args=[override],
                    detail='override ' + override)
    if cls == 'count_2_31':
        group, var = COUNTS[i % len(COUNTS)]
        new = ['2147483647', '2147483648', '4294967296', '-2147483649'][(i // 2) % 4]
        override = '&%s %s = %s /' % (group, var, new)
        # 2^31 - 1 fits in 32 bits: refused as a count or, for a seed, any outcome
        expect = 'any' if new == '2147483647' and var == 'random_seed' else 'error'
        return Case(cls, base, new, enc(text), expect, group, var, args=[override],
                    detail='override ' + override)
    raise ValueError(cls)


def make_case(cls, i, rng, base, text):
    """Deck i of mutation class `cls` from the cheap base deck `text`."""
    if cls.startswith('value_'):
        return value_case(cls, rng, base, text, i)
    if cls in ('group_char', 'text_outside', 'lone_sign', 'extreme_value', 'count_2_31'):
        return strict_case(cls, i, rng, base, text)

    if cls == 'delete_chars':
        groups = scan(text)
        n = 1 + rng.randrange(4)
        positions = set()
        while len(positions) < n:
            if rng.random() < 0.7 and groups:
                g = rng.choice(groups)
                positions.add(rng.randrange(g['start'], min(g['end'] + 1, len(text))))
            else:
                positions.add(rng.randrange(len(text)))
        removed = ''.join(text[p] for p in sorted(positions))
        mutated = ''.join(c for p, c in enumerate(text) if p not in positions)
        return Case(cls, base, 'delete_%d' % n, enc(mutated), 'any',
                    detail='deleted %r at %s' % (removed, sorted(positions)))

    if cls == 'group_misspelt':
        g = rng.choice(scan(text))
        old = text[g['start'] + 1:g['name_end']]
        new = typo(rng, old)
        mutated = text[:g['start'] + 1] + new + text[g['name_end']:]
        return Case(cls, base, 'typo', enc(mutated), 'error', new.lower(), None,
                    detail='&%s -> &%s' % (old, new))

    if cls == 'group_duplicated':
        g = rng.choice(scan(text))
        end = min(g['end'] + 1, len(text))
        block = text[g['start']:end]
        mutated = text[:end] + '\n' + block + text[end:]
        return Case(cls, base, 'repeat', enc(mutated), 'error', g['name'], None,
                    detail='&%s repeated' % g['name'])

    if cls == 'truncated':
        v = ['random', 'random', 'before_last_slash', 'random', 'empty'][i % 5]
        if v == 'empty':
            cut = 0
        elif v == 'before_last_slash':
            cut = mask(text).rfind('/')
        else:
            cut = rng.randrange(1, len(text))
            # a cut between two groups leaves a valid deck without the cheapened groups after
            # it (a work-precision study at its default 8 levels runs for minutes, correctly):
            # move such a cut into the next group, so the deck ends inside a group
            groups = scan(text)
            if not any(g['start'] < cut <= g['end'] for g in groups):
                later = [g['start'] for g in groups if g['start'] > cut]
                if later:
                    cut = min(later) + 2
        return Case(cls, base, v, enc(text[:cut]), 'error' if cut == 0 else 'any',
                    detail='cut at byte %d of %d' % (cut, len(text)))

    alt = (i + i // 18) % 2      # both variants on a base deck drawn twice
    if cls == 'line_crlf':
        if alt == 0:
            return Case(cls, base, 'crlf', enc(text.replace('\n', '\r\n')), 'ok',
                        detail='CRLF line ends')
        lines = text.split('\n')
        mixed = ''.join(line + ('\r\n' if k % 2 else '\n') for k, line in enumerate(lines[:-1]))
        return Case(cls, base, 'mixed', enc(mixed + lines[-1]), 'ok',
                    detail='every other line ends in CRLF')

    if cls == 'line_cr':
        return Case(cls, base, 'cr', enc(text.replace('\n', '\r')), 'ok',
                    detail='CR-only line ends')

    if cls == 'line_bom':
        if alt == 0:
            return Case(cls, base, 'bom_lf', b'\xef\xbb\xbf' + enc(text), 'ok',
                        detail='UTF-8 BOM, LF line ends')
        return Case(cls, base, 'bom_crlf', b'\xef\xbb\xbf' + enc(text.replace('\n', '\r\n')),
                    'ok', detail='UTF-8 BOM, CRLF line ends')

    if cls == 'long_line':
        v = ['comment', 'padded_value', 'long_title', 'long_output', 'long_list', 'one_line',
             'long_override'][i % 7]
        if v == 'comment':
            lines = text.split('\n')
            k = rng.randrange(len(lines))
            lines.insert(k, '! ' + 'x' * 100000)
            return Case(cls, base, v, enc('\n'.join(lines)), 'ok',
                        detail='100000-character comment line before line %d' % (k + 1))
        if v == 'padded_value':
            g, a = pick_assign(rng, text)
            eq = text.rfind('=', a['var_start'], a['val_start'])
            mutated = text[:eq + 1] + ' ' * 20000 + text[eq + 1:]
            return Case(cls, base, v, enc(mutated), 'ok', detail='&%s %s = <20000 blanks> %s'
                        % (g['name'], a['var'], short(text[a['val_start']:a['val_end']])))
        if v == 'long_title':
            title = ('fuzz title ' * 30)[:300]
            return Case(cls, base, v, enc(set_value(text, 'job', 'title', "'%s'" % title)),
                        'any', 'job', 'title', detail='&job title of 300 characters',
                        want_title=title)
        if v == 'long_output':
            prefix = 'long/' + ('d' * 60 + '/') * 4 + 'r' * 40
            return Case(cls, base, v, enc(set_value(text, 'job', 'output', "'%s'" % prefix)),
                        'any', 'job', 'output',
                        detail='&job output of %d characters' % len(prefix), want_output=prefix)
        if v == 'long_list':
            mutated = set_value(text, 'stops', 'node', ', '.join(['2'] * 100))
            return Case(cls, base, v, enc(mutated), 'error', 'stops', 'node',
                        detail='&stops node = 100 entries (at most 64)')
        if v == 'one_line':
            m = mask(text)
            kept = ''.join(c if m[p] != ' ' or c in ' \t' or c == '\n' else ' '
                           for p, c in enumerate(text))
            flat = ' '.join(kept.split())
            return Case(cls, base, v, enc(flat + '\n'), 'ok',
                        detail='whole deck on one line of %d characters' % len(flat))
        if v == 'long_override':
            override = '&job title = \'fuzz override\'' + ' ' * 5000 + ' /'
            return Case(cls, base, v, enc(text), 'ok', args=[override],
                        detail='override of %d characters (blank-padded)' % len(override))
    raise ValueError(cls)


def generate(seed, per_class):
    """Every fuzz deck, deterministically: the baseline decks, then per_class per class."""
    paths = sorted(p for p in os.listdir(os.path.join(ROOT, 'inputs')) if p.endswith('.nml'))
    bases = []
    for p in paths:
        with open(os.path.join(ROOT, 'inputs', p), encoding='utf-8') as f:
            bases.append((p, cheapen(f.read())))
    cases = [Case('baseline', p, 'cheap', enc(t), 'ok', detail='unmutated cheap deck')
             for p, t in bases]
    rng = random.Random(seed)
    for c, cls in enumerate(CLASSES):
        for i in range(per_class):
            name, text = bases[(i + c) % len(bases)]
            cases.append(make_case(cls, i, rng, name, text))
    for k, case in enumerate(cases):
        case.id = 'd%03d' % k
    return cases


# ------------------------------------------------------------------------------ running

BAD_TOKEN = re.compile(r'^[+-]?(nan|inf|infinity)(\(.*\))?$|^\*{3,}$', re.IGNORECASE)
BACKTRACE_RE = re.compile(r'ERROR STOP|Error termination|Backtrace|^#\d+ ', re.MULTILINE)
RUNTIME_RE = re.compile(r'^At line \d+ of file|Fortran runtime error|Program received signal|'
                        r'HDF5-DIAG|Fortran runtime warning|double free|corrupted|Segmentation',
                        re.MULTILINE)


def nonfinite_tokens(text, skip_comments):
    bad = []
    for line in text.splitlines():
        if skip_comments and line.lstrip().startswith('#'):
            continue
        for tok in line.replace(',', ' ').split():
            if BAD_TOKEN.match(tok.strip('()[];:')):
                bad.append(tok)
    return bad


def run_case(case, exe, top, timeout):
    cdir = os.path.join(top, case.id + '_' + case.cls)
    os.makedirs(cdir)
    deck = case.base
    with open(os.path.join(cdir, deck), 'wb') as f:
        f.write(case.data)
    env = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
    env.pop('GFORTRAN_ERROR_BACKTRACE', None)   # test the program's own default
    t0 = time.monotonic()
    timed_out = False
    try:
        # the address-space limit through the shell (preexec_fn is not safe with threads)
        p = subprocess.run(['/bin/sh', '-c', 'ulimit -v %d && exec "$@"' % (MEMORY_LIMIT >> 10),
                            'sh', exe, deck] + case.args, cwd=cdir, stdin=subprocess.DEVNULL,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout,
                           env=env)
        rc, out, err = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        timed_out = True
        rc, out, err = None, e.stdout or b'', e.stderr or b''
    elapsed = time.monotonic() - t0
    out = out.decode('utf-8', 'replace')
    err = err.decode('utf-8', 'replace')
    result = classify(case, cdir, deck, rc, out, err, timed_out)
    result['seconds'] = round(elapsed, 3)
    with open(os.path.join(cdir, 'stdout.txt'), 'w') as f:
        f.write(out)
    with open(os.path.join(cdir, 'stderr.txt'), 'w') as f:
        f.write(err)
    with open(os.path.join(cdir, 'case.json'), 'w') as f:
        json.dump(result, f, indent=1)
    return result


def files_in(cdir, deck):
    found = []
    for dirpath, _, names in os.walk(cdir):
        for n in names:
            rel = os.path.relpath(os.path.join(dirpath, n), cdir)
            if rel != deck:
                found.append(rel)
    return sorted(found)


def classify(case, cdir, deck, rc, out, err, timed_out):
    issues = []          # (issue, detail)
    files = files_in(cdir, deck)

    def add(issue, detail=''):
        issues.append((issue, detail))

    if timed_out:
        add('timeout')
    elif rc < 0:
        add('signal', str(-rc))
    m = RUNTIME_RE.search(err)
    if m:
        add('runtime_error', err[m.start():].splitlines()[0:2])
    if BACKTRACE_RE.search(err):
        add('backtrace')
    parts = [f for f in files if f.endswith('.part')]
    if parts:
        add('part_file_left', parts)

    if rc == 0:
        if case.expect == 'error':
            add('unexpected_ok', 'the mutation must be rejected')
        lines = out.splitlines()
        prefix = None
        for line in reversed(lines):
            if line.startswith('output: '):
                prefix = line[len('output: '):]
                break
        if prefix is None:
            add('missing_output', 'no "output: PREFIX" line on stdout')
        elif not os.path.isfile(os.path.join(cdir, prefix + '.h5')):
            add('missing_output', 'no %s.h5' % prefix)
        if case.want_output is not None and prefix != case.want_output:
            add('output_misplaced', 'asked %r, wrote %r' % (short(case.want_output, 300),
                                                              short(prefix or '', 300)))
        if case.want_title is not None and ('gapbeam: ' + case.want_title) not in lines:
            add('title_truncated', 'stdout does not show the title whole')
        bad = nonfinite_tokens('\n'.join(l for l in lines if not l.startswith('gapbeam: ')),
                               False)
        if bad:
            add('nonfinite_output', 'stdout: %s' % ' '.join(sorted(set(bad))[:5]))
        for f in files:
            if f.endswith(('.h5', '.checkpoint', '.part')):
                continue
            try:
                with open(os.path.join(cdir, f), encoding='utf-8', errors='replace') as fh:
                    bad = nonfinite_tokens(fh.read(), True)
            except OSError:
                continue
            if bad:
                add('nonfinite_output', '%s: %s' % (f, ' '.join(sorted(set(bad))[:5])))
    elif not timed_out and rc > 0:
        if case.expect == 'ok':
            add('unexpected_error', 'the mutation must run like the base deck')
        core = []
        for line in err.splitlines():
            if BACKTRACE_RE.search(line) or RUNTIME_RE.search(line):
                break
            if line.strip():
                core.append(line)
        leftover = [f for f in files if not f.endswith('.part')]
        if leftover:
            add('file_left_after_error', leftover[:4])
        if not any(i == 'runtime_error' for i, _ in issues):
            if rc != 1:
                add('bad_status', str(rc))
            if len(core) != 1:
                add('multi_line_error', '%d lines before the backtrace' % len(core))
            msg = core[0] if core else ''
            if not msg.startswith('error: '):
                add('no_error_prefix')
            if deck not in msg:
                add('deck_not_named')
            if case.group:
                if not re.search(r'&' + re.escape(case.group) + r'\b', msg, re.IGNORECASE):
                    add('group_not_named', '&' + case.group)
            elif not re.search(r'&[A-Za-z_]', msg):
                add('group_not_named', 'no &group')
            if case.var and not re.search(r'\b' + re.escape(case.var) + r'\b', msg,
                                          re.IGNORECASE):
                add('var_not_named', case.var)

    issues.sort(key=lambda x: ISSUE_ORDER.index(x[0]))
    if issues:
        outcome = issues[0][0]
    elif rc == 0:
        outcome = 'ok'
    else:
        outcome = 'clean_error'
    first_err = next((l for l in err.splitlines() if l.strip()), '')
    return {'id': case.id, 'class': case.cls, 'base': case.base, 'variant': case.variant,
            'detail': case.detail, 'expect': case.expect, 'group': case.group, 'var': case.var,
            'status': 'timeout' if timed_out else rc, 'outcome': outcome,
            'issues': [[i, d] for i, d in issues], 'stderr_first': first_err[:400],
            'args': [short(a, 80) for a in case.args]}


# ------------------------------------------------------------------------------ report


def table(rows, header):
    widths = [max(len(str(r[k])) for r in rows + [header]) for k in range(len(header))]
    fmt = '  '.join('%%-%ds' % w if k == 0 else '%%%ds' % w for k, w in enumerate(widths))
    print(fmt % tuple(header))
    for r in rows:
        print(fmt % tuple(r))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('exe', help='gapbeam executable')
    ap.add_argument('--seed', type=int, default=SEED)
    ap.add_argument('--per-class', type=int, default=24)
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--timeout', type=float, default=5.0, help='seconds per deck')
    ap.add_argument('--limit', type=float, default=60.0, help='seconds for the whole run')
    ap.add_argument('--only', default='', help='classes to run, comma separated')
    ap.add_argument('--keep', default='', help='keep the run directories under this folder')
    ap.add_argument('--json', default='', help='write every result to this file')
    ap.add_argument('--details', type=int, default=4, help='failing decks shown per class')
    ap.add_argument('--list', action='store_true', help='print the decks, run nothing')
    opts = ap.parse_args()

    cases = generate(opts.seed, opts.per_class)
    if opts.only:
        wanted = set(opts.only.split(','))
        cases = [c for c in cases if c.cls in wanted]
    if opts.list:
        for c in cases:
            print('%s  expect %-5s %s' % (c.describe(), c.expect, ' '.join(c.args)[:80]))
        print('%d decks' % len(cases))
        return 0

    exe = os.path.abspath(opts.exe)
    if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        print("FAIL  fuzz: GAPBEAM_EXE '%s' is not an executable file" % opts.exe)
        return 1
    if opts.keep:
        os.makedirs(opts.keep, exist_ok=True)
        top = tempfile.mkdtemp(prefix='fuzz-', dir=opts.keep)
    else:
        top = tempfile.mkdtemp(prefix='gapbeam-fuzz-')
    print('fuzz_decks.py: %s, seed %d, %d decks, %d workers, %g s per deck'
          % (exe, opts.seed, len(cases), opts.jobs, opts.timeout))
    t0 = time.monotonic()
    try:
        with ThreadPoolExecutor(max_workers=opts.jobs) as pool:
            results = list(pool.map(lambda c: run_case(c, exe, top, opts.timeout), cases))
    finally:
        if not opts.keep:
            shutil.rmtree(top, ignore_errors=True)
    wall = time.monotonic() - t0

    n_fail = 0
    classes = ['baseline'] + [c for c in CLASSES]
    for cls in classes:
        rs = [r for r in results if r['class'] == cls]
        if not rs:
            continue
        bad = [r for r in rs if r['outcome'] not in ('ok', 'clean_error')]
        good = 'ok %d, clean_error %d' % (sum(r['outcome'] == 'ok' for r in rs),
                                          sum(r['outcome'] == 'clean_error' for r in rs))
        if not bad:
            print('PASS  fuzz: %s: %d decks (%s)' % (cls, len(rs), good))
            continue
        n_fail += 1
        counts = {}
        for r in bad:
            counts[r['outcome']] = counts.get(r['outcome'], 0) + 1
        print('FAIL  fuzz: %s: %d of %d decks failed (%s; %s)' % (
            cls, len(bad), len(rs), ', '.join('%s %d' % kv for kv in sorted(counts.items())),
            good))
        for r in bad[:opts.details]:
            print('      %s %s [%s] %s -> %s; stderr: %s' % (
                r['id'], r['base'], r['variant'], r['detail'],
                '; '.join(i if not d else '%s (%s)' % (i, d) for i, d in r['issues']),
                short(r['stderr_first'], 200)))
        if len(bad) > opts.details:
            print('      ... and %d more' % (len(bad) - opts.details))
    if wall <= opts.limit:
        print('PASS  fuzz: whole run %.1f s (limit %g s)' % (wall, opts.limit))
    else:
        n_fail += 1
        print('FAIL  fuzz: whole run %.1f s (limit %g s)' % (wall, opts.limit))

    outcomes = ['ok', 'clean_error'] + ISSUE_ORDER
    present = [o for o in outcomes if any(r['outcome'] == o for r in results)]
    rows = []
    for cls in classes:
        rs = [r for r in results if r['class'] == cls]
        if rs:
            rows.append([cls] + [sum(r['outcome'] == o for r in rs) for o in present]
                        + [len(rs)])
    rows.append(['total'] + [sum(r['outcome'] == o for r in results) for o in present]
                + [len(results)])
    print('\nDecks by outcome (a failing deck counted under its first issue):')
    table(rows, ['class'] + present + ['decks'])
    issue_counts = {}
    for r in results:
        for i, _ in r['issues']:
            issue_counts[i] = issue_counts.get(i, 0) + 1
    if issue_counts:
        print('\nIssues (a deck can have several):')
        table([[i, issue_counts[i]] for i in ISSUE_ORDER if i in issue_counts],
              ['issue', 'decks'])
    slow = sorted(results, key=lambda r: -r['seconds'])[:3]
    print('\nslowest decks: ' + ', '.join('%s %s %.2f s' % (r['id'], r['base'], r['seconds'])
                                          for r in slow))
    if opts.json:
        with open(opts.json, 'w') as f:
            json.dump({'seed': opts.seed, 'wall_s': round(wall, 2), 'results': results}, f,
                      indent=1)
    if opts.keep:
        print('run directories kept in %s' % top)
    print('fuzz_decks.py: %d decks in %.1f s, %d checks failed' % (len(results), wall, n_fail))
    return 1 if n_fail else 0


if __name__ == '__main__':
    sys.exit(main())
