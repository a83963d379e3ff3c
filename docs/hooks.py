"""mkdocs hooks: the parameter table from the CLI parsers, the tutorials as pages, the API.

``parameters.md`` is generated at build time from ``shtaerman.cli.build_parser()`` (every
subcommand's options with their defaults and help), so it cannot drift from the CLI. Each
``tutorials/*.py`` (a jupytext percent script, run by the tests) becomes ``tutorials/*.md``:
markdown cells as text, code cells as Python blocks, the script itself offered for download;
with ``SHTAERMAN_DOCS_EXECUTE=1`` (``make docs``) the tutorials run and each cell's output follows
it (the tests run the tutorials themselves, so they build without).
The docstrings' Sphinx roles (``:func:`name```) become cross-references (:class:`SphinxRoles`).
In ``api.md`` the line ``<!-- public-api -->`` becomes one mkdocstrings block per name of
``shtaerman.__all__`` at its public path, grouped as inputs, computations, results.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import inspect
import io
import os
import re
import tempfile
import types
from pathlib import Path

import griffe
import jupytext
from mkdocs.structure.files import File, Files

HEADER = """# Parameters

Every input, with its default, generated from the package itself when this site was built. Study
files, sweep files and the Python API use the command-line names in snake_case
(`--shape-coefficient` is `shape_coefficient`); SI units everywhere.
"""

VOCABULARY_TEXT = """Every input of a study file, a sweep and the Python API: its key, its
command-line option and the commands that take it (or none: a study and sweep key only), its
default, meaning, unit, valid range and the kinds of computation that take it (study and sweep
kinds)."""


def _cell(text: str) -> str:
    """``text`` on one line of a markdown table cell: ``|`` escaped, and ``<``, ``>`` as
    entities (the help's ``sweep-<name>`` read as an HTML tag, and vanished)."""
    text = " ".join(text.split()).replace("<", "&lt;").replace(">", "&gt;")
    return text.replace("|", "\\|")


def _default(action: argparse.Action) -> str:
    if isinstance(action, argparse._StoreTrueAction):
        return "off"
    if isinstance(action, argparse._StoreFalseAction):  # --no-estimate: switches on an input
        return f"off ({action.dest} on)"
    if action.default in (None, argparse.SUPPRESS):
        return ""
    return f"`{action.default}`"


def _option_rows(parser: argparse.ArgumentParser) -> list[str]:
    formatter = argparse.HelpFormatter(parser.prog)  # the help alone: defaults have a column
    rows = ["| option | default | meaning |", "|---|---|---|"]
    for action in parser._actions:
        if isinstance(action, argparse._HelpAction) or action.help == argparse.SUPPRESS:
            continue
        names = ", ".join(action.option_strings) or action.dest.upper()
        if action.metavar and action.option_strings:
            names += f" {action.metavar}"
        if action.choices and not action.option_strings:
            names = "|".join(str(choice) for choice in action.choices)
        meaning = formatter._expand_help(action) if action.help else ""
        if action.choices and action.option_strings:
            meaning += f" (one of {', '.join(str(c) for c in action.choices)})"
        rows.append(f"| `{_cell(names)}` | {_cell(_default(action))} | {_cell(meaning)} |")
    return rows


def parameters_page() -> str:
    """The markdown of the parameters page, one table per subcommand."""
    from shtaerman.cli import build_parser

    parser = build_parser()
    [commands] = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    parts = [HEADER]
    try:  # the inputs of study files, sweeps and the API, where the package declares them
        vocabulary = importlib.import_module("shtaerman.vocabulary")
    except ImportError:
        vocabulary = None
    if vocabulary is not None and hasattr(vocabulary, "parameter_table"):
        parts += ["## Study files, sweeps and the Python API", "", VOCABULARY_TEXT, ""]
        parts.append(vocabulary.parameter_table(parser))
    if hasattr(importlib.import_module("shtaerman.problem"), "support_table"):
        parts += combinations_section()
        parts += options_section()
    parts += ["## The command line", "", "Every option of every command, and its default.", ""]
    for name, sub in commands.choices.items():
        summary = sub.description.splitlines()[0] if sub.description else ""
        parts += [f"### `shtaerman {name}`", "", _cell(summary), "", *_option_rows(sub), ""]
    return "\n".join(parts)


def combinations_section() -> list[str]:
    """Which parts of a problem combine, from ``shtaerman.problem.support_table()``: one table
    per loading, rows model x relaxation x geometry, columns the interface; a cell is "runs"
    or the input its refusal names (the reasons follow)."""
    from shtaerman.problem import SUPPORT, support_table

    verdicts = dict(support_table())  # every striker profile's
    interfaces = ("frictionless", "bonded", "coulomb")
    bodies = sorted({cell[:3] for cell in verdicts}, key=str)
    tables = []
    for loading in ("curve", "massless", "inertia"):
        tables += [f"**{LOADING_WORDS[loading]}**", ""]
        tables += ["| body, geometry | " + " | ".join(interfaces) + " |", "|---|---|---|---|"]
        for model, relaxing, geometry in bodies:
            cells = [verdicts[(model, relaxing, geometry, face, loading)] for face in interfaces]
            body = f"{model}{', Prony' if relaxing else ''}, {geometry}"
            tables.append(f"| {body} | " + " | ".join(c.split(":")[0] for c in cells) + " |")
        tables.append("")
    running = sum(verdict == "runs" for verdict in verdicts.values())
    return [
        "## Which parts combine",
        "",
        f"A problem is a striker, a body, a geometry, an interface and a loading "
        f"(`sh.Problem`). Of the {len(verdicts)} combinations below, {running} run; each other "
        "cell names the input that is refused, for the reason listed after the tables "
        "(`shtaerman.problem.SUPPORT`, the one place that decides it). They hold for every "
        "striker: a power law, a sphere or a tabulated profile.",
        "",
        *tables,
        *[f"- `{limit.parameter}`: {limit.reason}" for limit in SUPPORT],
        "",
    ]


def _where(when, cells: list) -> str:
    """The combinations of ``cells`` (``shtaerman.problem.Cell``) that a limit's predicate
    ``when`` selects, part by part (``model: rubber; loading: curve``; a part it leaves free is
    not named). A predicate that selects no such product of parts stops the build: it would
    need words of its own."""
    from itertools import product

    every = [sorted({cell[i] for cell in cells}, key=str) for i in range(len(cells[0]))]
    chosen = [sorted({cell[i] for cell in cells if when(cell)}, key=str) for i in range(len(every))]
    if sum(map(when, cells)) != len(list(product(*chosen))):
        raise ValueError(f"an option limit selects no product of parts: {chosen}")
    words = {False: "elastic", True: "Prony"}  # a Cell's relaxing
    return "; ".join(
        f"{name}: {', '.join(str(words.get(value, value)) for value in values)}"
        for name, values, all_values in zip(cells[0]._fields, chosen, every, strict=True)
        if values != all_values
    )


class _Placeholder(str):
    """A reason's ``{model}`` or ``{value}`` shown as ``<model>``, ``<value>``, whatever the
    format (``!r``, ``:g``)."""

    def __repr__(self) -> str:
        return str(self)

    def __format__(self, spec: str) -> str:
        return str(self)


def options_section() -> list[str]:
    """Which numerical and output options each combination takes, from
    ``shtaerman.problem.OPTION_SUPPORT``: one row per limit, its options, the combinations it
    limits and its reason."""
    from shtaerman.problem import OPTION_SUPPORT, support_table

    cells = [cell for cell, _ in support_table()]
    names = {"model": _Placeholder("<model>"), "value": _Placeholder("<value>")}
    rows = ["| options | where | reason |", "|---|---|---|"]
    for limit in OPTION_SUPPORT:
        options = ", ".join(f"`{option}`" for option in limit.options)
        reason = limit.reason.format(**names)
        rows.append(f"| {options} | {_cell(_where(limit.when, cells))} | {_cell(reason)} |")
    return [
        "## Which options apply where",
        "",
        "The numerical and output options a combination does not take "
        "(`shtaerman.problem.OPTION_SUPPORT`, the one place that decides it): each row names "
        "the options, the parts of the combinations it limits (a part not named: any) and the "
        "reason every route refuses them with (the command line, the API, study files and "
        "sweeps). Where the reason names a value or another option, that one is taken.",
        "",
        *rows,
        "",
    ]


LOADING_WORDS = {
    "curve": "Contact curve (contact)",
    "massless": "Impact on a massless body (dynamic --density2 0)",
    "inertia": "Impact with inertia (dynamic)",
}
"""A loading's name in the combination tables."""


EXECUTE = "SHTAERMAN_DOCS_EXECUTE"
"""Environment variable: set to 1, the tutorials run at build time and their output is shown."""


def _run_cells(cells: list[str], folder: Path) -> list[str]:
    """Run code cells in one namespace inside ``folder``; what each printed."""
    namespace: dict = {"__name__": "__main__"}
    printed = []
    previous = Path.cwd()
    os.chdir(folder)
    try:
        for source in cells:
            with contextlib.redirect_stdout(io.StringIO()) as out:
                exec(compile(source, "tutorial", "exec"), namespace)
            printed.append(out.getvalue())
    finally:
        os.chdir(previous)
    return printed


def tutorial_page(script: Path, execute: bool = False) -> str:
    """The markdown of one jupytext percent script: text cells, code cells in fences, and, with
    ``execute``, what each code cell printed (run in a temporary folder)."""
    cells = [c for c in jupytext.read(script, fmt="py:percent").cells if c.source.strip()]
    code = [c.source for c in cells if c.cell_type == "code"]
    printed = iter([""] * len(code))
    if execute:
        with tempfile.TemporaryDirectory() as folder:
            printed = iter(_run_cells(code, Path(folder)))
    parts = []
    for cell in cells:
        source = cell.source.strip()
        if cell.cell_type == "markdown":
            parts.append(source)
            continue
        parts.append(f"```python\n{source}\n```")
        output = next(printed).rstrip()
        if output:
            parts.append(f"```text\n{output}\n```")
    parts.append(
        f"[Download this tutorial as a script]({script.name}) (a jupytext percent script: "
        f"run it with `python {script.name}`, or open it as a notebook with jupytext)."
    )
    return "\n\n".join(parts) + "\n"


API_MARKER = "<!-- public-api -->"
API_GROUPS = {
    "Inputs": lambda name, obj: (
        inspect.isclass(obj)
        and not name.endswith(("Result", "Results", "Outcome", "Table"))
        and not issubclass(obj, Exception)
    ),
    "Computations": lambda name, obj: inspect.isfunction(obj),
    "Results": lambda name, obj: (
        inspect.isclass(obj) and name.endswith(("Result", "Results", "Outcome", "Table"))
    ),
    "Errors": lambda name, obj: inspect.isclass(obj) and issubclass(obj, Exception),
}


API_ORDER = [
    "Problem",
    "PowerLawIndenter",
    "Material",
    "impact",
    "contact",
    "dynamic",
    "run_study",
    "sweep",
]


def _rank(name: str) -> tuple[int, str]:
    return (API_ORDER.index(name) if name in API_ORDER else len(API_ORDER), name)


def _public_objects() -> dict[str, tuple[str, object]]:
    """Each public name: the path it is documented at (its public one), and the object."""
    import shtaerman

    found = {}
    for name in sorted(shtaerman.__all__, key=_rank):
        path, obj = f"shtaerman.{name}", getattr(shtaerman, name)
        if isinstance(obj, types.ModuleType) and callable(obj):  # sh.sweep: package and function
            path, obj = (
                f"shtaerman.api.{name}",
                getattr(importlib.import_module("shtaerman.api"), name),
            )
        found[name] = (path, obj)
    return found


def api_blocks() -> str:
    """mkdocstrings blocks for ``shtaerman.__all__``, grouped, at their public paths."""
    objects = _public_objects()
    parts = []
    for title, belongs in API_GROUPS.items():
        members = [path for name, (path, obj) in objects.items() if belongs(name, obj)]
        if members:
            parts.append(f"## {title}")
            parts += [f"::: {path}" for path in members]
    return "\n\n".join(parts)


ROLE = re.compile(r":(?:py:)?(?:func|class|meth|attr|data|const|mod|exc|obj):`(~?)([\w.]+)`")
"""A Sphinx cross-reference role: ``:func:`name```, ``:class:`~a.b.Name``` (shown as ``Name``)."""


def _target(obj: griffe.Object, name: str) -> str:
    """The full path ``name`` means in ``obj``'s docstring ("": none is found)."""
    head, _, rest = name.partition(".")
    try:
        path = name if head == "shtaerman" else obj.resolve(head) + (rest and f".{rest}")
        return obj.modules_collection[path].canonical_path
    except (griffe.NameResolutionError, griffe.AliasResolutionError, KeyError):
        return ""


def sphinx_roles_to_markdown(obj: griffe.Object, text: str) -> str:
    """``text`` with each Sphinx role of ``obj``'s docstring as a code span that links to its
    target where the site documents it (an optional mkdocs-autorefs reference)."""

    def replace(match: re.Match) -> str:
        shown = match[2].rsplit(".", 1)[-1] if match[1] else match[2]
        path = _target(obj, match[2])
        if not path:
            return f"`{shown}`"
        return f'<autoref identifier="{path}" optional><code>{shown}</code></autoref>'

    return ROLE.sub(replace, text)


class SphinxRoles(griffe.Extension):
    """Griffe extension (mkdocs.yml): the docstrings are written with Sphinx roles, which
    mkdocstrings' markdown would show raw; each becomes a code span, linked where it can be."""

    def on_object(self, *, obj: griffe.Object, **kwargs) -> None:
        """Rewrite the roles of ``obj``'s docstring, once the whole package is loaded."""
        if obj.docstring is not None:
            obj.docstring.value = sphinx_roles_to_markdown(obj, obj.docstring.value)


def on_page_markdown(markdown: str, page, config, files) -> str:
    """Fill ``api.md``'s marker with the public API's reference blocks."""
    if page.file.src_uri == "api.md":
        return markdown.replace(API_MARKER, api_blocks())
    return markdown


def on_files(files: Files, config) -> Files:
    """Add the generated pages: ``parameters.md`` and one page per tutorial script."""
    files.append(File.generated(config, "parameters.md", content=parameters_page()))
    execute = os.environ.get(EXECUTE) == "1"
    for script in sorted((Path(config["docs_dir"]) / "tutorials").glob("*.py")):
        page = f"tutorials/{script.stem}.md"
        files.append(File.generated(config, page, content=tutorial_page(script, execute)))
    return files
