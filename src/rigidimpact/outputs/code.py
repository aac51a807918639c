"""A derivation as code: one function of the scene's symbols returning every output
``rigidimpact evaluate`` gives, in C, JavaScript, Fortran, Rust or Octave.

The closed forms are printed by SymPy's code printers, with the common subexpressions
of all the outputs shared (:func:`sympy.cse`). Where the answer has cases (a frictional
impact's courses) the conditions are printed too, and a point outside every case gives
NaN rather than some branch's number. Rationals stay divisions of exact literals
(``1.0/3.0``), and constants such as :math:`\\sqrt 2` or :math:`\\pi` are computed by the
language, never written as rounded decimals. Each file also holds a ``main`` (or the
language's equivalent): run with ``name=value`` for each symbol it prints ``key = value``
lines, as ``evaluate`` does.

Before any number the function checks what ``evaluate`` checks (a restitution
coefficient in [0, 1], a positive mass, the bodies approaching at the contact) and
refuses the values with the reason, instead of returning numbers that are no answer.

What cannot be exported faithfully is left out and said so, in the file and in
:attr:`Program.notes`: the words ``evaluate`` prints beside the numbers (which rule,
the checks' residuals), and a scene solved with numbers only (several contacts, a
3-D contact solved in floating point) gives a function of no symbols holding the
numbers at the scene's ``[values]``.

Examples
--------
>>> text = to_code("discs", "c")
>>> print(text[text.index("int discs("):][:65])
int discs(double V_1ix, double V_1iy, double V_2ix, double V_2iy,
>>> "1.0/2.0" in text
True
"""

from __future__ import annotations

import keyword
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import sympy as sp
from sympy.printing.c import C99CodePrinter
from sympy.printing.codeprinter import CodePrinter
from sympy.printing.fortran import FCodePrinter
from sympy.printing.jscode import JavascriptCodePrinter
from sympy.printing.octave import OctaveCodePrinter
from sympy.printing.rust import RustCodePrinter

from rigidimpact.errors import InputError
from rigidimpact.outputs.atomic import write_file
from rigidimpact.paper.problems import PROBLEMS, derive
from rigidimpact.scenes.space import load_any
from rigidimpact.solve.derivation import Derivation

__all__ = ["Program", "program_of", "to_code", "LANGUAGES", "BUILD", "BUILTIN_VALUES",
           "SUFFIX", "write_code", "resolve_target"]

# the file name's ending for each language
SUFFIX = {"c": ".c", "js": ".js", "fortran": ".f90", "rust": ".rs", "octave": ".m"}
LANGUAGES = tuple(SUFFIX)

# how each file is built and run ({src}: the file, {exe}: the program), and the Debian
# package that gives the compiler or interpreter
BUILD: dict[str, dict[str, Any]] = {
    "c": {"compile": ["gcc", "-O2", "-std=c99", "-Wall", "-o", "{exe}", "{src}", "-lm"],
          "run": ["{exe}"], "tool": "gcc", "debian": "gcc"},
    "js": {"run": ["node", "{src}"], "tool": "node", "debian": "nodejs"},
    "fortran": {"compile": ["gfortran", "-O2", "-std=f2018", "-o", "{exe}", "{src}"],
                "run": ["{exe}"], "tool": "gfortran", "debian": "gfortran"},
    "rust": {"compile": ["rustc", "-O", "-o", "{exe}", "{src}"], "run": ["{exe}"],
             "tool": "rustc", "debian": "rustc"},
    "octave": {"run": ["octave", "--no-gui", "--norc", "--quiet", "{src}"],
               "tool": "octave", "debian": "octave"},
}

# values for the built-in problems, which state none (a scene's come from its [values]);
# the live page's sliders start here
BUILTIN_VALUES: dict[str, dict[str, float]] = {
    # the paper's re-strike at the start: e = 0, theta = 15 degrees, below the critical angle
    "barbell": {"m": 1.0, "M": 1.0, "L": 0.5, "theta": math.pi / 12, "e": 0.0, "v_ix": 1.0},
    "sticking": {"m": 1.0, "M": 2.0, "L": 0.5, "theta": math.pi / 6, "v_ix": 1.0},
    "discs": {"V_1ix": 1.0, "V_1iy": 0.0, "V_2ix": 0.0, "V_2iy": 0.0, "e": 0.5},
    "two-body": {"m_1": 1.0, "m_2": 2.0, "I_1": 0.1, "I_2": 0.3, "R_1y": 0.2, "R_2y": -0.1,
                 "V_1ix": 1.0, "V_1iy": 0.0, "V_2ix": -0.5, "V_2iy": 0.0, "omega_1iz": 0.0,
                 "omega_2iz": 0.5, "e": 0.5},
}

_RESERVED = {
    # C, JavaScript, Rust, Fortran and Octave words, and the math functions printed
    "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else",
    "enum", "extern", "float", "for", "goto", "if", "inline", "int", "long", "register",
    "restrict", "return", "short", "signed", "sizeof", "static", "struct", "switch",
    "typedef", "union", "unsigned", "void", "volatile", "while", "var", "let", "function",
    "new", "this", "typeof", "in", "of", "delete", "instanceof", "yield", "await", "class",
    "Infinity", "NaN", "undefined", "Math", "fn", "mut", "match", "loop", "impl", "use",
    "mod", "pub", "self", "Self", "crate", "super", "trait", "type", "where", "as", "ref",
    "move", "end", "then", "program", "module", "contains", "subroutine", "real",
    "integer", "logical", "implicit", "none", "intent", "out", "call", "stop", "elseif",
    "endif", "endfunction", "global", "persistent", "pi", "e", "i", "j", "Inf", "NA",
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "exp",
    "log", "sqrt", "pow", "fabs", "abs", "floor", "ceil", "merge", "sign", "max", "min",
    "main", "args", "argv", "keys", "status", "value", "name", "dp", "E", "PI",
    "NAN", "gamma", "beta", "erf", "y0", "y1", "j0", "j1", "exit", "printf", "string",
}
_TEMP = "cse"  # the prefix of the shared subexpressions' names


@dataclass(frozen=True)
class Program:
    """What one exported function computes, in any language.

    Parameters
    ----------
    name : str
        The function's name (an identifier made from the scene's name).
    title : str
    target : str
        What ``rigidimpact evaluate`` is given for the same numbers.
    symbols : tuple of Symbol
        The function's arguments, in order (by name).
    defaults : mapping of name to float
        The scene's ``[values]`` (or a built-in problem's stated ones): ``main`` uses
        them for a symbol it is not given.
    outputs : mapping of str to Expr
        ``evaluate``'s keys and their closed forms (NaN outside every case).
    regimes : tuple of str
        A frictional impact's course names; `regime` picks one (its index, -1: none).
    regime : Expr or None
    checks : tuple of (message, condition)
        What the values must satisfy, in order; a failing one refuses the values.
    notes : tuple of str
        What is left out, and why.
    at_values : bool
        Solved with numbers at the scene's values: a function of no symbols.
    formulas : mapping of str to Expr
        The closed forms before the NaN outside every case (for typesetting).
    """

    name: str
    title: str
    target: str
    symbols: tuple[sp.Symbol, ...]
    defaults: Mapping[str, float]
    outputs: Mapping[str, sp.Expr]
    regimes: tuple[str, ...] = ()
    regime: sp.Expr | None = None
    checks: tuple[tuple[str, sp.Basic], ...] = ()
    notes: tuple[str, ...] = ()
    at_values: bool = False
    formulas: Mapping[str, sp.Expr] = field(default_factory=dict)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.symbols)


def _identifier(text: str) -> str:
    """A name made into an identifier of every language."""
    word = re.sub(r"\W", "_", text.strip(), flags=re.ASCII).strip("_") or "scene"
    if word[0].isdigit():
        word = "s_" + word
    if word in _RESERVED or keyword.iskeyword(word) or word.startswith(_TEMP):
        word += "_"
    return word


def _nan_outside(expr: sp.Expr) -> sp.Expr:
    """A Piecewise without a last (expr, True) case gets (nan, True): no case, no number."""
    def fill(p: sp.Piecewise) -> sp.Piecewise:
        if p.args[-1].cond == sp.true:
            return p
        return sp.Piecewise(*p.args, (sp.nan, True))
    return expr.replace(lambda x: isinstance(x, sp.Piecewise), fill)


def _float_defaults(values: Mapping[Any, Any]) -> dict[str, float]:
    out = {}
    for key, value in values.items():
        name = key.name if isinstance(key, sp.Symbol) else str(key)
        try:
            out[name] = float(sp.sympify(value))
        except (TypeError, ValueError):
            continue
    return out


def resolve_target(target: Any) -> tuple[Derivation, str, dict[str, float], Any]:
    """(derivation, what evaluate is given, default values, scene or None)."""
    if isinstance(target, Derivation):
        return target, target.problem, dict(BUILTIN_VALUES.get(target.problem, {})), None
    text = str(target)
    if text in PROBLEMS:
        return derive(text), text, dict(BUILTIN_VALUES[text]), None
    if text.endswith(".toml") or Path(text).exists():
        scene = load_any(text)
        return scene.derivation(), text, _float_defaults(getattr(scene, "values", {})), scene
    raise InputError("export", f"unknown problem {text!r}; use one of {', '.join(PROBLEMS)} "
                     "or a scene file (.toml)")


def _role_checks(derivation: Derivation, used: set[sp.Symbol]) -> list[tuple[str, sp.Basic]]:
    """What the values must satisfy, over plain symbols (a positive symbol's ``m > 0`` is
    no condition to SymPy, but it is one to the exported code)."""
    plain = {s: sp.Symbol(s.name) for s in used}
    checks: list[tuple[str, sp.Basic]] = []
    covered: set[sp.Basic] = set()
    solution = derivation.solution
    # a 3-D scene's evaluate checks no roles (its values are read without them)
    spatial = solution is not None and (any(len(b.position) == 3 for b in solution.before)
                                        or any(len(c.point) == 3 for c in solution.contacts))
    for role in () if spatial else derivation.roles:
        expr = sp.sympify(role.expr)
        if role.zero or not expr.free_symbols or not expr.free_symbols <= used:
            continue
        # an identity (a point on a rod's end: l/2 - l sin^2/2 - l cos^2/2) is no check,
        # and its rounding in floating point must not refuse values evaluate accepts
        expr = sp.simplify(expr.xreplace(plain))
        if expr.is_number:
            continue
        parts = []
        if role.low is not None:
            parts.append(sp.StrictGreaterThan(expr, role.low) if role.open_low
                         else sp.GreaterThan(expr, role.low))
        if role.high is not None:
            parts.append(sp.LessThan(expr, role.high))
        condition = sp.And(*parts)
        if parts and condition != sp.true:
            covered |= expr.free_symbols if expr.is_Symbol else set()
            checks.append((f"{role.meaning} ({role.field} = {expr}) must lie in "
                           f"{role.range}", condition))
    for s in sorted(used, key=lambda s: s.name):
        x = plain[s]
        if x in covered:
            continue
        if s.is_positive:
            checks.insert(0, (f"{s.name} must be positive", sp.StrictGreaterThan(x, 0)))
        elif s.is_nonnegative:
            checks.insert(0, (f"{s.name} must not be negative", sp.GreaterThan(x, 0)))
        elif s.is_negative:
            checks.insert(0, (f"{s.name} must be negative", sp.StrictLessThan(x, 0)))
    if solution is not None and solution.approach_speed is not None:
        speed = sp.sympify(solution.approach_speed)
        if speed.free_symbols and speed.free_symbols <= used:
            checks.append(("with these values the bodies are not approaching at the contact",
                           sp.StrictGreaterThan(speed.xreplace(plain), 0)))
    return checks


def program_of(target: Any) -> Program:
    """The function to export for a built-in problem, a scene file or a Derivation.

    Examples
    --------
    >>> p = program_of("sticking")
    >>> p.names, list(p.outputs)
    (('L', 'M', 'm', 'theta', 'v_ix'), ['u_x', 'omega_z', 'h'])
    """
    derivation, where, defaults, scene = resolve_target(target)
    results = {k: sp.sympify(v) for k, v in derivation.results.items()}
    notes: list[str] = []
    used = set().union(*(v.free_symbols for v in results.values())) if results else set()
    at_values = not used and bool(defaults)
    if at_values:
        notes.append("solved with numbers at the scene's [values] (several contacts, or a "
                     "contact solved in floating point, have no closed form over the "
                     "symbols here): the function takes no symbols; for other values use "
                     "rigidimpact evaluate")
    if any(v.has(sp.Float) for v in results.values()):
        notes.append("some outputs were solved in floating point: they are written as the "
                     "floating-point numbers they are, to 17 digits")
    random_table = getattr(scene, "random", None)
    if random_table:
        notes.append("the [random] table's distributions are not exported: the function "
                     "gives the outputs at given values of the random symbols")
    symbols = tuple(sorted(used, key=lambda s: s.name))
    missing = [s.name for s in symbols if s.name not in defaults]
    if missing and scene is not None:
        notes.append(f"no [values] for {', '.join(missing)}: main needs them given")
    regimes: tuple[str, ...] = ()
    regime = None
    solution = derivation.solution
    if solution is not None and solution.regimes and not at_values:
        cases = [(name or "", sp.And(*conditions)) for name, conditions, _ in solution.regimes]
        if all(c.free_symbols <= used for _, c in cases):
            regimes = tuple(name for name, _ in cases)
            regime = sp.Piecewise(*((sp.Integer(i), c) for i, (_, c) in enumerate(cases)),
                                  (sp.Integer(-1), True))
    if solution is not None and (solution.regimes or solution.contact.by_regimes) \
            and regime is None:
        notes.append("the course the impact takes (evaluate's regime line) is not "
                     "exported: its outputs' cases are")
    notes.append("evaluate's lines in words (warnings, rule, checks) are not exported, "
                 "only its numbers")
    return Program(
        name=_identifier(Path(where).stem if where.endswith(".toml") else where),
        title=derivation.title, target=where, symbols=symbols,
        defaults={s.name: defaults[s.name] for s in symbols if s.name in defaults},
        outputs={k: _nan_outside(v) for k, v in results.items()},
        regimes=regimes, regime=regime,
        checks=() if at_values else tuple(_role_checks(derivation, used)),
        notes=tuple(notes), at_values=at_values, formulas=results)


# --------------------------------------------------------------------------- printers


class _C(C99CodePrinter):
    def __init__(self) -> None:
        super().__init__({"strict": True})


class _JS(JavascriptCodePrinter):
    def __init__(self) -> None:
        super().__init__({"strict": True})

    def _print_NaN(self, expr: Any) -> str:
        return "NaN"

    def _print_Relational(self, expr: Any) -> str:
        ops = {"==": "===", "!=": "!=="}
        return (f"{self.parenthesize(expr.lhs, 0)} {ops.get(expr.rel_op, expr.rel_op)} "
                f"{self.parenthesize(expr.rhs, 0)}")


class _Fortran(FCodePrinter):
    def __init__(self) -> None:
        super().__init__({"strict": True, "source_format": "free", "standard": 2008})

    def _print_NaN(self, expr: Any) -> str:
        return "ieee_value(1.0d0, ieee_quiet_nan)"


class _Rust(RustCodePrinter):
    def __init__(self) -> None:
        super().__init__({"strict": True})

    def _print_NaN(self, expr: Any) -> str:
        return "f64::NAN"

    def _print_Integer(self, expr: Any, _type: bool = False) -> str:
        return f"{int(expr)}_f64"  # every number a float: Rust does not mix the two

    # SymPy's Rust printer casts a product's factors to floats, and a cast factor loses
    # its parentheses (-(x + y)/5 printed as -1_f64/5.0*x + y); every number here is a
    # float already, so the generic printing, with its parentheses, is the right one
    def _print_Mul(self, expr: Any) -> str:
        return CodePrinter._print_Mul(self, expr)

    def _print_Add(self, expr: Any, order: Any = None) -> str:
        return CodePrinter._print_Add(self, expr, order)

    def _print_Pow(self, expr: Any) -> str:
        if expr.exp.is_Integer and expr.exp not in (-1, 1):
            return f"{self.parenthesize(expr.base, 1000)}.powi({int(expr.exp)})"
        # a root of a number is computed, not written as a rounded decimal
        if expr.base.is_Number and not expr.exp.is_Integer:
            base = f"({self._print(sp.Float(expr.base) if expr.base.is_Integer else expr.base)}" \
                   f"_f64)" if expr.base.is_Integer else f"({self._print(expr.base)})"
            if expr.exp == sp.Rational(1, 2):
                return f"{base}.sqrt()"
            if expr.exp == -sp.Rational(1, 2):
                return f"(1.0_f64/{base}.sqrt())"
            return f"{base}.powf({self._print(expr.exp)})"
        return super()._print_Pow(expr)


class _Octave(OctaveCodePrinter):
    def __init__(self) -> None:
        super().__init__({"strict": True, "inline": True})

    def _print_Piecewise(self, expr: Any) -> str:
        # the printer's own inline form multiplies each case by its condition, which
        # turns the NaN outside every case (and an unchosen case's infinity) into the
        # answer: a helper picks the first case that holds instead
        parts = []
        for value, condition in expr.args:
            parts += [self._print(condition), self._print(value)]
        return f"pick_({', '.join(parts)})"


_PRINTERS: dict[str, Callable[[], Any]] = {
    "c": _C, "js": _JS, "fortran": _Fortran, "rust": _Rust, "octave": _Octave}


@dataclass
class _Body:
    """The printed statements of the function: shared subexpressions, then each value."""

    temps: list[tuple[str, str]]
    logical: set[str]  # the shared subexpressions that are conditions, not numbers
    outputs: list[str]
    regime: str | None
    checks: list[str]
    arguments: list[str]


def _prepared(program: Program, lang: str) -> _Body:
    printer = _PRINTERS[lang]()
    case_blind = lang == "fortran"
    words: dict[str, sp.Symbol] = {}
    taken: set[str] = set()
    for s in program.symbols:
        word = _identifier(s.name)
        while (word.lower() if case_blind else word) in taken:
            word += "_"
        taken.add(word.lower() if case_blind else word)
        words[s.name] = sp.Symbol(word)

    def named(x: sp.Basic) -> sp.Basic:  # each symbol by its identifier, by name
        return x.xreplace({s: words[s.name] for s in x.free_symbols})
    exprs: list[sp.Basic] = [named(_nan_outside(v)) for v in program.outputs.values()]
    if program.regime is not None:
        exprs.append(named(program.regime))
    checks = [sp.Piecewise((1, named(c)), (0, True)) for _, c in program.checks]
    exprs += checks
    temps, reduced = sp.cse(exprs, symbols=sp.numbered_symbols(_TEMP), order="none")

    def show(x: sp.Basic) -> str:
        text = printer.doprint(x)
        return " ".join(line.strip() for line in text.splitlines()) if lang != "fortran" \
            else text
    n = len(program.outputs)
    shown = [show(x) for x in reduced]
    return _Body(temps=[(str(t), show(x)) for t, x in temps], outputs=shown[:n],
                 logical={str(t) for t, x in temps if isinstance(x, sp.logic.boolalg.Boolean)},
                 regime=shown[n] if program.regime is not None else None,
                 checks=shown[n + (program.regime is not None):],
                 arguments=[words[s.name].name for s in program.symbols])


def _header(program: Program, comment: str, lang: str) -> list[str]:
    build = BUILD[lang]
    exe = program.name
    src = program.name + SUFFIX[lang]
    lines = [f"{program.title}",
             f"Every output of `rigidimpact evaluate {Path(program.target).name}` from its "
             "closed forms, written by `rigidimpact export --to "
             f"{lang}` with SymPy's code printers (common subexpressions shared).", ""]
    if "compile" in build:
        lines.append("Build: " + " ".join(build["compile"]).format(exe=exe, src=src))
    run = " ".join(build["run"]).format(exe="./" + exe, src=src)
    example = " ".join(f"{k}={v!r}" for k, v in list(program.defaults.items())[:2])
    lines += [f"Run:   {run} {example}".rstrip(),
              "       (name=value for each symbol, angles in radians; a symbol not given "
              "takes the scene's value; several sets: separate them with --)"]
    if program.symbols:
        lines.append("Symbols: " + ", ".join(program.names))
    lines += [f"Note: {note}" for note in program.notes]
    wrapped = []
    for line in lines:
        while len(line) > 96:
            cut = line.rfind(" ", 0, 96)
            cut = cut if cut > 20 else 96
            wrapped.append(line[:cut])
            line = "       " + line[cut:].lstrip()
        wrapped.append(line)
    return [f"{comment} {line}".rstrip() for line in wrapped]


def _quoted(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _c(program: Program) -> str:
    body = _prepared(program, "c")
    p, n = program.name, len(program.outputs)
    ns = len(program.symbols)
    args = ", ".join([*(f"double {a}" for a in body.arguments), "double out[{size}]"])
    lines = ["/*"] + _header(program, " *", "c") + [" */", "",
             "#include <math.h>", "#include <stdio.h>", "#include <stdlib.h>",
             "#include <string.h>", ""]
    for macro, value in (("M_PI", "3.14159265358979323846264338327950288"),
                         ("M_E", "2.71828182845904523536028747135266250"),
                         ("M_SQRT2", "1.41421356237309504880168872420969808"),
                         ("M_SQRT1_2", "0.707106781186547524400844362104849039"),
                         ("M_PI_2", "1.57079632679489661923132169163975144"),
                         ("M_PI_4", "0.785398163397448309615660845819875721"),
                         ("M_1_PI", "0.318309886183790671537767526745028724"),
                         ("M_2_PI", "0.636619772367581343075535053490057448"),
                         ("M_LN2", "0.693147180559945309417232121458176568"),
                         ("M_LN10", "2.30258509299404568401799145468436421"),
                         ("M_2_SQRTPI", "1.12837916709551257389615890312154517")):
        lines += [f"#ifndef {macro}", f"#define {macro} {value}", "#endif"]
    keys = [*program.outputs, *(["regime"] if body.regime else [])]
    lines += ["", f"#define {p.upper()}_OUTPUTS {len(keys)}",
              f"static const char *const {p}_keys[{len(keys)}] = {{"
              + ", ".join(_quoted(k) for k in keys) + "};"]
    if body.regime:
        lines.append(f"static const char *const {p}_regimes[{len(program.regimes)}] = {{"
                     + ", ".join(_quoted(r) for r in program.regimes) + "};")
    if program.checks:
        lines.append(f"static const char *const {p}_refusals[{len(program.checks)}] = {{"
                     + ", ".join(_quoted(m) for m, _ in program.checks) + "};")
    lines += ["",
              f"/* Every output at these values, in the order of {p}_keys"
              + (f" (regime: an index into {p}_regimes, -1 for none)" if body.regime else "")
              + ". Returns 0, or k > 0 when the values are refused for the reason "
              + f"{p}_refusals[k - 1] (the outputs are then NaN). */",
              f"int {p}({args.format(size=len(keys))}) {{"]
    lines += [f"    const {'int' if t in body.logical else 'double'} {t} = {x};"
              for t, x in body.temps]
    for k, check in enumerate(body.checks, 1):
        lines += [f"    if (!({check})) {{",
                  f"        for (int i = 0; i < {len(keys)}; i++) out[i] = NAN;",
                  f"        return {k};", "    }"]
    lines += [f"    out[{i}] = {x};" for i, x in enumerate(body.outputs)]
    if body.regime:
        lines.append(f"    out[{n}] = {body.regime};")
    lines += ["    return 0;", "}", ""]
    names = ", ".join(_quoted(s) for s in program.names)
    defaults = ", ".join(repr(program.defaults.get(s, 0.0)) for s in program.names)
    given = ", ".join("1" if s in program.defaults else "0" for s in program.names)
    call = ", ".join(f"v[{i}]" for i in range(ns))
    lines += [
        "static int run(const double *v, const int *given) {",
        f"    static const char *const names[{max(ns, 1)}] = {{{names or '0'}}};",
        "    (void)names;",
        f"    for (int i = 0; i < {ns}; i++) {{",
        "        if (!given[i]) {",
        f"            fprintf(stderr, \"{p}: error: needs a value for %s\\n\", names[i]);",
        "            return 2;", "        }", "    }",
        f"    double out[{len(keys)}];",
        f"    int refused = {p}({call}{', ' if ns else ''}out);",
        "    if (refused) {",
        f"        fprintf(stderr, \"{p}: error: %s\\n\", {p}_refusals[refused - 1]);"
        if program.checks else "        (void)refused;",
        "        return 2;", "    }",
        f"    for (int i = 0; i < {n}; i++) printf(\"%s = %.17g\\n\", {p}_keys[i], out[i]);",
    ]
    if body.regime:
        lines += [f"    if (out[{n}] >= 0) printf(\"regime = %s\\n\", "
                  f"{p}_regimes[(int)out[{n}]]);"]
    lines += ["    return 0;", "}", "",
              "int main(int argc, char **argv) {",
              f"    static const char *const names[{max(ns, 1)}] = {{{names or '0'}}};",
              f"    const double start[{max(ns, 1)}] = {{{defaults or '0'}}};",
              f"    const int known[{max(ns, 1)}] = {{{given or '0'}}};",
              f"    double v[{max(ns, 1)}];", f"    int given[{max(ns, 1)}];",
              "    int sets = 0;",
              "    memcpy(v, start, sizeof v);", "    memcpy(given, known, sizeof given);",
              "    for (int a = 1; a <= argc; a++) {",
              "        if (a == argc || strcmp(argv[a], \"--\") == 0) {",
              "            if (sets++) printf(\"\\n\");",
              "            if (run(v, given)) return 2;",
              "            memcpy(v, start, sizeof v);",
              "            memcpy(given, known, sizeof given);",
              "            continue;", "        }",
              "        const char *eq = strchr(argv[a], '=');",
              "        int found = -1;",
              f"        for (int i = 0; eq && i < {ns}; i++)",
              "            if (strlen(names[i]) == (size_t)(eq - argv[a]) &&",
              "                strncmp(names[i], argv[a], (size_t)(eq - argv[a])) == 0) found = i;",
              "        if (!eq) {",
              f"            fprintf(stderr, \"{p}: error: expected name=value, got "
              "'%s'\\n\", argv[a]);",
              "            return 2;", "        }",
              "        if (found < 0) {",
              f"            fprintf(stderr, \"{p}: error: unknown symbol '%.*s'; the symbols are "
              f"{', '.join(program.names) or 'none'}\\n\", (int)(eq - argv[a]), argv[a]);",
              "            return 2;", "        }",
              "        char *end;",
              "        double x = strtod(eq + 1, &end);",
              "        if (end == eq + 1 || *end != '\\0' || !isfinite(x)) {",
              f"            fprintf(stderr, \"{p}: error: %s must be a finite number, "
              "got '%s'\\n\","
              " names[found], eq + 1);",
              "            return 2;", "        }",
              "        v[found] = x;", "        given[found] = 1;", "    }",
              "    return 0;", "}", ""]
    return "\n".join(lines)


def _js(program: Program) -> str:
    body = _prepared(program, "js")
    p = program.name
    lines = ["\"use strict\";"] + _header(program, "//", "js") + [""]
    lines += [f"const {p}_symbols = [{', '.join(_quoted(s) for s in program.names)}];",
              f"const {p}_defaults = {{"
              + ", ".join(f"{_quoted(k)}: {v!r}" for k, v in program.defaults.items()) + "};",
              f"const {p}_keys = [{', '.join(_quoted(k) for k in program.outputs)}"
              + (", \"regime\"" if body.regime else "") + "];"]
    if body.regime:
        lines.append(f"const {p}_regimes = [{', '.join(_quoted(r) for r in program.regimes)}];")
    lines += ["",
              "// Every output at these values, by evaluate's keys"
              + (" (regime: the course's name, null for none)" if body.regime else "")
              + "; throws a RangeError naming the reason when the values are refused.",
              f"function {p}({', '.join(body.arguments)}) {{"]
    lines += [f"  const {t} = {x};" for t, x in body.temps]
    for (message, _), check in zip(program.checks, body.checks, strict=True):
        lines += [f"  if (!({check})) {{ throw new RangeError({_quoted(message)}); }}"]
    lines.append("  return {")
    lines += [f"    {_quoted(k)}: {x}," for k, x in zip(program.outputs, body.outputs,
                                                     strict=True)]
    if body.regime:
        lines.append(f"    \"regime\": ({body.regime}) >= 0 ? {p}_regimes[{body.regime}] : null,")
    lines += ["  };", "}", ""]
    lines += [
        f"function {p}_main(args) {{",
        "  const sets = [[]];",
        "  for (const a of args) {",
        "    if (a === \"--\") { sets.push([]); } else { sets[sets.length - 1].push(a); }",
        "  }",
        "  const shown = [];",
        "  for (const set of sets) {",
        f"    const v = Object.assign({{}}, {p}_defaults);",
        "    for (const a of set) {",
        "      const at = a.indexOf(\"=\");",
        "      if (at < 0) { throw new Error(\"expected name=value, got '\" + a + \"'\"); }",
        "      const name = a.slice(0, at);",
        f"      if (!{p}_symbols.includes(name)) {{",
        "        throw new Error(\"unknown symbol '\" + name + \"'; the symbols are "
        f"{', '.join(program.names) or 'none'}\");",
        "      }",
        "      const text = a.slice(at + 1).trim();",
        "      const x = text === \"\" ? NaN : Number(text);",
        "      if (!Number.isFinite(x)) {",
        "        throw new Error(name + \" must be a finite number, got '\" + "
        "a.slice(at + 1) + \"'\");",
        "      }",
        "      v[name] = x;",
        "    }",
        f"    for (const name of {p}_symbols) {{",
        "      if (!(name in v)) { throw new Error(\"needs a value for \" + name); }",
        "    }",
        f"    const out = {p}(...{p}_symbols.map((name) => v[name]));",
        "    shown.push(Object.entries(out).filter(([, x]) => x !== null)",
        "      .map(([key, x]) => key + \" = \" + String(x)).join(\"\\n\"));",
        "  }",
        "  return shown.join(\"\\n\\n\");",
        "}", "",
        "if (typeof module !== \"undefined\") {",
        f"  module.exports = {{ {p}, {p}_symbols, {p}_defaults, {p}_keys, {p}_main }};",
        "  if (require.main === module) {",
        "    try {",
        f"      console.log({p}_main(process.argv.slice(2)));",
        "    } catch (error) {",
        f"      process.stderr.write(\"{p}: error: \" + error.message + \"\\n\");",
        "      process.exitCode = 2;",
        "    }",
        "  }",
        "}", ""]
    return "\n".join(lines)


def _fortran(program: Program) -> str:
    body = _prepared(program, "fortran")
    printer = _Fortran()
    p = program.name
    n = len(program.outputs)
    keys = [*program.outputs, *(["regime"] if body.regime else [])]
    width = max(len(k) for k in keys) if keys else 1
    lines = _header(program, "!", "fortran") + [
        "", f"module {p}_export", "  use, intrinsic :: ieee_arithmetic", "  implicit none",
        "  private",
        f"  public :: {p}, {p}_keys, {p}_outputs" + (f", {p}_regimes" if body.regime else "")
        + (f", {p}_refusals" if program.checks else ""),
        f"  integer, parameter :: {p}_outputs = {len(keys)}",
        f"  character(len={width}), parameter :: {p}_keys({len(keys)}) = "
        f"[character(len={width}) :: &"]
    lines += [f"    {_quoted(k)}" + (", &" if i < len(keys) - 1 else "]")
              for i, k in enumerate(keys)]
    for label, items in ((f"{p}_regimes", program.regimes if body.regime else ()),
                         (f"{p}_refusals", [m for m, _ in program.checks])):
        if items:
            w = max(len(x) for x in items)
            lines.append(f"  character(len={w}), parameter :: {label}({len(items)}) = "
                         f"[character(len={w}) :: &")
            lines += [f"    {_quoted(x)}" + (", &" if i < len(items) - 1 else "]")
                      for i, x in enumerate(items)]
    lines += ["contains", "",
              f"  ! Every output at these values, in the order of {p}_keys; status 0, or k > 0"
              f" when the values are refused for the reason {p}_refusals(k) (outputs NaN)",
              f"  subroutine {p}({', '.join([*body.arguments, 'out', 'status'])})"]
    for a in body.arguments:
        lines.append(f"    real(kind(1.0d0)), intent(in) :: {a}")
    lines += [f"    real(kind(1.0d0)), intent(out) :: out({len(keys)})",
              "    integer, intent(out) :: status"]
    for t, _ in body.temps:
        kind = "logical" if t in body.logical else "real(kind(1.0d0))"
        lines.append(f"    {kind} :: {t}")
    def assign(target: str, text: str) -> list[str]:
        out = printer._wrap_fortran([f"{target} = {text}"]) if hasattr(printer, "_wrap_fortran") \
            else [f"{target} = {text}"]
        return ["    " + line.strip() for line in out]
    for t, x in body.temps:
        lines += assign(t, x.strip())
    for k, check in enumerate(body.checks, 1):
        lines += ["    if (.not. (" + check.strip().replace("\n", " ") + " == 1)) then",
                  "      out = ieee_value(1.0d0, ieee_quiet_nan)", f"      status = {k}",
                  "      return", "    end if"]
    for i, x in enumerate(body.outputs, 1):
        lines += assign(f"out({i})", x.strip())
    if body.regime:
        lines += assign(f"out({n + 1})", body.regime.strip())
    lines += ["    status = 0", f"  end subroutine {p}", f"end module {p}_export", ""]
    ns = len(program.symbols)
    lines += [f"program {p}_main", f"  use {p}_export", "  use, intrinsic :: ieee_arithmetic",
              "  implicit none",
              f"  character(len=*), parameter :: names({max(ns, 1)}) = [character(len=32) :: "
              + (", ".join(_quoted(s) for s in program.names) or "\"\"") + "]",
              f"  real(kind(1.0d0)) :: v({max(ns, 1)}), start({max(ns, 1)}), x",
              f"  logical :: given({max(ns, 1)}), known({max(ns, 1)})",
              f"  real(kind(1.0d0)) :: out({p}_outputs)",
              "  character(len=4096) :: arg", "  integer :: a, i, at, found, status, count, sets",
              "  start = 0.0d0", "  known = .false."]
    for i, s in enumerate(program.names, 1):
        if s in program.defaults:
            lines += [f"  start({i}) = {printer.doprint(sp.Float(program.defaults[s], 17))}",
                      f"  known({i}) = .true."]
    lines += ["  v = start", "  given = known", "  sets = 0",
              "  count = command_argument_count()", "  do a = 1, count + 1",
              "    if (a <= count) call get_command_argument(a, arg)",
              "    if (a > count .or. trim(arg) == '--') then",
              "      if (sets > 0) write(*, '(a)') ''", "      sets = sets + 1",
              f"      do i = 1, {ns}", "        if (.not. given(i)) then",
              f"          write(0, '(3a)') '{p}: error: needs a value for ', trim(names(i))",
              "          stop 2, quiet=.true.", "        end if", "      end do",
              f"      call {p}(" + ", ".join([*(f"v({i})" for i in range(1, ns + 1)),
                                              "out", "status"]) + ")",
              "      if (status /= 0) then"]
    if program.checks:
        lines += [f"        write(0, '(2a)') '{p}: error: ', trim({p}_refusals(status))"]
    lines += ["        stop 2, quiet=.true.", "      end if",
              f"      do i = 1, {n}",
              f"        write(*, '(3a, es25.17e3)') trim({p}_keys(i)), ' = ', '', out(i)",
              "      end do"]
    if body.regime:
        lines += [f"      if (out({n + 1}) >= 0) write(*, '(2a)') 'regime = ', "
                  f"trim({p}_regimes(nint(out({n + 1})) + 1))"]
    lines += ["      v = start", "      given = known", "      cycle", "    end if",
              "    at = index(arg, '=')", "    if (at == 0) then",
              f"      write(0, '(3a)') '{p}: error: expected name=value, got ''', trim(arg), ''''",
              "      stop 2, quiet=.true.", "    end if", "    found = 0",
              f"    do i = 1, {ns}",
              "      if (arg(:at - 1) == trim(names(i))) found = i", "    end do",
              "    if (found == 0) then",
              f"      write(0, '(3a)') '{p}: error: unknown symbol ''', arg(:at - 1), "
              f"'''; the symbols are {', '.join(program.names) or 'none'}'",
              "      stop 2, quiet=.true.", "    end if",
              "    read(arg(at + 1:), *, iostat=status) x",
              "    if (status /= 0 .or. len_trim(arg(at + 1:)) == 0 .or. "
              ".not. ieee_is_finite(x)) then",
              f"      write(0, '(4a)') '{p}: error: ', trim(names(found)), "
              "' must be a finite number, got ', trim(arg(at + 1:))",
              "      stop 2, quiet=.true.", "    end if", "    v(found) = x",
              "    given(found) = .true.",
              "  end do", f"end program {p}_main", ""]
    # no line past Fortran's 132 characters
    wrapped = []
    for line in lines:
        while len(line) > 130 and not line.lstrip().startswith("!"):
            cut = line.rfind(", ", 0, 120) + 1
            if cut <= 0:
                cut = line.rfind(" ", 0, 120)
            wrapped.append(line[:cut] + " &")
            line = "      & " + line[cut:].lstrip()
        wrapped.append(line)
    return "\n".join(wrapped)


def _rust(program: Program) -> str:
    body = _prepared(program, "rust")
    p = program.name
    n = len(program.outputs)
    keys = [*program.outputs, *(["regime"] if body.regime else [])]
    ns = len(program.symbols)
    lines = _header(program, "//", "rust") + [
        "", "#![allow(non_snake_case, unused_parens, clippy::all)]",
        "#[allow(unused_imports)]", "use std::f64::consts::*;", "",
        f"pub const {p.upper()}_KEYS: [&str; {len(keys)}] = "
        f"[{', '.join(_quoted(k) for k in keys)}];",
        f"pub const {p.upper()}_SYMBOLS: [&str; {ns}] = "
        f"[{', '.join(_quoted(s) for s in program.names)}];"]
    if body.regime:
        lines.append(f"pub const {p.upper()}_REGIMES: [&str; {len(program.regimes)}] = "
                     f"[{', '.join(_quoted(r) for r in program.regimes)}];")
    lines += ["",
              f"/// Every output at these values, in the order of {p.upper()}_KEYS"
              + (" (regime: an index into the regimes, -1 for none)" if body.regime else "")
              + "; Err names the reason when the values are refused.",
              f"pub fn {p}({', '.join(f'{a}: f64' for a in body.arguments)}) "
              f"-> Result<[f64; {len(keys)}], &'static str> {{"]
    lines += [f"    let {t}: {'bool' if t in body.logical else 'f64'} = {x};"
              for t, x in body.temps]
    for (message, _), check in zip(program.checks, body.checks, strict=True):
        lines.append(f"    if !(({check}) == 1.0) {{ return Err({_quoted(message)}); }}")
    values = [*body.outputs, *([body.regime] if body.regime else [])]
    lines += ["    Ok([" + ", ".join(f"{x}" for x in values) + "])", "}", ""]
    defaults = ", ".join(f"{program.defaults.get(s, float('nan'))!r}_f64" if
                         s in program.defaults else "f64::NAN" for s in program.names)
    lines += ["fn main() {",
              f"    let start: [f64; {ns}] = [{defaults}];",
              "    let args: Vec<String> = std::env::args().skip(1).collect();",
              "    let mut sets: Vec<Vec<String>> = vec![vec![]];",
              "    for a in args {",
              "        if a == \"--\" { sets.push(vec![]); } "
              "else { sets.last_mut().unwrap().push(a); }",
              "    }",
              "    for (k, set) in sets.iter().enumerate() {",
              "        let mut v = start;",
              "        for a in set {",
              # match, not let-else: Debian's rustc (1.63) predates let-else
              "            let (name, text) = match a.split_once('=') {",
              "                Some(pair) => pair,",
              "                None => {",
              f"                    eprintln!(\"{p}: error: expected name=value, got '{{}}'\", "
              "a);",
              "                    std::process::exit(2);", "                }", "            };",
              f"            let i = match {p.upper()}_SYMBOLS.iter()"
              ".position(|s| *s == name) {",
              "                Some(i) => i,",
              "                None => {",
              f"                    eprintln!(\"{p}: error: unknown symbol '{{}}'; the symbols "
              f"are {', '.join(program.names) or 'none'}\", name);",
              "                    std::process::exit(2);", "                }", "            };",
              "            match text.trim().parse::<f64>() {",
              "                Ok(x) if x.is_finite() => v[i] = x,",
              "                _ => {",
              f"                    eprintln!(\"{p}: error: {{}} must be a finite number, "
              "got '{}'\", name, text);",
              "                    std::process::exit(2);", "                }",
              "            }", "        }",
              f"        for i in 0..{ns} {{",
              "            if v[i].is_nan() {",
              f"                eprintln!(\"{p}: error: needs a value for {{}}\", "
              f"{p.upper()}_SYMBOLS[i]);",
              "                std::process::exit(2);", "            }", "        }",
              f"        match {p}(" + ", ".join(f"v[{i}]" for i in range(ns)) + ") {",
              "            Err(reason) => {",
              f"                eprintln!(\"{p}: error: {{}}\", reason);",
              "                std::process::exit(2);", "            }",
              "            Ok(out) => {",
              "                if k > 0 { println!(); }",
              f"                for i in 0..{n} {{ println!(\"{{}} = {{:?}}\", "
              f"{p.upper()}_KEYS[i], out[i]); }}"]
    if body.regime:
        lines += [f"                if out[{n}] >= 0.0 {{ println!(\"regime = {{}}\", "
                  f"{p.upper()}_REGIMES[out[{n}] as usize]); }}"]
    lines += ["            }", "        }", "    }", "}", ""]
    return "\n".join(lines)


def _octave(program: Program) -> str:
    body = _prepared(program, "octave")
    p = program.name
    n = len(program.outputs)
    keys = [*program.outputs, *(["regime"] if body.regime else [])]
    lines = _header(program, "%", "octave") + ["", "1;  % a script that defines functions", "",
              f"% Every output at these values (named {p}_outputs: Octave warns of a "
              "function named "
              "as its script file), in the order of {p}_keys(); status 0, or k > 0 "
              f"when the values are refused (the reason: {p}_refusals(){{k}}; outputs NaN)",
              f"function [out, status] = {p}_outputs({', '.join(body.arguments)})"]
    lines += [f"  {t} = {x};" for t, x in body.temps]
    lines.append(f"  out = NaN(1, {len(keys)});")
    for k, check in enumerate(body.checks, 1):
        lines += [f"  if ~(({check}) == 1)", f"    status = {k};", "    return;", "  end"]
    lines += [f"  out({i}) = {x};" for i, x in enumerate(body.outputs, 1)]
    if body.regime:
        lines.append(f"  out({n + 1}) = {body.regime};")
    lines += ["  status = 0;", "end", "",
              "function v = pick_(varargin)",
              "  % the first case whose condition holds (the last argument: none holds)",
              "  for k = 1:2:numel(varargin) - 1",
              "    if varargin{k}", "      v = varargin{k + 1};", "      return;", "    end",
              "  end", "  v = varargin{end};", "end", "",
              f"function k = {p}_keys()",
              f"  k = {{{', '.join(repr(x) for x in keys)}}};", "end", "",
              f"function k = {p}_refusals()",
              f"  k = {{{', '.join(repr(m) for m, _ in program.checks)}}};", "end", ""]
    if body.regime:
        lines += [f"function k = {p}_regimes()",
                  f"  k = {{{', '.join(repr(r) for r in program.regimes)}}};", "end", ""]
    ns = len(program.symbols)
    defaults = ", ".join(repr(program.defaults[s]) if s in program.defaults else "NaN"
                         for s in program.names)
    lines += [f"names = {{{', '.join(repr(s) for s in program.names)}}};",
              f"start = [{defaults}];", "args = argv();", "sets = {{}};", "current = {};",
              "for a = 1:numel(args)",
              "  if strcmp(args{a}, '--')", "    sets{end + 1} = current;", "    current = {};",
              "  else", "    current{end + 1} = args{a};", "  end", "end",
              "sets{end + 1} = current;", "sets = sets(2:end);",
              "for s = 1:numel(sets)", "  v = start;", "  set = sets{s};",
              "  for a = 1:numel(set)", "    at = index(set{a}, '=');",
              "    if at == 0",
              f"      fprintf(2, '{p}: error: expected name=value, got ''%s''\\n', set{{a}});",
              "      exit(2);", "    end",
              "    name = set{a}(1:at - 1);", "    i = find(strcmp(names, name));",
              "    if isempty(i)",
              f"      fprintf(2, '{p}: error: unknown symbol ''%s''; the symbols are "
              f"{', '.join(program.names) or 'none'}\\n', name);",
              "      exit(2);", "    end",
              "    x = str2double(set{a}(at + 1:end));",
              "    if ~isfinite(x)",
              f"      fprintf(2, '{p}: error: %s must be a finite number, got ''%s''\\n', "
              "name, set{a}(at + 1:end));",
              "      exit(2);", "    end", "    v(i) = x;", "  end",
              "  for i = 1:numel(names)", "    if isnan(v(i))",
              f"      fprintf(2, '{p}: error: needs a value for %s\\n', names{{i}});",
              "      exit(2);", "    end", "  end",
              f"  args = num2cell(v(1:{ns}));",
              f"  [out, status] = {p}_outputs(args{{:}});",
              "  if status ~= 0"]
    if program.checks:
        lines += [f"    reasons = {p}_refusals();",
                  f"    fprintf(2, '{p}: error: %s\\n', reasons{{status}});"]
    lines += ["    exit(2);", "  end", "  if s > 1", "    fprintf('\\n');", "  end",
              f"  keys = {p}_keys();", f"  for i = 1:{n}",
              "    fprintf('%s = %.17g\\n', keys{i}, out(i));", "  end"]
    if body.regime:
        lines += [f"  if out({n + 1}) >= 0", f"    names_ = {p}_regimes();",
                  f"    fprintf('regime = %s\\n', names_{{out({n + 1}) + 1}});", "  end"]
    lines += ["end", ""]
    return "\n".join(lines)


_WRITERS: dict[str, Callable[[Program], str]] = {
    "c": _c, "js": _js, "fortran": _fortran, "rust": _rust, "octave": _octave}


def to_code(target: Any, lang: str) -> str:
    """The text of a file in `lang` holding one function that returns every output of
    ``rigidimpact evaluate`` for `target`, and a ``main`` that prints them.

    Parameters
    ----------
    target : str, Derivation or Program
        A built-in problem's name, a scene file, a :class:`Derivation` or a
        :class:`Program` already made.
    lang : str
        One of :data:`LANGUAGES`: ``c``, ``js``, ``fortran``, ``rust``, ``octave``.

    Raises
    ------
    InputError
        For an unknown language or target.
    """
    if lang not in _WRITERS:
        raise InputError("--to", f"unknown language {lang!r}; use one of "
                         f"{', '.join(LANGUAGES)} or html")
    program = target if isinstance(target, Program) else program_of(target)
    return _WRITERS[lang](program)


def write_code(target: Any, lang: str, path: Path) -> Path:
    """:func:`to_code` written to `path` whole or not at all."""
    text = to_code(target, lang)
    return write_file(path, lambda temporary: temporary.write_text(text, encoding="utf-8"))
