"""Write tests/data/golden/<scene>.json: the JSON of ``flyopt solve --json`` for every problem scene.

The committed copies pin flyopt's numbers: tests/test_golden.py compares every
problem scene's JSON against them, so that a restructuring that changes a
number is caught. Rerun only when a change of numbers is intended, and say
which and why in the commit.

    python tools/make_golden.py
"""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main():
    out_dir = ROOT / "tests" / "data" / "golden"
    out_dir.mkdir(parents=True, exist_ok=True)
    for scene in sorted((ROOT / "problems").glob("*.toml")):
        run = subprocess.run(
            [sys.executable, "-m", "flyopt", "solve", str(scene.relative_to(ROOT)), "--json"],
            capture_output=True,
            text=True,
            cwd=ROOT,
        )
        if run.returncode not in (0, 3):
            raise SystemExit(f"{scene.name}: exit {run.returncode}: {run.stderr.strip()}")
        data = json.loads(run.stdout)
        data.pop("flyopt_version", None)  # provenance, not a result: a release must not break the copies
        (out_dir / f"{scene.stem}.json").write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
        print(scene.name, run.returncode)


if __name__ == "__main__":
    main()
