"""The pool's workers run the erdesign of the process that made the pool, whatever folder it works in.

The fork server that starts the workers is a new interpreter; started from a folder holding another ``erdesign``
(a batch run from its records' folder, an installed copy beside a checkout), it imported that one and every worker
ran it: a pool's diagnosis then differed from the serial one (tests/test_diagnose_executor.py failed after
tests/test_batch.py, whose batches run from the records' folder, whenever the installed copy was older).
"""

import subprocess
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_workers_import_the_parents_erdesign_from_any_folder(tmp_path):
    fake = tmp_path / "erdesign"
    fake.mkdir()
    (fake / "__init__.py").write_text("MARK = 'the wrong erdesign'\n")
    code = textwrap.dedent(
        f"""
        import importlib.util, os, sys
        sys.path.insert(0, {str(ROOT)!r})
        import erdesign
        from erdesign.executor import PoolExecutor
        os.chdir({str(tmp_path)!r})  # a folder with another erdesign in it, as the fork server starts
        if __name__ == "__main__":
            with PoolExecutor(2) as pool:
                seen = {{s.origin for s in pool.map(importlib.util.find_spec, ["erdesign"] * 4)}}
            print(sorted(seen) == [erdesign.__file__], os.environ.get("PYTHONSAFEPATH"))
        """
    )
    script = tmp_path / "run.py"
    script.write_text(code)
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert out.returncode == 0, out.stderr[-2000:]
    # the workers' erdesign is the parent's; the environment is left as it was
    assert out.stdout.split() == ["True", "None"], out.stdout + out.stderr[-2000:]
