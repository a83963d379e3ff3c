"""The documentation site builds, and its tutorials run and compute what they say.

``mkdocs build --strict`` turns every warning (a broken link, a docstring mkdocstrings cannot
read, a page missing from the navigation) into a failure. Each tutorial (a jupytext percent
script in docs/tutorials) runs as a script in a fresh folder, in its own process; the names it
leaves behind are compared with the library and the command line.
"""

import argparse
import html
import importlib.util
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import shtaerman as sh
from shtaerman.cli import build_parser, main
from shtaerman.vocabulary import VOCABULARY, entry

ROOT = Path(__file__).resolve().parents[1]
TUTORIALS = ROOT / "docs" / "tutorials"

# Runs a tutorial as __main__ and prints the requested names (or name.attribute) as JSON.
RUNNER = """\
import json, runpy, sys
names = runpy.run_path(sys.argv[1], run_name="__main__")
def value(name):
    first, *attributes = name.split(".")
    found = names[first]
    for attribute in attributes:
        found = getattr(found, attribute)
    return found
wanted = {name: value(name) for name in sys.argv[2:]}
print("NAMESPACE " + json.dumps(wanted, default=lambda value: value.tolist()))
"""


def run_tutorial(name: str, tmp_path: Path, *names: str) -> dict:
    """Run ``docs/tutorials/NAME.py`` in ``tmp_path``; the values of ``names`` it defines."""
    script = TUTORIALS / f"{name}.py"
    done = subprocess.run(
        [sys.executable, "-c", RUNNER, str(script), *names],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, f"{name}.py failed:\n{done.stdout}\n{done.stderr}"
    assert "Traceback" not in done.stderr, done.stderr
    [line] = [line for line in done.stdout.splitlines() if line.startswith("NAMESPACE ")]
    return json.loads(line.removeprefix("NAMESPACE "))


def offline() -> list[str]:
    """A command prefix that runs a command with no network (a new network namespace with only
    a loopback), where ``unshare`` may make one; else none (the built pages are still checked
    for loads from the network, by test_theory_page_loads_nothing_from_the_network)."""
    for prefix in (["unshare", "-n"], ["unshare", "-rn"]):
        if (
            shutil.which(prefix[0])
            and subprocess.run([*prefix, "true"], capture_output=True).returncode == 0
        ):
            return prefix
    return []


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site built with ``mkdocs build --strict`` into a temporary folder, with no network
    where the system allows it (:func:`offline`); the tutorials are not run (the tests run
    them)."""
    out = tmp_path_factory.mktemp("site")
    done = subprocess.run(
        [*offline(), sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
        env={name: value for name, value in os.environ.items() if name != "SHTAERMAN_DOCS_EXECUTE"},
    )
    assert done.returncode == 0, f"mkdocs build --strict failed:\n{done.stdout}\n{done.stderr}"
    return out


def test_site_builds_with_every_page(site):
    for page in ("getting-started", "findings", "theory", "guide", "parameters", "api"):
        assert (site / page / "index.html").is_file(), page
    for script in TUTORIALS.glob("*.py"):
        page = (site / "tutorials" / script.stem / "index.html").read_text(encoding="utf-8")
        text = re.sub(r"<[^>]+>", "", page)  # the highlighted code without its markup
        assert "import shtaerman as sh" in text, script.name  # its code cells are rendered
        assert (site / "tutorials" / script.name).is_file()  # and the script is downloadable


LOADS = re.compile(
    r"<(?:script|link|img|iframe|source|audio|video|embed|object)\b[^>]*?"
    r"""\b(?:src|href|srcset|data)\s*=\s*["']?\s*((?:https?:)?//[^"'\s>]+)""",
    re.I,
)
"""A URL on the network that an element loads (a script, a stylesheet, a font's preconnect,
an image); links (``<a href>``) are not loads."""
CSS_LOADS = re.compile(r"""(?:url\(|@import)\s*["']?\s*((?:https?:)?//[^"')\s]+)""", re.I)
PROBE = """<script>
window.addEventListener("load", () => {
  const out = document.createElement("pre");
  out.id = "probe";
  out.textContent = JSON.stringify(EXPRESSION);
  document.body.appendChild(out);
});
</script>"""
"""Writes, at the load event, the JSON of a JavaScript expression into the DOM."""
NETWORK = 'performance.getEntriesByType("resource").map((e) => e.name)'
"""Every resource the page fetched over the network (Chromium lists http(s) loads, refused ones
included, and not the site's own file:// ones)."""
TABLES = """[...document.querySelectorAll("article table")].map((table) => (
  table.getBoundingClientRect().right - table.closest("article").getBoundingClientRect().right
))"""
"""How far each table of the page sticks out of the text's column, in CSS pixels."""


def probe(browser, page: Path, expression: str) -> tuple[object, str]:
    """Load ``page`` in Chromium with a probe of ``expression``: its value at the load event,
    and the DOM once the page's scripts have run (20 s of virtual time)."""
    probed = page.with_name("probed.html")  # beside it: the same relative links
    script = PROBE.replace("EXPRESSION", expression)
    probed.write_text(page.read_text(encoding="utf-8").replace("</body>", script + "</body>"))
    dom = browser("--virtual-time-budget=20000", "--dump-dom", probed.as_uri())
    match = re.search(r'<pre id="probe">(.*?)</pre>', dom, re.DOTALL)
    assert match, "the probe did not run: " + dom[-500:]
    return json.loads(html.unescape(match.group(1))), dom


def network_loads(page: Path) -> list[str]:
    """URLs on the network that ``page`` loads, itself or through the stylesheets it links."""
    text = page.read_text(encoding="utf-8")
    found = LOADS.findall(text)
    for sheet in re.findall(r'<link\b[^>]*\bhref="([^":]+\.css)"', text):
        found += CSS_LOADS.findall((page.parent / sheet).read_text(encoding="utf-8"))
    return found


def test_theory_page_loads_nothing_from_the_network(site):
    theory = site / "theory" / "index.html"
    # the MathJax of the CDN and the theme's web fonts were loaded from the network
    assert network_loads(theory) == []
    scripts = re.findall(r'<script src="([^"]+)"', theory.read_text(encoding="utf-8"))
    assert "../javascripts/mathjax/tex-svg.js" in scripts  # the MathJax shipped with the site
    licence = (site / "javascripts" / "mathjax" / "LICENSE").read_text(encoding="utf-8")
    assert licence.split()[:4] == ["Apache", "License", "Version", "2.0,"]  # shipped with it


def test_network_loads_sees_a_script_a_font_and_a_stylesheets_import(tmp_path):
    page = tmp_path / "page.html"
    (tmp_path / "style.css").write_text('@import "https://example.org/a.css";', encoding="utf-8")
    page.write_text(
        '<script src="https://cdn.example/m.js"></script><link href="//fonts.example/f">'
        '<link rel="stylesheet" href="style.css"><a href="https://doi.org/10.1">a link</a>',
        encoding="utf-8",
    )
    assert network_loads(page) == [
        "https://cdn.example/m.js",
        "//fonts.example/f",
        "https://example.org/a.css",
    ]


def test_theory_page_typesets_its_equations_with_no_network(site, browser):
    theory = site / "theory" / "index.html"
    formulas = theory.read_text(encoding="utf-8").count('class="arithmatex"')
    assert formulas > 300  # the page's \\( \\) and \\[ \\] formulas (389 when written)
    loaded, dom = probe(browser, theory, NETWORK)
    assert loaded == []  # nothing asked of the network
    # MathJax replaced each formula by its typeset SVG, none failed, and no TeX is left raw
    assert dom.count("<mjx-container") == formulas
    assert dom.count("<svg") >= formulas
    body = re.sub(r"<(script|style|pre)\b.*?</\1>", "", dom, flags=re.S)  # the page's text
    assert "merror" not in body and "data-mjx-error" not in body
    assert "\\[" not in body and "\\(" not in body


ADD_ON_PAGE = """<!doctype html><html><body>
<div class="arithmatex">\\[x^{5/3}\\]</div>
<script>window.document$ = { subscribe: () => {} };</script>
<script src="CONFIG"></script>
<script src="MATHJAX"></script>
<script>
async function probe() {
  await MathJax.startup.promise;
  const found = { menu: MathJax.startup.document.options.enableMenu };
  for (const name of ["a11y/explorer", "a11y/complexity", "a11y/sre"]) {
    try { await MathJax.loader.load(name); found[name] = "loaded"; }
    catch (error) { found[name] = "refused"; }
  }
  try { await window.SREfeature.custom("en"); found.locale = "loaded"; }
  catch (error) { found.locale = "refused"; }
  found.scripts = [...document.scripts].map((s) => s.src).filter((s) => s.includes("a11y"));
  found.network = performance.getEntriesByType("resource").map((e) => e.name)
    .filter((name) => name.startsWith("http"));
  found.typeset = document.querySelectorAll("mjx-container svg").length;
  const out = document.createElement("pre");
  out.id = "probe";
  out.textContent = JSON.stringify(found);
  document.body.appendChild(out);
}
probe();
</script></body></html>"""
"""A page with the docs' MathJax that asks it for its accessibility add-ons and SRE's locale."""


def test_mathjax_of_the_docs_loads_no_add_on(tmp_path, browser):
    # tex-svg.js's menu loads accessibility add-ons as components, and its speech engine's
    # locale files come from cdn.jsdelivr.net: the docs' config refuses them all, whatever a
    # reader switches on (the add-on's script was inserted, a request for a file not shipped)
    scripts = ROOT / "docs" / "javascripts"
    page = tmp_path / "page.html"
    text = ADD_ON_PAGE.replace("CONFIG", (scripts / "mathjax.js").as_uri())
    page.write_text(text.replace("MATHJAX", (scripts / "mathjax" / "tex-svg.js").as_uri()))
    dom = browser("--virtual-time-budget=20000", "--dump-dom", page.as_uri())
    match = re.search(r'<pre id="probe">(.*?)</pre>', dom, re.DOTALL)
    assert match, "the probe did not run: " + dom[-500:]
    found = json.loads(html.unescape(match.group(1)))
    assert found["menu"] is False  # no menu to switch an add-on on from
    for name in ("a11y/explorer", "a11y/complexity", "a11y/sre", "locale"):
        assert found[name] == "refused", name
    assert found["scripts"] == [] and found["network"] == []
    assert found["typeset"] == 1  # and the formula is typeset all the same


def test_parameter_tables_fit_the_page(site, browser):
    sticking_out, _ = probe(browser, site / "parameters" / "index.html", TABLES)
    # the study-file table's Meaning column ran 49 px past the text's edge, cut off
    assert max(sticking_out) <= 0.5  # half a pixel: rounding of the layout
    [commands] = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    # a table per group, per loading of the combinations (3), per command, and the option
    # limits' ("Which options apply where")
    assert len(sticking_out) == 3 + 3 + len(commands.choices) + 1


def test_api_reference_documents_the_public_api(site):
    page = (site / "api" / "index.html").read_text(encoding="utf-8")
    text = " ".join(re.sub(r"<[^>]+>", " ", page).split())
    # every public class and function (RIGID is a Material instance, documented with Material)
    names = set(sh.__all__) - {"__version__", "RIGID", "SweepSpec", "SweepOutcome"}
    documented = {name: f"shtaerman.{name}" for name in names}
    documented["sweep"] = "shtaerman.api.sweep"  # sh.sweep is also the package: its function
    for name, path in documented.items():
        assert f'id="{path}"' in page, name
        obj = getattr(sh.api, name)
        assert " ".join(obj.__doc__.split()[:3]) in text, name  # with its docstring
    assert 'id="shtaerman.SweepSpec"' in page and 'id="shtaerman.SweepOutcome"' in page


def test_api_reference_shows_no_raw_sphinx_role(site):
    page = (site / "api" / "index.html").read_text(encoding="utf-8")
    text = html.unescape(re.sub(r"<[^>]+>", "", page))
    # the docstrings' :func:`name` roles (34 were shown raw): as code, linked where documented
    assert re.findall(r":(?:py:)?[a-z]+:`?\w", text) == []
    target = "shtaerman.theory.ateb.ateb_sine"
    assert re.search(f'<a class="autorefs [^>]*href="#{target}"><code>ateb_sine</code></a>', page)
    # a target the site does not document is code, not a broken link
    assert '<span title="shtaerman.theory.layer"><code>shtaerman.theory.layer</code></span>' in page


def test_parameter_table_lists_every_cli_option_with_its_default(site):
    page = (site / "parameters" / "index.html").read_text(encoding="utf-8")
    [commands] = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    for name, parser in commands.choices.items():
        section = page.split(f"shtaerman {name}</code>", 1)[1]
        for action in parser._actions:
            if action.option_strings and action.option_strings[-1] != "--help":
                assert action.option_strings[-1] in section, (name, action.option_strings)
    contact = page.split("shtaerman contact</code>", 1)[1]
    refine = contact.split("--refine", 1)[1].split("</tr>", 1)[0]
    default = commands.choices["contact"].get_default("refine")
    assert f"<code>{default}</code>" in refine


def help_options(command: str, capsys) -> set[str]:
    """The options that ``shtaerman COMMAND --help`` lists."""
    with pytest.raises(SystemExit) as exit:
        main([command, "--help"])
    assert exit.value.code == 0
    return set(re.findall(r"(?<![\w-])--[A-Za-z0-9][\w-]*", capsys.readouterr().out))


def test_parameter_page_shows_only_options_the_cli_takes(site, capsys):
    page = (site / "parameters" / "index.html").read_text(encoding="utf-8")
    [commands] = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    taken = {name: help_options(name, capsys) for name in commands.choices}
    everywhere = set().union(*taken.values())
    # every option on the page is one of some command (--thickness-ratio and --dynamic were not)
    assert set(re.findall(r"<code>(--[\w-]+)", page)) <= everywhere
    rows = re.findall(r"<td><code>(\w+)</code><br>(.*?)</td>", page)
    assert len(rows) == len(VOCABULARY)  # one per input, each with its option or none
    for key, cell in rows:
        shown = re.fullmatch(r"<code>(--[\w-]+)</code> \(([\w, -]+)\)", cell)
        if shown is None:  # a study and sweep key with no option
            assert cell == "study and sweep key only" and entry(key).kinds, key
            assert "--" + key.replace("_", "-") not in everywhere, key
            continue
        option, listed = shown[1], shown[2].split(", ")
        assert listed == [name for name, options in taken.items() if option in options], key


def test_tutorial_own_indenter(tmp_path, capsys):
    got = run_tutorial(
        "own_indenter",
        tmp_path,
        *("x_c", "P_c", "t_c", "x_c_formula", "force_estimate", "shtaerman_ratio"),
        *("curve.depth", "impact.restitution", "impact.x_max", "impact.P_max"),
    )
    indenter = sh.PowerLawIndenter(shape_coefficient=12.0, exponent=1.8)
    rubber = sh.Material(youngs_modulus=4e6, poisson_ratio=0.49)
    exact = sh.impact(indenter, rubber, mass=0.25, velocity=2.0)
    case = "--exponent 1.8 --shape-coefficient 12 --E1 inf --E2 4e6 --nu2 0.49"
    assert main(["impact", *case.split(), "--mass", "0.25", "--velocity", "2", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    for key in ("x_c", "P_c", "t_c"):  # the API and the CLI give the same exact impact
        assert got[key] == pytest.approx(getattr(exact, key), rel=1e-12), key
        assert got[key] == pytest.approx(cli[key], rel=1e-12), key
    assert got["x_c_formula"] == pytest.approx(got["x_c"], rel=1e-12)
    # the FEM curve reaches this case's x_c, not the paper's, and agrees with Shtaerman within
    # its own estimate (the estimator's measured effectivity >= 0.55 allows up to 1.8x)
    assert got["curve.depth"][-1] == pytest.approx(got["x_c"], rel=1e-12)
    assert 4e-3 < got["x_c"] < 5e-3
    assert 0 < got["force_estimate"] < 5e-3
    assert max(abs(r) for r in got["shtaerman_ratio"]) <= 2 * got["force_estimate"]
    # the dynamic impact loses energy to waves: a slower rebound, a shallower, softer impact
    assert 0.5 < got["impact.restitution"] < 1
    assert got["impact.x_max"] < got["x_c"] and got["impact.P_max"] < got["P_c"]


def test_tutorial_dynamic_impact(tmp_path):
    got = run_tutorial("dynamic_impact", tmp_path, "result", "differences", "estimate")
    dynamic = got["result"]["dynamic"] if "dynamic" in got["result"] else got["result"]
    restitution = dynamic["restitution"]
    loss = 1 - restitution**2
    # waves take energy, less than the first-order estimate and within 30 % of it
    assert 0.85 < restitution < 1
    assert 0.7 * got["estimate"]["energy_fraction"] < loss < got["estimate"]["energy_fraction"]
    # the quasi-static force overstates the dynamic peak, more at 3 m/s than at 1 m/s
    assert 0 < got["differences"]["1.0"] < got["differences"]["3.0"] < 0.1
    assert all(0 < error < 1e-2 for error in got["result"]["error_estimate"].values())


def test_tutorial_finite_strain(tmp_path):
    got = run_tutorial("finite_strain", tmp_path, "ratio_at_x_c")
    # incompressible rubber softens below beta x^q at x_c, the compressible one stiffens
    assert 0.9 < got["ratio_at_x_c"]["0.5"] < 0.99
    assert 1.01 < got["ratio_at_x_c"]["0.3"] < 1.2


def test_tutorial_sweep(tmp_path):
    got = run_tutorial("sweep", tmp_path, "rows")
    assert len(got["rows"]) == 6
    indenter = sh.PowerLawIndenter(shape_coefficient=12.0, exponent=1.8)
    for row in got["rows"]:
        assert row["status"] == "ok"
        rubber = sh.Material(youngs_modulus=float(row["E2 [Pa]"]), poisson_ratio=0.49)
        exact = sh.impact(indenter, rubber, mass=0.25, velocity=float(row["velocity [m/s]"]))
        assert float(row["x_c [m]"]) == pytest.approx(exact.x_c, rel=1e-12)


def test_citation_and_licence_match_the_package():
    yaml = pytest.importorskip("yaml")  # PyYAML comes with mkdocs (the docs extra)
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert citation["cff-version"] == "1.2.0"
    assert citation["version"] == sh.__version__
    [paper] = citation["references"]
    assert paper["doi"] in (ROOT / "README.md").read_text(encoding="utf-8")
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert citation["license"] == project["license"]["text"] == "MIT"
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("MIT License\n")
    assert citation["authors"] == [{"name": "the shtaerman developers"}]  # an entity
    # the changelog has the package's version, released on the citation's date, and its
    # version policy, which the README links to
    changelog = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert f"\n## [{sh.__version__}] - {citation['date-released']}\n" in changelog
    assert "\n## Version policy\n" in changelog and "**breaking**" in changelog
    assert "[CHANGELOG.md](CHANGELOG.md)" in (ROOT / "README.md").read_text(encoding="utf-8")


def docs_commands() -> list[str]:
    """Every ``shtaerman`` command in the docs pages' console blocks, comments removed."""
    found = []
    for page in sorted((ROOT / "docs").glob("*.md")):
        for block in re.findall(r"```console\n(.*?)```", page.read_text(encoding="utf-8"), re.S):
            lines = (re.sub(r"\s+#\s.*$", "", line).strip() for line in block.splitlines())
            found += [line for line in lines if line.startswith("shtaerman ")]
    return found


@pytest.mark.parametrize("command", docs_commands())
def test_docs_commands_parse(command, capsys):
    # the pages' examples use only options the command line has (they are not all run: the
    # README's are, by test_readme.py)
    words = shlex.split(command)[1:]
    if "--help" in words:
        return
    try:
        build_parser().parse_args(words)
    except SystemExit as exit:
        pytest.fail(f"{command}: exit {exit.code}: {capsys.readouterr().err}")


PYTHON_BLOCKS = [
    (page.stem, block)
    for page in sorted((ROOT / "docs").glob("*.md"))
    for block in re.findall(r"```python\n(.*?)```", page.read_text(encoding="utf-8"), re.S)
]


@pytest.mark.parametrize("page, block", PYTHON_BLOCKS, ids=[page for page, _ in PYTHON_BLOCKS])
def test_docs_python_blocks_run(page, block, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a block that writes a file (docs/fit.md: drop.csv) writes it here
    namespace = {}
    exec(compile(block, f"docs/{page}.md", "exec"), namespace)
    # the numbers the pages' comments show (exact impacts)
    if page == "getting-started":  # this case: A = 12, n = 1.8, 4 MPa, 0.25 kg at 2 m/s
        q = namespace["q"]
        assert (q.x_c, q.P_c, q.t_c) == pytest.approx((4.6252e-3, 276.266, 3.3827e-3), rel=1e-4)
    if page == "guide" and "pad" in namespace:  # one Problem: its cell, and a run
        cell = ("rubber", True, "layer bonded", "frictionless", "inertia")
        assert namespace["pad"].cell == cell
        assert 0.0 < namespace["result"].restitution <= 1.0
    elif page == "guide" and "table" in namespace:  # the effect table, friction included
        table = namespace["table"]
        # nu2 = 0.49: Dundurs' beta = (1 - 2 nu) / (2 (1 - nu)) = 0.0098 nearly decouples the
        # shear from the normal contact: bonded with mu 0.5 moves P_max by -5e-5 (measured)
        friction, none = table.run("friction alone"), table.run("none")
        assert friction.refused is None
        assert friction.values["P_max"] == pytest.approx(none.values["P_max"], rel=2e-4)
        # the waves alone: P_max 1.5 % below the paper's P_c = 64.96 N (coarse mesh)
        assert table.run("waves alone").values["P_max"] == pytest.approx(63.95, rel=2e-3)
    elif page == "guide":  # the paper's example with the theory layer
        impact, contact = namespace["impact"], namespace["contact"]
        assert impact.x_c == pytest.approx(8.5175e-3, rel=1e-4)
        assert impact.P_c == pytest.approx(986.21, rel=1e-5)
        assert impact.t_c == pytest.approx(4.1052e-3, rel=1e-4)
        assert contact.pressure(0.0, impact.x_c) == pytest.approx(impact.p_c, rel=1e-9)
    if page == "fit":  # the synthetic drop test: every value back within its interval
        fitted = namespace["result"].fitted
        true = {"E2": 7.5e6, "g1": 0.3, "time_offset": 1e-3, "baseline": 0.5}
        for name, value in true.items():
            assert fitted[name]["low"] <= value <= fitted[name]["high"], name
        # the page's printed E2 (one seed, so one exact number: the fit is deterministic)
        assert fitted["E2"]["value"] == pytest.approx(7.5209e6, rel=1e-4)


def test_docs_python_blocks_are_checked():
    assert {page for page, _ in PYTHON_BLOCKS} == {"getting-started", "guide", "fit"}


def test_hook_shows_each_cells_output_when_executing(tmp_path, monkeypatch):
    spec = importlib.util.spec_from_file_location("docs_hooks", ROOT / "docs" / "hooks.py")
    hooks = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(hooks)
    script = tmp_path / "tiny.py"
    script.write_text(
        '# %% [markdown]\n# # Tiny\n\n# %%\nx = 6 * 7\nprint("x is", x)\n\n'
        '# %%\nimport os\nprint(os.listdir("."))\n',
        encoding="utf-8",
    )
    monkeypatch.chdir(tmp_path)
    page = hooks.tutorial_page(script, execute=True)
    assert '```python\nx = 6 * 7\nprint("x is", x)\n```\n\n```text\nx is 42\n```' in page
    assert "```text\n[]\n```" in page  # run in a fresh, empty folder, not in the docs
    assert "```text" not in hooks.tutorial_page(script)  # the default build runs nothing


def test_parameter_page_lists_the_study_and_sweep_vocabulary(site):
    vocabulary = pytest.importorskip("shtaerman.vocabulary")  # where the package declares it
    page = (site / "parameters" / "index.html").read_text(encoding="utf-8")
    for item in vocabulary.VOCABULARY:
        assert f"<code>{item.name}</code>" in page, item.name


def test_the_parameter_page_shows_which_parts_combine(site):
    """The grid comes from shtaerman.problem.support_table(): every cell and every reason."""
    from shtaerman.problem import SUPPORT, support_table

    page = html.unescape(re.sub(r"<[^>]+>", " ", (site / "parameters" / "index.html").read_text()))
    running = sum(verdict == "runs" for _, verdict in support_table())
    assert f"Of the 108 combinations below, {running} run" in " ".join(page.split())
    for limit in SUPPORT:
        assert " ".join(limit.reason.split()) in " ".join(page.split())


def test_the_parameter_page_shows_which_options_apply_where(site):
    """Every limit of shtaerman.problem.OPTION_SUPPORT is a row: its options, the combinations
    it limits and its reason (the page showed SUPPORT alone)."""
    from shtaerman.problem import OPTION_SUPPORT

    page = html.unescape(re.sub(r"<[^>]+>", " ", (site / "parameters" / "index.html").read_text()))
    text = " ".join(page.split())
    assert "Which options apply where" in text
    for limit in OPTION_SUPPORT:
        reason = limit.reason.replace("{model!r}", "<model>").replace("{model}", "<model>")
        reason = re.sub(r"\{value[^}]*\}", "<value>", reason)
        assert " ".join(reason.split()) in text, reason
        assert all(option in text for option in limit.options)
    # the massless body's limit names its loading and only it (a row: options, where, reason)
    assert "layer_rate loading: massless applies to a body with mass only" in text
    assert "max_time loading: curve applies with accuracy" in text


def test_the_parameter_page_shows_angle_brackets_as_text(site):
    """The sweep's '--out' help 'sweep-<name>' was read as an HTML tag and vanished."""
    page = (site / "parameters" / "index.html").read_text(encoding="utf-8")
    text = html.unescape(re.sub(r"<[^>]+>", "", page))
    assert "result folder (default: sweep-<name>)" in " ".join(text.split())


def test_findings_link_every_validated_result_to_its_row():
    """Each published comparison of the Validation page (a ``##`` section) is quoted by the
    finding it covers, and every such link names a heading of that page (mkdocs --strict
    reports a broken anchor only as INFO)."""
    from markdown.extensions.toc import slugify

    headings = re.findall(r"^#{2,3} (.+)$", (ROOT / "docs/validation.md").read_text(), re.M)
    anchors = {slugify(h, "-") for h in headings}
    sections = re.findall(r"^## (.+)$", (ROOT / "docs/validation.md").read_text(), re.M)
    linked = re.findall(r"\(validation\.md#([\w-]+)\)", (ROOT / "docs/findings.md").read_text())
    assert set(linked) <= anchors, set(linked) - anchors
    assert {slugify(h, "-") for h in sections} <= set(linked)


def test_every_cross_reference_in_a_docstring_names_what_exists():
    """A :data:/:func:/:class: reference to shtaerman.X resolves (PROFILE_SUPPORT, deleted,
    was still named by sh.dynamic's docstring; sneddon.tabulated_integrals by profiles')."""
    import importlib

    pattern = re.compile(r":(?:data|func|class|meth|attr):`~?(shtaerman(?:\.\w+)+)`")
    missing = []
    for path in sorted((ROOT / "src" / "shtaerman").rglob("*.py")):
        for match in pattern.finditer(path.read_text(encoding="utf-8")):
            names = match.group(1).split(".")
            for cut in range(len(names) - 1, 0, -1):  # the longest importable module
                try:
                    found = importlib.import_module(".".join(names[:cut]))
                except ImportError:
                    continue
                for name in names[cut:]:  # a dataclass's field is no class attribute
                    fields = getattr(found, "__dataclass_fields__", {})
                    found = fields[name] if name in fields else getattr(found, name, None)
                if found is None:
                    missing.append(f"{path.relative_to(ROOT)}: {match.group(1)}")
                break
    assert missing == []
