"""make grade's files for learning platforms: headers, quoting and contents, against each platform's documented
import format (sources cited in :func:`course.classroom.grade.exports`). No notebook is run."""

from __future__ import annotations

import csv

from course.classroom.grade import Row, exports, read_roster, roster_emails, write_exports

WORTH = {"ch01_ex1": 1.0, "ch01_ex2": 1.0, "ch02_ex1": 2.0}
ROWS = [Row("s1", "a.ipynb", "ch01_ex1", "s1", "1", "right"), Row("s1", "a.ipynb", "ch02_ex1", "s1", "1", "right"),
        Row("s2", "b.ipynb", "ch01_ex1", "s2", "0", "wrong"),
        Row("=cmd|' /c calc'!a0", "c.ipynb", "ch01_ex1", "x", "1", "right"),
        Row("(placeholder ID student-id) d.ipynb", "d.ipynb", "ch01_ex1", "student-id", "1", "right")]
NAMES = {"s1": 'Tim, "Vic"', "s2": "Ada Lovelace", "s3": "Absent Student"}
EMAILS = {"s1": "vic@example.org", "s3": "absent@example.org"}


def _read(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.reader(f))


def test_each_platforms_columns_and_rows():
    out = exports(ROWS, NAMES, WORTH, EMAILS)
    canvas, moodle, roster, scores = (out[k] for k in ("canvas.csv", "moodle.csv", "gradescope_roster.csv",
                                                        "gradescope.csv"))
    assert canvas[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Jacobians ch01", "Jacobians ch02"]
    assert canvas[1] == ["    Points Possible", "", "", "", "", "2", "2"]
    assert ['Tim, "Vic"', "", "s1", "", "", "1", "2"] in canvas
    assert ["Absent Student", "", "s3", "", "", "0", "0"] in canvas  # on the roster, no notebook: 0 points
    assert moodle[0] == ["ID number", "Full name", "Email address", "Jacobians ch01", "Jacobians ch02"]
    assert ["s1", 'Tim, "Vic"', "vic@example.org", "1", "2"] in moodle
    assert "Total" not in " ".join(moodle[0])
    assert roster == [["Name", "Email", "SID"], ['Tim, "Vic"', "vic@example.org", "s1"],
                      ["Absent Student", "absent@example.org", "s3"]]  # (Gradescope needs an email: s2 has none)
    assert scores[0] == ["Name", "SID", "Email", "ch01", "ch02", "Total Score"]
    assert ['Tim, "Vic"', "s1", "vic@example.org", "1", "2", "3"] in scores
    for table in out.values():
        assert all(len(r) == len(table[0]) for r in table)
        assert not [r for r in table if any("placeholder" in c for c in r)]


def test_files_are_rfc4180_utf8_and_defused(tmp_path):
    write_exports(tmp_path, ROWS, NAMES, EMAILS, WORTH)
    raw = (tmp_path / "canvas.csv").read_bytes()
    assert raw.startswith(b"Student,ID,SIS User ID,") and raw.count(b"\r\n") == len(_read(tmp_path / "canvas.csv"))
    assert b'"Tim, ""Vic"""' in raw  # a comma and quotes: quoted, quotes doubled
    assert b"'=cmd|' /c calc'!a0" in raw and b",=cmd" not in raw  # a formula is never a formula
    for name in ("canvas.csv", "moodle.csv", "gradescope_roster.csv", "gradescope.csv"):
        table = _read(tmp_path / name)
        assert table == [[c if not c.startswith("=") else "'" + c for c in row]
                         for row in exports(ROWS, NAMES, WORTH, EMAILS)[name]]


def test_the_roster_gives_names_and_emails(tmp_path):
    path = tmp_path / "roster.csv"
    path.write_text("\ufeffEmail,SIS User ID,Name\nvic@example.org, S1 ,\"Tim, Vic\"\n,s2,Ada\n", encoding="utf-8")
    assert read_roster(path) == {"s1": "Tim, Vic", "s2": "Ada"}
    assert roster_emails(path) == {"s1": "vic@example.org"}
    path.write_text("ID,Email\ns1,vic@example.org\n", encoding="utf-8")
    assert read_roster(path) == {"s1": ""}  # (the email column is never taken for the name)
