"""The command line: a thin face over the layers, and the only place that prints.

Bad input gets one line on standard error naming what is wrong, and exit status 2.

Examples
--------
>>> main(["derive", "discs", "--json"])  # doctest: +ELLIPSIS
{
  "problem": "discs",
...
0
>>> main(["derive", "nonsense"])
2
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NoReturn

from rigidimpact.cli.common import (
    _check_plot_path,
    _check_workers,
    _derivation,
    _expr_json,
    _finite_json,
    _print_json,
    _settings,
)
from rigidimpact.cli.sweep import _cmd_sweep, _files_only, _progress_bar, _tasks_bar
from rigidimpact.errors import InputError

__all__ = ["main"]


class _Parser(argparse.ArgumentParser):
    """argparse that reports a usage error in one line, with exit status 2."""

    def error(self, message: str) -> NoReturn:
        print(f"{self.prog}: error: {message} (see --help)", file=sys.stderr)
        raise SystemExit(2)


def _has_regimes(d: Any) -> bool:
    # a 3-D contact's course is one of its setup lines (its cone is not Routh's diagram)
    return d.solution is not None and d.solution.contact.by_regimes and \
        not d.solution.tangent_impulses


def _regime_list(d: Any) -> list[tuple[str, tuple, Any]]:
    """(name, conditions, solution) of each course a frictional impact can take."""
    solution = d.solution
    return list(solution.regimes) or [(solution.regime, (), solution)]


def _regimes_json(d: Any) -> list[dict[str, Any]]:
    return [{"name": name, "conditions": [str(c) for c in conditions],
             "results": {k: _expr_json(v) for k, v in sol.results().items()}}
            for name, conditions, sol in _regime_list(d)]


def _print_regimes(d: Any) -> None:
    """Each course of a frictional impact: its conditions and its impulse (Routh)."""
    print("\nThe impulse by Routh's method, course by course:")
    for name, conditions, sol in _regime_list(d):
        print(f"  {name}:")
        for condition in conditions:
            print(f"      if {condition}")
        print(f"      P_n = {sol.normal_impulse}\n      P_t = {sol.tangential_impulse}")


def _checks_line(checks: dict[str, Any]) -> str:
    """One line saying how an answer's own checks came out (see Solution.checks)."""
    worst = max(checks, key=lambda k: checks[k])
    return (f"checks: {len(checks)} conditions (momentum, each contact's laws, energy) "
            "from the bodies and impulses alone; " + (
                "every residual is zero" if checks[worst] == 0 else
                f"largest residual {float(checks[worst]):.3g} ({worst})"))


def _random_of(target: str) -> Any:
    """The scene's [random] table and the scene, or (None, None)."""
    from rigidimpact.paper.problems import PROBLEMS

    if target in PROBLEMS:
        return None, None
    from rigidimpact.scenes.space import load_any

    scene = load_any(target)
    return getattr(scene, "random", None), scene


def _distributions_figure(path: Path, scene: Any, found: dict) -> None:
    """Each [random] output's histogram of draws under its exact density, to `path`."""
    _files_only()
    from rigidimpact.figures import draw_distributions

    left_out = draw_distributions(scene, path, found)
    if left_out:
        print(f"rigidimpact: note: --plot draws an output driven by one random input with "
              f"every other symbol given; left out: {', '.join(left_out)}", file=sys.stderr)


def _cmd_derive(args: argparse.Namespace) -> int:
    _check_workers(args)
    d = _derivation(args.target)
    table, scene = _random_of(args.target)
    if (args.workers is not None or args.scheduler) and not table:
        raise InputError("--workers", "only a scene with a [random] table runs on Dask")
    if args.plot:
        if not table:
            raise InputError("--plot", "derive draws the distributions of a scene's "
                             "[random] outputs: this one has no [random] table")
        _check_plot_path(Path(args.plot))
    found: dict = {}
    if table:  # numpy, scipy and Dask only where something is drawn
        from rigidimpact.analyses.distributions import (
            distributions_json,
            distributions_text,
            scene_distributions,
        )
        found = scene_distributions(scene, dict(d.results), args.workers, args.scheduler,
                                    progress=None if args.json else _tasks_bar)
        if args.plot:
            _distributions_figure(Path(args.plot), scene, found)
    from rigidimpact.outputs.latex import equation_latex, fragment, to_latex
    for warning in d.warnings:
        print(f"rigidimpact: warning: {warning}", file=sys.stderr)
    if args.json:
        _print_json({
            "problem": d.problem,
            "title": d.title,
            "equations": [{"label": eq.label, "paper": eq.paper,
                           "sympy": str(eq.as_sympy()), "latex": equation_latex(eq)}
                          for eq in d.equations],
            "unknowns": [str(u) for u in d.unknowns],
            "results": {k: _expr_json(v) for k, v in d.results.items()},
            "named": {k: _expr_json(v) for k, v in d.named.items()},
            "definitions": {k: _expr_json(v) for k, v in d.definitions.items()},
            "seconds": round(d.seconds, 4),
            "warnings": list(d.warnings),
            **({"regimes": _regimes_json(d)} if _has_regimes(d) else {}),
            **({"distributions": distributions_json(found)} if found else {}),
            **({"outcomes": [{"rule": o.rule, "order": list(o.order), "acted": list(o.acted),
                              "results": {k: _expr_json(v) for k, v in o.results().items()},
                              **({"checks": {k: str(v) for k, v in o.checks.items()},
                                  "warnings": list(o.warnings)} if o.checks else {}),
                              **({"conditions": [str(c) for c in o.conditions]}
                                 if o.conditions else {})}
                             for o in d.outcomes]} if d.outcomes else {}),
        })
        return 0
    if args.format == "latex":
        for eq in d.equations:
            print(f"% {eq.label}\n\\begin{{equation}}\n  {equation_latex(eq)}\n"
                  "\\end{equation}")
        for key in d.results:
            print(fragment(d, key), end="")
        for key, value in d.definitions.items():
            print(f"% named group\n\\begin{{equation}}\n  {key} = {to_latex(value)}\n"
                  "\\end{equation}")
        for key, entry in found.items():
            if "density" not in entry:
                continue
            low, high = entry["support"]
            lines = [f"f(y) = {to_latex(entry['density'])}, \\quad "
                     f"{to_latex(low)} < y < {to_latex(high)}",
                     f"\\mathrm{{E}}[y] = {to_latex(entry['mean'])}"]
            if "below_zero" in entry:
                lines.append(f"P(y < 0) = {to_latex(entry['below_zero'])}")
            for line in lines:
                print(f"% distribution of {key} (y), random: {', '.join(entry['random'])}"
                      f"\n\\begin{{equation}}\n  {line}\n\\end{{equation}}")
        return 0
    print(f"{d.title}  [{d.problem}]")
    for line in d.setup:
        print(f"  {line}")
    if d.outcomes:
        from rigidimpact.solve.collision import rule_laws

        print(f"\nLaws: {rule_laws(d.outcomes[0].rule, d.outcomes[0].frictional)}")
        print("\nEquations solved" + (" (every case and order):" if len(d.outcomes) > 1
                                       else ":"))
        for eq in d.equations:
            print(f"  {eq.label}:\n      {eq.lhs} = {eq.rhs}")
        print(f"for {', '.join(map(str, d.unknowns))}")
        for outcome in d.outcomes:
            print(f"\n{outcome.label} (contacts that acted: {', '.join(outcome.acted)}):")
            if outcome.courses:
                print("  courses: " + "; ".join(outcome.courses))
            if outcome.method and outcome.method not in outcome.notes:
                print(f"  solved: {outcome.method}")
            for note in outcome.notes:
                print(f"  note: {note}")
            if outcome.conditions:
                print("  when " + " and ".join(map(str, outcome.conditions)))
            for key, value in outcome.results().items():
                print(f"  {key} = {value}")
            if outcome.checks:
                print("  " + _checks_line(outcome.checks))
            for warning in outcome.warnings:
                print(f"  warning: {warning}")
        if found:
            print("\n" + "\n".join(distributions_text(table, scene.values, found)))
        print(f"\n({d.seconds:.2f} s)")
        return 0
    numbered = any(eq.paper for eq in d.equations)
    print("\nLaws (paper's equation numbers):" if numbered else "\nLaws:")
    if scene is not None and len(getattr(scene, "contacts", ())) == 1:
        print("  (in the contact's frame, from its point: x along its normal, y along its "
              "tangent,\n  the normal turned +90 degrees; the results below are in the "
              "scene's x and y)")
    for eq in d.equations:
        number = f"{eq.paper:<14} " if numbered else ""
        print(f"  {number}{eq.label}:\n      {eq.lhs} = {eq.rhs}")
    if _has_regimes(d):
        _print_regimes(d)
    print(f"\nSolved for {', '.join(map(str, d.unknowns))}:")
    for key, value in d.results.items():
        print(f"  {key} = {value}")
    for key, value in d.definitions.items():
        print(f"\nWith {key} = {value}:")
        for name, named in d.named.items():
            print(f"  {name} = {named}")
    if found:
        print("\n" + "\n".join(distributions_text(table, scene.values, found)))
    print(f"\n({d.seconds:.2f} s)")
    return 0


def _cmd_verify(args: argparse.Namespace) -> int:
    from rigidimpact.verify import run_checks

    if args.jobs is not None and not 1 <= args.jobs <= 64:
        raise InputError("--jobs", f"must lie between 1 and 64, got {args.jobs}")
    rows = run_checks(jobs=args.jobs if args.jobs is not None else (os.cpu_count() or 1))
    failed = sum(row.status != "pass" for row in rows)
    if args.json:
        _print_json({
            "checks": [{"id": r.id, "paper": r.paper, "status": r.status,
                        "description": r.description, "detail": r.detail,
                        "seconds": round(r.seconds, 4)} for r in rows],
            "passed": len(rows) - failed,
            "failed": failed,
        })
    else:
        width = max(len(r.id) for r in rows)
        for r in rows:
            print(f"{r.status.upper():<5} {r.id:<{width}}  {r.paper:<22} {r.description}")
            if r.status != "pass":
                print(f"      {r.detail}")
        print(f"{len(rows) - failed} passed, {failed} failed")
    return 1 if failed else 0


def _cmd_export_code(args: argparse.Namespace) -> int:
    """``export SCENE --to LANG --out FILE``: the derivation as code, or as a live page."""
    from rigidimpact.outputs.code import LANGUAGES, write_code

    if args.to not in (*LANGUAGES, "html"):
        raise InputError("--to", f"unknown language {args.to!r}; use one of "
                         f"{', '.join(LANGUAGES)} or html")
    if len(args.targets) != 1:
        raise InputError("--to", f"exports one problem or scene, got {len(args.targets)}")
    if args.pdf:
        raise InputError("--pdf", "goes with the LaTeX export (no --to)")
    out = Path(args.out)
    if out.is_dir():
        raise InputError("--out", f"{str(out)!r} is a folder; with --to give a file name")
    if not out.parent.is_dir():
        raise InputError("--out", f"no such folder: {str(out.parent)!r}")
    if args.to == "html":
        from rigidimpact.outputs.live import write_live

        written = write_live(args.targets[0], out)
    else:
        written = write_code(args.targets[0], args.to, out)
    if args.json:
        _print_json([str(written)])
    else:
        print(written)
    return 0


def _cmd_export(args: argparse.Namespace) -> int:
    if args.to is not None:
        return _cmd_export_code(args)
    from rigidimpact.outputs.latex import PDFLATEX_PACKAGE, write_export
    from rigidimpact.paper.problems import PROBLEMS
    from rigidimpact.verify import run_checks

    targets = args.targets or list(PROBLEMS)
    derivations = [_derivation(t) for t in targets]
    checks = run_checks() if not args.targets else []
    try:
        written = write_export(Path(args.out), derivations, checks, pdf=args.pdf)
    except RuntimeError as exc:
        raise InputError("--pdf", str(exc)) from None
    if args.json:
        _print_json([str(p) for p in written])
    else:
        for path in written:
            print(path)
    if args.pdf and not any(p.suffix == ".pdf" for p in written):  # no pdflatex here
        print(f"rigidimpact: note: no PDF: it needs pdflatex, which is not installed "
              f"(Debian: apt-get install {PDFLATEX_PACKAGE}); derivations.tex is written",
              file=sys.stderr)
    return 0


def _evaluation(target: str, settings: Sequence[str], dps: int | None,
                exact: bool = False):
    """Evaluate a problem or scene at its [values], overridden by each --set NAME=VALUE
    (with `exact`, each result as an exact number too)."""
    from rigidimpact.paper.problems import PROBLEMS
    from rigidimpact.scenes.space import load_any

    if target in PROBLEMS:
        derivation = _derivation(target)
        values, sources = _settings({}, settings)
        return derivation.evaluate(values, dps, sources, exact)
    scene = load_any(target)
    values, sources = _settings(scene.values, settings)
    return scene.evaluate(values, sources, dps, exact)


def _is_rounded(x: Any) -> bool:
    """Whether an exact result is a rounded one after all (a rule solved in floats)."""
    import sympy as sp

    return isinstance(x, sp.Basic) and x.has(sp.Float)


def _cmd_evaluate(args: argparse.Namespace) -> int:
    import mpmath

    if args.dps is not None and not 5 <= args.dps <= 10000:
        raise InputError("--dps", f"must lie between 5 and 10000, got {args.dps}")
    if args.plot:
        _check_plot_path(Path(args.plot))
    result = _evaluation(args.target, args.set, args.dps, args.exact)
    if args.plot:
        if "sample" not in result.extra:
            raise InputError("--plot", "evaluate draws the spread of a sample of orders: "
                             "give the scene rule = \"sequential\", orders = N, seed = S")
        from rigidimpact.outputs.atomic import write_file
        _files_only()
        from rigidimpact.figures import close
        from rigidimpact.outputs.plots import order_spread

        rows = [row["results"] for row in result.extra["orders"]]
        figure = order_spread(rows, result.extra["sample"])
        write_file(Path(args.plot), lambda temporary: figure.savefig(temporary, format="png"),
                   "--plot")
        close(figure)

    def literal(x: Any) -> str:  # a float's repr, or an mpmath number beyond float64
        if isinstance(x, float):
            return repr(x)
        return mpmath.nstr(x, args.dps or 17, min_fixed=-3, max_fixed=3)

    for warning in result.warnings:
        print(f"rigidimpact: warning: {warning}", file=sys.stderr)
    if args.json:  # full-precision JSON number literals (mpmath values are not floats)
        body = [f"  {json.dumps(k)}: {literal(v)}" for k, v in result.numbers.items()]
        if result.regime is not None:
            body.append(f'  "regime": {json.dumps(result.regime)}')
        body += [f"  {json.dumps(k)}: {json.dumps(_finite_json(v))}"
                 for k, v in result.extra.items()]
        if result.warnings:
            body.append(f'  "warnings": {json.dumps(list(result.warnings))}')
        if result.exact is not None:
            body.append(f'  "exact": {json.dumps({k: str(v) for k, v in result.exact.items()})}')
        print("{\n" + ",\n".join(body) + "\n}")
    else:
        for key, value in result.numbers.items():
            if result.exact is not None and not _is_rounded(result.exact[key]):
                print(f"{key} = {result.exact[key]}  ({literal(value)})")
                continue
            print(f"{key} = {literal(value)}")
        if result.regime is not None:
            print(f"regime = {result.regime}")
        if result.extra and len(result.extra.get("orders", ())) > 1:
            count = len(result.extra["orders"])
            shown = result.extra["rule"].split(" ", 1)[-1]
            print(f"rule = sequential in {count} orders (every order, or the sample "
                  f"asked for; the numbers above are the first order's, {shown}: see "
                  f"--json \"orders\" for each); contacts that acted there: "
                  f"{', '.join(result.extra['acted']) or 'none'}")
        elif "rule" in result.extra:
            print(f"rule = {result.extra['rule']}; contacts that acted: "
                  f"{', '.join(result.extra['acted']) or 'none'}")
        if result.extra.get("checks"):
            print(_checks_line(result.extra["checks"]))
            if "courses" in result.extra:
                print(f"courses: {'; '.join(result.extra['courses'])}")
            if "sample" in result.extra:
                sample = result.extra["sample"]
                print(f"a sample of {sample['orders']} orders (seed {sample['seed']}, "
                      f"{sample['distinct']} distinct), not every order; spread:")
                for key, (low, high) in result.extra["spread"].items():
                    print(f"  {key}: {low:.10g} .. {high:.10g}")
                return 0
            for row in result.extra.get("orders", ()):
                shown = ", ".join(f"{k} = {v:.10g}" for k, v in row["results"].items()
                                  if not k.endswith("tangential_impulse"))
                print(f"  order {', '.join(row['order'])}: {shown}")
    return 0


def _cmd_routh(args: argparse.Namespace) -> int:
    """The impulse path of a Coulomb contact at the scene's values, as numbers or a PNG."""
    from rigidimpact.laws.routh import diagram
    from rigidimpact.scenes.scene import load_scene

    scene = load_scene(args.scene)
    if args.plot:
        _check_plot_path(Path(args.plot))
    values, sources = _settings(scene.values, args.set)
    derivation = scene.derivation()
    exact = derivation.checked(values, sources)
    found = diagram(scene.impact(), {derivation.symbols[k]: v for k, v in exact.items()})
    if args.plot:
        from rigidimpact.outputs.atomic import write_file
        _files_only()
        from rigidimpact.figures import close
        from rigidimpact.outputs.plots import routh_diagram

        figure = routh_diagram(found, scene.title)
        write_file(Path(args.plot), lambda temporary: figure.savefig(temporary, format="png"),
                   "--plot")
        close(figure)
    path = [[float(a), float(b)] for a, b in found.regime.path]
    if args.json:
        _print_json({"regime": found.regime.name, "law": found.law, "mu": float(found.mu),
                     "e": float(found.e), "path": path,
                     "W": [[float(x) for x in row] for row in found.W.tolist()],
                     "v_before": [float(x) for x in found.v_before]})
    elif not args.plot:
        print(f"regime: {found.regime.name} ({found.law} restitution, e = "
              f"{float(found.e):g}, mu = {float(found.mu):g})")
        for p_n, p_t in path:
            print(f"  P_n = {p_n:.10g}  P_t = {p_t:.10g}")
    return 0


def _cmd_stability(args: argparse.Namespace) -> int:
    from rigidimpact.analyses.stability import run_suite

    report = run_suite()
    if args.json:
        _print_json(report)
    else:
        print(f"{report['cases']} cases; errors relative to each quantity's magnitude "
              f"(bound {report['bound']:.0e})")
        for row in report["rows"]:
            print(f"  {row['problem']:>10} {row['quantity']:<22} cases {row['cases']:>5}  "
                  f"scaled {row['scaled_error']:.1e}  relative {row['rel_error']:.1e}  "
                  f"condition {row['condition']:.1e}  {'ok' if row['passed'] else 'FAIL'}")
        worst = report["worst"]
        print(f"worst: {worst['quantity']} {worst['rel_error']:.2e}")
    return 0 if all(row["passed"] for row in report["rows"]) else 1


def _raw_json(data: Any, numbers: dict[str, str]) -> str:
    """JSON text in which the values under `numbers`' keys are written as given literals."""
    marked = {key: f"@@{key}@@" for key in numbers}
    text = json.dumps({k: marked.get(k, v) for k, v in data.items()}, indent=2)
    for key, literal in numbers.items():
        text = text.replace(json.dumps(marked[key]), literal)
    return text


def _cmd_critical_angle(args: argparse.Namespace) -> int:
    import mpmath

    from rigidimpact.analyses.restrike import critical_angle
    from rigidimpact.outputs.latex import to_latex

    result = critical_angle(args.e, args.mass_ratio)
    digits = args.digits
    if not 5 <= digits <= 35:
        raise InputError("--digits", f"must lie between 5 and 35, got {digits}")

    def literal(x: Any) -> str:
        return "null" if x is None else mpmath.nstr(x, digits, min_fixed=-3, max_fixed=4)

    equation = result.equation
    if args.json:
        windows = "[" + ", ".join(f"[{literal(lo)}, {literal(hi)}]"
                                  for lo, hi in result.windows_deg) + "]"
        edges = [[{"deg": f"@{id(x)}", "kind": x.kind,
                   "equation": None if x.equation is None else _expr_json(x.equation)}
                  for x in pair] for pair in result.windows]
        text = _raw_json({"e": str(result.restitution), "mass_ratio": str(result.mass_ratio),
                          "theta_c_deg": None, "theta_c_rad": None,
                          "equation": {"sympy": str(equation), "latex": to_latex(equation)},
                          "windows_deg": None, "edges": edges},
                         {"theta_c_deg": literal(result.theta_c_deg),
                          "theta_c_rad": literal(result.theta_c), "windows_deg": windows})
        for pair in result.windows:  # each edge's degrees, as a number literal too
            for x in pair:
                text = text.replace(json.dumps(f"@{id(x)}"), literal(x.deg))
        print(text)
        return 0
    print(f"e = {result.restitution}, m/M = {result.mass_ratio}")
    print(f"critical angle: {literal(result.theta_c_deg)} deg "
          f"({literal(result.theta_c)} rad)" if result.theta_c is not None
          else "critical angle: none (no window starts below 90 deg with an outrace edge)")
    print(f"equation: {equation}")
    if not result.windows:
        print("no re-strike at any initial angle in (0, 180) deg")
    for lo, hi in result.windows:
        print(f"re-strike for theta in [{literal(lo.deg)}, {literal(hi.deg)}] deg "
              f"({lo.kind} .. {hi.kind})")
    return 0


def _cmd_simulate(args: argparse.Namespace) -> int:
    from rigidimpact.scenes.space import SpaceScene, load_any
    from rigidimpact.simulate import explain, run

    scene = load_any(args.scene)
    if isinstance(scene, SpaceScene):
        return _simulate_space(scene, args)
    if args.set:
        values, sources = _settings({}, args.set)
        scene = scene.with_values(values, sources)
    if args.plot:
        _check_plot_path(Path(args.plot))
    if args.animate:
        _check_plot_path(Path(args.animate), (".gif", ".mp4"), "--animate")
    if args.explain:
        print(explain(scene))
        if not args.json and not args.plot:
            return 0
    outcome = run(scene)
    _said_and_drawn(args, scene, outcome, "outcome")
    if args.json:
        _print_json(outcome.as_json())
        return 0
    for event in outcome.events:
        extra = ", ".join(f"{k} {', '.join(v) if k in ('acted', 'contacts') else v}"
                          for k, v in event.items() if k not in ("kind", "t", "why"))
        print(f"t = {event['t'] + 0.0:.12g}: {event['kind']}"  # + 0.0: no "-0"
              + (f" ({extra})" if extra else "")
              + (f": {event['why']}" if "why" in event else ""))
    for key, value in outcome.final.items():
        print(f"{key} = {value + 0.0 if isinstance(value, float) else value!r}")
    if "rule" in outcome.details:
        print(f"rule = {outcome.details['rule']}; contacts that acted: "
              f"{', '.join(outcome.details['acted']) or 'none'}")
    if "rigid" in outcome.details:  # tangential compliance: the rigid contact beside it
        print("the rigid contact gives: " + ", ".join(
            f"{key} = {value:.10g}" for key, value in outcome.details["rigid"].items()))
    print(f"cost: {outcome.wall_s:.3g} s wall, {outcome.ode_steps} ODE steps")
    return 0


def _simulate_space(scene: Any, args: argparse.Namespace) -> int:
    """``simulate`` of a 3-D scene: the impact, or a sphere's tangentially compliant
    bounce, until separation; past it, a sphere's bounces among fixed planes, with its
    path drawn from above and from the side (``--plot``) and animated (``--animate``)."""
    from rigidimpact.simulate.planner import goes_past_impact, make_plan
    from rigidimpact.simulate.space import run_space
    from rigidimpact.solve.derivation import read_values

    past = goes_past_impact(scene.simulate)
    for option, path, suffixes in (("--plot", args.plot, (".png",)),
                                   ("--animate", args.animate, (".gif",))):
        if path and not past:
            raise InputError(option, "this 3-D run ends at the impact (until = "
                             "\"separation\"): nothing moves to draw; give [simulate] "
                             "until a time or impacts a count")
        if path:
            _check_plot_path(Path(path), suffixes, option)
    settings, sources = _settings(scene.values, args.set or [])
    values = read_values(settings, dict(sources), scene.data_symbols, (), scene.name)
    if args.explain:
        print(make_plan(scene.simulate).explain())
        if not args.json:
            return 0
    outcome = run_space(scene, values)
    _said_and_drawn(args, scene, outcome, "space")
    if args.json:
        _print_json(outcome.as_json())
        return 0
    for event in outcome.events:
        print(f"t = {event['t'] + 0.0:.12g}: "
              + (f"{event['ball']} " if "ball" in event else "") + event["kind"]
              + (f" on {event['with']} ({event['plane']})" if "with" in event else
                 f" on {event['plane']}" if "plane" in event else "")
              + (f" ({event['course']})" if event.get("course") else "")
              + (f": {event['why']}" if "why" in event else ""))
    for note in outcome.details.get("notes", ()):
        print(f"note: {note}")
    for key, value in outcome.final.items():
        print(f"{key} = {value + 0.0 if isinstance(value, float) else value!r}")
    if "rigid" in outcome.details and scene.simulate.get("effects"):
        print("the rigid contact gives: " + ", ".join(
            f"{key} = {value:.10g}" for key, value in outcome.details["rigid"].items()))
    print(f"cost: {outcome.wall_s:.3g} s wall, {outcome.ode_steps} ODE steps")
    return 0


def _said_and_drawn(args: argparse.Namespace, scene: Any, outcome: Any, kind: str) -> None:
    """A run's warnings on stderr, and its figure and animation where asked (`kind`:
    ``"outcome"``, a planar run; ``"space"``, a 3-D one)."""
    for warning in outcome.details.get("warnings", ()):
        print(f"rigidimpact: warning: {warning}", file=sys.stderr)
    if not (args.plot or args.animate):
        return
    _files_only()
    from rigidimpact import figures

    plot, animate = ((figures.plot_space, figures.animate_space) if kind == "space" else
                     (figures.plot_outcome, figures.animate_outcome))
    if args.plot:
        plot(scene, outcome, Path(args.plot))
        print(f"rigidimpact: figure written to {args.plot}", file=sys.stderr)
    if args.animate:
        animate(scene, outcome, Path(args.animate))
        print(f"rigidimpact: animation written to {args.animate}", file=sys.stderr)


def _cmd_bench(args: argparse.Namespace) -> int:
    _files_only()
    from rigidimpact.analyses.bench import run_bench, write_outputs

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise InputError("--out", f"not a folder: {str(out)!r}")
    try:  # before the long run, not after it
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError("--out", f"cannot make {str(out)!r}: {exc.strerror or exc}") from None
    if not os.access(out, os.W_OK | os.X_OK):
        raise InputError("--out", f"cannot write in {str(out)!r} (permission denied)")
    from rigidimpact.analyses.bench import FAMILIES

    unknown = [f for f in args.family if f not in FAMILIES]
    if unknown:
        raise InputError("--family", f"unknown family {unknown[0]!r}; the families are "
                         f"{', '.join(FAMILIES)}")
    report = run_bench(quick=args.quick, families=args.family or FAMILIES,
                       progress=_progress_bar)
    try:
        paths = write_outputs(report, out)
    except OSError as exc:
        raise InputError("--out", f"cannot write the bench there: {exc.strerror or exc}") \
            from None
    if args.json:
        _print_json({k: v for k, v in report.items()})
        return 0
    print(paths[1].read_text(encoding="utf-8"))
    print("\n".join(f"wrote {p}" for p in paths))
    return 0


def _build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="rigidimpact",
                     description="Derive, verify and simulate impulsive collisions of "
                                 "rigid bodies, in the plane and in space (after Mungan, "
                                 "Eur. J. Phys. 28, 2007).")
    parser.add_argument("--version", action=_Version, nargs=0,
                        help="show the program's version number and exit")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    p = sub.add_parser("derive", help="derive a collision symbolically")
    p.add_argument("target", metavar="NAME-OR-SCENE",
                   help="barbell, sticking, discs, two-body, or a scene file")
    p.add_argument("--format", choices=("text", "latex"), default="text")
    p.add_argument("--json", action="store_true")
    p.add_argument("--workers", type=int, metavar="N",
                   help="a scene's [random] Monte Carlo on N local Dask workers where "
                        "its draws repay them (else here, said): the same answer")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="... or on the Dask cluster at ADDRESS (tcp://host:8786)")
    p.add_argument("--plot", metavar="PNG", help="a scene with [random]: each output's "
                   "histogram of draws under its exact density, to this PNG file")
    p.set_defaults(run=_cmd_derive)

    p = sub.add_parser("verify", help="check every result of the paper")
    p.add_argument("--jobs", type=int, metavar="N",
                   help="worker processes (default: one per core; 1 runs in this process)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=_cmd_verify)

    p = sub.add_parser("export", help="write LaTeX fragments and a whole document; with "
                                      "--to, one derivation as code or as a live page")
    p.add_argument("targets", nargs="*", metavar="NAME-OR-SCENE",
                   help="what to export (default: every built-in problem)")
    p.add_argument("--out", required=True, metavar="DIR-OR-FILE",
                   help="the folder of the LaTeX export; with --to, the file written")
    p.add_argument("--to", metavar="LANG",
                   help="c, js, fortran, rust, octave: one function returning every "
                        "output of evaluate, and a main; html: a live page with a slider "
                        "per symbol (one self-contained file)")
    p.add_argument("--pdf", action="store_true",
                   help="also compile with pdflatex where it is installed (Debian: "
                        "texlive-latex-base); without it the .tex is written and a note "
                        "says so")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=_cmd_export)

    p = sub.add_parser("evaluate", help="evaluate the results numerically")
    p.add_argument("target", metavar="NAME-OR-SCENE")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a value for a symbol (repeat); a scene's [values] are defaults")
    p.add_argument("--dps", type=int, help="mpmath with this many significant digits")
    p.add_argument("--exact", action="store_true",
                   help="each result also as an exact number (rationals, roots), the "
                   "scene's decimals read as the fractions they write (0.3 is 3/10); a "
                   "result solved in floating point is printed as the float it is")
    p.add_argument("--json", action="store_true")
    p.add_argument("--plot", metavar="PNG", help="with a sample of orders: a histogram of "
                   "each output that varies over it")
    p.set_defaults(run=_cmd_evaluate)

    p = sub.add_parser("routh", help="Routh's diagram of a scene's frictional contact")
    p.add_argument("scene", metavar="SCENE")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a value for a symbol (repeat); a scene's [values] are defaults")
    p.add_argument("--plot", metavar="FILE", help="draw the diagram to a PNG file")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=_cmd_routh)

    p = sub.add_parser("critical-angle", help="the re-strike analysis of section 2")
    p.add_argument("--e", default="0", metavar="E", help="restitution in [0, 1] (default 0)")
    p.add_argument("--mass-ratio", default="1", metavar="R", help="m/M (default 1)")
    p.add_argument("--digits", type=int, default=30, help="significant digits printed")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=_cmd_critical_angle)

    p = sub.add_parser("simulate", help="run the model a scene's [simulate] table asks for")
    p.add_argument("scene", metavar="SCENE")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a value for a symbol (repeat); a scene's [values] are defaults")
    p.add_argument("--explain", action="store_true", help="print the plan")
    p.add_argument("--plot", metavar="FILE", help="draw the trajectories to a PNG file")
    p.add_argument("--animate", metavar="FILE",
                   help="animate the motion to a GIF (or MP4 where ffmpeg exists)")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=_cmd_simulate)

    p = sub.add_parser("bench", help="accuracy against time for every method")
    p.add_argument("--quick", action="store_true", help="a smaller grid (under 2 minutes)")
    p.add_argument("--family", action="append", default=[], metavar="NAME",
                   help="only this family of methods (repeat); the throughput of the "
                        "fused kernels is always measured")
    p.add_argument("--out", default="build/bench", metavar="DIR")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=_cmd_bench)

    p = sub.add_parser("sweep", help="every result over a grid of parameter sets, into "
                                     ".npy files (chunked, bounded memory), a CSV table "
                                     "and, with --plot, a figure")
    p.add_argument("target", metavar="NAME-OR-SCENE")
    p.add_argument("--grid", action="append", default=[], metavar="NAME=START:STOP:COUNT",
                   help="a range for a symbol (repeat; the grid is their product)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a value for a symbol (repeat); a scene's [values] are defaults")
    p.add_argument("--keys", metavar="KEY,KEY", help="only these results (default: all)")
    p.add_argument("--backend", default="numpy", choices=("numpy", "numba"),
                   help="numba (an optional extra): a compiled loop over the cores")
    p.add_argument("--out", required=True, metavar="DIR",
                   help="the folder written whole: KEY.npy, summary.json and table.csv "
                        "(one row a set, up to 1e6 sets)")
    p.add_argument("--plot", metavar="PNG", help="draw each result against the swept "
                   "symbol (one --grid) to a PNG file")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--workers", type=int, metavar="N",
                   help="on N local Dask workers where the sets repay them (else "
                        "here, said), 2^20 sets a task: the same numbers")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="... or on the Dask cluster at ADDRESS (tcp://host:8786)")
    p.set_defaults(run=_cmd_sweep)

    p = sub.add_parser("stability", help="the hard-case suite against mpmath references")
    p.add_argument("--json", action="store_true")
    p.set_defaults(run=_cmd_stability)
    return parser


class _Version(argparse.Action):
    """``--version``: the installed version, read from the package's metadata only when
    asked (reading it costs every other command's start)."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> NoReturn:
        print(f"rigidimpact {_version()}")
        parser.exit()


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("rigidimpact")
    except PackageNotFoundError:
        return "unknown"


def _cached(args: argparse.Namespace, argv: list[str]) -> int:
    """`derive`, answered from the cache of derivations already made where it holds this
    one (:mod:`rigidimpact.outputs.cache`), else run and kept."""
    import contextlib
    import io

    from rigidimpact.outputs import cache

    name = cache.key(argv, args.target) if cache.folder() is not None else None
    if name is None:
        return args.run(args)
    kept = cache.replay(name)
    if kept is not None:
        sys.stdout.write(kept[0])
        sys.stderr.write(kept[1])
        return 0
    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = args.run(args)
    finally:  # what was printed is shown, whatever happened
        sys.stdout.write(out.getvalue())
        sys.stderr.write(err.getvalue())
    if status == 0:
        cache.store(name, out.getvalue(), err.getvalue())
    return status


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status.

    Bad input ends in one line on standard error and status 2; Ctrl-C in one line and
    status 130; a closed output pipe (``| head``) quietly. An unexpected error is one
    line too (set ``RIGIDIMPACT_DEBUG=1`` for the traceback), status 70.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).
    """
    parser = _build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        return int(exc.code or 0)
    try:
        if args.run is _cmd_derive and args.workers is None and not args.scheduler:
            return _cached(args, list(sys.argv[1:] if argv is None else argv))
        return args.run(args)
    except InputError as exc:
        print(f"rigidimpact: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("rigidimpact: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # the reader went away (| head): say nothing, and keep Python from complaining
        # when it flushes standard output at exit
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 141
    except (RecursionError, MemoryError) as exc:
        print(f"rigidimpact: error: the input is too large or deeply nested to handle "
              f"({type(exc).__name__})", file=sys.stderr)
        return 2
    except Exception as exc:  # one line for the user; the traceback on request
        if os.environ.get("RIGIDIMPACT_DEBUG"):
            raise
        message = " ".join(str(exc).split())[:300]
        print(f"rigidimpact: internal error: {type(exc).__name__}: {message} (please "
              "report it; RIGIDIMPACT_DEBUG=1 shows the traceback)", file=sys.stderr)
        return 70

