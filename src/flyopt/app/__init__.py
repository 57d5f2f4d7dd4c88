"""``flyopt app``: the local web app (the ``app`` extra brings Panel).

:mod:`flyopt.app.model` is the app without a browser: the templates, the
checking of the editor's text by flyopt's own loader, and the answer (card,
diagrams, report, JSON) read from the one solve the report makes;
:mod:`flyopt.app.page` lays it out with Panel, imported only when the app is
served. The app stands above the command line (its top floor): it reuses
``flyopt report``'s solve and provenance, and nothing imports it but
``flyopt app``.
"""
