"""A verify run served from one made before: for the tests of stopping and resuming, which
check which studies are computed, kept and completed, not the computing or the drawing (~4 CPU s
a study's figures, each time); tests/test_verify.py checks the drawing on the folder served from.

As a script, ``python served_verify.py PICKLE verify ARGS...`` is ``shtaerman verify ARGS...``
with its studies and files served from ``PICKLE`` ((outcomes by study name, folder, results));
a study with no outcome there computes until the process is killed (tests/test_verify.py).
"""

import json
import pickle
import shutil
import signal
import sys
from pathlib import Path

import shtaerman.output.folder


def serve_writing(setattr_, outcomes: dict, done: Path, results: dict) -> None:
    """Through ``setattr_`` (a monkeypatch's), serve ``study_entry`` and ``shared_figures``
    from ``done``, the folder a verify wrote with these ``results``, for what it wrote there:
    an outcome of ``outcomes`` (the very object), the exponents of its figures, PNG. A copy of
    its files and its results.json entry; anything else is written as usual."""
    folder = shtaerman.output.folder
    write, draw = folder.study_entry, folder.shared_figures
    exponents = {entry["inputs"]["exponent"] for entry in results["studies"].values()}
    done_for = tuple(sorted(exponents - {None}))

    def study_entry(outcome, stage, figure_format="png"):
        name = outcome.study.name
        if figure_format != "png" or outcome is not outcomes.get(name):
            return write(outcome, stage, figure_format)
        shutil.copytree(done / name, stage / name)
        return json.loads(json.dumps(results["studies"][name]))

    def shared_figures(stage, exponents, figure_format):
        drawn_for = tuple(sorted(set(exponents)))
        if figure_format != "png" or drawn_for != done_for:
            return draw(stage, exponents, figure_format)
        for path in results["figures"].values():
            shutil.copy2(done / path, Path(stage) / path)
        return drawn_for, dict(results["figures"])

    setattr_(folder, "study_entry", study_entry)
    setattr_(folder, "shared_figures", shared_figures)


def _main(served: str) -> int:
    from shtaerman.entry import main

    outcomes, done, results = pickle.loads(Path(served).read_bytes())
    folder = shtaerman.output.folder

    def run_study(study, *, quick=False, progress=None):
        if study.name not in outcomes:  # a computation that lasts until the test kills it
            while True:
                signal.pause()
        assert quick and outcomes[study.name].study == study
        return outcomes[study.name]

    folder.run_study = run_study
    serve_writing(setattr, outcomes, Path(done), results)
    return main()


if __name__ == "__main__":
    sys.exit(_main(sys.argv.pop(1)))
