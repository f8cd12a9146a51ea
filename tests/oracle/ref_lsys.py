#!/usr/bin/env python3
"""ref_lsys.py -- an independent reference deriver for Sylva .syl models.

Written separately from the C compiler, straight from docs/language.md, to produce
expected ("golden") derived strings.  It covers the DETERMINISTIC subset of the language:

  * single-letter / single-digit modules, declared multi-letter modules (`module Fl, Fr`,
    matched greedily inside a word), turtle symbols, `@X` / `?X` / `~name` special modules;
  * parametric modules with C-like expressions (`^` power, right-assoc, tighter than unary
    minus; `%` is fmod; `&& || !`, comparisons, `c ? a : b`; trig in degrees), `const`, `param`
    (overridable with --set), `fn name(a, b) = expr`;
  * conditions; rules tried in file order, first applicable wins, none => identity;
  * branch-aware left/right context with `ignore` (or `consider`) per docs/language.md §9.5-§9.6:
    the left context walks back along the path to the root, skipping complete bracketed
    branches and ignored symbols; the right context skips branches it does not name, may
    descend into a branch written in it (`B > [C]D`: of the side branches that start there,
    the first whose beginning matches), and after the named part of such a branch skips the
    rest of that branch.
  * new contexts (lpfg's `<<` and `>>`, docs/language.md "New contexts"): `L << A` matches L,
    as a left context would, in the string being produced (the successors already written in
    this step); `A >> R` matches R, as a right context would, in the new string to the right
    when the step is derived backward (last module first).  `direction forward|backward
    [when EXPR]` (EXPR over `step`, 1 for the first step) says which way each step goes.  A
    rule with `<<` takes part only in forward steps, one with `>>` only in backward ones.
    Implemented the slow and obvious way: each module's new context is matched by the old
    context code against the whole partial output, rebuilt for every module.

  * tables (docs/language.md, Tables): rules in `group NAME { }` take part only in the steps
    where a `use NAME when EXPR` line holds (EXPR reads `step`, 1 for the first); for a
    module, the rules of the used groups come first, then the ungrouped ones, in file order;
  * the cut: when a step ends, every `%` and the rest of its branch leave the string, up to
    the `]` that closes the branch (kept); a `%` outside any branch ends the string.  The
    axiom (step 0) is printed as written.

Not supported (the script says so and exits with status 3): stochastic rules (weights),
random functions, decompose blocks, curves.  `interpret { }` blocks (and groups inside them)
are read and ignored (they never change the derived string).

Output (canonical form): modules concatenated without spaces; a module with parameters is
printed as NAME(v1,v2,...) with every value formatted by C's %g, e.g. F(1)[+(25.7)F(0.5)]X.
A module that was written with no parentheses is printed bare.

Usage:
  ref_lsys.py FILE.syl [-n STEPS] [--model NAME] [--set NAME=VALUE ...] [--counts]
              [--all-steps]
    -n STEPS     derivation length (default: the model's `derive`, else 0)
    --model      which model of the file (default: the first)
    --counts     print the number of modules after each step 0..n instead of the string
    --all-steps  print the string after each step 0..n, one per line
"""

import argparse
import math
import re
import sys

# --------------------------------------------------------------------------------------------
# Errors


class SylError(Exception):
    pass


class Unsupported(Exception):
    pass


# --------------------------------------------------------------------------------------------
# Expressions: tokenizer + precedence-climbing parser producing Python closures.

_EXPR_TOKEN = re.compile(
    r"\s*(?:(?P<num>(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?)"
    r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>&&|\|\||==|!=|<=|>=|[-+*/%^<>!?:(),]))"
)


def _tokenize_expr(text):
    toks = []
    pos = 0
    text = text.rstrip()
    while pos < len(text):
        m = _EXPR_TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise SylError("bad expression near %r in %r" % (text[pos:], text))
        pos = m.end()
        if m.group("num") is not None:
            toks.append(("num", float(m.group("num"))))
        elif m.group("name") is not None:
            toks.append(("name", m.group("name")))
        else:
            toks.append(("op", m.group("op")))
    toks.append(("end", None))
    return toks


def _deg_trig(f):
    return lambda x: f(math.radians(x))


def _inv_trig(f):
    return lambda x: math.degrees(f(x))


def _clamp(x, lo, hi):
    return lo if x < lo else hi if x > hi else x


def _pow(a, b):
    try:
        return math.pow(a, b)
    except (OverflowError, ValueError):
        return float("nan")


def _div(a, b):
    if b == 0.0:
        if a == 0.0 or a != a:
            return float("nan")
        return math.copysign(float("inf"), a) * math.copysign(1.0, b)
    return a / b


def _fmod(a, b):
    if b == 0.0:
        return float("nan")
    return math.fmod(a, b)


BUILTINS = {
    "sin": _deg_trig(math.sin),
    "cos": _deg_trig(math.cos),
    "tan": _deg_trig(math.tan),
    "asin": _inv_trig(math.asin),
    "acos": _inv_trig(math.acos),
    "atan": _inv_trig(math.atan),
    "atan2": lambda y, x: math.degrees(math.atan2(y, x)),
    "sqrt": math.sqrt,
    "exp": math.exp,
    "log": math.log,
    "pow": _pow,
    "abs": abs,
    "floor": math.floor,
    "ceil": math.ceil,
    "min": min,
    "max": max,
    "clamp": _clamp,
    "rad": math.radians,
    "deg": math.degrees,
}
RANDOM_FUNCS = ("uniform", "normal", "random", "rand")

# binary operators: precedence (higher binds tighter)
_BINPREC = {
    "||": 1,
    "&&": 2,
    "==": 3, "!=": 3,
    "<": 4, ">": 4, "<=": 4, ">=": 4,
    "+": 5, "-": 5,
    "*": 6, "/": 6, "%": 6,
}


def _b(x):
    return 1.0 if x else 0.0


class _ExprParser:
    """Builds a closure f(env, funcs) -> float."""

    def __init__(self, text):
        self.text = text
        self.toks = _tokenize_expr(text)
        self.i = 0

    def peek(self):
        return self.toks[self.i]

    def take(self):
        t = self.toks[self.i]
        self.i += 1
        return t

    def expect(self, op):
        t = self.take()
        if t != ("op", op):
            raise SylError("expected %r in expression %r" % (op, self.text))

    def parse(self):
        e = self.ternary()
        if self.peek()[0] != "end":
            raise SylError("trailing text in expression %r" % self.text)
        return e

    def ternary(self):
        c = self.binary(1)
        if self.peek() == ("op", "?"):
            self.take()
            a = self.ternary()
            self.expect(":")
            b = self.ternary()
            return lambda env, fn, c=c, a=a, b=b: a(env, fn) if c(env, fn) != 0.0 else b(env, fn)
        return c

    def binary(self, minprec):
        left = self.unary()
        while True:
            t = self.peek()
            if t[0] != "op" or t[1] not in _BINPREC or _BINPREC[t[1]] < minprec:
                return left
            op = t[1]
            self.take()
            right = self.binary(_BINPREC[op] + 1)
            left = self._mkbin(op, left, right)

    @staticmethod
    def _mkbin(op, l, r):
        if op == "+":
            return lambda e, f: l(e, f) + r(e, f)
        if op == "-":
            return lambda e, f: l(e, f) - r(e, f)
        if op == "*":
            return lambda e, f: l(e, f) * r(e, f)
        if op == "/":
            return lambda e, f: _div(l(e, f), r(e, f))
        if op == "%":
            return lambda e, f: _fmod(l(e, f), r(e, f))
        if op == "<":
            return lambda e, f: _b(l(e, f) < r(e, f))
        if op == ">":
            return lambda e, f: _b(l(e, f) > r(e, f))
        if op == "<=":
            return lambda e, f: _b(l(e, f) <= r(e, f))
        if op == ">=":
            return lambda e, f: _b(l(e, f) >= r(e, f))
        if op == "==":
            return lambda e, f: _b(l(e, f) == r(e, f))
        if op == "!=":
            return lambda e, f: _b(l(e, f) != r(e, f))
        if op == "&&":
            return lambda e, f: _b(l(e, f) != 0.0 and r(e, f) != 0.0)
        if op == "||":
            return lambda e, f: _b(l(e, f) != 0.0 or r(e, f) != 0.0)
        raise SylError("unknown operator " + op)

    def unary(self):
        t = self.peek()
        if t == ("op", "-"):
            self.take()
            a = self.unary()
            return lambda e, f: -a(e, f)
        if t == ("op", "+"):
            self.take()
            return self.unary()
        if t == ("op", "!"):
            self.take()
            a = self.unary()
            return lambda e, f: _b(a(e, f) == 0.0)
        return self.power()

    def power(self):
        base = self.primary()
        if self.peek() == ("op", "^"):
            self.take()
            expo = self.unary()  # right-associative; allows 2^-1
            return lambda e, f: _pow(base(e, f), expo(e, f))
        return base

    def primary(self):
        t = self.take()
        if t[0] == "num":
            v = t[1]
            return lambda e, f: v
        if t[0] == "name":
            name = t[1]
            if self.peek() == ("op", "("):
                self.take()
                args = []
                if self.peek() != ("op", ")"):
                    args.append(self.ternary())
                    while self.peek() == ("op", ","):
                        self.take()
                        args.append(self.ternary())
                self.expect(")")
                if name in RANDOM_FUNCS:
                    raise Unsupported("random function %s()" % name)
                return lambda e, f, name=name, args=args: f[name](*[a(e, f) for a in args])

            def var(e, f, name=name):
                try:
                    return e[name]
                except KeyError:
                    raise SylError("unknown name %r" % name)
            return var
        if t == ("op", "("):
            e = self.ternary()
            self.expect(")")
            return e
        raise SylError("unexpected %r in expression %r" % (t[1], self.text))


def compile_expr(text):
    return _ExprParser(text).parse()


# --------------------------------------------------------------------------------------------
# Module strings

SINGLE_SYMBOLS = set("+-&^\\/|[]!'$%.;,~{}*")


class Template:
    """A module as written in an axiom / successor / context: name, list of expression
    texts (None when written without parentheses)."""

    __slots__ = ("name", "args")

    def __init__(self, name, args):
        self.name = name
        self.args = args

    def arity(self):
        return 0 if self.args is None else len(self.args)

    def __repr__(self):
        return self.name + ("" if self.args is None else "(" + ",".join(self.args) + ")")


def _split_args(text):
    """'a, f(b,c), d' -> ['a', 'f(b,c)', 'd'] (top-level commas)."""
    parts, depth, cur = [], 0, []
    for ch in text:
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append("".join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    last = "".join(cur).strip()
    if parts or last:
        parts.append(last)
    return parts


def split_word(word, declared):
    """Split a maximal [A-Za-z0-9_] run into modules: declared names greedily (longest first),
    otherwise every character is its own module."""
    out = []
    i = 0
    names = sorted(declared, key=len, reverse=True)
    while i < len(word):
        for d in names:
            if word.startswith(d, i):
                out.append(d)
                i += len(d)
                break
        else:
            out.append(word[i])
            i += 1
    return out


_SPECIAL_AT = re.compile(r"@(?:[A-Z][a-z]?|[a-z])")
_SPECIAL_Q = re.compile(r"\?[A-Z][a-z]?")
_SPECIAL_TILDE = re.compile(r"~[A-Za-z_][A-Za-z0-9_]*")
_WORD = re.compile(r"[A-Za-z0-9_]+")


def parse_modules(text, declared):
    """Parse a module sequence into a list of Templates."""
    mods = []
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        if ch.isspace():
            i += 1
            continue
        names = None
        m = None
        if ch == "@":
            m = _SPECIAL_AT.match(text, i)
        elif ch == "?":
            m = _SPECIAL_Q.match(text, i)
        elif ch == "~":
            m = _SPECIAL_TILDE.match(text, i)
        if m:
            names = [m.group(0)]
            i = m.end()
        elif _WORD.match(text, i):
            m = _WORD.match(text, i)
            names = split_word(m.group(0), declared)
            i = m.end()
        elif ch in SINGLE_SYMBOLS:
            names = [ch]
            i += 1
        else:
            raise SylError("unexpected character %r in %r" % (ch, text))
        # optional parameter list, attached to the last module of the word
        j = i
        while j < n and text[j] in " \t":
            j += 1
        args = None
        if j < n and text[j] == "(":
            depth, k = 0, j
            while k < n:
                if text[k] == "(":
                    depth += 1
                elif text[k] == ")":
                    depth -= 1
                    if depth == 0:
                        break
                k += 1
            if k >= n:
                raise SylError("unbalanced parentheses in %r" % text)
            args = _split_args(text[j + 1:k])
            i = k + 1
        for nm in names[:-1]:
            mods.append(Template(nm, None))
        mods.append(Template(names[-1], args))
    return mods


# --------------------------------------------------------------------------------------------
# Models

# (the turtle's and the mesher's settings are read and ignored: they do not change a derivation)
SETTINGS = ("derive", "angle", "step", "width", "seed", "widthfactor", "tropism", "colour", "direction", "lod")


class Rule:
    def __init__(self, left, pred, right, cond, succ, weight, text, block, group=None):
        self.left = left          # list of Templates (formal params = names)
        self.pred = pred          # Template
        self.right = right        # list of Templates
        self.cond = cond          # closure or None
        self.succ = succ          # list of (name, [closures] or None)
        self.weight = weight      # text or None
        self.text = text
        self.block = block
        self.group = group        # name of its group, or None
        self.newleft = []         # `<<`: matched in the string being produced (forward steps)
        self.newright = []        # `>>`: matched in the new string to the right (backward steps)


class Model:
    def __init__(self, name):
        self.name = name
        self.settings = {}
        self.consts = []          # (name, expr text, kind) in order
        self.fns = []             # (name, [params], expr text)
        self.declared = []
        self.ignore = None
        self.consider = None
        self.axiom_text = None
        self.rule_lines = []      # (text, block, group)
        self.uses = []            # (group, condition text or None)


def _strip_comments(src):
    src = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), src, flags=re.S)
    out = []
    for line in src.split("\n"):
        k = line.find("#")
        if k >= 0:
            line = line[:k]
        out.append(line)
    return out


def _logical_lines(lines):
    """Join physical lines while parentheses are open (as the C lexer does)."""
    buf, depth = [], 0
    for line in lines:
        buf.append(line)
        depth += line.count("(") - line.count(")")
        if depth <= 0:
            yield " ".join(buf).strip()
            buf, depth = [], 0
    if buf:
        yield " ".join(buf).strip()


def parse_file(src):
    models = []
    cur = None
    blocks = []                   # open blocks: "interpret", "decompose" or ("group", NAME)
    for line in _logical_lines(_strip_comments(src)):
        block = next((b for b in blocks if isinstance(b, str)), None)
        group = next((b[1] for b in blocks if isinstance(b, tuple)), None)
        if not line:
            continue
        if cur is None:
            m = re.match(r"lsystem\s+([A-Za-z_][A-Za-z0-9_]*)\s*\{$", line)
            if m:
                cur = Model(m.group(1))
                models.append(cur)
                continue
            if line.startswith(("const", "param", "fn", "curve", "module")):
                raise Unsupported("file-level declarations")
            if line.startswith("scene"):
                raise Unsupported("scene blocks")
            raise SylError("unexpected top-level line %r" % line)
        if line == "}":
            if blocks:
                blocks.pop()
            else:
                cur = None
            continue
        m = re.match(r"(interpret|decompose)\s*\{$", line)
        if m:
            if m.group(1) != "interpret":
                raise Unsupported("%s blocks" % m.group(1))
            blocks.append(m.group(1))
            continue
        m = re.match(r"group\s+(\w+)\s*\{$", line)
        if m:
            blocks.append(("group", m.group(1)))
            continue
        m = re.match(r"use\s+(\w+)(?:\s+when\s+(.*))?$", line)
        if m and "->" not in line:
            cur.uses.append((m.group(1), m.group(2)))
            continue
        word = line.split(None, 1)[0]
        rest = line[len(word):].strip()
        if word in SETTINGS:
            cur.settings[word] = rest
        elif word in ("const", "param"):
            for part in _split_args(rest):
                name, _, expr = part.partition("=")
                cur.consts.append((name.strip(), expr.strip(), word))
        elif word == "fn":
            m = re.match(r"fn\s+(\w+)\s*\(([^)]*)\)\s*=\s*(.*)$", line)
            if not m:
                raise SylError("bad fn line %r" % line)
            params = [p.strip() for p in m.group(2).split(",") if p.strip()]
            cur.fns.append((m.group(1), params, m.group(3)))
        elif word == "curve":
            raise Unsupported("curves")
        elif word == "module":
            for part in _split_args(rest):
                cur.declared.append(part.split("(")[0].strip())
        elif word == "ignore":
            cur.ignore = rest
        elif word == "consider":
            cur.consider = rest
        elif word == "axiom":
            cur.axiom_text = rest
        else:
            cur.rule_lines.append((line, block or "produce", group))
    if cur is not None:
        raise SylError("model %s not closed" % cur.name)
    return models


_ARROW = re.compile(r"-->|->|\u2192")


def _find_top(text, chars):
    """Index of the first char of `chars` at parenthesis depth 0, or -1."""
    depth = 0
    for k, ch in enumerate(text):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif depth == 0 and ch in chars:
            return k
    return -1


def parse_rule(line, block, declared):
    # the arrow: first '->', '-->' or '→' outside parentheses
    depth = 0
    am = None
    for m in _ARROW.finditer(line):
        if line[:m.start()].count("(") == line[:m.start()].count(")"):
            am = m
            break
    if am is None:
        raise SylError("no arrow in rule %r" % line)
    lhs, rhs = line[:am.start()].strip(), line[am.end():].strip()
    cond = None
    k = _find_top(lhs, ":")
    if k >= 0:
        cond = lhs[k + 1:].strip()
        lhs = lhs[:k].strip()
    weight = None
    k = _find_top(rhs, ":")
    if k >= 0:
        weight = rhs[k + 1:].strip()
        rhs = rhs[:k].strip()
    left, right = [], []
    newleft, newright = [], []
    k = lhs.find("<<")
    if k >= 0:
        newleft = parse_modules(lhs[:k], declared)
        lhs = lhs[k + 2:]
    k = lhs.find(">>")
    if k >= 0:
        newright = parse_modules(lhs[k + 2:], declared)
        lhs = lhs[:k]
    if (newleft and _find_top(lhs, "<") >= 0) or (newright and _find_top(lhs, ">") >= 0):
        raise SylError("old and new context on one side in %r" % line)
    if newleft and newright:
        raise SylError("both << and >> in %r" % line)
    k = _find_top(lhs, "<")
    if k >= 0:
        left = parse_modules(lhs[:k], declared)
        lhs = lhs[k + 1:]
    k = _find_top(lhs, ">")
    if k >= 0:
        right = parse_modules(lhs[k + 1:], declared)
        lhs = lhs[:k]
    pred = parse_modules(lhs, declared)
    if len(pred) != 1:
        raise SylError("predecessor must be one module in %r" % line)
    pred = pred[0]
    if any(t.name in "[]" for t in left):
        raise Unsupported("brackets in a left context")
    if left and left[0].name == "*" and len(left) == 1:
        left = []
    if right and right[0].name == "*" and len(right) == 1:
        right = []
    for t in [pred] + left + right:
        for a in t.args or []:
            if not re.match(r"^[A-Za-z_][A-Za-z0-9_]*$", a):
                raise SylError("formal parameter %r is not a name in %r" % (a, line))
    if rhs == "*":
        rhs = ""
    succ = [(t.name, None if t.args is None else [compile_expr(a) for a in t.args])
            for t in parse_modules(rhs, declared)]
    r = Rule(left, pred, right, compile_expr(cond) if cond else None, succ, weight, line, block)
    if any(t.name in "[]" for t in newleft):
        raise SylError("brackets in a new left context")
    r.newleft, r.newright = newleft, newright
    return r


# --------------------------------------------------------------------------------------------
# Derivation

class LSystem:
    def __init__(self, model, overrides=None):
        self.model = model
        self.funcs = dict(BUILTINS)
        env = {}
        overrides = dict(overrides or {})
        for name, expr, kind in model.consts:
            if kind == "param" and name in overrides:
                env[name] = float(overrides.pop(name))
            else:
                env[name] = compile_expr(expr)(env, self.funcs)
        if overrides:
            raise SylError("--set of unknown param(s): %s" % ", ".join(overrides))
        self.consts = env
        for name, params, expr in model.fns:
            self.funcs[name] = self._mkfn(params, compile_expr(expr))
        declared = model.declared
        self.rules = []
        for t, b, g in model.rule_lines:
            r = parse_rule(t, b, declared)
            r.group = g
            self.rules.append(r)
        groups = {g for _, _, g in model.rule_lines if g}
        for g, _ in model.uses:
            if g not in groups:
                raise SylError("use of unknown group %r" % g)
        self.uses = [(g, compile_expr(c) if c else None) for g, c in model.uses]
        self.rules = [r for r in self.rules if r.block == "produce"]
        if any(r.weight is not None for r in self.rules):
            raise Unsupported("stochastic (weighted) rules")
        self.by_pred = {}
        for r in self.rules:
            self.by_pred.setdefault((r.pred.name, r.pred.arity()), []).append(r)
        ign = set()
        if model.ignore:
            ign = {t.name for t in parse_modules(model.ignore, declared)}
        self.ignore = ign
        self.consider = None
        if model.consider:
            self.consider = {t.name for t in parse_modules(model.consider, declared)}
        if model.axiom_text is None:
            raise SylError("model %s has no axiom" % model.name)
        self.axiom = [(t.name, None if t.args is None else
                       tuple(compile_expr(a)(env, self.funcs) for a in t.args))
                      for t in parse_modules(model.axiom_text, declared)]
        d = model.settings.get("derive")
        self.derive = int(compile_expr(d)(env, self.funcs)) if d else 0
        # direction D [when EXPR]: D on the steps where EXPR holds (always without `when`)
        self.dir_backward, self.dir_when = False, None
        dtext = model.settings.get("direction")
        if dtext:
            word, _, rest = dtext.partition(" ")
            if word not in ("forward", "backward"):
                raise SylError("direction %r" % dtext)
            self.dir_backward = word == "backward"
            rest = rest.strip()
            if rest:
                if not rest.startswith("when"):
                    raise SylError("direction %r" % dtext)
                self.dir_when = compile_expr(rest[4:].strip())

    def backward(self, k):
        """Whether step k (1 for the first) is derived backward."""
        if self.dir_when is None:
            return self.dir_backward
        if k is None:
            raise Unsupported("direction ... when, without a step number")
        env = dict(self.consts)
        env["step"] = float(k)
        return self.dir_backward if self.dir_when(env, self.funcs) != 0.0 else not self.dir_backward

    def _mkfn(self, params, body):
        consts = self.consts
        funcs = self.funcs

        def f(*args):
            if len(args) != len(params):
                raise SylError("wrong number of arguments")
            e = dict(consts)
            e.update(zip(params, args))
            return body(e, funcs)
        return f

    # -- context helpers ---------------------------------------------------------------------
    def _skipped(self, name):
        if self.consider is not None:
            return name not in self.consider
        return name in self.ignore

    @staticmethod
    def _bind(tmpl, mod, env):
        """Match template (formal params) against module; bind into env. False if no match."""
        name, vals = mod
        if tmpl.name != name:
            return False
        if tmpl.arity() != (0 if vals is None else len(vals)):
            return False
        if tmpl.args:
            for p, v in zip(tmpl.args, vals):
                env[p] = v
        return True

    def _left(self, ctx, s, match, i, env):
        j = i - 1
        k = len(ctx) - 1
        while k >= 0:
            if j < 0:
                return False
            name = s[j][0]
            if name == "]":
                j = match[j] - 1          # skip a complete branch
                continue
            if name == "[":
                j -= 1                    # leave the branch: continue on the parent axis
                continue
            if self._skipped(name):
                j -= 1
                continue
            if not self._bind(ctx[k], s[j], env):
                return False
            k -= 1
            j -= 1
        return True

    def _right(self, ctx, s, match, i, env):
        return self._right_seq(ctx, 0, len(ctx), s, match, i + 1, env)

    @staticmethod
    def _ctx_close(ctx, k):
        """Index of the "]" that closes the "[" at ctx[k]."""
        depth = 0
        for m in range(k, len(ctx)):
            if ctx[m].name == "[":
                depth += 1
            elif ctx[m].name == "]":
                depth -= 1
                if depth == 0:
                    return m
        raise SylError("unbalanced '[' in a right context")

    def _right_seq(self, ctx, k, end, s, match, j, env):
        """Match ctx[k:end] from string position j on, inside the current branch."""
        n = len(s)
        while k < end:
            c = ctx[k]
            if c.name == "[":
                # a branch named in the context: the side branches that start here are tried
                # in turn; the first whose beginning matches the part inside is taken, the
                # rest of it is skipped, and matching goes on after it
                close = self._ctx_close(ctx, k)
                while j < n and s[j][0] not in "[]" and self._skipped(s[j][0]):
                    j += 1
                while j < n and s[j][0] == "[":
                    trial = dict(env)
                    if self._right_seq(ctx, k + 1, close, s, match, j + 1, trial):
                        env.update(trial)
                        break
                    j = match[j] + 1
                    while j < n and s[j][0] not in "[]" and self._skipped(s[j][0]):
                        j += 1
                else:
                    return False
                j = match[j] + 1
                k = close + 1
                continue
            while True:
                if j >= n:
                    return False
                name = s[j][0]
                if name == "[":
                    j = match[j] + 1      # a branch the context does not name: skip it
                    continue
                if name == "]":
                    return False          # end of the branch: nothing more to the right
                if self._skipped(name):
                    j += 1
                    continue
                break
            if not self._bind(c, s[j], env):
                return False
            j += 1
            k += 1
        return True

    @staticmethod
    def _brackets(s):
        match = [0] * len(s)
        stack = []
        for k, (name, _) in enumerate(s):
            if name == "[":
                stack.append(k)
            elif name == "]":
                if not stack:
                    raise SylError("unbalanced ']' in string")
                o = stack.pop()
                match[o] = k
                match[k] = o
        if stack:
            raise SylError("unbalanced '[' in string")
        return match

    def active_groups(self, k):
        env = dict(self.consts)
        env["step"] = float(k)
        return {g for g, c in self.uses if c is None or c(env, self.funcs) != 0.0}

    @staticmethod
    def cut(s):
        """Each '%' and the rest of its branch leave the string; the closing ']' stays."""
        if all(m[0] != "%" for m in s):
            return s  # nothing to cut (most strings; step's own fresh list)
        out, i = [], 0
        while i < len(s):
            if s[i][0] != "%":
                out.append(s[i])
                i += 1
                continue
            depth = 0
            while i < len(s):
                if s[i][0] == "[":
                    depth += 1
                elif s[i][0] == "]":
                    if depth == 0:
                        break
                    depth -= 1
                i += 1
        return out

    @staticmethod
    def _partial_brackets(s):
        """Bracket pairs of a piece of a string: a bracket whose partner is outside has none."""
        match = [None] * len(s)
        stack = []
        for k, (name, _) in enumerate(s):
            if name == "[":
                stack.append(k)
            elif name == "]" and stack:
                o = stack.pop()
                match[o] = k
                match[k] = o
        return match

    def step(self, s, k=1):
        """Step k (1 for the first: read by `direction ... when` and `use ... when`)."""
        back = self.backward(k)
        active = self.active_groups(k) if self.uses else set()
        match = self._brackets(s)
        out = []          # forward: the string produced so far
        suffix = []       # backward: the new string to the right of the module being rewritten
        funcs = self.funcs
        order = range(len(s) - 1, -1, -1) if back else range(len(s))
        for i in order:
            mod = s[i]
            succ = self._rewrite(s, i, mod, match, out, suffix, back, funcs, active)
            if succ is None:
                succ = [mod]
            if back:
                suffix[0:0] = succ
            else:
                out.extend(succ)
        return self.cut(suffix if back else out)

    def _rewrite(self, s, i, mod, match, out, suffix, back, funcs, active):
        name, vals = mod
        rules = self.by_pred.get((name, 0 if vals is None else len(vals)))
        if not rules:
            return None
        # the rules of the used groups first, then the ungrouped ones, each in file order
        rules = ([r for r in rules if r.group is not None and r.group in active] +
                 [r for r in rules if r.group is None])
        for r in rules:
            env = dict(self.consts)
            if not self._bind(r.pred, mod, env):
                continue
            if r.newleft:
                if back or not self._left(r.newleft, out, self._partial_brackets(out), len(out), env):
                    continue
            if r.newright:
                if not back or not self._right(r.newright, suffix, self._partial_brackets(suffix), -1, env):
                    continue
            if r.left or r.right:
                if r.left and not self._left(r.left, s, match, i, env):
                    continue
                if r.right and not self._right(r.right, s, match, i, env):
                    continue
            if r.cond is not None and r.cond(env, funcs) == 0.0:
                continue
            return [(sname, None if sargs is None else tuple([a(env, funcs) for a in sargs]))
                    for sname, sargs in r.succ]
        return None


def to_text(s):
    parts = []
    for name, vals in s:
        if vals is None:
            parts.append(name)
        else:
            parts.append(name + "(" + ",".join(["%g" % v for v in vals]) + ")")
    return "".join(parts)


PICEK_KEYS = ("iteration", "angle", "reduction", "radius", "thickness", "axiom", "rule")


def _picek_lines(src):
    """Pícek's plant files (his thesis, Table 3.2): `;` comments, then `key: value` lines."""
    for line in src.split("\n"):
        line = line.split(";", 1)[0].strip()
        if line:
            yield line


def is_picek(src):
    for line in _picek_lines(src):
        m = re.match(r"([a-z]+)\s*:", line)
        return bool(m) and m.group(1) in PICEK_KEYS
    return False


def parse_picek(src, name):
    """The file as one model: iteration is the derivation length, every character a module,
    and rules sharing a predecessor a uniform (hence weighted, unsupported) choice."""
    cur = Model(name)
    rules = []
    for line in _picek_lines(src):
        key, _, value = line.partition(":")
        key, value = key.strip(), value.strip()
        if key == "iteration":
            cur.settings["derive"] = value
        elif key == "axiom":
            cur.axiom_text = " ".join(value.replace(" ", ""))
        elif key == "rule":
            pred, _, succ = value.partition("->")
            rules.append((pred.strip(), " ".join(succ.replace(" ", ""))))
    preds = [p for p, _ in rules]
    for pred, succ in rules:
        weight = " : 1" if preds.count(pred) > 1 else ""
        cur.rule_lines.append(("%s -> %s%s" % (pred, succ, weight), "produce", None))
    return [cur]


def load(path, model_name=None, overrides=None):
    with open(path, encoding="utf-8") as f:
        src = f.read()
    models = parse_picek(src, "picek") if is_picek(src) else parse_file(src)
    if not models:
        raise SylError("no lsystem in %s" % path)
    if model_name is None:
        model = models[0]
    else:
        found = [m for m in models if m.name == model_name]
        if not found:
            raise SylError("no model %r in %s" % (model_name, path))
        model = found[0]
    return LSystem(model, overrides)


def main(argv=None):
    ap = argparse.ArgumentParser(description="Reference deriver for .syl (deterministic subset)")
    ap.add_argument("file")
    ap.add_argument("-n", type=int, default=None)
    ap.add_argument("--model", default=None)
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--counts", action="store_true")
    ap.add_argument("--all-steps", action="store_true")
    a = ap.parse_args(argv)
    overrides = {}
    for kv in a.set:
        k, _, v = kv.partition("=")
        overrides[k.strip()] = float(v)
    try:
        ls = load(a.file, a.model, overrides)
        n = ls.derive if a.n is None else a.n
        s = ls.axiom
        if a.counts:
            print("0 %d" % len(s))
        elif a.all_steps:
            print(to_text(s))
        for k in range(1, n + 1):
            s = ls.step(s, k)
            if a.counts:
                print("%d %d" % (k, len(s)))
            elif a.all_steps:
                print(to_text(s))
        if not a.counts and not a.all_steps:
            sys.stdout.write(to_text(s) + "\n")
    except Unsupported as e:
        sys.stderr.write("ref_lsys: unsupported: %s\n" % e)
        return 3
    except SylError as e:
        sys.stderr.write("ref_lsys: error: %s\n" % e)
        return 2
    return 0


def cached_main(argv):
    """main(), its output kept in SYLVA_ORACLE_CACHE (a folder tests/run-all makes for one run)
    under the hash of this file, the arguments and the model's bytes: the release and the ASan
    pass ask the same derivations, and the answer depends on nothing else (one file is read)."""
    import hashlib, io, os
    cache = os.environ.get("SYLVA_ORACLE_CACHE")
    path = next((a for a in argv if not a.startswith("-")), None)
    if not cache or path is None or not os.path.isfile(path):
        return main(argv)
    h = hashlib.sha256()
    for part in (open(__file__, "rb").read(), "\0".join(argv).encode(), open(path, "rb").read()):
        h.update(hashlib.sha256(part).digest())
    entry = os.path.join(cache, h.hexdigest())
    try:
        with open(entry, "rb") as f:
            code, out_len = (int(x) for x in f.readline().split())
            data = f.read()
        sys.stdout.buffer.write(data[:out_len])
        sys.stdout.flush()
        sys.stderr.buffer.write(data[out_len:])
        return code
    except (OSError, ValueError):
        pass
    out, err = io.StringIO(), io.StringIO()
    real = sys.stdout, sys.stderr
    sys.stdout, sys.stderr = out, err
    try:
        code = main(argv)
    finally:
        sys.stdout, sys.stderr = real
    o, e = out.getvalue().encode(), err.getvalue().encode()
    sys.stdout.buffer.write(o)
    sys.stdout.flush()
    sys.stderr.buffer.write(e)
    os.makedirs(cache, exist_ok=True)
    tmp = "%s.%d" % (entry, os.getpid())
    with open(tmp, "wb") as f:
        f.write(b"%d %d\n" % (code or 0, len(o)) + o + e)
    os.replace(tmp, entry)  # whole or not at all: the passes may run at once
    return code


if __name__ == "__main__":
    sys.exit(cached_main(sys.argv[1:]))
