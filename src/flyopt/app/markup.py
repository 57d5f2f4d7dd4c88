"""The page's own markup (the answer card, the footer) in a component that changes it in place.

Panel's ``HTML`` pane asks Bokeh to lay the whole page out again at every change of its text (traced in
chromium: some 170 ms of ``compute_layout`` for one card, most of the card's latency after the server had sent
it, docs/app.md "Latency"). This component (a :class:`panel.custom.JSComponent`, as
:mod:`flyopt.app.hover`) puts the new markup in its element and nothing else: the browser reflows what the
markup changed, as for any HTML. The markup is flyopt's own (:func:`flyopt.app.model.card_html`,
:func:`flyopt.app.model.provenance_html`), every user string in it escaped there, as for the ``HTML`` pane
it replaces; the component runs no ``<script>`` it holds (``innerHTML`` does not run them).
"""

from __future__ import annotations

from functools import cache
from typing import Any

ESM = """
export function render({ model, el }) {
  const box = document.createElement('div')
  const show = () => { box.innerHTML = model.html }
  show()
  model.on('html', show)
  el.style.width = '100%'
  el.appendChild(box)
}
"""


@cache
def markup_class() -> type:
    """The component class (made once: Panel is imported only by the app)."""
    import param
    from panel.custom import JSComponent

    class Markup(JSComponent):
        """The markup ``html``, shown as it changes, without a layout of the whole page."""

        html = param.String(default="")

        _esm = ESM

    return Markup


def markup(html: str, **kwargs: Any) -> Any:
    """A :func:`markup_class` component showing ``html``."""
    return markup_class()(html=html, **kwargs)
