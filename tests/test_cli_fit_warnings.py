"""``erdesign fit`` says each problem of a record once: a hole in the time column is warned about as the record is
read, and not listed again among the fit's data findings (issue 27)."""

from importlib import resources

import erdesign.cli.fit  # noqa: F401  (registers the command)
from erdesign.cli.main import main
from erdesign.data.findings import FINDING_KINDS
from erdesign.data.measurement import WARNED_AT_READ

MAKRIS = str(resources.files("erdesign.examples") / "makris.toml")
RECORD = resources.files("erdesign.examples") / "measurements" / "makris_hidden_seal_friction.csv"


def test_a_time_gap_is_said_once(tmp_path, capsys):
    lines = RECORD.read_text().splitlines()
    rows = [i for i, line in enumerate(lines) if line and not line.startswith("#")][1:]
    holed = tmp_path / "holed.csv"
    # 100 rows (a third of a second at 300 Hz) left out in the middle: one hole
    holed.write_text("\n".join(line for i, line in enumerate(lines) if i not in rows[300:400]) + "\n")
    code = main(["fit", str(holed), "--damper", MAKRIS, "--json"])
    _, err = capsys.readouterr()
    assert code == 0, err
    assert err.count("the time column has 1 hole") == 1, err
    assert "warning: holed.csv: time: the time column has 1 hole" in err  # the one kept: the reader's warning


def test_kinds_warned_at_read_are_finding_kinds():
    assert set(WARNED_AT_READ) <= set(FINDING_KINDS)
