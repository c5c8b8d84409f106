"""``erdesign fit`` and ``erdesign diagnose`` say each problem of a record once: a hole in the time column is warned
about as the record is read, and not listed again among the data findings (issue 27)."""

from importlib import resources

import erdesign.cli.diagnose  # noqa: F401  (registers the command)
import erdesign.cli.fit  # noqa: F401
from erdesign.cli.main import main
from erdesign.data.findings import FINDING_KINDS
from erdesign.data.measurement import WARNED_AT_READ

MAKRIS = str(resources.files("erdesign.examples") / "makris.toml")
RECORD = resources.files("erdesign.examples") / "measurements" / "makris_hidden_seal_friction.csv"


def holed_record(folder):
    lines = RECORD.read_text().splitlines()
    rows = [i for i, line in enumerate(lines) if line and not line.startswith("#")][1:]
    holed = folder / "holed.csv"
    # 100 rows (a third of a second at 300 Hz) left out in the middle: one hole
    holed.write_text("\n".join(line for i, line in enumerate(lines) if i not in rows[300:400]) + "\n")
    return holed


def test_a_time_gap_is_said_once(tmp_path, capsys):
    code = main(["fit", str(holed_record(tmp_path)), "--damper", MAKRIS, "--json"])
    _, err = capsys.readouterr()
    assert code == 0, err
    assert err.count("the time column has 1 hole") == 1, err
    assert "warning: holed.csv: time: the time column has 1 hole" in err  # the one kept: the reader's warning


def test_diagnose_says_a_time_gap_once_and_counts_it_among_the_findings(tmp_path, capsys):
    code = main(["diagnose", str(holed_record(tmp_path)), "--damper", MAKRIS])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert (out + err).count("the time column has 1 hole") == 1, out + err
    assert "warning: holed.csv: time: the time column has 1 hole" in err
    assert "time_gap: warned above as the record was read" in out
    # the JSON keeps every finding
    main(["diagnose", str(holed_record(tmp_path)), "--damper", MAKRIS, "--json"])
    out, _ = capsys.readouterr()
    assert '"kind": "time_gap"' in out


def test_kinds_warned_at_read_are_finding_kinds():
    assert set(WARNED_AT_READ) <= set(FINDING_KINDS)
