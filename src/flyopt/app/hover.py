"""A diagram with read-outs under the pointer: the report's SVG and its curves' values at the pointer's abscissa.

A Panel component (:class:`panel.custom.JSComponent`, Panel's documented way for a page to run its own script:
an ``HTML`` pane would run whatever ``<script>`` its text holds, a Panel of user text must not rely on that) that
shows a figure's SVG as drawn by the report (:func:`flyopt.app.model.figure_svg`) and, over the Axes that
have read-outs (:mod:`flyopt.report.plots.readout`), follows the pointer: it maps the pointer into the SVG's user
units (the browser's own ``getScreenCTM``, whatever the SVG's scale on the page), finds the Axes under it and the
nearest abscissa of its grid (the recorded data-to-SVG transform, :func:`flyopt.report.plots.readout.to_svg`
mirrored), and draws a vertical guide through it, a dot on each curve and a box with the recorded texts
("φ = 131.8 deg", "M_d = 0.4625 kN·m"). Where the Axes has named points (:func:`flyopt.report.plots.readout.points`:
a Pareto front's designs, the energy–mass curve) and one is within :data:`~flyopt.report.plots.readout.REACH`
pixels of the pointer, it rings the nearest (a marker before a point of a line) and shows its texts instead. On a
drawing with a named height (:func:`flyopt.report.plots.readout.ordinate`: r on the axial section) and no curves,
a horizontal guide shows the height under the pointer. The texts are put in as text
(``textContent``), never as markup; the script formats no number: every value is written by the report's rule in
Python. A click on a link ``#pick-N`` of the SVG (a Pareto point) sets ``picked`` to N and counts ``clicks``.
How much of the diagram is in view is sent back (``seen``, the browser's IntersectionObserver), so that the
diagrams in view are drawn first (:mod:`flyopt.app.diagrams`).
"""

from __future__ import annotations

from functools import cache
from typing import Any

from flyopt.report.plots.readout import REACH

#: The read-out's look (inside the component: its shadow root takes no page style).
STYLE = """
.hover {position: relative; width: 100%; content-visibility: auto; contain-intrinsic-size: auto 420px;}
.readout {position: absolute; pointer-events: none; background: rgba(255, 255, 255, 0.94); border: 1px solid #999;
 border-radius: 3px; padding: 3px 6px; font: 12px/1.35 sans-serif; white-space: nowrap; z-index: 10;
 box-shadow: 0 1px 3px rgba(0, 0, 0, 0.2);}
.readout .swatch {display: inline-block; width: 10px; height: 3px; margin: 0 5px 3px 0; vertical-align: middle;}
.readout .first {color: #444;}
"""

ESM = """
const NS = 'http://www.w3.org/2000/svg'
const REACH = __REACH__  // flyopt.report.plots.readout.REACH

function fraction(value, axis) {
  const [first, last] = axis.lim
  if (axis.log) return (Math.log10(value) - Math.log10(first)) / (Math.log10(last) - Math.log10(first))
  return (value - first) / (last - first)
}

function toSvg(entry, x, y) {  // flyopt.report.plots.readout.to_svg
  const [left, top, right, bottom] = entry.box
  return [left + fraction(x, entry.x) * (right - left), bottom - fraction(y, entry.y) * (bottom - top)]
}

export function render({ model, el }) {
  const box = document.createElement('div')
  const holder = document.createElement('div')
  const tip = document.createElement('div')
  tip.className = 'readout'
  tip.style.display = 'none'
  box.append(holder, tip)
  let data = null
  let svg = null
  let guide = null
  const show = () => {
    box.className = 'hover figure figure-' + String(model.key).replace(/[^A-Za-z0-9_-]/g, '')
    holder.innerHTML = model.svg
    svg = holder.querySelector('svg')
    guide = null
    tip.style.display = 'none'
    try { data = model.readout ? JSON.parse(model.readout) : null } catch (error) { data = null }
  }
  const hide = () => {
    tip.style.display = 'none'
    if (guide) guide.style.display = 'none'
  }
  const mark = (entry, index) => {
    if (!guide || !svg.contains(guide)) {
      guide = document.createElementNS(NS, 'g')
      guide.setAttribute('class', 'readout-guide')
      guide.setAttribute('pointer-events', 'none')
      svg.appendChild(guide)
    }
    guide.replaceChildren()
    guide.style.display = ''
    if (index < 0) return
    const [u] = toSvg(entry, entry.at[index], entry.y.lim[0])
    const line = document.createElementNS(NS, 'line')
    for (const [k, v] of [['x1', u], ['x2', u], ['y1', entry.box[1]], ['y2', entry.box[3]]]) line.setAttribute(k, v)
    line.setAttribute('stroke', '#555')
    line.setAttribute('stroke-width', '0.8')
    line.setAttribute('stroke-dasharray', '3 2')
    guide.appendChild(line)
    entry.values.forEach((values, k) => {
      const value = values[index]
      if (value === null) return
      const [, v] = toSvg(entry, entry.at[index], value)
      if (v < entry.box[1] || v > entry.box[3]) return
      const dot = document.createElementNS(NS, 'circle')
      dot.setAttribute('cx', u)
      dot.setAttribute('cy', v)
      dot.setAttribute('r', '3')
      dot.setAttribute('fill', entry.colours[k])
      dot.setAttribute('stroke', 'white')
      guide.appendChild(dot)
    })
  }
  const ring = (entry, index) => {
    mark(entry, -1)
    const [u, v] = toSvg(entry, ...entry.marks.xy[index])
    for (const [r, width, colour] of [['7', '1.2', '#222'], ['5', '2', entry.marks.colours[index]]]) {
      const dot = document.createElementNS(NS, 'circle')  // a dark ring round one of the point's colour
      for (const [k, value] of [['cx', u], ['cy', v], ['r', r], ['fill', 'none'], ['stroke-width', width]]) {
        dot.setAttribute(k, value)
      }
      dot.setAttribute('stroke', colour)
      guide.appendChild(dot)
    }
  }
  const nearest = (entry, p, scale) => {  // within REACH pixels, the nearest marker, else line's point; or -1
    let found = -1
    let best = [2, 0]
    entry.marks.xy.forEach(([x, y], i) => {
      const [u, v] = toSvg(entry, x, y)
      const distance = Math.hypot(u - p.x, v - p.y)
      const rank = entry.marks.ranks[i]
      if (distance * scale > REACH) return
      if (rank < best[0] || (rank === best[0] && distance < best[1])) { best = [rank, distance]; found = i }
    })
    return found
  }
  const list = (rows, colours) => {  // the texts, each curve's after a swatch of its colour
    tip.replaceChildren()
    rows.forEach((text, k) => {
      if (text === null) return
      const row = document.createElement('div')
      if (k === 0) row.className = 'first'
      else if (colours[k - 1]) {
        const swatch = document.createElement('span')
        swatch.className = 'swatch'
        swatch.style.background = colours[k - 1]
        row.appendChild(swatch)
      }
      row.appendChild(document.createTextNode(text))
      tip.appendChild(row)
    })
  }
  box.addEventListener('pointermove', (event) => {
    if (!data || !svg) return
    const matrix = svg.getScreenCTM()
    if (!matrix) return
    const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix.inverse())
    const entry = data.axes.find((e) => p.x >= e.box[0] && p.x <= e.box[2] && p.y >= e.box[1] && p.y <= e.box[3])
    if (!entry) { hide(); return }
    const near = entry.marks ? nearest(entry, p, Math.hypot(matrix.a, matrix.b)) : -1
    if (near >= 0) {
      ring(entry, near)
      list(entry.marks.rows[near], [])
    } else if (entry.at.length) {
      let index = 0
      let closest = Infinity
      entry.at.forEach((x, i) => {
        const distance = Math.abs(toSvg(entry, x, entry.y.lim[0])[0] - p.x)
        if (distance < closest) { closest = distance; index = i }
      })
      mark(entry, index)
      list(entry.rows[index], entry.colours)
    } else if (entry.across) {  // a drawing's named height: a horizontal guide at the nearest of its grid
      let index = 0
      let closest = Infinity
      entry.across.at.forEach((y, i) => {
        const distance = Math.abs(toSvg(entry, entry.x.lim[0], y)[1] - p.y)
        if (distance < closest) { closest = distance; index = i }
      })
      mark(entry, -1)
      const [, v] = toSvg(entry, entry.x.lim[0], entry.across.at[index])
      const line = document.createElementNS(NS, 'line')
      for (const [k, value] of [['x1', entry.box[0]], ['x2', entry.box[2]], ['y1', v], ['y2', v]]) {
        line.setAttribute(k, value)
      }
      line.setAttribute('stroke', '#555')
      line.setAttribute('stroke-width', '0.8')
      line.setAttribute('stroke-dasharray', '3 2')
      guide.appendChild(line)
      list([entry.across.rows[index]], [])
    } else { hide(); return }
    tip.style.display = 'block'
    const frame = box.getBoundingClientRect()
    const x = event.clientX - frame.left
    const y = event.clientY - frame.top
    const left = x + 14 + tip.offsetWidth > frame.width ? x - 14 - tip.offsetWidth : x + 14
    tip.style.left = Math.max(0, left) + 'px'
    tip.style.top = Math.max(0, y - tip.offsetHeight - 10) + 'px'
  })
  box.addEventListener('pointerleave', hide)
  box.addEventListener('click', (event) => {  // a link #pick-N of the SVG: picked = N
    const link = event.target.closest('a')
    if (!link) return
    const href = link.getAttribute('href') || link.getAttribute('xlink:href') || ''
    const found = href.match(/pick-(\\d+)$/)
    if (!found) return
    event.preventDefault()
    model.picked = parseInt(found[1])
    model.clicks = model.clicks + 1
  })
  // how much of the diagram is in view (0 to 1): the server draws the diagrams in view first (flyopt.app.diagrams)
  const watcher = new IntersectionObserver((entries) => {
    for (const entry of entries) {
      const fraction = entry.isIntersecting ? Math.round(entry.intersectionRatio * 100) / 100 : 0
      if (model.seen !== fraction) model.seen = fraction
    }
  }, { threshold: [0, 0.1, 0.25, 0.5, 0.75, 0.9, 1] })
  watcher.observe(box)
  show()
  model.on('svg', show)
  model.on('readout', show)
  model.on('key', show)
  el.style.width = '100%'
  el.appendChild(box)
}
"""


ESM = ESM.replace("__REACH__", str(REACH))


@cache
def hover_svg() -> type:
    """The component class (made once: Panel is imported only by the app)."""
    import param
    from panel.custom import JSComponent

    class HoverSVG(JSComponent):
        """A figure's SVG (``svg``) with read-outs (``readout``: the JSON of
        :func:`flyopt.report.plots.readout.record`, "" for none); ``key`` names it (class ``figure-KEY``);
        ``picked`` the N of the last link ``#pick-N`` clicked, ``clicks`` how many were; ``seen`` the fraction
        of it in the browser's view (0 to 1: its IntersectionObserver's)."""

        svg = param.String(default="")
        readout = param.String(default="")
        key = param.String(default="")
        picked = param.Integer(default=-1)
        clicks = param.Integer(default=0)
        seen = param.Number(default=0.0, bounds=(0.0, 1.0))

        _esm = ESM
        _stylesheets = [STYLE]

    return HoverSVG


def hover_figure(svg: str, readout: str, key: str, **kwargs: Any) -> Any:
    """A :func:`hover_svg` component showing ``svg`` with its read-outs."""
    return hover_svg()(svg=svg, readout=readout, key=key, **kwargs)
