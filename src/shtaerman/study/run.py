"""Running one study of any kind: the kind registry (:mod:`.kinds`) picks its runner.

The one place where a study's validity warnings are kept: :func:`run_study` catches the
:class:`~shtaerman.guards.ValidityWarning` of every run of the study (a limit declared in
:mod:`shtaerman.guards`), records them once each in the outcome's ``warnings``
(:func:`recorded_warnings`, results.json's ``warnings`` and the reports' warnings) and says
each once, naming the study.
"""

from __future__ import annotations

import contextlib
import dataclasses
import warnings
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from ..guards import ValidityWarning
from ..problem import worded
from ..validation import InputError
from .checks import Outcome
from .kinds import kind_function

__all__ = ["Progress", "recorded_warnings", "run_study", "say_warnings"]

Progress = Callable[[str], None]
"""Receives one line of progress."""


def run_study(study: Any, *, quick: bool = False, progress: Progress | None = None) -> Outcome:
    """Run one study of any kind (its ``kind`` attribute; see :mod:`.kinds`); its validity
    warnings are recorded in the outcome's ``warnings`` (:class:`~.checks.Outcome`) and said
    once each.

    Raises
    ------
    InputError
        An input the FEM refuses only once it runs (e.g. a contact smaller than the mesh
        resolves), prefixed with the study file and the study's name.
    """
    run = kind_function(getattr(study, "kind", "contact"), "run")
    with _recording(study) as found:
        try:
            outcome = run(study, quick, progress)
        except InputError as error:
            said = _in_file_words(error, quick)
            raise InputError(f"{_where(study)}: {said}", error.parameter) from None
    return dataclasses.replace(outcome, warnings=tuple(found))


def recorded_warnings(outcome: Outcome) -> list[str]:
    """The validity warnings :func:`run_study` recorded for ``outcome``, once each in the
    order issued ([] for an outcome a kind's runner made without it)."""
    return list(outcome.warnings)


def say_warnings(study: Any, texts: Iterable[str]) -> None:
    """Issue each of a study's recorded warnings ``texts`` as a :class:`ValidityWarning`
    naming the study (a study run elsewhere, e.g. in a dask worker)."""
    for text in texts:
        warnings.warn(f"{_where(study)}: {text}", ValidityWarning, stacklevel=2)


def _in_file_words(error: InputError, quick: bool) -> str:
    """A run's refusal in the study file's words: a head naming its parameter becomes its key
    (``key 'contact.depths': ...``), an input named in Python's (``mesh_size=...``) the key of
    the table that ran (``[quick] mesh_size`` when ``quick``)."""
    from .schema import STUDY_KEYS, TABLE_OF

    table = "quick" if quick else "numerics"
    numerics = {name: f"{table}.{name}" for name, of in TABLE_OF.items() if of == "numerics"}
    keys = {**STUDY_KEYS, **numerics}
    text, head = worded(str(error), "file", keys), f"{error.parameter}: "
    if error.parameter in keys and text.startswith(head):
        return f"key '{keys[error.parameter]}': {text.removeprefix(head)}"
    return text


def _where(study: Any) -> str:
    return f"{study.source}: study {study.name!r}"


@contextlib.contextmanager
def _recording(study: Any) -> Iterator[list[str]]:
    """Catch every warning issued inside; on leaving (an error too), fill the yielded list
    with the validity warnings' texts, once each, and issue every warning again once: a
    validity warning naming the study, another as it was (its own place)."""
    found: list[str] = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")  # a limit passed again, or by another study, counts
            yield found
    finally:
        said = set()
        for warning in caught:
            category = warning.category
            text = worded(str(warning.message), "file")  # its inputs are the file's keys
            validity = issubclass(category, ValidityWarning)
            key = (
                (category, text) if validity else (category, text, warning.filename, warning.lineno)
            )
            if key in said:
                continue
            said.add(key)
            message: Warning | str = warning.message
            if text != str(message):
                message = category(text)
            if validity:
                found.append(text)
                message = category(f"{_where(study)}: {text}")
            warnings.warn_explicit(message, category, warning.filename, warning.lineno)
