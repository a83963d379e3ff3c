"""Helpers the figure tests share: the Figure a plot would save, and a vector file's text.

A helper module, not a test module: a test file imports it (``from figure_helpers import
capture``) instead of importing another test file, which would collect that file's tests twice
and tie the two together.
"""

from pathlib import Path


def svg_text(path: Path) -> str:
    """The text of the SVG file ``path``, asserted to be one (XML with an ``<svg`` element)."""
    text = path.read_text(encoding="utf-8")
    assert text.startswith("<?xml") and "<svg" in text[:1000]
    return text


def capture(monkeypatch, module, draw):
    """The (first) matplotlib Figure ``draw`` would save through ``module.save``."""
    captured = []

    def fake(figure, path, *_args, **_kwargs):
        captured.append(figure)
        return Path(path)

    monkeypatch.setattr(module, "save", fake)
    draw()
    return captured[0]
