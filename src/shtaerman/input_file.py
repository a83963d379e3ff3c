"""Reading a user's small input file (a measurement, a profile, a Prony series) safely.

A path that is not a regular file (a directory, a device such as ``/dev/zero``, a FIFO) or a
file larger than :data:`MAX_INPUT_BYTES` is refused in one line before anything is read, so a
wrong path can neither hang the run nor exhaust the memory.
"""

from __future__ import annotations

import csv
import io
import os
import stat
from pathlib import Path

from .validation import InputError

__all__ = ["MAX_INPUT_BYTES", "csv_rows", "read_input_csv", "read_input_text"]

MAX_INPUT_BYTES = 200 << 20
"""Largest input file read, in bytes (200 MiB: some 10 million rows of a two-column CSV)."""


def read_input_text(path: str | Path, option: str, what: str) -> str:
    """The UTF-8 text of the regular file ``path`` (a BOM dropped).

    Parameters
    ----------
    path : str or Path
        The file; a symbolic link to a regular file is followed.
    option : str
        The parameter named in an error (e.g. ``"profile"``).
    what : str
        Prefix of the error message (e.g. ``"--profile"``).

    Raises
    ------
    InputError
        The file cannot be opened, is not a regular file, is larger than
        :data:`MAX_INPUT_BYTES` or is not UTF-8.
    """
    where = str(path)
    try:
        handle = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as error:
        raise InputError(f"{what}: cannot read {where!r}: {error.strerror}", option) from None
    info = os.fstat(handle)
    if not stat.S_ISREG(info.st_mode):
        os.close(handle)
        raise InputError(
            f"{what}: {where!r} is not a regular file (a directory, device or pipe); "
            "give a CSV file",
            option,
        )
    with os.fdopen(handle, "rb") as stream:
        if info.st_size > MAX_INPUT_BYTES:
            raise InputError(
                f"{what}: {where!r} holds {info.st_size} bytes; at most {MAX_INPUT_BYTES} are read",
                option,
            )
        try:
            data = stream.read(MAX_INPUT_BYTES + 1)
        except OSError as error:
            raise InputError(f"{what}: cannot read {where!r}: {error.strerror}", option) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise InputError(f"{what}: {where!r}: {_not_utf8(data, error.start)}", option) from None


def _not_utf8(data: bytes, start: int) -> str:
    """Where the byte ``data[start]``, not UTF-8, stands (line, column) and what to do."""
    line_start = max(data.rfind(b"\n", 0, start), data.rfind(b"\r", 0, start)) + 1
    column = len(data[line_start:start].decode("utf-8-sig", "replace")) + 1
    ends = sum(data.count(end, 0, line_start) for end in (b"\n", b"\r"))  # LF, CR (old Mac)
    line = ends - data.count(b"\r\n", 0, line_start) + 1  # a CRLF ends one line
    return (
        f"line {line}, column {column}: byte 0x{data[start]:02x} "
        "is not UTF-8 (a Latin-1 or Windows file?); save the file as UTF-8 text"
    )


_SEPARATORS = (";", "\t")
"""Column separators of other locales' spreadsheets (European Excel writes ';'), refused by name."""


def read_input_csv(path: str | Path, option: str, what: str) -> str:
    """The text of the CSV file ``path`` (:func:`read_input_text`), whose columns are separated
    by ','.

    Raises
    ------
    InputError
        As :func:`read_input_text`, or if the header line (the first line neither blank nor a
        ``#`` comment) separates its columns by ';' or a tab instead of ','.
    """
    text = read_input_text(path, option, what)
    lines = (line for line in io.StringIO(text, newline="") if line.strip())  # lazily: huge
    header = next((line for line in lines if not line.lstrip().startswith("#")), "")
    for separator in _SEPARATORS:
        if separator in header and "," not in header:
            shown = repr(separator)
            raise InputError(
                f"{what}: {str(path)!r}: column separator {shown} found; use ','", option
            )
    return text


def csv_rows(
    text: str, where: str, option: str, limit: int | None = None
) -> tuple[list[list[str]], list[int]]:
    """The rows of the CSV ``text`` (the header first) and each one's line number in the file,
    blank lines and lines starting with ``#`` (comments) skipped, so that an error names a
    row as an editor shows it; at most ``limit`` rows (None: all), the rest not parsed.

    Raises
    ------
    InputError
        ``"{where}: line N: ..."`` (parameter ``option``) if the row starting on line N is not
        CSV: a cell longer than the csv module's field limit (131072 characters: an unclosed
        quote runs to the end of the file, or binary data without line ends); or if it holds
        more or fewer cells than the header (a stray or missing comma: which column is which?).
    """
    reader = csv.reader(io.StringIO(text, newline=""))  # a line ends in LF, CRLF or CR (old Mac)
    rows, lines, start = [], [], 1
    try:
        for row in reader:
            if any(cell.strip() for cell in row) and not row[0].lstrip().startswith("#"):
                if rows and len(row) != len(rows[0]):
                    cells = f"{len(row)} cell{'s' * (len(row) != 1)}"
                    raise InputError(
                        f"{where}: line {reader.line_num}: {cells} where the header has "
                        f"{len(rows[0])}; give every row the header's columns",
                        option,
                    )
                rows.append(row)
                lines.append(reader.line_num)
                if len(rows) == limit:
                    break
            start = reader.line_num + 1
    except csv.Error as error:
        reason = f"not CSV ({error})"
        if "field larger than field limit" in str(error):
            reason = (
                f"a cell of more than {csv.field_size_limit()} characters (an unclosed quote, "
                "or not a text CSV); close the quote, or give the data as a text CSV"
            )
        raise InputError(f"{where}: line {start}: {reason}", option) from None
    return rows, lines
