"""The hostile corpus, tools/hostile.py, run whole (issue 25's acceptance): every case must hold.

Each of its cases runs ``python -m flyopt`` on a hostile scene, file, option or output path
and must end with exit 0, 2 or 3 within its timeout, one line on error, no traceback, no
warning, nothing read or written outside the scene's folder (see the tool's docstring).
The run takes many minutes, so the test is slow (``pytest -m slow``); it fails naming every
case that does not hold, with what went wrong.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import flyopt

ROOT = Path(__file__).resolve().parents[1]
HOSTILE = ROOT / "tools" / "hostile.py"


@pytest.mark.slow
# The whole corpus takes some 9.5 minutes on 2 CPUs alone (566 s on 2026-11-30; each case has its own timeout in
# tools/hostile.py), so the suite's 600 s for a hang stopped it on a host shared with another run.
@pytest.mark.timeout(1800)
def test_every_hostile_case_holds(tmp_path):
    outcomes_file = tmp_path / "outcomes.json"
    # The cases run `python -m flyopt` in their own folders: the package under test, not whichever
    # flyopt the interpreter would find from there.
    source = str(Path(flyopt.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [source, os.environ.get("PYTHONPATH")]))}
    run = subprocess.run(
        [sys.executable, str(HOSTILE), "--jobs", "2", "--json", str(outcomes_file)],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
    )
    assert outcomes_file.exists(), f"tools/hostile.py did not finish (exit {run.returncode}): {run.stderr[-2000:]}"
    outcomes = json.loads(outcomes_file.read_text())
    assert len(outcomes) > 500, f"the corpus has only {len(outcomes)} cases"
    failed = [o for o in outcomes if o["problems"]]
    said = "\n".join(f"{o['name']}: {'; '.join(o['problems'])} (flyopt {' '.join(o['args'])[:160]})" for o in failed)
    assert not failed, f"{len(failed)} of {len(outcomes)} hostile cases do not hold:\n{said}"
    assert run.returncode == 0, run.stdout[-2000:]
