"""`shtaerman verify --quick`: the main job end to end on coarse meshes, as CI runs it."""

import json
import re
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np
import pytest
from served_verify import serve_writing

import shtaerman
import shtaerman.output.folder
from shtaerman.cli import main
from shtaerman.output.files import FOLDER_MARKER
from shtaerman.study.contact.runner import IMPACT_KEYS
from shtaerman.study.schema import shipped_studies

STUDIES = [str(p) for p in shipped_studies() if p.stem in ("paper", "hertz")]
"""The studies of the session's quick verify run (tests/conftest.py)."""
FIRST, SECOND = (Path(p).stem for p in STUDIES)
"""Their names, in the order they run."""


@pytest.fixture(scope="module")
def run(quick_verify):
    """The session's ``verify --quick`` of the paper and Hertz studies (tests/conftest.py)."""
    return quick_verify


def test_verify_passes(run):
    code, _, results = run
    assert code == 0 and results["passed"] is True and results["quick"] is True


def test_results_schema(run):
    _, _, results = run
    assert set(results) >= {"studies", "environment", "passed"}
    assert set(results["studies"]) == {"paper", "hertz"}
    for study in results["studies"].values():
        assert set(study) >= {"contact", "impact", "passed"}
        assert {"beta_fem", "beta_analytic", "exponent_fem", "steps", "mesh", "timings"} <= set(
            study["contact"]
        )
        assert set(study["impact"]) == {"analytic", "fem_fitted", "fem_tabulated"}
        for variant in study["impact"].values():
            assert set(variant) == set(IMPACT_KEYS)
    assert results["environment"]["packages"]["scikit-fem"]


def test_fem_fed_impact_agrees_with_exact(run):
    # the 0.2 % for x_c, P_c, t_c; measured on the quick mesh: <= 2e-4
    paper = run[2]["studies"]["paper"]
    for variant in ("fem_fitted", "fem_tabulated"):
        for key in ("x_c", "P_c", "t_c"):
            assert abs(paper["differences"][variant][key]) < 2e-3


def test_convergence_study_in_results(run):
    # quick mode: the paper study's three coarsest meshes (5k-15k dofs); the force error falls
    # 1.5e-3 -> 7.4e-4 -> 3.7e-4, an observed order of about 2 (2.6 over five default levels)
    convergence = run[2]["studies"]["paper"]["convergence"]
    forces = [level["errors"]["force"] for level in convergence["levels"]]
    assert len(forces) == 3 and forces[0] > forces[1] > forces[2]
    assert convergence["fitted_orders"]["force"] > 1.5
    assert (run[1] / "paper" / "convergence.png").is_file()


def test_images_are_pictures(run):
    _, out, _ = run
    pngs = sorted(out.rglob("*.png"))
    assert len(pngs) >= 2 * 9 + 1 + 1  # 9 per study, the paper's convergence, the Ateb figure
    for path in pngs:
        image = mpimg.imread(path)[..., :3]
        # not blank: real contrast and many distinct colours (RGB packed into one integer)
        assert image.std() > 0.05, path.name
        rgb = np.round(image * 255).astype(np.int64).reshape(-1, 3)
        assert np.unique(rgb @ np.array([65536, 256, 1])).size > 50, path.name


def test_report_is_self_contained(run):
    _, out, _ = run
    page = (out / "report.html").read_text()
    sources = re.findall(r'src="([^"]*)"', page)
    assert sources and all(s.startswith("data:image/png;base64,") for s in sources)
    assert "PASS" in page and "paper" in page
    assert "![" in (out / "report.md").read_text()


def test_existing_folder_is_kept_without_force(run, capsys):
    _, out, _ = run
    before = sorted(p.name for p in out.iterdir())
    assert main(["verify", "--quick", "--workers", "1", "--out", str(out), *STUDIES]) == 2
    assert "use --force" in capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == before


def test_failed_run_leaves_nothing(tmp_path, monkeypatch):
    def broken(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(shtaerman.output.folder, "run_study", broken)
    out = tmp_path / "run"
    assert main(["verify", "--quick", "--workers", "1", "--out", str(out), *STUDIES]) == 130
    assert list(tmp_path.iterdir()) == []


def test_failing_study_exits_1(tmp_path):
    study = tmp_path / "strict.toml"
    [paper] = [path for path in STUDIES if path.endswith("paper.toml")]
    text = open(paper).read()
    assert "force = 1e-3" in text
    # the strict force tolerance fails; the convergence study plays no part in that (dropped)
    text = re.sub(r"(?ms)^\[convergence\].*?(?=^\[|\Z)", "", text)
    assert "sizes" not in text
    study.write_text(text.replace("force = 1e-3", "force = 1e-9"))
    assert main(["verify", "--quick", "--out", str(tmp_path / "run"), str(study)]) == 1
    results = json.loads((tmp_path / "run" / "results.json").read_text())
    assert results["passed"] is False
    # the report names the failing check first, with its value and tolerance
    report = (tmp_path / "run" / "report.md").read_text()
    assert report.index("## FAILED checks") < report.index("## Summary")
    assert "- **paper**: contact force = " in report and "tolerance ±1.0e-09" in report


def test_malformed_study_is_exit_2(tmp_path, capsys):
    study = tmp_path / "bad.toml"
    study.write_text("[indenter]\nexponent = 'x'\n")
    assert main(["verify", "--out", str(tmp_path / "run"), str(study)]) == 2
    err = capsys.readouterr().err
    assert "bad.toml: key 'indenter.exponent': exponent must be a number in (1, 20], got 'x'" in err
    assert not (tmp_path / "run").exists()


def test_studies_run_as_dask_tasks_give_the_same_results(quick_verify, tmp_path, capsys):
    # the same two quick studies as quick_verify (in-process), now one dask task each on a
    # local cluster of two worker processes: every check value is identical
    out = tmp_path / "dask"
    assert main(["verify", "--quick", "--workers", "2", "--out", str(out), *STUDIES]) == 0
    assert "2 studies on 2 workers" in capsys.readouterr().err
    on_dask = json.loads((out / "results.json").read_text())
    in_process = quick_verify[2]
    assert list(on_dask["studies"]) == list(in_process["studies"])  # the files' order
    for name, study in in_process["studies"].items():
        assert on_dask["studies"][name]["checks"] == study["checks"]
    assert (out / "report.html").is_file() and not list(tmp_path.glob(".*partial*"))
    # the Ateb figures, a task of their own on a worker there, drawn in this process here:
    # the same captions and the same bytes
    assert on_dask["figures"] == in_process["figures"] and len(on_dask["figures"]) == 2
    for path in on_dask["figures"].values():
        assert (out / path).read_bytes() == (quick_verify[1] / path).read_bytes()


def test_the_shared_figures_are_drawn_for_the_exponents_the_entries_have(quick_verify):
    # run_verification draws the Ateb figures of the studies' exponents as the studies run;
    # finish_verification keeps them only if its entries (what results.json records) have the
    # same exponents, else draws them again: they must agree for the shipped studies
    from shtaerman.output.folder import study_exponents
    from shtaerman.study.schema import load_study

    studies = [study for path in STUDIES for study in load_study(path)]
    entries = quick_verify[2]["studies"].values()
    assert (
        sorted(set(study_exponents(studies)))
        == sorted({entry["inputs"]["exponent"] for entry in entries})
        == [1.5, 2.0]
    )


@pytest.mark.parametrize("workers", ["1", "2"])
def test_a_study_the_fem_refuses_at_run_time_names_its_file(tmp_path, capfd, workers):
    # a depth below the mesh's resolution is refused only once the FEM runs: the message
    # named no file, and two studies on dask workers printed a "Compute Failed" traceback
    # before it (QA)
    paper = next(p for p in shipped_studies() if p.stem == "paper")
    text = re.sub(r'(?m)^depths = "impact".*$', "depths = [1e-15, 1e-3]", paper.read_text())
    studies = [tmp_path / "tiny.toml", tmp_path / "tiny2.toml"]
    studies[0].write_text(text)
    studies[1].write_text(re.sub(r"(?m)^name = .*$", 'name = "tiny2"', text))
    out = tmp_path / "out"
    argv = ["verify", *map(str, studies), "--quick", "--workers", workers, "--out", str(out)]
    assert main(argv) == 2
    err = capfd.readouterr().err
    assert re.search(
        r"shtaerman: error: .*tiny2?\.toml: study '(paper|tiny2)': "
        r"key 'contact.depths': the smallest, 1e-15 m",
        err,
    )
    assert "Traceback" not in err and "Compute Failed" not in err
    assert not out.exists()


def _interrupting(quick_outcomes, stop_at, served):
    """A run_study that serves the session's quick outcomes and raises ``stop_at`` (an
    exception instance) for the study named in it."""

    def run_study(study, *, quick=False, progress=None):
        served.append(study.name)
        if study.name == stop_at[0]:
            raise stop_at[1]
        assert quick and quick_outcomes[study.name].study == study
        return quick_outcomes[study.name]

    return run_study


def _serve_writing(patch, quick_outcomes, quick_verify):
    """Serve the files of the session's quick outcomes from quick_verify's folder
    (tests/served_verify.py)."""
    _, done, results = quick_verify
    serve_writing(patch.setattr, quick_outcomes, done, results)


@pytest.fixture(scope="module")
def interrupted(quick_outcomes, quick_verify, tmp_path_factory):
    """The folder of ``verify --quick`` of STUDIES stopped by Ctrl-C in its second study (exit
    130), written once: the tests that resume from it copy it (incomplete.json and the folder
    marker name no absolute path, so a copy is the folder such a run leaves). Its writing
    (the first study's figures and fields) took 3 CPU s per test."""
    out = tmp_path_factory.mktemp("interrupted") / "run"
    with pytest.MonkeyPatch.context() as patch:
        _serve_writing(patch, quick_outcomes, quick_verify)
        patched = _interrupting(quick_outcomes, [SECOND, KeyboardInterrupt()], [])
        patch.setattr(shtaerman.output.folder, "run_study", patched)
        assert main(["verify", "--quick", "--workers", "1", "--out", str(out), *STUDIES]) == 130
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [FOLDER_MARKER, "incomplete.json", FIRST]
    )
    return out


def _interrupted_copy(interrupted, out):
    """A copy at ``out`` of the interrupted run's folder."""
    import shutil

    shutil.copytree(interrupted, out)
    return out


@pytest.mark.parametrize(("signal_like", "code"), [(KeyboardInterrupt(), 130), ("terminated", 143)])
def test_an_interrupted_verify_keeps_finished_studies_and_resumes(
    quick_outcomes, quick_verify, tmp_path, monkeypatch, capsys, signal_like, code
):
    from shtaerman.cli import Terminated

    stop = Terminated() if signal_like == "terminated" else signal_like
    _serve_writing(monkeypatch, quick_outcomes, quick_verify)
    served = []
    patched = _interrupting(quick_outcomes, [SECOND, stop], served)
    monkeypatch.setattr(shtaerman.output.folder, "run_study", patched)
    out = tmp_path / "run"
    argv = ["verify", "--quick", "--workers", "1", "--out", str(out), *STUDIES]
    assert main(argv) == code
    err = capsys.readouterr().err
    assert served == [FIRST, SECOND]
    # the finished study is kept, complete, with the marker; no results.json, no report
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [FOLDER_MARKER, "incomplete.json", FIRST]
    )
    assert sorted(p.name for p in (out / FIRST).iterdir()) == sorted(
        p.name for p in (quick_verify[1] / FIRST).iterdir()
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]  # no staging debris
    assert "1 of 2 studies finished and kept" in err
    command = err.split("complete them with: ")[1].strip()
    assert command.endswith("--resume") and "--quick" in command
    # the printed command computes only the missing study and writes the whole folder
    served.clear()
    monkeypatch.setattr(
        shtaerman.output.folder, "run_study", _interrupting(quick_outcomes, [None], served)
    )
    assert main(command.split()[1:]) == 0
    assert served == [SECOND]
    results = json.loads((out / "results.json").read_text())
    expected = quick_verify[2]
    assert list(results["studies"]) == [FIRST, SECOND]
    for name, study in expected["studies"].items():
        assert results["studies"][name]["checks"] == study["checks"]
    assert not (out / "incomplete.json").exists() and (out / "report.html").is_file()
    assert sorted(p.name for p in out.iterdir()) == sorted(
        p.name for p in quick_verify[1].iterdir()
    )


def test_resume_refuses_other_studies_than_the_interrupted_runs(
    quick_outcomes, interrupted, tmp_path, monkeypatch, capsys
):
    """The adversary's item: 'verify paper hertz' stopped after paper, resumed as 'verify paper
    dynamic --resume', ran dynamic and dropped hertz for good (exit 0)."""
    patched = _interrupting(quick_outcomes, [SECOND, KeyboardInterrupt()], [])
    monkeypatch.setattr(shtaerman.output.folder, "run_study", patched)
    out = _interrupted_copy(interrupted, tmp_path / "run")
    before = sorted(p.name for p in out.iterdir())
    other = [study for study in STUDIES if Path(study).stem == FIRST]
    argv = ["verify", "--quick", "--workers", "1", "--out", str(out), *other, "--resume"]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    # the command line's option, as every refusal there (it said 'resume: ...')
    assert err.startswith("shtaerman: error: --resume: the interrupted run was of"), err
    assert SECOND in err and "\n" not in err
    assert sorted(p.name for p in out.iterdir()) == before  # nothing dropped


def test_a_resume_refusal_names_the_option_on_the_command_line_and_the_keyword_in_python(
    tmp_path, capsys
):
    """verify --resume's refusals say --resume (old code: 'resume: ...', the API's keyword);
    the library raises them with the keyword and declares it (the Python route's words)."""
    from shtaerman.output.folder import PROGRESS_FILE, kept_entries

    assert main(["verify", "--resume"]) == 2
    assert capsys.readouterr().err == (
        "shtaerman: error: --resume: name the folder to complete with --out DIR\n"
    )
    (tmp_path / PROGRESS_FILE).write_text("not json", encoding="utf-8")
    with pytest.raises(shtaerman.InputError) as refused:
        kept_entries(tmp_path, [], quick=True)
    assert str(refused.value).startswith(f"resume: {PROGRESS_FILE} is not one this tool wrote")
    assert refused.value.parameter == "resume"


def test_a_verify_stopped_after_every_study_says_the_summary_is_missing_and_resume_writes_it(
    quick_outcomes, quick_verify, tmp_path, monkeypatch, capsys
):
    """Ctrl-C once every study has finished, while results.json and the reports are written:
    it said "2 of 2 studies finished and kept ...; complete them with", as if studies were
    missing. It says that the summary is, and the command writes it without computing any."""
    _serve_writing(monkeypatch, quick_outcomes, quick_verify)
    served = []
    monkeypatch.setattr(
        shtaerman.output.folder, "run_study", _interrupting(quick_outcomes, [None], served)
    )
    finish = shtaerman.output.folder.finish_verification

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(shtaerman.output.folder, "finish_verification", interrupted)
    out = tmp_path / "run"
    assert main(["verify", "--quick", "--workers", "1", "--out", str(out), *STUDIES]) == 130
    err = capsys.readouterr().err.splitlines()[-1]
    assert served == [FIRST, SECOND] and not (out / "results.json").exists()
    assert err.startswith(
        f"shtaerman: interrupted: all 2 studies finished and kept in {str(out)!r}, the summary "
        "and reports not written; write them with: shtaerman verify "
    )
    assert err.endswith("--resume")
    monkeypatch.setattr(shtaerman.output.folder, "finish_verification", finish)
    assert main(err.split("write them with: ")[1].split()[1:]) == 0
    assert served == [FIRST, SECOND]  # no study computed again
    results = json.loads((out / "results.json").read_text())
    assert list(results["studies"]) == [FIRST, SECOND] and (out / "report.html").is_file()


def test_resume_refuses_a_folder_no_interrupted_run_left(quick_verify, tmp_path, capsys):
    _, out, _ = quick_verify
    before = sorted(p.name for p in out.iterdir())
    argv = ["verify", "--quick", "--workers", "1", "--out", str(out), "--resume", *STUDIES]
    assert main(argv) == 2
    assert "holds no interrupted run to complete (no incomplete.json)" in capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == before


def test_resume_recomputes_a_study_whose_inputs_changed(
    quick_outcomes, quick_verify, interrupted, tmp_path, monkeypatch, capsys
):
    _serve_writing(monkeypatch, quick_outcomes, quick_verify)
    served = []
    out = _interrupted_copy(interrupted, tmp_path / "run")
    # the kept study was run for other inputs (edited file): it is computed again
    progress = json.loads((out / "incomplete.json").read_text())
    progress["studies"][FIRST]["fingerprint"] = "0" * 16
    (out / "incomplete.json").write_text(json.dumps(progress))
    served.clear()
    monkeypatch.setattr(
        shtaerman.output.folder, "run_study", _interrupting(quick_outcomes, [None], served)
    )
    argv = ["verify", "--quick", "--workers", "1", "--out", str(out), "--resume", *STUDIES]
    assert main(argv) == 0
    assert served == [FIRST, SECOND]
    # and a quick folder is not completed by a full run
    capsys.readouterr()
    out2 = _interrupted_copy(interrupted, tmp_path / "run2")
    monkeypatch.setattr(
        shtaerman.output.folder,
        "run_study",
        _interrupting(quick_outcomes, [SECOND, KeyboardInterrupt()], served),
    )
    argv = ["verify", "--workers", "1", "--out", str(out2), "--resume", *STUDIES]
    assert main(argv) == 2
    assert "the interrupted run was with --quick" in capsys.readouterr().err
    assert sorted(p.name for p in out2.iterdir()) == sorted(
        [FOLDER_MARKER, "incomplete.json", FIRST]
    )
    # nor by a run of other studies: the finished one would be deleted without a word
    argv = ["verify", "--quick", "--workers", "1", "--out", str(out2), "--resume", STUDIES[1]]
    assert main(argv) == 2
    assert f"the interrupted run also finished '{FIRST}'" in capsys.readouterr().err
    assert sorted(p.name for p in out2.iterdir()) == sorted(
        [FOLDER_MARKER, "incomplete.json", FIRST]
    )


def test_resume_on_dask_computes_only_the_missing_study(
    quick_outcomes, quick_verify, interrupted, tmp_path, monkeypatch, capsys
):
    monkeypatch.setattr(  # in this process only: the resume's study runs on a dask worker
        shtaerman.output.folder,
        "run_study",
        _interrupting(quick_outcomes, [SECOND, KeyboardInterrupt()], []),
    )
    out = _interrupted_copy(interrupted, tmp_path / "run")
    argv = ["verify", "--quick", "--workers", "2", "--out", str(out), "--resume", *STUDIES]
    assert main(argv) == 0
    assert "1 studies on 1 workers" in capsys.readouterr().err
    results = json.loads((out / "results.json").read_text())
    assert list(results["studies"]) == [FIRST, SECOND]
    for name, study in quick_verify[2]["studies"].items():
        assert results["studies"][name]["checks"] == study["checks"]
    assert not (out / "incomplete.json").exists()


def test_sweep_values_too_close_to_name_apart_are_refused_in_words_a_user_can_act_on(
    tmp_path, capsys
):
    paper = next(p for p in shipped_studies() if p.stem == "paper")
    study = tmp_path / "sw.toml"
    study.write_text(paper.read_text() + "\n[sweep]\nvelocity = [1.0000001, 1.0000002]\n")
    assert main(["verify", "--quick", "--out", str(tmp_path / "run"), str(study)]) == 2
    err = capsys.readouterr().err
    assert f"the [sweep] of {study} gives two studies the name 'paper-v01'" in err
    assert "rename one" not in err and err.count("\n") == 1
    assert not (tmp_path / "run").exists()


def test_study_files_that_cannot_be_read_are_one_line(tmp_path, capsys):
    import os

    deep = tmp_path / "deep.toml"
    deep.write_text("a = " + "[" * 5000)
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    huge = tmp_path / "huge.toml"
    with open(huge, "wb") as stream:
        stream.truncate(17 << 20)
    for path, needle in [
        (deep, "not valid TOML (nested too deeply)"),
        (fifo, "not a regular file"),
        (huge, "a study file has at most"),
    ]:
        assert main(["verify", "--out", str(tmp_path / "run"), str(path)]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"shtaerman: error: {path}: {needle}") and err.count("\n") == 1
    assert not (tmp_path / "run").exists()


def test_too_many_study_depths_are_refused_before_the_run(tmp_path, capsys, monkeypatch):
    """1001 depths in a study were refused by the FEM only once the run (and its progress bar)
    had started; the check now runs with the others, before the output folder is made."""
    import shtaerman.output.folder as folder

    def never(*args, **kwargs):
        raise AssertionError("the run started")

    monkeypatch.setattr(folder, "run_verification", never)
    path = tmp_path / "many.toml"
    assert main(["init-study", str(path)]) == 0
    depths = ", ".join(f"{1e-6 * (i + 1):g}" for i in range(1001))
    path.write_text(path.read_text().replace('depths = "impact"', f"depths = [{depths}]"))
    capsys.readouterr()
    code = main(["verify", str(path), "--quick", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert "key 'contact.depths': expected a list of 2 to 1000 increasing depths" in err
    assert "(1001 values)" in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("failure", ["numerical", "disk full"])
def test_an_error_keeps_the_finished_studies_and_says_how_to_resume(
    quick_outcomes, quick_verify, tmp_path, monkeypatch, capsys, failure
):
    """An error that is no signal (a failed FEM computation, a full disk while writing) kept
    nothing of the studies that had finished; they are kept as for Ctrl-C, and a failed
    computation names its study file and study."""
    import errno

    from shtaerman.validation import NumericalFailureError

    _serve_writing(monkeypatch, quick_outcomes, quick_verify)
    served = []
    if failure == "numerical":
        error = NumericalFailureError("Newton did not converge; refine the mesh")
        monkeypatch.setattr(
            shtaerman.output.folder,
            "run_study",
            _interrupting(quick_outcomes, [SECOND, error], served),
        )
    else:
        monkeypatch.setattr(
            shtaerman.output.folder, "run_study", _interrupting(quick_outcomes, [None], served)
        )
        write = shtaerman.output.folder.study_entry

        def full_disk(outcome, stage, figure_format="png"):
            if outcome.study.name == SECOND:
                raise OSError(errno.ENOSPC, "No space left on device", str(stage / SECOND))
            return write(outcome, stage, figure_format)

        monkeypatch.setattr(shtaerman.output.folder, "study_entry", full_disk)
    out = tmp_path / "run"
    assert main(["verify", "--quick", "--workers", "1", "--out", str(out), *STUDIES]) == 1
    [line] = capsys.readouterr().err.strip().splitlines()[-1:]
    source = next(path for path in STUDIES if Path(path).stem == SECOND)
    if failure == "numerical":
        assert line.startswith(f"shtaerman: error: {source}: study '{SECOND}': Newton did not ")
    else:
        assert line.startswith("shtaerman: error: No space left on device (")
    assert f"; 1 of 2 studies finished and kept in '{out}'; complete them with: " in line
    assert sorted(p.name for p in out.iterdir()) == sorted(
        [FOLDER_MARKER, "incomplete.json", FIRST]
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]
    monkeypatch.undo()
    _serve_writing(monkeypatch, quick_outcomes, quick_verify)
    served.clear()
    monkeypatch.setattr(
        shtaerman.output.folder, "run_study", _interrupting(quick_outcomes, [None], served)
    )
    assert main(line.split("complete them with: ")[1].split()[1:]) == 0
    assert served == [SECOND]
    results = json.loads((out / "results.json").read_text())
    assert list(results["studies"]) == [FIRST, SECOND]


def test_a_sigkill_of_verify_keeps_the_finished_studies_for_resume(
    quick_outcomes, quick_verify, tmp_path, monkeypatch, capsys
):
    """SIGKILL of the verify process after its first study finished: the next
    ``verify --resume --out SAME`` finds that study (it is kept, not computed again) and says
    where it is; SIGTERM and Ctrl-C kept it, SIGKILL lost it. The killed process is
    ``shtaerman verify`` served the session's first study (tests/served_verify.py)."""
    import os
    import pickle
    import signal
    import subprocess
    import sys
    import time

    out = tmp_path / "run"
    argv = ["verify", "--quick", "--workers", "1", "--out", str(out), *STUDIES]
    env = {**os.environ, "PYTHONPATH": str(Path(shtaerman.__file__).parents[1])}
    served = tmp_path / "served.pickle"
    first = {FIRST: quick_outcomes[FIRST]}  # it computes the second until killed
    served.write_bytes(pickle.dumps((first, quick_verify[1], quick_verify[2])))
    process = subprocess.Popen(
        [sys.executable, str(Path(__file__).with_name("served_verify.py")), str(served), *argv],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    deadline = time.monotonic() + 300
    progress = tmp_path / f".run.partial-{process.pid}" / "content" / "incomplete.json"
    while not progress.is_file():
        assert process.poll() is None and time.monotonic() < deadline
        time.sleep(0.05)
    process.send_signal(signal.SIGKILL)
    process.wait()
    kept = {p.name: p.stat().st_mtime_ns for p in (progress.parent / FIRST).iterdir()}
    _serve_writing(monkeypatch, quick_outcomes, quick_verify)
    served = []
    monkeypatch.setattr(
        shtaerman.output.folder, "run_study", _interrupting(quick_outcomes, [None], served)
    )
    assert main([*argv, "--resume"]) == 0
    err = capsys.readouterr().err
    assert f"a killed run (pid {process.pid}) left its finished part in '{out}'" in err
    assert served == [SECOND]
    assert {p.name: p.stat().st_mtime_ns for p in (out / FIRST).iterdir()} == kept
    results = json.loads((out / "results.json").read_text())
    assert list(results["studies"]) == [FIRST, SECOND] and results["passed"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run", "served.pickle"]


def test_a_killed_verify_in_a_default_folder_is_found_by_the_next_run(
    quick_outcomes, quick_verify, tmp_path, monkeypatch, capsys
):
    """A SIGKILLed verify without --out left its finished part in a hidden staging folder that
    a later run (another time stamp, another name) never looked at: the next verify without
    --out puts it in place and says how to complete it."""
    import subprocess
    import sys

    from shtaerman.output.folder import PROGRESS_FILE

    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    name = "shtaerman-results-20260101-000000-1"
    content = tmp_path / f".{name}.partial-{child.pid}" / "content"
    content.mkdir(parents=True)
    (content / PROGRESS_FILE).write_text("{}")
    (content.parent / "keep").write_text(PROGRESS_FILE)
    (tmp_path / name).mkdir()  # its reservation
    monkeypatch.chdir(tmp_path)
    _serve_writing(monkeypatch, quick_outcomes, quick_verify)
    served = []
    monkeypatch.setattr(
        shtaerman.output.folder, "run_study", _interrupting(quick_outcomes, [None], served)
    )
    assert main(["verify", "--quick", "--workers", "1", *STUDIES]) == 0
    err = capsys.readouterr().err
    assert f"a killed run (pid {child.pid}) left its finished part in" in err and name in err
    assert (tmp_path / name / PROGRESS_FILE).read_text() == "{}"
    assert not any(p.name.startswith(".") for p in tmp_path.iterdir())


def test_verify_workers_are_capped_at_the_studies_to_compute_and_the_memory(
    tmp_path, monkeypatch, capsys
):
    """verify --workers 16 for 2 studies started 16 worker processes; now one per study left
    to compute and no more than the available memory holds, said in one line."""
    import contextlib

    import shtaerman.sweep.engine as engine
    import shtaerman.sweep.verify as on_dask

    started = []

    @contextlib.contextmanager
    def no_cluster(workers=None, scheduler=None):
        started.append(workers)
        raise KeyboardInterrupt
        yield

    monkeypatch.setattr(on_dask, "dask_client", no_cluster)
    argv = ["verify", "--quick", "--workers", "16", *STUDIES]
    assert main([*argv, "--out", str(tmp_path / "a")]) == 130
    assert started == [2]
    assert "shtaerman: starting 2 of 16 workers: 2 studies to compute\n" in capsys.readouterr().err
    monkeypatch.setattr(engine, "available_memory", lambda: 1.2e9)
    assert main([*argv, "--out", str(tmp_path / "b")]) == 130
    assert started == [2, 1]
    assert (
        "shtaerman: starting 1 of 16 workers: the available memory (1.2 GB) holds 1 of about "
        "800 MB\n" in capsys.readouterr().err
    )


def test_a_failed_computation_on_a_dask_worker_comes_back_as_itself(monkeypatch):
    """A study task returns its refused input or failed computation (the worker logs no
    traceback); the executor raises it again in this process, named by its study."""
    import shtaerman.sweep.verify as on_dask
    from shtaerman.validation import InputError, NumericalFailureError

    def failing(study, stage, quick, figure_format):
        raise NumericalFailureError(f"{study}: Newton did not converge")

    monkeypatch.setattr(on_dask, "compute_study", failing)
    result = on_dask.verify_task("s.toml: study 'a'", "/nowhere", True)
    assert result == {"failure": ("numerical", "s.toml: study 'a': Newton did not converge")}
    assert on_dask.FAILURES == {"input": InputError, "numerical": NumericalFailureError}


def test_the_verify_process_imports_no_renderer_before_its_workers_start():
    """The process that hands the studies to dask draws no study's figure: pyvista, VTK's
    rendering and matplotlib's axes cost it ~0.5 s of CPU (0.8 s instead of 1.3 s of imports
    before the cluster starts, benchmarks/verify_cost.py) while both cores wait for work."""
    import subprocess
    import sys

    probe = (
        "import sys\n"
        "from shtaerman.cli import verify\n"
        "from shtaerman.output.folder import run_verification\n"
        "from shtaerman.sweep.verify import run_verification_on_dask\n"
        "from shtaerman.study.schema import load_study, shipped_studies\n"
        "[s for p in shipped_studies() for s in load_study(p)]\n"
        "heavy = ('pyvista', 'vtkmodules.vtkRenderingCore', 'matplotlib.axes')\n"
        "print(sorted(m for m in heavy if m in sys.modules))\n"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_shared_figures_load_no_vtk(run, tmp_path):
    """The reports and the figures of no study (the Ateb functions) are drawn by the process
    that, on dask, runs no study: it must not import pyvista and VTK for them (issue 32; they
    cost it ~0.25 s CPU). Run in a fresh interpreter, on the session run's entries."""
    import shutil
    import subprocess
    import sys

    stage = tmp_path / "run"
    shutil.copytree(run[1], stage)  # the reports read the studies' figures; keep run's folder
    (stage / "ateb.png").unlink()
    script = (
        "import json, sys; from pathlib import Path\n"
        "from shtaerman.output.folder import finish_verification\n"
        f"studies = json.loads(Path({str(stage / 'results.json')!r}).read_text())['studies']\n"
        f"results = finish_verification(Path({str(stage)!r}), studies, quick=True)\n"
        "print(json.dumps([sorted(results['figures']), 'pyvista' in sys.modules,"
        " 'vtkmodules' in sys.modules]))\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    figures, pyvista, vtk = json.loads(done.stdout.splitlines()[-1])
    assert figures and (stage / "ateb.png").is_file()  # the Ateb figure was drawn again
    assert not pyvista and not vtk


def test_in_process_runs_the_studies_on_one_blas_thread(tmp_path, monkeypatch):
    # as a dask task does (sweep/verify.py): on two BLAS threads `verify --workers 1` printed
    # numbers up to 9e-7 (relative) from the default run's (issue 32)
    from threadpoolctl import threadpool_info, threadpool_limits

    folder = shtaerman.output.folder
    seen = []

    def record(study, *args):
        seen.append(
            {info["num_threads"] for info in threadpool_info() if info["user_api"] == "blas"}
        )
        return {}

    monkeypatch.setattr(folder, "compute_study", record)
    with threadpool_limits(limits=2, user_api="blas"):
        drawn = folder.in_process(
            [object()], tmp_path, True, "png", print, lambda study, entry: None, lambda: "drawn"
        )
    assert seen == [{1}] and drawn == "drawn"


_LAYER_AFTER_HERTZ = """
from shtaerman.fem import mesh
from shtaerman.study.run import run_study
from shtaerman.study.schema import find_study, load_study

def run(name):
    mesh._unit_meshes.clear()  # the study's meshes are not yet made in this process
    (study,) = load_study(find_study(name))
    return run_study(study, quick=True)

def numbers():
    outcome = run("layer")
    contact = {k: v for k, v in outcome.contact.to_dict().items() if k != "timings"}
    return repr(outcome.accuracy.estimates), repr(contact)

first = numbers()
run("hertz")
print(numbers() == first)
"""


def test_a_study_computes_the_same_numbers_after_another_in_its_process():
    """A resumed verify ran the layer study in a fresh process, the full run after other studies
    on the same worker: its central-pressure estimate differed by 1.35e-7 (user57), through a
    mesh gmsh made after a wider model (tests/test_fem_mesh.py). Bitwise equal: a fresh
    interpreter runs the layer first, then Hertz, then the layer again."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[1] / "src")}
    done = subprocess.run(
        [sys.executable, "-c", _LAYER_AFTER_HERTZ], env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "True"
