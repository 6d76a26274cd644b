"""A small parser of UDUNITS-2 unit strings, for the tests of gapbeam's `units` attributes.

It accepts the product-power form of the UDUNITS-2 grammar (unidata udunits2lib, "Unit Syntax"):

    unit    := product
    product := power { sep power }          sep: blanks, '.', '*' or '/'
    power   := basic [ exponent ]           exponent: an integer, written 2, -1, ^2, ^-1 or **-1
    basic   := symbol | number | '(' product ')'

with the symbols of the UDUNITS-2 database that gapbeam uses (SI base and derived units, with an
optional SI prefix) and pure numbers ('1' for a dimensionless value). Exponents are integers, as
in UDUNITS-2: 'kg-1/2' is NOT a unit string (the parser reads it as kg^-1 divided by the number
2, which :func:`parse` refuses, since a number after '/' makes no sense in gapbeam's units).

``parse(text)`` returns the dimension exponents as a dict, e.g. parse('N m-1') ->
{'kg': 1, 's': -2}, and raises ``ValueError`` with the reason for anything else.
"""

import re

# symbol -> dimensions in SI base units (rad and sr are dimensionless in UDUNITS-2)
_UNITS = {
    "m": {"m": 1},
    "g": {"kg": 1},          # with a prefix: kg
    "s": {"s": 1},
    "A": {"A": 1},
    "K": {"K": 1},
    "mol": {"mol": 1},
    "cd": {"cd": 1},
    "rad": {},
    "sr": {},
    "Hz": {"s": -1},
    "N": {"kg": 1, "m": 1, "s": -2},
    "Pa": {"kg": 1, "m": -1, "s": -2},
    "J": {"kg": 1, "m": 2, "s": -2},
    "W": {"kg": 1, "m": 2, "s": -3},
    "degree": {},
}
_PREFIXES = {"k": 1e3, "m": 1e-3, "u": 1e-6, "µ": 1e-6, "c": 1e-2, "M": 1e6, "G": 1e9,
             "n": 1e-9}

_TOKEN = re.compile(r"\s*(?:(\()|(\))|(\*\*|\^)|([*./])|([A-Za-zµ]+)|([+-]?\d+(?:\.\d+)?(?:[eE][+-]?\d+)?))")


def _tokens(text):
    pos, out = 0, []
    text = text.rstrip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise ValueError("unexpected character {!r} at {}".format(text[pos], pos))
        kind = next(i for i in range(1, 7) if m.group(i) is not None)
        value = m.group(kind)
        # blanks between two operands are a multiplication
        if out and kind in (1, 5, 6) and out[-1][0] in (2, 5, 6) and text[pos].isspace():
            out.append((4, " "))
        out.append((kind, value))
        pos = m.end()
    return out


def _symbol(name):
    if name in _UNITS:
        return dict(_UNITS[name])
    for p in _PREFIXES:
        if name.startswith(p) and name[len(p):] in _UNITS:
            return dict(_UNITS[name[len(p):]])
    raise ValueError("unknown unit symbol {!r}".format(name))


def _add(a, b, k=1):
    out = dict(a)
    for d, e in b.items():
        out[d] = out.get(d, 0) + k * e
        if out[d] == 0:
            del out[d]
    return out


def parse(text):
    """Dimensions of a UDUNITS-2 unit string (dict base unit -> integer exponent)."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError("empty unit string")
    toks = _tokens(text)
    pos = 0

    def peek():
        return toks[pos] if pos < len(toks) else (0, None)

    def basic():
        nonlocal pos
        kind, value = peek()
        if kind == 1:
            pos += 1
            dims = product()
            if peek()[0] != 2:
                raise ValueError("')' missing")
            pos += 1
            return dims, False
        if kind == 5:
            pos += 1
            return _symbol(value), False
        if kind == 6:
            pos += 1
            if float(value) == 0:
                raise ValueError("a zero scale")
            return {}, True
        raise ValueError("expected a unit, a number or '(' at token {}".format(pos + 1))

    def power():
        nonlocal pos
        dims, is_number = basic()
        kind, value = peek()
        if kind == 3:
            pos += 1
            kind, value = peek()
            if kind != 6 or not re.fullmatch(r"[+-]?\d+", value):
                raise ValueError("an exponent must be an integer")
            pos += 1
            return _add({}, dims, int(value)), is_number
        if kind == 6 and not is_number:
            if not re.fullmatch(r"[+-]?\d+", value):
                raise ValueError("an exponent must be an integer, got {!r}".format(value))
            pos += 1
            return _add({}, dims, int(value)), is_number
        return dims, is_number

    def product():
        nonlocal pos
        dims, _ = power()
        while peek()[0] == 4:
            op = peek()[1]
            pos += 1
            d, is_number = power()
            if op == "/" and is_number:
                raise ValueError("a number after '/' (a fractional exponent such as kg-1/2 "
                                 "is not UDUNITS-2)")
            dims = _add(dims, d, -1 if op == "/" else 1)
        return dims

    dims = product()
    if pos != len(toks):
        raise ValueError("trailing text from token {}".format(pos + 1))
    return dims
