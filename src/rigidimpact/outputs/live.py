"""A derivation as a live page: one self-contained HTML file, a slider per symbol.

The page evaluates the scene in the browser with the JavaScript export
(:mod:`rigidimpact.outputs.code`): nothing is computed by Python for given slider
positions, nothing is fetched (a Content-Security-Policy forbids any request), and the
formulas are typeset by the browser itself from MathML, which SymPy prints: no font or
script is downloaded or vendored. The page shows every output as a number, the
formulas, the bodies before and after the impact with their velocities, and their
free flight after it; for the paper's barbell, the flight to the re-strike and the
critical angle below which the barbell strikes the ball again, found in the page from
the same exported function.

Examples
--------
>>> page = live_page("sticking")
>>> page.startswith("<!DOCTYPE html>"), "http://" in page.replace("http://www.w3.org", "")
(True, False)
"""

from __future__ import annotations

import html
import json
import math
from pathlib import Path
from typing import Any

import sympy as sp
from sympy.functions.elementary.trigonometric import TrigonometricFunction
from sympy.printing.mathml import MathMLPresentationPrinter

from rigidimpact.outputs.atomic import write_file
from rigidimpact.outputs.code import Program, program_of, resolve_target, to_code

__all__ = ["live_page", "write_live", "slider_ranges", "drawing_program"]

_MAX_MATHML = 6000  # a formula longer than this (as MathML) is not typeset, but said


def slider_ranges(program: Program) -> dict[str, tuple[float, float]]:
    """Each symbol's slider range: around its value (a tenth of it to twice it), within
    what its role allows (a restitution coefficient's [0, 1])."""
    bounds: dict[str, list[float]] = {}
    for _, condition in program.checks:
        for rel in ([condition] if not isinstance(condition, sp.And) else condition.args):
            if isinstance(rel, sp.Rel) and rel.lhs.is_Symbol and rel.rhs.is_number:
                low, high = bounds.setdefault(rel.lhs.name, [-math.inf, math.inf])
                if rel.rel_op in (">", ">="):
                    bounds[rel.lhs.name][0] = max(low, float(rel.rhs))
                else:
                    bounds[rel.lhs.name][1] = min(high, float(rel.rhs))
    angles = {s.name for x in program.formulas.values()
              for f in x.atoms(sp.sin, sp.cos, sp.tan) for s in f.free_symbols}
    ranges = {}
    for name in program.names:
        v = program.defaults.get(name, 1.0)
        low, high = (v / 10, 2 * v) if v > 0 else (2 * v, v / 10) if v < 0 else (-1.0, 1.0)
        if name in angles and 0 < v < math.pi / 2:  # an angle: the whole quarter turn
            low, high = math.pi / 360, math.pi / 2
        lo_bound, hi_bound = bounds.get(name, [-math.inf, math.inf])
        if lo_bound == 0 and hi_bound == 1:  # a coefficient in [0, 1]: the whole of it
            low, high = 0.0, 1.0
        low, high = max(low, lo_bound), min(high, hi_bound)
        if v == 0 and lo_bound >= 0:
            low, high = 0.0, 1.0 if hi_bound > 1 else hi_bound
        ranges[name] = (low, high)
    return ranges


def _solution(target: Any) -> Any:
    derivation = resolve_target(target)[0]
    solution = derivation.solution
    if solution is None and derivation.outcomes:
        solution = derivation.outcomes[0]
    return derivation, solution


def drawing_program(program: Program, target: Any) -> tuple[Program, list[dict[str, Any]]]:
    """The numbers the page draws with, as a second exported function: each free body's
    centre, its parts, its velocity and spin before and after; and the bodies' layout."""
    _, solution = _solution(target)
    outputs: dict[str, sp.Expr] = {}
    bodies: list[dict[str, Any]] = []
    if solution is None or any(len(b.position) != 2 for b in solution.before):
        return program, []
    used = set(program.symbols)
    for before, after in zip(solution.before, solution.after, strict=True):
        if before.support == "fixed":
            continue
        values = {"x": before.position[0], "y": before.position[1],
                  "vx": before.velocity[0], "vy": before.velocity[1], "w": before.spin,
                  "vx2": after.velocity[0], "vy2": after.velocity[1], "w2": after.spin}
        parts = [p for p in before.parts if p.label != before.name]
        for i, part in enumerate(parts):
            values[f"p{i}x"], values[f"p{i}y"] = part.position[0], part.position[1]
        dims = dict(before.dimensions)
        if "radius" in dims:
            values["r"] = dims["radius"]
        exprs = {k: sp.sympify(v) for k, v in values.items()}
        if not all(x.free_symbols <= used for x in exprs.values()):
            return program, []
        outputs |= {f"{before.name}.{k}": v for k, v in exprs.items()}
        bodies.append({"name": before.name, "parts": len(parts), "radius": "r" in values,
                       "shape": before.shape, "pivot": before.pivot is not None})
    drawing = Program(name=program.name + "_drawing", title=program.title,
                      target=program.target, symbols=program.symbols,
                      defaults=program.defaults, outputs=outputs)
    return drawing, bodies


def _surfaces(target: Any, program: Program) -> list[list[float]]:
    """Fixed surfaces at the scene's values: a contact with a fixed body, as its point and
    normal (numbers: a floor or a wall does not move with the sliders)."""
    derivation, solution = _solution(target)
    if solution is None:
        return []
    fixed = {b.name for b in solution.before if b.support == "fixed"}
    at = {s: program.defaults.get(s.name, 1.0) for s in program.symbols}
    found = []
    for contact in solution.contacts:
        if contact.bodies and (contact.second in fixed or contact.first in fixed):
            try:
                found.append([float(sp.sympify(x).xreplace(at)) for x in
                              (*contact.point[:2], *contact.normal[:2])])
            except (TypeError, ValueError):
                continue
    return found


class _Presentation(MathMLPresentationPrinter):
    """SymPy's MathML, with a trigonometric function's whole power written on its name,
    as a textbook writes it (sin^2 theta, not sin(theta)^2)."""

    def _print_Pow(self, e: sp.Pow) -> Any:
        base, power = e.base, e.exp
        if isinstance(base, TrigonometricFunction) and power.is_Integer and power > 1:
            row = self.dom.createElement("mrow")
            named = self.dom.createElement("msup")
            name = self.dom.createElement("mi")
            name.appendChild(self.dom.createTextNode(type(base).__name__))
            named.appendChild(name)
            named.appendChild(self._print(power))
            row.appendChild(named)
            applied = self.dom.createElement("mo")
            applied.appendChild(self.dom.createTextNode("\u2061"))  # function application
            row.appendChild(applied)
            row.appendChild(self._print(base.args[0]) if base.args[0].is_Atom else
                            self._paren(base.args[0]))
            return row
        return super()._print_Pow(e)

    def _print_TrigonometricFunction(self, e: Any) -> Any:
        if not e.args[0].is_Atom:
            return super()._print_Function(e)
        row = self.dom.createElement("mrow")  # sin theta: no brackets round a symbol
        name = self.dom.createElement("mi")
        name.appendChild(self.dom.createTextNode(type(e).__name__))
        applied = self.dom.createElement("mo")
        applied.appendChild(self.dom.createTextNode("\u2061"))
        for part in (name, applied, self._print(e.args[0])):
            row.appendChild(part)
        return row

    # SymPy's printer looks a function's method up by the function's own name
    _print_sin = _print_cos = _print_tan = _print_cot = _print_sec = _print_csc = \
        _print_TrigonometricFunction

    def _paren(self, x: sp.Expr) -> Any:
        fenced = self.dom.createElement("mrow")
        for text, part in (("(", None), (None, x), (")", None)):
            if part is None:
                bracket = self.dom.createElement("mo")
                bracket.appendChild(self.dom.createTextNode(text))
                fenced.appendChild(bracket)
            else:
                fenced.appendChild(self._print(part))
        return fenced


def _formula(key: str, expr: sp.Expr) -> str:
    text = _Presentation().doprint(expr)
    if len(text) > _MAX_MATHML:
        return ("<span class='long'>a formula too long to typeset here "
                f"({sp.count_ops(expr)} operations); the export holds it whole</span>")
    name = f"<mtext>{html.escape(key)}</mtext>"
    return (f'<math display="block"><mrow>{name}<mo>=</mo>{text}</mrow></math>')


_STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.2em auto; max-width: 1200px;
       padding: 0 1em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.15em; margin-top: 1.4em; }
.grid { display: grid; grid-template-columns: repeat(auto-fit, minmax(380px, 1fr));
        gap: 1.5em; }
.slider { display: grid; grid-template-columns: 6em 1fr 8em; gap: .5em;
          align-items: center; margin: .3em 0; }
.slider input[type=number] { width: 8em; }
table.outputs { border-collapse: collapse; font-variant-numeric: tabular-nums; }
table.outputs td { padding: .15em .8em; border-bottom: 1px solid #ddd; }
td.value { text-align: right; font-family: ui-monospace, monospace; }
#refused { color: #a00; font-weight: bold; min-height: 1.2em; }
.formulas { overflow-x: auto; } .formulas math { margin: .4em 0; font-size: 1.1em; }
.note { color: #555; font-size: .9em; } svg { border: 1px solid #ccc; background: #fcfcfc; }
.long { color: #555; font-style: italic; }
"""

_PAGE_SCRIPT = r"""
"use strict";
const NAME = %(name)s;
const RANGES = %(ranges)s;
const BODIES = %(bodies)s;
const SURFACES = %(surfaces)s;
const BARBELL = %(barbell)s;
const fn = %(fn)s;
const draw_fn = %(draw_fn)s;
const symbols = %(symbols)s;
const state = {};

function values() { return symbols.map((s) => state[s]); }

function shown(x) {
  if (typeof x !== "number") { return String(x); }
  if (!Number.isFinite(x)) { return "no value (outside every case)"; }
  return Number(x.toPrecision(10)).toString();
}

function bodiesAt(v) {
  if (!draw_fn) { return []; }
  const d = draw_fn(...v);
  return BODIES.map((b) => {
    const g = (k) => d[b.name + "." + k];
    const parts = [];
    for (let i = 0; i < b.parts; i++) { parts.push([g("p" + i + "x"), g("p" + i + "y")]); }
    return { name: b.name, x: g("x"), y: g("y"), vx: g("vx"), vy: g("vy"), w: g("w"),
             vx2: g("vx2"), vy2: g("vy2"), w2: g("w2"), r: b.radius ? g("r") : null,
             parts: parts, pivot: b.pivot };
  });
}

// a body's points at time t of free flight after the impact (its parts turn with it)
function flown(b, t) {
  const c = Math.cos(b.w2 * t), s = Math.sin(b.w2 * t);
  const x = b.x + b.vx2 * t, y = b.y + b.vy2 * t;
  return { x: x, y: y, parts: b.parts.map(([px, py]) => {
    const dx = px - b.x, dy = py - b.y;
    return [x + c * dx - s * dy, y + s * dx + c * dy];
  }) };
}

// the barbell: the first time after the impact at which the rod meets the ball again
// (the ball on the segment between the spheres), within one turn; null if none
function restrike(ball, bar) {
  if (!(Math.abs(bar.w2) > 0)) { return null; }
  const turn = 2 * Math.PI / Math.abs(bar.w2);
  const steps = 4000;
  const side = (t) => {
    const f = flown(bar, t), p = [ball.x + ball.vx2 * t, ball.y + ball.vy2 * t];
    const [a, b] = f.parts;
    const ux = b[0] - a[0], uy = b[1] - a[1];
    const along = ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / (ux * ux + uy * uy);
    return [ux * (p[1] - a[1]) - uy * (p[0] - a[0]), along];
  };
  let t0 = turn * 1e-6, [s0] = side(t0);
  for (let i = 1; i <= steps; i++) {
    const t1 = turn * i / steps;
    const [s1, along1] = side(t1);
    if (s0 * s1 <= 0) {
      let lo = t0, hi = t1;
      for (let k = 0; k < 80; k++) {
        const mid = (lo + hi) / 2;
        if (side(lo)[0] * side(mid)[0] <= 0) { hi = mid; } else { lo = mid; }
      }
      const along = side(hi)[1];
      if (along >= -1e-12 && along <= 1 + 1e-12) { return hi; }
    }
    t0 = t1; s0 = s1;
  }
  return null;
}

// the critical angle: the upper end of the lowest window of initial angles (below 90
// degrees) in which the barbell strikes the ball again, found by a scan and bisection
// on the exported function's answers (null: no window ends below 90 degrees)
function criticalAngle(v) {
  const at = symbols.indexOf(BARBELL.angle);
  const hits = (theta) => {
    const w = v.slice(); w[at] = theta;
    const bs = bodiesAt(w);
    return restrike(bs[BARBELL.ball], bs[BARBELL.bar]) !== null;
  };
  const n = 90, top = Math.PI / 2;
  let first = -1;
  for (let i = 1; i < n; i++) {
    const hit = hits(top * i / n);
    if (hit && first < 0) { first = i; }
    if (!hit && first >= 0) {
      let lo = top * (i - 1) / n, hi = top * i / n;
      for (let k = 0; k < 50; k++) {
        const mid = (lo + hi) / 2;
        if (hits(mid)) { lo = mid; } else { hi = mid; }
      }
      return (lo + hi) / 2;
    }
  }
  return null;
}

function svgEl(tag, attrs) {
  const el = document.createElementNS("http://www.w3.org/2000/svg", tag);
  for (const [k, x] of Object.entries(attrs)) { el.setAttribute(k, x); }
  return el;
}

// the motion is drawn in a frame moving at `drift` (for the barbell: with its centre, as
// the paper reads the re-strike); the two frames agree at the impact
function shifted(f, t, drift) {
  const dx = drift[0] * t, dy = drift[1] * t;
  return { x: f.x - dx, y: f.y - dy, parts: f.parts.map(([px, py]) => [px - dx, py - dy]) };
}

function picture(svg, bodies, which, t, paths, mark, drift = [0, 0]) {
  while (svg.firstChild) { svg.removeChild(svg.firstChild); }
  const pts = [];
  for (const b of bodies) {
    pts.push([b.x, b.y]); for (const p of b.parts) { pts.push(p); }
    if (b.r) { pts.push([b.x + b.r, b.y + b.r], [b.x - b.r, b.y - b.r]); }
  }
  for (const path of paths) { for (const p of path) { pts.push(p); } }
  pts.push([0, 0]);
  const xs = pts.map((p) => p[0]).filter(Number.isFinite);
  const ys = pts.map((p) => p[1]).filter(Number.isFinite);
  let x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.min(...ys), y1 = Math.max(...ys);
  const size = Math.max(x1 - x0, (y1 - y0) * 4 / 3, 1e-9) * 1.3;
  const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  const W = Number(svg.getAttribute("width")), k = W / size;
  const H = Number(svg.getAttribute("height"));
  const X = (x) => W / 2 + (x - cx) * k, Y = (y) => H / 2 - (y - cy) * k;
  const speeds = bodies.flatMap((b) => [Math.hypot(b.vx, b.vy), Math.hypot(b.vx2, b.vy2)]);
  const vs = 0.25 * size / Math.max(...speeds.filter(Number.isFinite), 1e-12);
  for (const s of SURFACES) {
    const [px, py, nx, ny] = s; const tx = -ny, ty = nx, h = size;
    svg.appendChild(svgEl("line", { x1: X(px - tx * h), y1: Y(py - ty * h),
      x2: X(px + tx * h), y2: Y(py + ty * h), stroke: "#888", "stroke-width": 3 }));
  }
  if (mark) {
    const r = Math.max(mark.r, size / 3);
    svg.appendChild(svgEl("line", { x1: X(0), y1: Y(0), x2: X(r * Math.cos(mark.angle)),
      y2: Y(r * Math.sin(mark.angle)), stroke: "#c60", "stroke-dasharray": "6 4",
      "stroke-width": 1.5 }));
    const label = svgEl("text", { x: X(r * Math.cos(mark.angle)) + 4,
      y: Y(r * Math.sin(mark.angle)), fill: "#c60", "font-size": 12 });
    label.textContent = mark.text; svg.appendChild(label);
  }
  const colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#17becf"];
  paths.forEach((path, i) => {
    svg.appendChild(svgEl("polyline", { points: path.map((p) => X(p[0]) + "," + Y(p[1]))
      .join(" "), fill: "none", stroke: colours[i % colours.length], "stroke-opacity": 0.5 }));
  });
  bodies.forEach((b, i) => {
    const f = t === null ? { x: b.x, y: b.y, parts: b.parts } : shifted(flown(b, t), t, drift);
    const colour = colours[i % colours.length];
    for (const p of f.parts) {
      svg.appendChild(svgEl("line", { x1: X(f.x), y1: Y(f.y), x2: X(p[0]), y2: Y(p[1]),
        stroke: colour, "stroke-width": 2 }));
      svg.appendChild(svgEl("circle", { cx: X(p[0]), cy: Y(p[1]), r: 6, fill: colour }));
    }
    svg.appendChild(svgEl("circle", { cx: X(f.x), cy: Y(f.y),
      r: b.r ? Math.max(2, b.r * k) : 5, fill: b.r ? "none" : colour, stroke: colour,
      "stroke-width": 2 }));
    const vx = which === "before" ? b.vx : b.vx2, vy = which === "before" ? b.vy : b.vy2;
    if (t === null && Number.isFinite(vx) && Math.hypot(vx, vy) > 0) {
      svg.appendChild(svgEl("line", { x1: X(f.x), y1: Y(f.y), x2: X(f.x + vx * vs),
        y2: Y(f.y + vy * vs), stroke: "#000", "stroke-width": 1.5,
        "marker-end": "url(#arrow-" + which + ")" }));
    }
    const label = svgEl("text", { x: X(f.x) + 6, y: Y(f.y) - 8, "font-size": 12,
                                  fill: colour });
    label.textContent = b.name; svg.appendChild(label);
  });
  const defs = svgEl("defs", {});
  const marker = svgEl("marker", { id: "arrow-" + which, viewBox: "0 0 10 10", refX: 9,
    refY: 5, markerWidth: 6, markerHeight: 6, orient: "auto-start-reverse" });
  marker.appendChild(svgEl("path", { d: "M 0 0 L 10 5 L 0 10 z" }));
  defs.appendChild(marker); svg.appendChild(defs);
}

let motion = null;

function update() {
  const v = values();
  const refused = document.getElementById("refused");
  let out = null;
  try { out = fn(...v); refused.textContent = ""; }
  catch (error) { refused.textContent = "These values are refused: " + error.message; }
  for (const row of document.querySelectorAll("[data-key]")) {
    const x = out === null ? NaN : out[row.dataset.key];
    row.dataset.value = out === null ? "" : String(x);
    row.textContent = out === null ? "-" : shown(x);
    row.title = row.dataset.value;
  }
  const bodies = out === null ? [] : bodiesAt(v);
  document.getElementById("figures").style.display = bodies.length ? "" : "none";
  if (!bodies.length) { return; }
  picture(document.getElementById("before"), bodies, "before", null, [], null);
  picture(document.getElementById("after"), bodies, "after", null, [], null);
  // the motion: free flight after the impact, to the re-strike for the barbell
  let end = null, note = "";
  const status = document.getElementById("restrike");
  let mark = null;
  if (BARBELL) {
    end = restrike(bodies[BARBELL.ball], bodies[BARBELL.bar]);
    const critical = criticalAngle(v);
    status.dataset.turn = end === null ? "" : String(end);
    status.dataset.critical = critical === null ? "" : String(critical);
    note = (end === null ? "No re-strike within a turn of the barbell." :
      "The barbell strikes the ball again at t = " + shown(end) + ".") + " " +
      (critical === null ? "No critical angle below 90 degrees here." :
       "Critical angle: " + shown(critical * 180 / Math.PI) + " degrees (dashed): " +
       "below it the barbell comes round and strikes the ball again.");
    if (critical !== null) {
      const L = Math.hypot(bodies[BARBELL.bar].x, bodies[BARBELL.bar].y);
      mark = { angle: critical, r: 2.2 * L, text: "θc" };
    }
  }
  const span = end !== null ? end : (() => {
    const turning = bodies.map((b) => Math.abs(b.w2)).filter((w) => w > 0);
    return turning.length ? Math.PI / Math.max(...turning) : 1;
  })();
  status.textContent = note;
  // the barbell's motion in the frame of its centre: it turns in place and the ball
  // drifts past it, so the re-strike is seen where it happens
  const drift = BARBELL ? [bodies[BARBELL.bar].vx2, bodies[BARBELL.bar].vy2] : [0, 0];
  const paths = bodies.flatMap((b) => {
    const list = [];
    for (let i = 0; i <= 200; i++) {
      const f = shifted(flown(b, span * i / 200), span * i / 200, drift);
      list.push([f.x, f.y]); f.parts.forEach((p, j) => { (list.parts = list.parts || [])
        [j] = (list.parts[j] || []).concat([p]); });
    }
    return [list].concat(list.parts || []);
  });
  const svg = document.getElementById("motion");
  let frame = 0;
  if (motion !== null) { clearInterval(motion); }
  const tick = () => {
    picture(svg, bodies, "after", span * frame / 120, paths, mark, drift);
    frame = (frame + 1) % 121;
  };
  tick();
  motion = setInterval(tick, 40);
}

function setup() {
  const holder = document.getElementById("sliders");
  for (const s of symbols) {
    const [lo, hi] = RANGES[s];
    const row = document.createElement("div"); row.className = "slider";
    const label = document.createElement("label"); label.textContent = s;
    const range = document.createElement("input");
    Object.assign(range, { type: "range", min: lo, max: hi, step: "any" });
    range.id = "slider-" + s;
    const number = document.createElement("input");
    Object.assign(number, { type: "number", step: "any" });
    number.id = "value-" + s;
    const start = DEFAULTS[s] !== undefined ? DEFAULTS[s] : (lo + hi) / 2;
    state[s] = start; range.value = String(start); number.value = String(start);
    range.addEventListener("input", () => { state[s] = Number(range.value);
      number.value = range.value; update(); });
    number.addEventListener("input", () => { const x = Number(number.value);
      if (number.value !== "" && Number.isFinite(x)) { state[s] = x; range.value = String(x);
        update(); } });
    label.htmlFor = number.id;
    row.append(label, range, number); holder.appendChild(row);
  }
  update();
}
document.addEventListener("DOMContentLoaded", setup);
"""


def _barbell(program: Program, bodies: list[dict[str, Any]]) -> dict[str, Any] | None:
    """Where the page finds the paper's barbell: a two-sphere body, a ball and an angle."""
    bars = [i for i, b in enumerate(bodies) if b["shape"] == "barbell" and b["parts"] == 2]
    balls = [i for i, b in enumerate(bodies) if b["shape"] == "particle"]
    if len(bars) != 1 or len(balls) != 1 or "theta" not in program.names:
        return None
    return {"bar": bars[0], "ball": balls[0], "angle": "theta"}


def live_page(target: Any) -> str:
    """The live page of a built-in problem or scene file, as HTML text.

    Parameters
    ----------
    target : str or Derivation
        A built-in problem's name, a scene file, or a Derivation.
    """
    program = program_of(target)
    drawing, bodies = drawing_program(program, target)
    name = program.name
    ranges = slider_ranges(program)
    barbell = _barbell(program, bodies)
    fn_js = to_code(program, "js")
    draw_js = to_code(drawing, "js") if bodies else ""
    rows = "\n".join(f"<tr><td><code>{html.escape(k)}</code></td>"
                     f"<td class='value' data-key='{html.escape(k, quote=True)}'>-</td></tr>"
                     for k in [*program.outputs, *(["regime"] if program.regime is not None
                                                  else [])])
    formulas = "\n".join(_formula(k, v) for k, v in program.formulas.items())
    notes = "".join(f"<li>{html.escape(n)}</li>" for n in program.notes)
    script = _PAGE_SCRIPT
    for key, value in {
            "name": json.dumps(name), "ranges": json.dumps(ranges),
            "bodies": json.dumps(bodies), "surfaces": json.dumps(_surfaces(target, program)),
            "barbell": json.dumps(barbell), "fn": name,
            "draw_fn": drawing.name if bodies else "null",
            "symbols": f"{name}_symbols"}.items():
        script = script.replace(f"%({key})s", value)
    script = script.replace("DEFAULTS[s]", f"{name}_defaults[s]")
    sliders = ("<p class='note'>Drag a slider or type a value (angles in radians).</p>"
               if program.symbols else
               "<p class='note'>This scene is solved with numbers at its values: there is "
               "no slider.</p>")
    motion_words = ("The flight after the impact to the re-strike, seen from the barbell's "
                    "centre as it moves on (the frame the paper reads the re-strike in); the "
                    "dashed ray marks the critical angle." if barbell else
                    "Each free body's flight after the impact (no forces, no further "
                    "contact).")
    policy = ("default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
              "img-src data:")
    title = html.escape(program.title)
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="{policy}">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title} (live)</title>
<style>{_STYLE}</style>
</head><body>
<h1>{title}</h1>
<p class="note">A live page written by <code>rigidimpact export {html.escape(
        Path(program.target).name)} --to html</code>: the numbers are computed in this page
by the JavaScript export of the derivation's closed forms; it needs no server and
fetches nothing.</p>
<div class="grid"><div>
<h2>The symbols</h2>
<div id="sliders"></div>
{sliders}
<p id="refused"></p>
<h2>The outputs</h2>
<table class="outputs">{rows}</table>
</div><div id="figures">
<h2>Before and after the impact</h2>
<svg id="before" width="280" height="280" role="img" aria-label="the bodies before"></svg>
<svg id="after" width="280" height="280" role="img" aria-label="the bodies after"></svg>
<p class="note">Left: the bodies at the impact with their velocities before; right: with
their velocities after (arrows to one scale).</p>
<h2>After the impact</h2>
<svg id="motion" width="440" height="330" role="img" aria-label="the motion"></svg>
<p class="note">{motion_words}</p>
<p id="restrike"></p>
</div></div>
<h2>The formulas</h2>
<div class="formulas">{formulas}</div>
<ul class="note">{notes}</ul>
<script>{fn_js}</script>
<script>{draw_js}</script>
<script>{script}</script>
</body></html>
"""


def write_live(target: Any, path: Path) -> Path:
    """:func:`live_page` written to `path` whole or not at all."""
    text = live_page(target)
    return write_file(Path(path), lambda temporary: temporary.write_text(text,
                                                                         encoding="utf-8"))
